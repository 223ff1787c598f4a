// The engine is a body of its own on the central axis, driven by its map; the converter couples
// two bodies through the torques of its tables, and its lock-up clutch is an ordinary clutch.
#include "read/driveline_table.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <variant>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "pogear/parameters.hpp"
#include "pogear/run_limits.hpp"
#include "read/friction_curve.hpp"
#include "read/model_parameters.hpp"

namespace pogear {
namespace {

// A list of plain numbers (the key's documented unit), at least `fewest`, strictly increasing when asked.
std::vector<double> numbers(const SceneReader& r, const toml::node& n, const char* key, std::size_t fewest,
                            bool increasing) {
  if (!n.is_array() || n.as_array()->size() < fewest)
    r.fail(n, fmt::format("{} is a list of at least {} plain number{} in its unit (docs/scene-format.md, \"Engine and "
                          "converter\")", key, fewest, fewest == 1 ? "" : "s"));
  std::vector<double> out;
  for (const toml::node& e : *n.as_array()) {
    if (!e.is_integer() && !e.is_floating_point()) r.fail(e, fmt::format("{} holds plain numbers (in its unit)", key));
    const double v = *e.value<double>();
    if (!std::isfinite(v)) r.fail(e, fmt::format("{} holds a number that is not finite", key));
    if (increasing && !out.empty() && !(v > out.back()))
      r.fail(e, fmt::format("{} must increase strictly ({} follows {})", key, v, out.back()));
    out.push_back(v);
  }
  return out;
}

const toml::node& required(const SceneReader& r, const toml::node& table, const char* key, const char* example,
                           const char* what) {
  const toml::node* k = table.as_table()->get(key);
  if (!k) r.fail(table, fmt::format("{} needs {}, e.g. {} = {}", what, key, key, example));
  return *k;
}

// A body the converter joins: turning, on the central axis.
int central_body(const SceneReader& r, const toml::node& n, const Topology& t, const char* role) {
  const std::string name = r.identifier(n, role);
  if (const std::string why = fixed_body_refusal(t, name, role); !why.empty()) r.fail(n, why);
  const int b = find_body(t, name);
  if (b < 0) r.fail(n, fmt::format("[converter] {} '{}' is not a body of the model", role, name));
  if (t.bodies[static_cast<std::size_t>(b)].axis != AxisKind::central)
    r.fail(n, fmt::format("[converter] {} '{}' is not on the central axis; a converter joins two coaxial shafts", role, name));
  return b;
}

// The largest efficiency sigma TR(sigma) of a linear TR on [x0, x1] from y0 with slope m.
double largest_efficiency(double x0, double x1, double y0, double m) {
  auto eta = [&](double s) { return s * (y0 + m * (s - x0)); };
  double best = std::max(eta(x0), eta(x1));
  if (m != 0)
    if (const double s = (x0 - y0 / m) / 2; s > x0 && s < x1) best = std::max(best, eta(s));
  return best;
}

void check_converter(const SceneReader& r, const toml::table& v, const rt::ConverterData& c) {
  const std::vector<double>& sr = c.capacity.x;
  const toml::node& at_sr = *v.get("speed_ratio");
  if (sr.front() != 0) r.fail(at_sr, "speed_ratio starts at 0, the stall point");
  if (!(sr.back() < 1))
    r.fail(at_sr, "speed_ratio ends below 1: a coupling passes no torque at equal speeds, and pogear takes 1/K^2 "
                  "linearly to 0 and TR to 1 from the last point to 1 (docs/scene-format.md)");
  for (std::size_t i = 0; i < sr.size(); ++i) {
    if (!(c.capacity.y[i] > 0))
      r.fail(*v.get("capacity_factor"), fmt::format("capacity_factor must be positive ({} at speed ratio {})",
                                                    c.capacity.y[i] / rad_per_s_per_rpm, sr[i]));
    // 1/K^2 is the torque per speed squared: it stays a normal double for K from 1e-15 to 1e15.
    if (!(c.capacity.y[i] >= 1e-15 && c.capacity.y[i] <= 1e15))
      r.fail(*v.get("capacity_factor"), fmt::format("capacity_factor {} rpm/sqrt(N m) at speed ratio {} is outside the "
                                                    "range pogear computes with; converters' are 50 to 1000",
                                                    c.capacity.y[i] / rad_per_s_per_rpm, sr[i]));
    if (!(c.torque_ratio.y[i] > 0))
      r.fail(*v.get("torque_ratio"), fmt::format("torque_ratio must be positive ({} at speed ratio {})",
                                                 c.torque_ratio.y[i], sr[i]));
  }
  // Efficiency sigma TR <= 1 on every segment and on the tail to (1, 1): a converter creates no power.
  std::vector<double> x = sr, y = c.torque_ratio.y;
  x.push_back(1);
  y.push_back(1);
  for (std::size_t i = 0; i + 1 < x.size(); ++i) {
    const double eta = largest_efficiency(x[i], x[i + 1], y[i], (y[i + 1] - y[i]) / (x[i + 1] - x[i]));
    if (eta > 1 + 1e-12)
      r.fail(*v.get("torque_ratio"),
             fmt::format("the converter's efficiency SR * TR reaches {:.6g} between speed ratios {} and {}, above 1: it "
                         "would create power; lower the torque ratio there (TR at most 1/SR)", eta, x[i], x[i + 1]));
  }
}

}  // namespace

void read_engine(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir, Scene& s) {
  if (!n.is_table()) r.fail(n, "[engine] must be a table");
  const toml::table& v = *n.as_table();
  r.only_keys(v, {"inertia", "throttle", "map_speeds", "map_throttles", "map_torques"}, "[engine]");
  Topology& t = s.model;
  EngineSpec e;
  e.where = r.loc(n);
  const toml::node& inertia = required(r, n, "inertia", "\"0.25*kg*m^2\"", "[engine]");
  const double J = r.quantity(inertia, inertia_dimension(), "inertia");
  if (!(J > 0)) r.fail(inertia, fmt::format("the engine's inertia must be positive (it is {})", J));
  e.throttle = read_signal(r, required(r, n, "throttle", "{ step = 0.6, at = \"0.2*s\" }", "[engine]"), scene_dir,
                           SignalQuantity::throttle);
  e.throttle_where = r.loc(*v.get("throttle"));
  const toml::node& speeds = required(r, n, "map_speeds", "[800, 2000, 4000, 6000]", "[engine]");
  e.map.speeds = numbers(r, speeds, "map_speeds", 1, true);
  for (double& w : e.map.speeds) w *= rad_per_s_per_rpm;
  const toml::node& throttles = required(r, n, "map_throttles", "[0, 1]", "[engine]");
  e.map.throttles = numbers(r, throttles, "map_throttles", 1, true);
  if (e.map.throttles.front() < 0 || e.map.throttles.back() > 1)
    r.fail(throttles, "map_throttles are from 0 to 1");
  const toml::node& torques = required(r, n, "map_torques", "[[-30, -40], [250, 230]]", "[engine]");
  if (!torques.is_array() || torques.as_array()->size() != e.map.throttles.size())
    r.fail(torques, fmt::format("map_torques has one row per throttle of map_throttles ({}), each one torque [N m] per "
                                "speed of map_speeds ({})", e.map.throttles.size(), e.map.speeds.size()));
  for (const toml::node& row : *torques.as_array()) {
    e.map.torque.push_back(numbers(r, row, "a row of map_torques", 1, false));
    if (e.map.torque.back().size() != e.map.speeds.size())
      r.fail(row, fmt::format("this row of map_torques has {} torques; map_speeds has {} speeds",
                              e.map.torque.back().size(), e.map.speeds.size()));
    for (const double T : e.map.torque.back())
      if (!(std::abs(T) <= rt::kLargestParameter)) r.fail(row, fmt::format("map torque {} N m is out of range", T));
  }

  for (const Body* b : every_body(t))
    if (b->name == engine_body_name)
      r.fail(n, fmt::format("the model has a body named '{}', which [engine] adds; rename the model's", engine_body_name));
  Body engine;
  engine.name = engine_body_name;
  engine.inertia_parameter = "J_engine";
  engine.friction_parameter = "b_engine";
  engine.where = e.where;
  add_scene_parameter(r, n, "[engine]", t, "J_engine", J, inertia_dimension(), "kg*m^2");
  add_scene_parameter(r, n, "[engine]", t, "b_engine", 0, rotational_damping_dimension(), "");
  add_turning_body(t, std::move(engine));
  e.body = static_cast<int>(t.bodies.size()) - 1;
  // It turns on its own: one more degree of freedom, which the rigid model keeps.
  if (!t.default_keep.empty()) t.default_keep.push_back(engine_body_name);
  s.engine = std::move(e);
}

void read_converter(const SceneReader& r, const toml::node& n, Scene& s) {
  if (!n.is_table()) r.fail(n, "[converter] must be a table");
  const toml::table& v = *n.as_table();
  r.only_keys(v, {"pump", "turbine", "speed_ratio", "capacity_factor", "torque_ratio", "lockup"}, "[converter]");
  Topology& t = s.model;
  ConverterSpec c;
  c.where = r.loc(n);
  if (const toml::node* p = v.get("pump")) c.pump = central_body(r, *p, t, "pump");
  else if (s.engine) c.pump = s.engine->body;
  else r.fail(n, "[converter] needs its pump body, e.g. pump = \"engine\" with an [engine], or a body of the model");
  c.turbine = central_body(r, required(r, n, "turbine", "\"in\"", "[converter]"), t, "turbine");
  if (c.turbine == c.pump) r.fail(*v.get("turbine"), "the converter's turbine is its pump; name two bodies");
  const toml::node& sr = required(r, n, "speed_ratio", "[0, 0.4, 0.8, 0.9]", "[converter]");
  const std::vector<double> ratios = numbers(r, sr, "speed_ratio", 1, true);
  const toml::node& k = required(r, n, "capacity_factor", "[150, 155, 190, 260]", "[converter]");
  std::vector<double> capacity = numbers(r, k, "capacity_factor", 1, false);
  const toml::node& tr = required(r, n, "torque_ratio", "[2.1, 1.6, 1.1, 1.0]", "[converter]");
  const std::vector<double> torque_ratio = numbers(r, tr, "torque_ratio", 1, false);
  if (capacity.size() != ratios.size())
    r.fail(k, fmt::format("capacity_factor has {} values; it has one per speed_ratio ({})", capacity.size(), ratios.size()));
  if (torque_ratio.size() != ratios.size())
    r.fail(tr, fmt::format("torque_ratio has {} values; it has one per speed_ratio ({})", torque_ratio.size(), ratios.size()));
  for (double& K : capacity) K *= rad_per_s_per_rpm;  // rpm / sqrt(N m) -> (rad/s) / sqrt(N m)
  c.curves.capacity = {ratios, capacity};
  c.curves.torque_ratio = {ratios, torque_ratio};
  check_converter(r, v, c.curves);

  if (const toml::node* l = v.get("lockup")) {
    if (!l->is_table()) r.fail(*l, "lockup is a table { capacity = \"600*N*m\", static_ratio = 1.2 }");
    r.only_keys(*l->as_table(), {"capacity", "static_ratio", "friction_curve"}, "the lock-up clutch");
    if (find_friction_element(t, lockup_clutch_name) >= 0 || find_body(t, lockup_clutch_name) >= 0)
      r.fail(*l, fmt::format("the model has an element or body named '{}', which the lock-up clutch is; rename the "
                             "model's", lockup_clutch_name));
    FrictionElement e;
    e.name = lockup_clutch_name;
    e.first = c.pump;
    e.second = c.turbine;
    e.where = e.bodies_where = e.static_ratio_where = r.loc(*l);
    e.capacity_parameter = capacity_parameter_name(lockup_clutch_name);
    const toml::node& cap = required(r, *l, "capacity", "\"600*N*m\"", "the lock-up clutch");
    const double capacity_nm = r.quantity(cap, torque_dimension(), "capacity");
    if (!(capacity_nm > 0)) r.fail(cap, fmt::format("the lock-up's capacity must be positive (it is {})", capacity_nm));
    add_scene_parameter(r, cap, "[converter]", t, e.capacity_parameter, capacity_nm, torque_dimension(), "N*m");
    if (const toml::node* m = l->as_table()->get("static_ratio")) {
      if (!m->is_integer() && !m->is_floating_point()) r.fail(*m, "static_ratio is a plain number, e.g. 1.2");
      const double ratio = *m->value<double>();
      if (!(ratio >= 1 && ratio <= 10)) r.fail(*m, "static_ratio is static over kinetic friction, from 1 to 10");
      e.static_ratio = fmt::format("{}", ratio);
      e.static_ratio_where = r.loc(*m);
    }
    // Checked against the static ratio with every element's (static_friction_ratio).
    if (const toml::node* f = l->as_table()->get("friction_curve")) read_friction_curve(r, *f, e);
    t.friction_elements.push_back(std::move(e));
  }
  s.converter = std::move(c);
}

void check_driveline(const Scene& s) {
  if (!s.engine && !s.converter) return;
  // Their torques follow the speeds through tables: the equilibrium is a nonlinear problem, where the
  // gear's alone is linear and solved exactly.
  if (s.start == Start::steady)
    throw InputError(s.start_where,
                     "start = \"steady\" is not available with an [engine] or a [converter]: their tables make the "
                     "equilibrium nonlinear; start from given speeds (start = \"rigid\" or a gear, with omega_engine)");
  if (!s.engine) return;
  // The throttle is piecewise linear: its extremes over the run are at 0, the horizon and its breakpoints.
  std::vector<double> times = rt::breakpoints(s.engine->throttle, 0.0, s.horizon);
  times.push_back(0.0);
  times.push_back(s.horizon);
  for (const double at : times)
    for (const double p : {rt::value(s.engine->throttle, at), rt::value(s.engine->throttle, std::nextafter(at, 0.0))})
      if (!(p >= 0 && p <= 1))
        throw InputError(s.engine->throttle_where,
                         fmt::format("the throttle is {} at t = {} s; it is from 0 (closed) to 1 (wide open) over the "
                                     "whole run", p, at));
}

}  // namespace pogear
