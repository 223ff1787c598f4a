// See slip_control.hpp: [slip_control] as speed controllers of the elements' slips.
#include "read/slip_control.hpp"

#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>

#include "names/model_variables.hpp"
#include "read/friction_curve.hpp"
#include "read/loads_and_controllers.hpp"
#include "read/model_parameters.hpp"
#include "read/signal_start.hpp"
#include "read/toml_reader.hpp"

namespace pogear {

namespace {

constexpr std::size_t max_controllers = 16;  // with the brakes and clutches, a mode is a 32-bit set

// The sign of the target's first value other than zero over its own times [0, horizon] (a
// piecewise linear signal: its values at 0, its breakpoints and the horizon), or 0 when it is zero
// throughout. Its `before` is no target: the controller is off until the target starts.
int target_sign(const ControllerSpec& c, double horizon) {
  std::vector<double> times = rt::breakpoints(c.set_point, 0.0, horizon);
  times.push_back(horizon);
  times.insert(times.begin(), 0.0);
  for (const double t : times)
    for (const double v : {rt::value(c.set_point, std::nextafter(t, 0.0)), rt::value(c.set_point, t)})
      if (v != 0) return v > 0 ? 1 : -1;
  return 0;
}

}  // namespace

void read_slip_control(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir, Scene& s) {
  if (!n.is_table())
    r.fail(n, "[slip_control] must be a table of <element> = { target = <slip speed signal>, kp = \"<s/rad>\", "
              "ki = \"<1/rad>\" }");
  const Topology& model = s.model;
  for (const auto& [key, value] : *n.as_table()) {
    const std::string element(key.str());
    const int k = find_friction_element(model, element);
    if (k < 0) {
      std::string names;
      for (const auto& e : model.friction_elements) names += (names.empty() ? "" : ", ") + e.name;
      throw InputError(toml_location(s.file, key.source()),
                       fmt::format("'{}' is no brake or clutch of the model (it has {}); [slip_control] controls the "
                                   "slip of one of them", element, names));
    }
    if (!value.is_table())
      r.fail(value, "a slip controller is a table { target = <slip speed signal>, kp = \"<s/rad>\", ki = \"<1/rad>\" }");
    const toml::table& t = *value.as_table();
    r.only_keys(t, {"target", "kp", "ki", "tracking_time", "start"}, "a slip controller");
    if (std::none_of(s.engagement.begin(), s.engagement.end(), [&](const EngagementSpec& e) { return e.element == k; }))
      r.fail(value, fmt::format("{} has a slip controller but no command in [engagement]; give it its command until "
                                "the controller starts, e.g. {} = \"0\" (open)", element, element));
    if (s.controllers.size() >= max_controllers)
      r.fail(value, fmt::format("more than {} controllers and slip controllers; a scene has at most {}", max_controllers,
                                max_controllers));
    ControllerSpec c;
    c.name = "slip_" + element;
    c.where = r.loc(value);
    c.supplies = k;
    if (c.name.size() > max_name_length)
      r.fail(value, fmt::format("'{}', the name of the slip controller's variables, is longer than {} characters; "
                                "give the element a shorter name", c.name, max_name_length));
    if (std::any_of(s.controllers.begin(), s.controllers.end(), [&](const ControllerSpec& o) { return o.name == c.name; }))
      r.fail(value, fmt::format("[controllers] has a controller named '{}', the name of {}'s slip controller; rename "
                                "the controller", c.name, element));
    for (const VariableKind kind : {VariableKind::controller_torque, VariableKind::controller_integral,
                                    VariableKind::controller_error, VariableKind::set_point})
      if (const std::string name = controller_variable_name(kind, c.name); find_parameter(model, name))
        r.fail(value, fmt::format("the model has a parameter named '{}', which the generated code uses for {}'s slip "
                                  "controller; rename the parameter", name, element));
    const toml::node* target = t.get("target");
    if (!target)
      r.fail(value, "the slip controller has no target; add target = <slip speed signal>, e.g. { table = [[0, "
                    "\"30*rad/s\"], [\"0.3*s\", \"0*rad/s\"]], when = \"B2 slipping\" }");
    c.set_point = read_signal(r, *target, scene_dir, SignalQuantity::speed);
    c.set_point_start = read_signal_start(r, *target, c.set_point, scene_dir, SignalQuantity::speed);
    if (std::holds_alternative<rt::Sine>(c.set_point))
      r.fail(*target, "a slip controller's target is a constant, step, ramp or table: a sine changes the slip's sign");
    // The gains per unit command: times the capacity they are torques, negative in the speed
    // controller's law kp (ref - slip) + ki theta (a slip above its target calls for more torque).
    const double capacity = parameter_value(model, model.friction_elements[static_cast<std::size_t>(k)].capacity_parameter);
    double kp = 0, ki = 0;
    const toml::node* kp_node = t.get("kp");
    const toml::node* ki_node = t.get("ki");
    if (kp_node) kp = r.coefficient(*kp_node, time_dimension(), "kp", "0.01*s/rad");
    if (ki_node) ki = r.coefficient(*ki_node, Dimension{}, "ki", "0.5/rad");
    if (kp < 0 || ki < 0 || (kp == 0 && ki == 0))
      r.fail(kp < 0 ? *kp_node : ki < 0 ? *ki_node : value,
             "a slip controller's gains kp and ki are non-negative and not both zero; give kp = \"<s/rad>\" (command "
             "per slip speed) and ki = \"<1/rad>\" (command per slip angle)");
    c.kp = -kp * capacity;
    c.ki = -ki * capacity;
    if (const toml::node* v = t.get("tracking_time")) {
      if (ki == 0) r.fail(*v, "tracking_time is the time constant with which the integral follows a limit; it needs ki");
      c.tracking_time = r.quantity(*v, time_dimension(), "tracking_time");
      if (!(c.tracking_time > 0)) r.fail(*v, "tracking_time must be positive, e.g. \"0.05*s\"");
    } else if (ki > 0) {
      if (kp == 0)
        r.fail(value, "a slip controller with no kp needs tracking_time, the time constant with which its integral "
                      "follows a limit (kp / ki, the default, is zero)");
      c.tracking_time = kp / ki;
      c.integral_time_tracking = true;
    }
    if (const toml::node* v = t.get("start")) {
      if (c.set_point_start)
        r.fail(*v, "the target's `when` starts the slip controller; drop start, or the target's when");
      c.start = r.quantity(*v, time_dimension(), "start");
      if (!(c.start >= 0)) r.fail(*v, "start is a time from 0 on, e.g. \"1*s\"");
    }
    // The limits' sign comes with the horizon (check_slip_control); the torque stays within the capacity.
    c.torque_min = -capacity;
    c.torque_max = capacity;
    s.controllers.push_back(std::move(c));
  }
  if (s.controllers_where.file.empty()) s.controllers_where = r.loc(n);
}

void check_slip_control(Scene& s) {
  for (ControllerSpec& c : s.controllers) {
    if (c.supplies < 0) continue;
    const std::string& element = s.model.friction_elements[static_cast<std::size_t>(c.supplies)].name;
    // Its torque limit, the capacity at full command, would vary with the slip it controls.
    if (varies_with_slip(s.model.friction_elements[static_cast<std::size_t>(c.supplies)]))
      throw InputError(c.where, fmt::format("{}'s friction varies with slip (friction_curve in the model), which a slip "
                                            "controller does not take; control an element of constant friction, or give "
                                            "{} a constant ratio", element, element));
    const int sign = target_sign(c, s.horizon);
    if (sign == 0)
      throw InputError(c.where, fmt::format("the target of {}'s slip controller is zero throughout the run; a target "
                                            "has the sign of the slip it holds (slip_{} in the CSV)", element, element));
    (sign > 0 ? c.torque_min : c.torque_max) = 0;
    for (const auto& [v, value] : s.initial)
      if (v.kind == VariableKind::controller_torque && s.controllers[static_cast<std::size_t>(v.index)].name == c.name)
        throw InputError(s.initial_where, fmt::format("Tc_{} is the torque of {}'s slip controller, which starts from "
                                                      "zero when it starts; drop it from [initial]", c.name, element));
  }
}

bool has_slip_control(const Scene& s) {
  return std::any_of(s.controllers.begin(), s.controllers.end(), [](const ControllerSpec& c) { return c.supplies >= 0; });
}

int slip_controller_of(const Scene& s, int element) {
  for (std::size_t c = 0; c < s.controllers.size(); ++c)
    if (s.controllers[c].supplies == element) return static_cast<int>(c);
  return -1;
}

}  // namespace pogear
