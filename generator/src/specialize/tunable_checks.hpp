// What a scene's tunable parameters may be: the units and sign `--param` accepts for each, and the
// geometry a tunable radius cannot follow, refused.
#pragma once

#include <string>

#include "derive/derivation.hpp"
#include "read/scene.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// What `--param` accepts for tunable `name` (at `value`, SI), and the sign its roles in the model ask for.
TunableParameter tunable_parameter(const Topology& t, const std::string& name, double value);

// Refuses a tunable radius that a geometry relation ties to a radius the model gives as a number.
void check_tunable_geometry(const Scene& sc, const Derivation& d, const GiNaC::exmap& fold);

}  // namespace pogear
