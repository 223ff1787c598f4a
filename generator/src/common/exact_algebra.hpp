// Exact rational numbers and matrices: parameters enter the algebra as exact rationals, and R, L
// and the like are multiplied and solved exactly, skipping the zeros of these sparse matrices.
#pragma once

#include <vector>

#include <Eigen/Dense>
#include <ginac/ginac.h>

namespace pogear {

// The double v as an exact rational. Parameters enter the algebra exactly, so every number
// pogear prints is the correctly rounded value of an exact expression: two different formulas
// for the same quantity give the same double.
GiNaC::numeric exact_number(double v);

double to_double(const GiNaC::ex& e);  // throws std::domain_error when e is not a real number

// e with `values` (symbol -> number) put in, computed exactly: the number GiNaC's subs gives, but
// by one walk over e, without building the substituted tree (the closed forms of a long chain
// are megabytes). Anything the walk does not know (functions, non-integer powers, symbols
// without a number) goes through subs; the result is then not necessarily a number.
GiNaC::ex exact_value(const GiNaC::ex& e, const GiNaC::exmap& values);
GiNaC::numeric as_number(const GiNaC::ex& e);  // throws std::domain_error when e is not a number

// Products and solutions of matrices of exact numbers (else std::domain_error), skipping zeros: R, L and the like are
// sparse, and GiNaC's own dense routines treat every entry as a symbolic expression.
GiNaC::matrix exact_product(const GiNaC::matrix& a, const GiNaC::matrix& b);
GiNaC::matrix exact_solve(const GiNaC::matrix& a, const GiNaC::matrix& b);  // a x = b; throws if a is singular
// The given rows of x, in that order; unknowns no given row depends on are not computed.
GiNaC::matrix exact_solve_rows(const GiNaC::matrix& a, const GiNaC::matrix& b, const std::vector<int>& rows);

// Every entry of `m` at the given substitutions (SI values); throws if one stays symbolic.
Eigen::MatrixXd evaluate_matrix(const GiNaC::matrix& m, const GiNaC::exmap& values);
// Every entry of `m` with `values` put in, exactly (see exact_value).
GiNaC::matrix exact_matrix(const GiNaC::matrix& m, const GiNaC::exmap& values);

}  // namespace pogear
