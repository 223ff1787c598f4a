// The temperatures a scene's runs give, by the engaged elements' order.
#include "specialize/element_thermal.hpp"

namespace pogear {

std::vector<rt::ElementThermal> element_thermal(const SpecializedScene& model) {
  std::vector<rt::ElementThermal> out;
  for (const ThermalSpec& th : model.scene.thermal)
    if (const int k = friction_run_index(model, th.element); k < static_cast<int>(model.friction.size()))
      out.push_back({k, th.heat_capacity, th.conductance, th.ambient, th.initial});
  return out;
}

}  // namespace pogear
