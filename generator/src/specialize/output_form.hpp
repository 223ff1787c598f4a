// The outputs of a specialized system as matrices, y = C x + D u (+ E dx/dt), read off the
// symbolic output expressions: what the generated output_matrices() prints.
#pragma once

#include <string>

#include <ginac/ginac.h>

#include "specialize/specialization.hpp"

namespace pogear {

struct OutputForm {
  GiNaC::matrix C;  // ny x nx
  GiNaC::matrix D;  // ny x nu
  // ny x nx, the outputs' dependence on dx/dt, left to the generated code when dx/dt is solved
  // numerically (SpecializedSystem::implicit): C + E M and D + E N are then the outputs' matrices. Zero
  // otherwise: the symbolic M and N are put in, so C and D are exact.
  GiNaC::matrix E;
  bool reads_derivatives = false;  // whether E has a nonzero entry
};

OutputForm output_form(const SpecializedSystem& sys, const SymbolTable& symbols);

}  // namespace pogear
