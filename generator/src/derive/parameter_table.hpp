// The model's parameter table as the reports print it.
#pragma once

#include <string>
#include <vector>

#include "derive/derivation.hpp"

namespace pogear {

// One row per parameter: its name, its text as given (or m Z / 2 from teeth), its SI value with
// unit, and where it is defined ("line 41", "its teeth, line 12"); then the radii the geometry gives,
// with their mesh.
std::vector<std::vector<std::string>> parameter_table(const Derivation& d);

}  // namespace pogear
