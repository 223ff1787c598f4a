// The parameter substitutions of a scene: what specialization folds into the equations and what
// the reference numeric model evaluates at.
#pragma once

#include <ginac/ginac.h>

#include "derive/derivation.hpp"
#include "read/scene.hpp"

namespace pogear {

// A scene's parameter values, folded once per scene: every non-tunable parameter as an exact number,
// or as an expression in the tunables for parameters defined through one and for derived radii that
// follow a tunable radius; zeros for the parameters of effects the scene leaves out. `equations`
// keeps the tunables as symbols (what the specialized equations read); `numbers` has them at their
// values too (initial states, the reference model, the diagnostics).
struct SceneValues {
  GiNaC::exmap equations, numbers;
};

SceneValues scene_values(const Scene& scene, const Derivation& d);

}  // namespace pogear
