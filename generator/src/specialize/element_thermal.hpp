// The temperatures a scene's runs give (its [thermal]), in the runtime's terms.
#pragma once

#include <vector>

#include "pogear/element_thermal.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The scene's [thermal], each element by its index among model.friction (the engaged elements:
// check_thermal refuses the others).
std::vector<rt::ElementThermal> element_thermal(const SpecializedScene& model);

}  // namespace pogear
