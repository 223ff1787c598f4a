// Lookups in a gear's description by name and index.
#include "names/model.hpp"

#include <algorithm>

#include <fmt/format.h>

namespace pogear {

int find_body(const Topology& t, const std::string& name) {
  for (int i = 0; i < static_cast<int>(t.bodies.size()); ++i)
    if (t.bodies[i].name == name) return i;
  return -1;
}

int mesh_count(const Topology& t, const Mesh& m) {
  return std::max(t.bodies[m.first.body].count, t.bodies[m.second.body].count);
}

int find_friction_element(const Topology& t, const std::string& name) {
  for (int i = 0; i < static_cast<int>(t.friction_elements.size()); ++i)
    if (t.friction_elements[i].name == name) return i;
  return -1;
}

const Wheel& wheel(const Topology& t, WheelRef w) { return t.bodies.at(w.body).wheels.at(w.wheel); }

std::string wheel_label(const Topology& t, WheelRef w) {
  const Body& b = t.bodies.at(w.body);
  const Wheel& wh = b.wheels.at(w.wheel);
  return wh.name == b.name ? b.name : fmt::format("{} of body {}", wh.name, b.name);
}

}  // namespace pogear
