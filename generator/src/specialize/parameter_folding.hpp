// The parameter substitutions of a scene: what specialization folds into the equations and what
// the reference numeric model evaluates at.
#pragma once

#include <ginac/ginac.h>

#include "derive/derivation.hpp"
#include "read/scene.hpp"

namespace pogear {

// Values of every non-tunable parameter (every parameter without `keep_tunables`), as exact
// numbers, or as expressions in the tunables for parameters defined through one and for derived
// radii that follow a tunable radius; zeros for the parameters of effects the scene leaves out.
GiNaC::exmap parameter_folding(const Scene& scene, const Derivation& d, bool keep_tunables);

}  // namespace pogear
