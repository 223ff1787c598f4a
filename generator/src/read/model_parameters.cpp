// The model's parameter table: every parameter's text, SI value and unit and where it was
// defined, evaluated once (parameters may refer to each other) and checked against its roles.
#include "read/model_parameters.hpp"

#include <functional>
#include <map>
#include <set>

#include <fmt/format.h>

#include "pogear/parameters.hpp"

namespace pogear {

// In dependency order, so that `b_p = "b_c"` works wherever b_c stands in the file.
void evaluate_parameters(std::vector<Parameter>& parameters) {
  std::map<std::string, const Parameter*> by_name;
  for (const auto& p : parameters) by_name[p.name] = &p;
  std::map<std::string, Quantity> done;
  std::set<std::string> visiting;
  std::function<void(const Parameter&)> visit = [&](const Parameter& p) {
    if (done.count(p.name)) return;
    if (!visiting.insert(p.name).second)
      throw InputError(p.where, fmt::format("parameter '{}' is defined through itself", p.name));
    for (const auto& ref : referenced_names(p.text))
      if (auto it = by_name.find(ref); it != by_name.end()) visit(*it->second);
    done[p.name] = evaluate_quantity(p.text, done, p.where, p.column_offset);
    visiting.erase(p.name);
  };
  for (const auto& p : parameters) visit(p);
  for (auto& p : parameters) p.value = done[p.name];
}

std::map<std::string, Quantity> parameter_quantities(const Topology& t) {
  std::map<std::string, Quantity> known;
  for (const auto& p : t.parameters) known[p.name] = p.value;
  return known;
}

const Parameter* find_parameter(const Topology& t, const std::string& name) {
  for (const auto& p : t.parameters)
    if (p.name == name) return &p;
  return nullptr;
}

double parameter_value(const Topology& t, const std::string& name) {
  const Parameter* p = find_parameter(t, name);
  if (!p) throw InputError(SourceLocation{t.file, 0, 0}, fmt::format("missing parameter '{}'", name));
  return p->value.si;
}

void check_parameter_roles(const Topology& t) {
  struct Role {
    std::string name;
    Dimension dimension;
    bool positive;  // strictly; otherwise non-negative
    const char* what;
    SourceLocation used_at;
  };
  std::vector<Role> roles;
  for (const auto& b : t.bodies) {
    if (b.fixed) continue;  // no inertia, no friction, no planet axis
    roles.push_back({b.inertia_parameter, inertia_dimension(), true, "an inertia", b.where});
    roles.push_back({b.friction_parameter, rotational_damping_dimension(), false, "a bearing friction coefficient", b.where});
    if (b.axis == AxisKind::carried) roles.push_back({b.distance_parameter, length_dimension(), true, "an axis distance", b.where});
  }
  for (const auto& m : t.meshes) {
    if (m.shaft) {
      // N m/rad and N m s/rad: the radian is a plain number.
      roles.push_back({m.stiffness_parameter, torque_dimension(), true, "a shaft's torsional stiffness", m.where});
      roles.push_back({m.damping_parameter, rotational_damping_dimension(), false, "a shaft's damping coefficient", m.where});
      continue;
    }
    roles.push_back({m.stiffness_parameter, stiffness_dimension(), true, "a mesh stiffness", m.where});
    roles.push_back({m.damping_parameter, linear_damping_dimension(), false, "a mesh damping coefficient", m.where});
    for (const std::string& radius : {contact_radius(t, m, m.first), contact_radius(t, m, m.second)})
      roles.push_back({radius, length_dimension(), true, "a radius", m.where});
  }
  for (const auto& e : t.friction_elements)
    roles.push_back({e.capacity_parameter, torque_dimension(), true,
                     e.is_brake() ? "a brake's torque capacity" : "a clutch's torque capacity", e.where});
  for (const auto& role : roles) {
    const Parameter* p = find_parameter(t, role.name);
    if (!p) {
      if (role.dimension == length_dimension()) continue;  // may follow from the geometry
      throw InputError(role.used_at, fmt::format("missing parameter '{}' ({}); add it under [parameters], e.g. "
                                                 "{} = \"...\"",
                                                 role.name, role.what, role.name));
    }
    if (p->value.has_unit && !(p->value.dimension == role.dimension))
      throw InputError(p->where, p->value.dimension == Dimension{}
                                     ? fmt::format("parameter '{}' is {} but has no unit (rad, deg, rev and pi are "
                                                   "plain numbers); it needs {}",
                                                   role.name, role.what, describe(role.dimension))
                                     : fmt::format("parameter '{}' is {} but has unit {}; it needs {}", role.name,
                                                   role.what, describe(p->value.dimension), describe(role.dimension)));
    const double v = p->value.si;
    if (role.positive ? !(v > 0.0) : !(v >= 0.0))
      throw InputError(p->where, fmt::format("parameter '{}' is {} and must be {} (it is {})", role.name, role.what,
                                             role.positive ? "positive" : "zero or positive", v));
    // The range `--param` holds tunables to as well (runtime/pogear/parameters.hpp): beyond it,
    // ranks and the elastic model's matrices overflow or underflow to garbage.
    constexpr double smallest = pogear::rt::kSmallestParameter, largest = pogear::rt::kLargestParameter;
    if (v != 0.0 && !(v >= smallest && v <= largest))
      throw InputError(p->where, fmt::format("parameter '{}' is {} of {} (SI), outside the range pogear computes "
                                             "with, {:g} to {:g}; check the value and its unit",
                                             role.name, role.what, v, smallest, largest));
  }
  for (const auto& e : t.friction_elements) static_friction_ratio(t, e);
}

double static_friction_ratio(const Topology& t, const FrictionElement& e) {
  std::map<std::string, Quantity> known;
  for (const auto& p : t.parameters) known[p.name] = p.value;
  const Quantity q = evaluate_quantity(e.static_ratio, known, e.static_ratio_where, e.static_ratio_column_offset);
  if (q.has_unit && !(q.dimension == Dimension{}))
    throw InputError(e.static_ratio_where, fmt::format("static_ratio of '{}' has unit {}; it is a plain number, static "
                                                       "over kinetic friction", e.name, describe(q.dimension)));
  // Static friction is at least the kinetic one; a ratio above 10 is no material pair's.
  if (!(q.si >= 1.0 && q.si <= 10.0))
    throw InputError(e.static_ratio_where, fmt::format("static_ratio of '{}' is {}; static over kinetic friction is from "
                                                       "1 to 10 (1 when they are equal)", e.name, q.si));
  // An element that locks holds at least the torque it carried slipping into the lock: else it breaks
  // away at once and chatters.
  if (!e.curve_ratio.empty() && e.curve_ratio.front() > q.si)
    throw InputError(e.friction_curve_where, fmt::format("friction_curve of '{}' is {} at zero slip, above its static_ratio "
                                                         "{}; static friction is at least the kinetic one as it locks: "
                                                         "raise static_ratio or lower the curve's first ratio",
                                                         e.name, e.curve_ratio.front(), q.si));
  return q.si;
}

}  // namespace pogear
