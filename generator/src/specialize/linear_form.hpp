// Reading a specialized system's linear right-hand side as matrices: dx/dt = M x + N u.
#pragma once

#include "specialize/specialization.hpp"

namespace pogear {

// dx/dt = M x + N u, read off the (linear) right-hand side with the temporaries substituted.
// Each term of a row is differentiated once, by its own variable: differentiating the whole row
// by every variable re-added the row's big numbers (k^3 additions for a rigid chain of k states).
// The sums of the derivatives are the same canonical expressions diff gives; a row with a term
// of another shape goes through diff.
void linear_form(const SymbolTable& s, SpecializedSystem& sys);

// The same reading for any rows linear in the variables (symbols): row i = sum_j C(i, j) v_j + a
// part free of them, which is dropped. A row that is not linear gets its derivatives instead.
GiNaC::matrix linear_coefficients(const std::vector<GiNaC::ex>& rows, const std::vector<GiNaC::ex>& variables);

}  // namespace pogear
