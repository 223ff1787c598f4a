// Loads and controllers as a scene file writes them: every value with its unit, every name checked
// against the model and against the names the generated code gives their variables.
#include "read/loads_and_controllers.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "pogear/parameters.hpp"

#include "read/model_parameters.hpp"
#include "read/signal_start.hpp"
#include "names/model_variables.hpp"

namespace pogear {
namespace {

Dimension times_seconds(Dimension d, int power) {
  d.exponent[2] += power;
  return d;
}

int body_named(const SceneReader& r, const toml::node& n, const std::string& name, std::string_view what) {
  const int b = find_body(*r.model, name);
  if (const std::string why = fixed_body_refusal(*r.model, name, what); !why.empty()) r.fail(n, why);
  if (b < 0) {
    std::string names;
    for (const auto& body : r.model->bodies) names += (names.empty() ? "" : ", ") + body.name;
    r.fail(n, fmt::format("{} '{}' is not a body of the model; its bodies are {}", what, name, names));
  }
  return b;
}

double non_negative(const SceneReader& r, const toml::node& n, const Dimension& dim, std::string_view what,
                    std::string_view example_unit) {
  const double v = r.coefficient(n, dim, what, example_unit);
  if (v < 0) r.fail(n, fmt::format("{} is negative; a load takes power from the gear (a torque that drives it is an "
                                   "input in [inputs])", what));
  // The range of the model's parameters (model_parameters.cpp): beyond it the equations over- or underflow.
  constexpr double smallest = rt::kSmallestParameter, largest = rt::kLargestParameter;
  if (v != 0 && !(v >= smallest && v <= largest))
    r.fail(n, fmt::format("{} is {:g} (SI), outside the range pogear computes with, {:g} to {:g}; check the value and "
                          "its unit", what, v, smallest, largest));
  return v;
}

}  // namespace

std::vector<LoadSpec> read_loads(const SceneReader& r, const toml::node& n) {
  if (!n.is_table()) r.fail(n, "[loads] must be a table of <body> = { constant = ..., linear = ..., quadratic = ... }");
  std::vector<LoadSpec> out;
  for (const auto& [key, value] : *n.as_table()) {
    const int body = body_named(r, value, std::string(key.str()), "the load's body");
    if (!value.is_table())
      r.fail(value, "a load is a table { constant = \"<torque>\", linear = \"<N*m*s/rad>\", quadratic = "
                    "\"<N*m*s^2/rad^2>\" }, each part optional");
    const toml::table& t = *value.as_table();
    r.only_keys(t, {"constant", "linear", "quadratic"}, "a load");
    LoadSpec l;
    l.body = body;
    l.where = r.loc(value);
    if (const toml::node* v = t.get("constant")) l.constant = non_negative(r, *v, torque_dimension(), "constant", "5*N*m");
    if (const toml::node* v = t.get("linear"))
      l.linear = non_negative(r, *v, times_seconds(torque_dimension(), 1), "linear", "0.5*N*m*s/rad");
    if (const toml::node* v = t.get("quadratic"))
      l.quadratic = non_negative(r, *v, times_seconds(torque_dimension(), 2), "quadratic", "0.002*N*m*s^2/rad^2");
    out.push_back(l);
  }
  std::sort(out.begin(), out.end(), [](const LoadSpec& a, const LoadSpec& b) { return a.body < b.body; });
  return out;
}

std::vector<ControllerSpec> read_controllers(const SceneReader& r, const toml::node& n,
                                             const std::filesystem::path& scene_dir, const Topology& model) {
  if (!n.is_table())
    r.fail(n, "[controllers] must be a table of <name> = { body = ..., set_point = ..., kp = ..., ki = ... }");
  // With the model's brakes and clutches (at most 12), the modes of a run are bits of 32.
  constexpr std::size_t max_controllers = 16;
  if (n.as_table()->size() > max_controllers)
    r.fail(n, fmt::format("{} controllers; a scene has at most {}", n.as_table()->size(), max_controllers));
  std::vector<ControllerSpec> out;
  for (const auto& [key, value] : *n.as_table()) {
    if (!value.is_table())
      r.fail(value, "a controller is a table { body = \"<body>\", speed_of = \"<body>\", set_point = <speed signal>, "
                    "kp = \"<N*m*s/rad>\", ki = \"<N*m/rad>\" }");
    const toml::table& t = *value.as_table();
    r.only_keys(t, {"body", "speed_of", "set_point", "kp", "ki", "torque_min", "torque_max", "tracking_time"},
                "a controller");
    ControllerSpec c;
    c.name = std::string(key.str());
    c.where = r.loc(value);
    if (!is_name(c.name) || c.name.size() > max_name_length)
      r.fail(value, fmt::format("controller name '{}' must be letters, digits and '_', from a letter, at most {} "
                                "characters (it names the controller's variables in the generated code)",
                                c.name, max_name_length));
    for (const VariableKind kind : {VariableKind::controller_torque, VariableKind::controller_integral,
                                    VariableKind::controller_error, VariableKind::set_point})
      if (const std::string name = controller_variable_name(kind, c.name); find_parameter(model, name))
        r.fail(value, fmt::format("the model has a parameter named '{}', which the generated code uses for controller "
                                  "'{}'; rename the controller", name, c.name));
    const toml::node* body = t.get("body");
    if (!body) r.fail(value, "the controller names no body; add body = \"<body>\", the body whose torque it sets");
    c.body = body_named(r, *body, r.string(*body, "body"), "the controller's body");
    c.measured = c.body;
    if (const toml::node* m = t.get("speed_of")) c.measured = body_named(r, *m, r.string(*m, "speed_of"), "speed_of");
    const toml::node* set_point = t.get("set_point");
    if (!set_point) r.fail(value, "the controller has no set_point; add set_point = \"<speed>\", e.g. \"1500*rpm\"");
    c.set_point = read_signal(r, *set_point, scene_dir, SignalQuantity::speed);
    c.set_point_start = read_signal_start(r, *set_point, c.set_point, scene_dir, SignalQuantity::speed);
    const toml::node* kp = t.get("kp");
    const toml::node* ki = t.get("ki");
    if (kp) c.kp = r.coefficient(*kp, times_seconds(torque_dimension(), 1), "kp", "1.5*N*m*s/rad");
    if (ki) c.ki = r.coefficient(*ki, torque_dimension(), "ki", "4*N*m/rad");
    if (c.kp < 0 || c.ki < 0 || (c.kp == 0 && c.ki == 0))
      r.fail(c.kp < 0 ? *kp : c.ki < 0 ? *ki : value,
             "a controller's gains kp and ki are non-negative and not both zero; give kp = \"<N*m*s/rad>\" "
             "and ki = \"<N*m/rad>\"");
    if (const toml::node* v = t.get("torque_min")) c.torque_min = r.quantity(*v, torque_dimension(), "torque_min");
    if (const toml::node* v = t.get("torque_max")) c.torque_max = r.quantity(*v, torque_dimension(), "torque_max");
    if (!(c.torque_min < c.torque_max))
      r.fail(*t.get("torque_max"), fmt::format("torque_max ({} N m) is not above torque_min ({} N m); give the limits "
                                               "of the torque the controller can apply", c.torque_max, c.torque_min));
    if (const toml::node* v = t.get("tracking_time")) {
      if (!c.limited() || c.ki == 0)
        r.fail(*v, "tracking_time is the time constant with which the integral follows a torque limit; it needs "
                   "torque_min or torque_max, and ki");
      c.tracking_time = r.quantity(*v, time_dimension(), "tracking_time");
      if (!(c.tracking_time > 0)) r.fail(*v, "tracking_time must be positive, e.g. \"0.1*s\"");
    } else if (c.limited() && c.ki > 0) {
      if (c.kp == 0)
        r.fail(value, "a controller with torque limits and no kp needs tracking_time, the time constant with which "
                      "its integral follows a limit (kp / ki, the default, is zero)");
      c.tracking_time = c.kp / c.ki;  // the integral time: Astrom and Hagglund's choice for PI control
      c.integral_time_tracking = true;
    }
    out.push_back(std::move(c));
  }
  return out;
}

std::optional<Variable> find_scene_variable(const Scene& s, std::string_view name,
                                            std::initializer_list<VariableKind> kinds) {
  if (auto v = find_variable(s.model, name, kinds)) return v;
  for (const VariableKind kind : kinds)
    if (of_vehicle(kind) && s.vehicle && variable_name(s.model, {kind, 0}) == name) return Variable{kind, 0};
  for (const VariableKind kind : kinds)
    if (((kind == VariableKind::engine_torque && s.engine) || (of_driveline(kind) && kind != VariableKind::engine_torque && s.converter)) &&
        variable_name(s.model, {kind, 0}) == name)
      return Variable{kind, 0};
  for (const VariableKind kind : kinds)
    if (of_controller(kind))
      for (std::size_t c = 0; c < s.controllers.size(); ++c)
        if (controller_variable_name(kind, s.controllers[c].name) == name) return Variable{kind, static_cast<int>(c)};
  return std::nullopt;
}

std::vector<std::string> controller_names(const Scene& scene) {
  std::vector<std::string> names;
  for (const ControllerSpec& c : scene.controllers) names.push_back(c.name);
  return names;
}

}  // namespace pogear
