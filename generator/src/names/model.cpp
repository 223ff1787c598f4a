// Lookups in a gear's description by name and index.
#include "names/model.hpp"

#include <algorithm>
#include <stdexcept>

#include <fmt/format.h>

#include "common/printer.hpp"

namespace pogear {

int find_body(const Topology& t, const std::string& name) {
  for (int i = 0; i < static_cast<int>(t.bodies.size()); ++i)
    if (t.bodies[i].name == name) return i;
  return -1;
}

const Body& body(const Topology& t, int index) {
  const auto turning = static_cast<int>(t.bodies.size());
  return index < turning ? t.bodies.at(index) : t.grounded.at(index - turning);
}

bool is_grounded(const Topology& t, int index) { return index >= static_cast<int>(t.bodies.size()); }

std::vector<const Body*> every_body(const Topology& t) {
  std::vector<const Body*> all;
  for (const Body& b : t.bodies) all.push_back(&b);
  for (const Body& b : t.grounded) all.push_back(&b);
  return all;
}

namespace {

bool is_fixed_body(const Topology& t, std::string_view name) {
  return std::any_of(t.grounded.begin(), t.grounded.end(), [&](const Body& b) { return b.name == name; });
}

std::string turning_bodies(const Topology& t) {
  std::vector<std::string> names;
  for (const Body& b : t.bodies) names.push_back(b.name);
  return joined(names);
}

}  // namespace

std::string fixed_body_refusal(const Topology& t, const std::string& name, std::string_view what) {
  if (!is_fixed_body(t, name)) return "";
  return fmt::format("{} '{}' is fixed (the housing holds it), so it has no speed and takes no torque; name a body "
                     "that turns: {}", what, name, turning_bodies(t));
}

std::string fixed_variable_refusal(const Topology& t, std::string_view variable) {
  for (const std::string_view prefix : {"omega_", "tau_"})
    if (variable.starts_with(prefix) && is_fixed_body(t, variable.substr(prefix.size())))
      return fmt::format("'{}' is of body '{}', which is fixed (the housing holds it), so it has no speed and takes no "
                         "torque; name a body that turns: {}", variable, variable.substr(prefix.size()), turning_bodies(t));
  return "";
}

int mesh_count(const Topology& t, const Mesh& m) {
  return std::max(body(t, m.first.body).count, body(t, m.second.body).count);
}

void add_turning_body(Topology& t, Body b) {
  const int turning = static_cast<int>(t.bodies.size());
  for (Mesh& m : t.meshes)
    for (WheelRef* w : {&m.first, &m.second})
      if (w->body >= turning) ++w->body;
  for (FrictionElement& e : t.friction_elements) {
    if (e.first >= turning) ++e.first;
    if (e.second >= turning) ++e.second;
  }
  t.bodies.push_back(std::move(b));
}

std::size_t toothed_mesh_count(const Topology& t) {
  return static_cast<std::size_t>(std::count_if(t.meshes.begin(), t.meshes.end(), [](const Mesh& m) { return !m.shaft; }));
}

bool has_shafts(const Topology& t) { return toothed_mesh_count(t) < t.meshes.size(); }

int find_friction_element(const Topology& t, const std::string& name) {
  for (int i = 0; i < static_cast<int>(t.friction_elements.size()); ++i)
    if (t.friction_elements[i].name == name) return i;
  return -1;
}

const Wheel& wheel(const Topology& t, WheelRef w) { return body(t, w.body).wheels.at(w.wheel); }

std::string contact_radius(const Topology& t, const Mesh& m, WheelRef w) {
  if (m.shaft) throw std::logic_error("a shaft has no wheels, so no contact radius");
  return m.centre_distance.empty() ? wheel(t, w).radius_parameter : "rw_" + wheel(t, w).name + "_" + m.name;
}

std::string wheel_label(const Topology& t, WheelRef w) {
  const Body& b = body(t, w.body);
  const Wheel& wh = b.wheels.at(w.wheel);
  return wh.name == b.name ? b.name : fmt::format("{} of body {}", wh.name, b.name);
}

}  // namespace pogear
