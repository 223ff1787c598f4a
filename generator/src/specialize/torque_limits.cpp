// See torque_limits.hpp: a limited controller's data, found in the system's inputs and states.
#include "specialize/torque_limits.hpp"

#include <algorithm>

namespace pogear {

std::vector<rt::TorqueLimitData> torque_limit_data(const SpecializedScene& model, const SpecializedSystem& sys,
                                                   const std::vector<rt::TriggeredSignal>& triggered) {
  std::vector<rt::TorqueLimitData> out;
  for (const int c : sys.limited_controllers) {
    const ControllerSpec& k = model.scene.controllers[static_cast<std::size_t>(c)];
    rt::TorqueLimitData l;
    l.name = k.name;
    l.torque_min = k.torque_min;
    l.torque_max = k.torque_max;
    if (k.supplies >= 0) {
      l.supplies = friction_run_index(model, k.supplies);
      l.starts_at = k.start;
      const Variable theta{VariableKind::controller_integral, c}, ref{VariableKind::set_point, c};
      const auto x = std::find_if(sys.states.begin(), sys.states.end(), [&](const StatePort& s) { return s.variable == theta; });
      l.integral = x - sys.states.begin();
      int signal = 0;  // the target's index among the system's signals
      for (const InputPort& u : sys.inputs) {
        if (u.variable == ref) break;
        signal += u.signal.has_value();
      }
      for (std::size_t i = 0; i < triggered.size(); ++i)
        if (!triggered[i].command && triggered[i].index == signal) l.started_by = static_cast<int>(i);
    }
    out.push_back(std::move(l));
  }
  return out;
}

}  // namespace pogear
