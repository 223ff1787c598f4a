// Loads and controllers as a scene file writes them: every value with its unit, every name checked
// against the model and against the names the generated code gives their variables.
#include "loads_and_controllers.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "model_parameters.hpp"
#include "model_variables.hpp"

namespace pogear {
namespace {

Dimension times_seconds(Dimension d, int power) {
  d.exponent[2] += power;
  return d;
}

int body_named(const SceneReader& r, const toml::node& n, const std::string& name, std::string_view what) {
  const int b = find_body(*r.model, name);
  if (b < 0) {
    std::string names;
    for (const auto& body : r.model->bodies) names += (names.empty() ? "" : ", ") + body.name;
    r.fail(n, fmt::format("{} '{}' is not a body of the model; its bodies are {}", what, name, names));
  }
  return b;
}

double non_negative(const SceneReader& r, const toml::node& n, const Dimension& dim, std::string_view what) {
  const double v = r.quantity(n, dim, what);
  if (v < 0) r.fail(n, fmt::format("{} is negative; a load takes power from the gear (a torque that drives it is an "
                                   "input in [inputs])", what));
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
    if (const toml::node* v = t.get("constant")) l.constant = non_negative(r, *v, torque_dimension(), "constant");
    if (const toml::node* v = t.get("linear")) l.linear = non_negative(r, *v, times_seconds(torque_dimension(), 1), "linear");
    if (const toml::node* v = t.get("quadratic"))
      l.quadratic = non_negative(r, *v, times_seconds(torque_dimension(), 2), "quadratic");
    out.push_back(l);
  }
  std::sort(out.begin(), out.end(), [](const LoadSpec& a, const LoadSpec& b) { return a.body < b.body; });
  return out;
}

std::vector<ControllerSpec> read_controllers(const SceneReader& r, const toml::node& n,
                                             const std::filesystem::path& scene_dir, Topology& model) {
  if (!n.is_table())
    r.fail(n, "[controllers] must be a table of <name> = { body = ..., set_point = ..., kp = ..., ki = ... }");
  std::vector<ControllerSpec> out;
  for (const auto& [key, value] : *n.as_table()) {
    if (!value.is_table())
      r.fail(value, "a controller is a table { body = \"<body>\", speed_of = \"<body>\", set_point = <speed signal>, "
                    "kp = \"<N*m*s/rad>\", ki = \"<N*m/rad>\" }");
    const toml::table& t = *value.as_table();
    r.only_keys(t, {"body", "speed_of", "set_point", "kp", "ki", "torque_min", "torque_max"}, "a controller");
    ControllerSpec c;
    c.name = std::string(key.str());
    c.where = r.loc(value);
    const bool name_ok = !c.name.empty() && c.name.size() <= max_name_length &&
                         std::isalpha(static_cast<unsigned char>(c.name[0])) &&
                         std::all_of(c.name.begin(), c.name.end(),
                                     [](char ch) { return std::isalnum(static_cast<unsigned char>(ch)) || ch == '_'; });
    if (!name_ok)
      r.fail(value, fmt::format("controller name '{}' must be letters, digits and '_', from a letter, at most {} "
                                "characters (it names the controller's variables in the generated code)",
                                c.name, max_name_length));
    for (const char* prefix : {"Tc_", "theta_", "e_", "ref_"})
      if (find_parameter(model, prefix + c.name))
        r.fail(value, fmt::format("the model has a parameter named '{}{}', which the generated code uses for controller "
                                  "'{}'; rename the controller", prefix, c.name, c.name));
    const toml::node* body = t.get("body");
    if (!body) r.fail(value, "the controller names no body; add body = \"<body>\", the body whose torque it sets");
    c.body = body_named(r, *body, r.string(*body, "body"), "the controller's body");
    c.measured = c.body;
    if (const toml::node* m = t.get("speed_of")) c.measured = body_named(r, *m, r.string(*m, "speed_of"), "speed_of");
    const toml::node* set_point = t.get("set_point");
    if (!set_point) r.fail(value, "the controller has no set_point; add set_point = \"<speed>\", e.g. \"1500*rpm\"");
    c.set_point = read_signal(r, *set_point, scene_dir, SignalQuantity::speed);
    if (const toml::node* v = t.get("kp")) c.kp = r.quantity(*v, times_seconds(torque_dimension(), 1), "kp");
    if (const toml::node* v = t.get("ki")) c.ki = r.quantity(*v, torque_dimension(), "ki");
    if (c.kp < 0 || c.ki < 0 || (c.kp == 0 && c.ki == 0))
      r.fail(value, "a controller's gains kp and ki are non-negative and not both zero; give kp = \"<N*m*s/rad>\" "
                    "and ki = \"<N*m/rad>\"");
    for (const char* limit : {"torque_min", "torque_max"})
      if (const toml::node* v = t.get(limit))
        r.fail(*v, "torque limits of a controller are not simulated yet; drop torque_min and torque_max, or limit "
                   "the set-point instead");
    model.controllers.push_back(c.name);
    out.push_back(std::move(c));
  }
  return out;
}

}  // namespace pogear
