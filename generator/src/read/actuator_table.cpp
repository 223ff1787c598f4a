// A scene's [actuators]: per brake or clutch a fill delay and a lag time constant, read with their
// units and checked against the scene's engagement.
#include "read/actuator_table.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "common/quantity.hpp"
#include "read/slip_control.hpp"

namespace pogear {

std::vector<ActuatorSpec> read_actuators(const SceneReader& r, const toml::node& n) {
  const toml::table& t = r.table(n, "[actuators]");
  std::vector<ActuatorSpec> out;
  for (const auto& [key, value] : t) {
    const std::string name(key.str());
    ActuatorSpec a;
    a.element = find_friction_element(*r.model, name);
    if (a.element < 0) fail_no_friction_element(r, value, name, "[actuators] gives an element's fill delay and lag");
    const std::string what = fmt::format("[actuators] {}", name);
    const toml::table& e = r.table(value, what);
    r.only_keys(e, {"fill_delay", "time_constant"}, what);
    a.where = r.loc(value);
    if (e.empty())
      r.fail(value, fmt::format("{} needs fill_delay (e.g. \"30*ms\"), time_constant (e.g. \"40*ms\") or both", what));
    for (const auto& [field, target] : {std::pair{"fill_delay", &a.fill_delay}, std::pair{"time_constant", &a.time_constant}})
      if (const toml::node* v = e.get(field)) {
        *target = r.quantity(*v, time_dimension(), field);
        // Shorter than a nanosecond is below what a shift's events resolve, and longer than an hour
        // is no actuator: a typing error either way.
        if (!(*target >= 0)) r.fail(*v, fmt::format("{} is negative; a delay or lag is 0 or more", field));
        if (*target > 0 && !(*target >= 1e-9 && *target <= 3600))
          r.fail(*v, fmt::format("{} is 0 or from 1e-9 s to 3600 s; give it in s or ms, e.g. \"40*ms\"", field));
      }
    out.push_back(a);
  }
  std::sort(out.begin(), out.end(), [](const ActuatorSpec& a, const ActuatorSpec& b) { return a.element < b.element; });
  return out;
}

void check_actuators(const Scene& s) {
  for (const ActuatorSpec& a : s.actuators) {
    const FrictionElement& f = s.model.friction_elements[static_cast<std::size_t>(a.element)];
    if (!engages(s, a.element))
      throw InputError(a.where, fmt::format("the scene does not engage {}, so its actuator has nothing to apply; give "
                                            "{} a command in [engagement], or drop it from [actuators]", f.name, f.name));
    if (f.one_way)
      throw InputError(a.where, fmt::format("{} is a one-way element, which holds by its shape, not by a command; drop "
                                            "it from [actuators]", f.name));
    if (slip_controller_of(s, a.element) >= 0)
      throw InputError(a.where, fmt::format("{} is under slip control, whose command the actuator would lag through a "
                                            "state of its own, which pogear does not model yet; drop {} from [actuators] "
                                            "or from [slip_control]", f.name, f.name));
  }
}

}  // namespace pogear
