// Shafts join bodies of one axis, the central one: a shaft on a planet would turn with its carrier,
// and between two fixed parallel axes it would need the layout's heights, which only meshes place.
#include "read/shaft_table.hpp"

#include <fmt/format.h>

#include "common/printer.hpp"
#include "read/topology.hpp"

namespace pogear {
namespace {

std::string body_names(const Topology& t) {
  std::vector<std::string> names;
  for (const Body& b : t.bodies) names.push_back(b.name);
  return joined(names, ", ");
}

int shaft_end(const TomlReader& r, const toml::node& n, const Topology& t, const std::string& shaft) {
  const std::string name = r.identifier(n, "a body");
  const int i = find_body(t, name);
  if (i < 0)
    r.fail(n, fmt::format("shaft '{}' names '{}', which is not a body; the bodies are {}", shaft, name, body_names(t)));
  const Body& b = t.bodies[static_cast<std::size_t>(i)];
  if (b.axis != AxisKind::central)
    r.fail(n, fmt::format("shaft '{}' ends at '{}', which turns about {}; a shaft joins two bodies on the central "
                          "axis (give a driveline body of its own, axis = \"central\")",
                          shaft, name, b.axis == AxisKind::carried ? "a planet axis" : "a fixed parallel axis"));
  return i;
}

}  // namespace

void read_shafts(const TomlReader& r, const toml::node& list, Topology& t) {
  if (!list.is_array_of_tables()) r.fail(list, "'shaft' must be written as [[shaft]] tables");
  if (t.meshes.size() + list.as_array()->size() > max_meshes)
    r.fail(list, fmt::format("{} meshes and shafts; pogear derives gears of at most {} (the symbolic derivation grows "
                             "steeply with the size); model a smaller part of the driveline",
                             t.meshes.size() + list.as_array()->size(), max_meshes));
  for (const toml::node& n : *list.as_array()) {
    const toml::table& st = *n.as_table();
    r.only_keys(st, {"name", "bodies", "stiffness", "damping"}, "a [[shaft]]");
    const toml::node* name = st.get("name");
    if (!name) r.fail(st, "a [[shaft]] needs a name, e.g. name = \"output_shaft\"");
    Mesh m;
    m.shaft = true;
    m.name = r.identifier(*name, "a shaft name");
    m.where = r.loc(*name);
    const toml::node* b = st.get("bodies");
    if (!b || !b->is_array() || b->as_array()->size() != 2)
      r.fail(b ? *b : static_cast<const toml::node&>(st),
             fmt::format("shaft '{}' needs the two bodies it joins, e.g. bodies = [\"out\", \"wheels\"]", m.name));
    const toml::array& pair = *b->as_array();
    m.first = {shaft_end(r, pair[0], t, m.name), -1};
    m.second = {shaft_end(r, pair[1], t, m.name), -1};
    if (m.first.body == m.second.body)
      r.fail(pair[1], fmt::format("shaft '{}' joins body '{}' to itself; name two bodies", m.name,
                                  t.bodies[static_cast<std::size_t>(m.first.body)].name));
    if (t.bodies[static_cast<std::size_t>(m.first.body)].fixed && t.bodies[static_cast<std::size_t>(m.second.body)].fixed)
      r.fail(pair[1], fmt::format("shaft '{}' joins two fixed bodies, so it never twists; leave it out", m.name));
    m.stiffness_parameter = "K_" + m.name;
    m.damping_parameter = "b_" + m.name;
    if (const toml::node* k = st.get("stiffness")) m.stiffness_parameter = r.identifier(*k, "stiffness");
    if (const toml::node* c = st.get("damping")) m.damping_parameter = r.identifier(*c, "damping");
    t.meshes.push_back(std::move(m));
  }
}

void check_shaft_names(const Topology& t) {
  for (const Mesh& m : t.meshes) {
    if (!m.shaft) continue;
    auto refuse = [&](std::string_view what, const SourceLocation& at, std::string_view why) {
      throw InputError(m.where, fmt::format("shaft '{}' has the name of the {} at line {}: {}; give the shaft another name",
                                            m.name, what, at.line, why));
    };
    for (const Body* b : every_body(t))
      if (b->name == m.name) refuse("body", b->where, fmt::format("the body's bearing friction and the shaft's damping would both be b_{}", m.name));
    for (const Mesh& other : t.meshes) {  // the later of two is refused, naming the earlier
      if (&other == &m) break;
      if (other.name == m.name) refuse(other.shaft ? "shaft" : "mesh", other.where, "names tell them apart");
    }
    for (const FrictionElement& e : t.friction_elements)
      if (e.name == m.name)
        refuse(e.is_brake() ? "brake" : "clutch", e.where, fmt::format("both torques would be T_{}", m.name));
  }
}

}  // namespace pogear
