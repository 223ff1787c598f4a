// The vehicle is reflected to the gear side of the final drive (ratio i, omega_out = i omega_wheels):
// inertia (m r^2 + J_w) / i^2, half-shaft stiffness and damping / i^2, road load torque / i; so the
// model keeps its shafts and loads, and the outputs scale back (speed r omega / i, torque i T).
#include "read/vehicle_table.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>

#include <fmt/format.h>

#include "pogear/parameters.hpp"

#include "common/printer.hpp"
#include "read/model_parameters.hpp"

namespace pogear {
namespace {

constexpr double standard_gravity = 9.80665;  // m/s^2

Dimension dimension(int m, int kg, int s) {
  Dimension d;
  d.exponent = {m, kg, s};
  return d;
}

void add_parameter(const SceneReader& r, const toml::node& where, Topology& t, const std::string& name, double value,
                   const Dimension& dim, const std::string& unit) {
  add_scene_parameter(r, where, "[vehicle]", t, name, value, dim, unit);
}

}  // namespace

void read_vehicle(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir, Scene& s) {
  if (!n.is_table()) r.fail(n, "[vehicle] must be a table");
  const toml::table& v = *n.as_table();
  r.only_keys(v, {"body", "mass", "wheel_radius", "final_drive", "wheel_inertia", "rolling_resistance", "grade",
                  "air_density", "drag_coefficient", "frontal_area", "half_shaft_stiffness", "half_shaft_damping"},
              "[vehicle]");
  Topology& t = s.model;
  auto required = [&](const char* key, const char* example) -> const toml::node& {
    const toml::node* k = v.get(key);
    if (!k) r.fail(n, fmt::format("[vehicle] needs {}, e.g. {} = {}", key, key, example));
    return *k;
  };
  auto positive = [&](const toml::node& k, double x, const char* what) {
    if (!(x > 0)) r.fail(k, fmt::format("{} must be positive (it is {})", what, x));
    return x;
  };
  auto non_negative = [&](const char* key, const Dimension& dim, const char* what) {
    const toml::node* k = v.get(key);
    if (!k) return 0.0;
    const double x = r.quantity(*k, dim, what);
    if (!(x >= 0)) r.fail(*k, fmt::format("{} must be zero or positive (it is {})", what, x));
    return x;
  };
  VehicleSpec spec;
  const toml::node& body = required("body", "\"out\"");
  const std::string name = r.identifier(body, "the vehicle's body");
  if (const std::string why = fixed_body_refusal(t, name, "drive the vehicle"); !why.empty()) r.fail(body, why);
  spec.body = find_body(t, name);
  if (spec.body < 0) r.fail(body, fmt::format("[vehicle] body '{}' is not a body of the model", name));
  if (t.bodies[static_cast<std::size_t>(spec.body)].axis != AxisKind::central)
    r.fail(body, fmt::format("[vehicle] body '{}' is not on the central axis; the half-shafts turn with a body on it", name));
  const toml::node& mass = required("mass", "\"1650*kg\"");
  spec.mass = positive(mass, r.quantity(mass, dimension(0, 1, 0), "mass"), "mass");
  const toml::node& radius = required("wheel_radius", "\"0.32*m\"");
  spec.wheel_radius = positive(radius, r.quantity(radius, length_dimension(), "wheel_radius"), "wheel_radius");
  spec.final_drive = 1;
  if (const toml::node* k = v.get("final_drive"))
    spec.final_drive = positive(*k, r.quantity(*k, Dimension{}, "final_drive"), "final_drive");
  spec.wheel_inertia = non_negative("wheel_inertia", inertia_dimension(), "wheel_inertia");
  spec.rolling_resistance = non_negative("rolling_resistance", Dimension{}, "rolling_resistance");
  if (const toml::node* k = v.get("grade")) {
    const rt::Signal grade = read_signal(r, *k, scene_dir, SignalQuantity::angle);
    spec.grade = rt::value(grade, 0.0);
    std::vector<double> angles{spec.grade};
    if (const auto* table = std::get_if<rt::Table>(&grade)) {
      spec.grade_table = *table;
      angles = table->v;
    }
    for (const double a : angles)
      if (!(std::abs(a) < std::numbers::pi / 2))
        r.fail(*k, fmt::format("grade is an angle of the road, e.g. \"3*deg\"; {} rad is not one", a));
  }
  const double density = v.get("air_density") ? non_negative("air_density", dimension(-3, 1, 0), "air_density") : 1.2;
  const double cd = non_negative("drag_coefficient", Dimension{}, "drag_coefficient");
  const double area = non_negative("frontal_area", dimension(2, 0, 0), "frontal_area");
  if (const toml::node *c = v.get("drag_coefficient"), *a = v.get("frontal_area"); (c == nullptr) != (a == nullptr))
    r.fail(c ? *c : *a, "aerodynamic drag needs both drag_coefficient and frontal_area; give both, or neither");
  spec.drag = density * cd * area / 2;
  const toml::node& k_hs = required("half_shaft_stiffness", "\"12000*N*m/rad\"");
  const double stiffness = positive(k_hs, r.quantity(k_hs, torque_dimension(), "half_shaft_stiffness"), "half_shaft_stiffness");
  const double damping = non_negative("half_shaft_damping", rotational_damping_dimension(), "half_shaft_damping");
  spec.where = r.loc(n);

  for (const Body* b : every_body(t))
    if (b->name == vehicle_body_name)
      r.fail(n, fmt::format("the model has a body named '{}', which [vehicle] adds; rename the model's", vehicle_body_name));
  for (const Mesh& m : t.meshes)
    if (m.name == half_shaft_name || m.name == vehicle_body_name)
      r.fail(n, fmt::format("the model has a mesh or shaft named '{}', which [vehicle] adds; rename the model's", m.name));
  for (const FrictionElement& e : t.friction_elements)
    if (e.name == half_shaft_name || e.name == vehicle_body_name)
      r.fail(n, fmt::format("the model has a brake or clutch named '{}', which [vehicle] adds; rename the model's", e.name));
  const double i2 = spec.final_drive * spec.final_drive;
  Body vehicle;
  vehicle.name = vehicle_body_name;
  vehicle.inertia_parameter = "J_vehicle";
  vehicle.friction_parameter = "b_vehicle";
  vehicle.where = spec.where;
  add_parameter(r, n, t, "J_vehicle", (spec.mass * spec.wheel_radius * spec.wheel_radius + spec.wheel_inertia) / i2,
                inertia_dimension(), "kg*m^2");
  add_parameter(r, n, t, "b_vehicle", 0, rotational_damping_dimension(), "");
  add_parameter(r, n, t, "K_half_shafts", stiffness / i2, torque_dimension(), "N*m");
  add_parameter(r, n, t, "b_half_shafts", damping / i2, rotational_damping_dimension(), "N*m*s");
  add_turning_body(t, std::move(vehicle));
  spec.vehicle_body = static_cast<int>(t.bodies.size()) - 1;
  Mesh shaft;
  shaft.shaft = true;
  shaft.name = half_shaft_name;
  shaft.first = {spec.body, -1};
  shaft.second = {spec.vehicle_body, -1};
  shaft.stiffness_parameter = "K_half_shafts";
  shaft.damping_parameter = "b_half_shafts";
  shaft.output_scale = spec.final_drive;  // the torque at the wheels
  shaft.where = spec.where;
  t.meshes.push_back(std::move(shaft));
  s.vehicle = spec;
}

void add_road_load(Scene& s) {
  const VehicleSpec& v = *s.vehicle;
  for (const LoadSpec& l : s.loads)
    if (l.body == v.vehicle_body)
      throw InputError(l.where, "[loads] names the vehicle, whose road load [vehicle] gives; leave it out of [loads]");
  // At the wheels: r (C_rr m g cos a + m g sin a) + r (rho c_d A / 2) v |v|, v = r omega_w; reflected
  // through the final drive, torque / i at omega = i omega_w.
  const double r_i = v.wheel_radius / v.final_drive;
  LoadSpec road;
  road.body = v.vehicle_body;
  road.constant = r_i * v.mass * standard_gravity * (v.rolling_resistance * std::cos(v.grade) + std::sin(v.grade));
  if (v.grade_table)  // the input is the torque on the body, -constant(t)
    road.varying = rt::GradeLoad{*v.grade_table, -r_i * v.mass * standard_gravity,
                                 -r_i * v.mass * standard_gravity * v.rolling_resistance};
  road.quadratic = v.drag * r_i * r_i * r_i;
  road.where = v.where;
  // The scales of the two parts at the gear: the car's weight as a torque (m g r / i), the drag's coefficient.
  for (const auto& [what, c] : {std::pair{"the weight's", r_i * v.mass * standard_gravity}, std::pair{"the drag's", road.quadratic}})
    if (c != 0 && !(c >= rt::kSmallestParameter && c <= rt::kLargestParameter))
      throw InputError(v.where, fmt::format("[vehicle] makes {} road load {:g} (SI) at the gear, outside the "
                                            "range pogear computes with, {:g} to {:g}; check the vehicle's values and "
                                            "their units", what, c, rt::kSmallestParameter, rt::kLargestParameter));
  if (road.constant != 0 || road.quadratic != 0 || road.varying) s.loads.push_back(road);
}

// vehicle_jerk is the elastic model's: there the half-shafts' twist makes the car's acceleration a
// function of the state, whose rate the outputs read off dx/dt. The rigid model's acceleration jumps
// with every event and input step.
void check_vehicle_jerk(const Scene& s) {
  const bool jerk = std::find(s.outputs.begin(), s.outputs.end(), Variable{VariableKind::vehicle_jerk, 0}) != s.outputs.end();
  if (!jerk) return;
  if (!s.effects.elastic())
    throw InputError(s.outputs_where, "vehicle_jerk is an output of the elastic model, where the half-shafts' twist "
                                      "smooths the car's acceleration; add shaft_compliance (and mesh_compliance) to "
                                      "effects, or drop vehicle_jerk");
  if (s.compare_rigid)
    throw InputError(s.outputs_where, "vehicle_jerk is an output of the elastic model only (the rigid model's "
                                      "acceleration jumps at every event and input step); drop compare_rigid, or "
                                      "vehicle_jerk");
}

}  // namespace pogear
