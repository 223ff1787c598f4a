// The temperatures a scene's runs give, by the engaged elements' order.
#include "specialize/element_thermal.hpp"

#include <algorithm>

namespace pogear {

std::vector<rt::ElementThermal> element_thermal(const SpecializedScene& model) {
  std::vector<rt::ElementThermal> out;
  for (const ThermalSpec& th : model.scene.thermal) {
    const auto k = std::find_if(model.friction.begin(), model.friction.end(),
                                [&](const FrictionRun& f) { return f.element == th.element; });
    if (k == model.friction.end()) continue;
    out.push_back({static_cast<int>(k - model.friction.begin()), th.heat_capacity, th.conductance, th.ambient, th.initial});
  }
  return out;
}

}  // namespace pogear
