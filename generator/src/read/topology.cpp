// Reads model files (TOML) into a Topology, checking names, references, units and signs, and
// locating every complaint at the value it concerns.
#include "read/topology.hpp"

#include <algorithm>
#include <cerrno>
#include <cmath>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <toml++/toml.h>

#include "pogear/input_file.hpp"
#include "read/model_parameters.hpp"
#include "read/body_table.hpp"
#include "read/friction_curve.hpp"
#include "read/gear_table.hpp"
#include "read/shaft_table.hpp"
#include "read/toml_reader.hpp"
#include "read/tooth_counts.hpp"
#include "names/model_variables.hpp"

namespace pogear {
namespace {

const toml::array& array_of_tables(const TomlReader& r, const toml::table& root, std::string_view key,
                                   std::string_view example) {
  const toml::node* n = root.get(key);
  if (!n) throw InputError(SourceLocation{r.file, 0, 0},
                           fmt::format("no [[{}]] entries; add at least one, e.g. {}", key, example));
  if (!n->is_array_of_tables())
    r.fail(*n, fmt::format("'{}' must be written as [[{}]] tables", key, key));
  return *n->as_array();
}

WheelRef resolve_wheel(const TomlReader& r, const Topology& t, const toml::node& n) {
  const std::string name = r.identifier(n, "a mesh terminal");
  std::vector<WheelRef> found;
  for (int bi = 0; bi < static_cast<int>(t.bodies.size()); ++bi)
    for (int wi = 0; wi < static_cast<int>(t.bodies[bi].wheels.size()); ++wi)
      if (t.bodies[bi].wheels[wi].name == name) found.push_back({bi, wi});
  if (found.size() == 1) return found[0];
  if (found.empty()) {
    const int bi = find_body(t, name);
    if (bi >= 0 && t.bodies[bi].wheels.size() == 1) return {bi, 0};
    if (bi >= 0) {
      std::string list;
      for (const auto& w : t.bodies[bi].wheels) list += (list.empty() ? "" : ", ") + w.name;
      r.fail(n, fmt::format("body '{}' has several wheels ({}); name the one that meshes", name, list));
    }
    std::string list;
    for (const auto& b : t.bodies)
      for (const auto& w : b.wheels) list += (list.empty() ? "" : ", ") + w.name;
    r.fail(n, fmt::format("no wheel or body named '{}'; the wheels are {}", name, list));
  }
  r.fail(n, fmt::format("wheel name '{}' is ambiguous: a body of that name has it as its only wheel, and another "
                        "body has a wheel of that name too; rename one of them", name));
}

void check_unique_names(const Topology& t, bool meshes) {
  std::map<std::string, SourceLocation> seen;
  auto claim = [&](const std::string& name, const SourceLocation& where, std::string_view what) {
    auto [it, fresh] = seen.emplace(name, where);
    if (!fresh)
      throw InputError(where, fmt::format("duplicate name '{}' ({}); it is already used at line {}", name, what,
                                          it->second.line));
  };
  for (const auto& b : t.bodies) claim(b.name, b.where, "body");
  seen.clear();
  for (const auto& b : t.bodies)
    for (const auto& w : b.wheels)
      if (!(b.wheels.size() == 1 && w.name == b.name)) claim(w.name, w.where, "wheel");
  seen.clear();
  if (!meshes) return;
  for (const auto& m : t.meshes) {
    if (m.shaft) continue;  // check_shaft_names
    claim(m.name, m.where, "mesh");
    // A body's bearing friction and a mesh's damping are both b_<name>: one name, two parameters.
    if (const int b = find_body(t, m.name); b >= 0)
      throw InputError(m.where, fmt::format("mesh '{}' has the name of the body at line {}: the body's bearing friction "
                                            "and the mesh's damping would both be b_{}; give the mesh another name",
                                            m.name, t.bodies[static_cast<std::size_t>(b)].where.line, m.name));
  }
}

void check_carriers(Topology& t) {
  for (const auto& b : t.bodies) {
    if (b.axis != AxisKind::carried) continue;
    if (find_body(t, b.carrier) < 0)
      throw InputError(b.where, fmt::format("body '{}' is carried by '{}', which is not a body of this model",
                                            b.name, b.carrier));
    // Follow the chain of carriers; a loop would give a planet no axis at all.
    std::set<std::string> seen{b.name};
    const Body* c = &b;
    while (c->axis == AxisKind::carried) {
      if (!seen.insert(c->carrier).second)
        throw InputError(b.where, fmt::format("body '{}' is carried, through its carriers, by itself", b.name));
      c = &t.bodies[find_body(t, c->carrier)];
    }
  }
}

// A mesh between two lumped planets (a pinion pair of a double-pinion set) stands for as many pairs
// as each of them counts planets.
void check_lumped_meshes(const Topology& t) {
  for (const auto& m : t.meshes) {
    const Body& a = t.bodies[m.first.body];
    const Body& b = t.bodies[m.second.body];
    if (a.count != b.count && a.axis == AxisKind::carried && b.axis == AxisKind::carried)
      throw InputError(m.where, fmt::format("mesh '{}' joins planet '{}' (count {}) and planet '{}' (count {}); "
                                            "planets that mesh with each other are lumped in equal numbers",
                                            m.name, a.name, a.count, b.name, b.count));
  }
}

// Whether two bodies turn about one axis, as a clutch needs. Central bodies do; planets do when one
// carrier holds them at one distance on one side. Fixed axes are placed by the wheels they mesh
// with, which a clutch's pair of bodies need not share, so two fixed-axis bodies are taken at
// the file's word.
bool coaxial(const Body& a, const Body& b) {
  if (a.axis != b.axis) return false;
  if (a.axis != AxisKind::carried) return true;
  return a.carrier == b.carrier && a.distance_parameter == b.distance_parameter && a.side == b.side;
}

// Why two fixed-axis bodies certainly turn about different axes, or "": wheels that mesh with each
// other never share an axis, and a body drawn above the central wheels it meshes with is not on the
// axis of one drawn below them. (Otherwise their axes are placed by radii the file may not give yet,
// and the file's word is taken.)
std::string different_fixed_axes(const Topology& t, int a, int b) {
  auto mates_central = [&](int body, int& side) {
    bool any = false;
    for (const Mesh& m : t.meshes)
      for (const auto& [own, mate] : {std::pair{m.first, m.second}, std::pair{m.second, m.first}})
        if (own.body == body) {
          if (t.bodies[mate.body].axis != AxisKind::central) return false;
          any = true;
        }
    side = t.bodies[body].side;
    return any;
  };
  for (const Mesh& m : t.meshes)
    if ((m.first.body == a && m.second.body == b) || (m.first.body == b && m.second.body == a))
      return fmt::format("they mesh with each other (mesh {})", m.name);
  int side_a = 0, side_b = 0;
  if (mates_central(a, side_a) && mates_central(b, side_b) && side_a != side_b)
    return "one is drawn above the central axis, the other below it";
  return "";
}

const char* axis_description(const Body& b) {
  switch (b.axis) {
    case AxisKind::central: return "the central axis";
    case AxisKind::fixed: return "a fixed axis";
    case AxisKind::carried: return "a planet axis";
  }
  return "";
}

// [[brake]] and [[clutch]] tables, each checked as it is read; duplicates once all are read.
void read_friction_elements(const TomlReader& r, const toml::table& root, Topology& t) {
  for (const bool brake : {true, false}) {
    const char* key = brake ? "brake" : "clutch";
    const toml::node* list = root.get(key);
    if (!list) continue;
    if (!list->is_array_of_tables()) r.fail(*list, fmt::format("'{}' must be written as [[{}]] tables", key, key));
    for (const toml::node& n : *list->as_array()) {
      const toml::table& et = *n.as_table();
      if (brake) r.only_keys(et, {"name", "body", "capacity", "static_ratio", "one_way", "friction_curve"}, "a [[brake]]");
      else r.only_keys(et, {"name", "bodies", "capacity", "static_ratio", "one_way", "friction_curve"}, "a [[clutch]]");
      FrictionElement e;
      const toml::node* name = et.get("name");
      if (!name) r.fail(et, fmt::format("a [[{}]] needs a name, e.g. name = \"{}\"", key, brake ? "B1" : "C1"));
      e.name = r.identifier(*name, fmt::format("a {} name", key));
      e.where = r.loc(*name);
      auto body_of = [&](const toml::node& b) {
        const std::string body = r.identifier(b, "a body");
        const int i = find_body(t, body);
        if (i < 0) {
          std::string list;
          for (const auto& x : t.bodies) list += (list.empty() ? "" : ", ") + x.name;
          r.fail(b, fmt::format("{} '{}' names '{}', which is not a body; the bodies are {}", key, e.name, body, list));
        }
        return i;
      };
      if (brake) {
        const toml::node* b = et.get("body");
        if (!b) r.fail(et, fmt::format("brake '{}' needs the body it holds, e.g. body = \"r\"", e.name));
        e.first = body_of(*b);
        if (t.bodies[e.first].fixed)
          r.fail(*b, fmt::format("brake '{}' holds '{}', which is fixed already (fixed = true); remove the brake, or "
                                 "fixed = true if the brake releases it", e.name, t.bodies[e.first].name));
        if (t.bodies[e.first].axis == AxisKind::carried)
          r.fail(*b, fmt::format("brake '{}' holds '{}', a planet, whose axis moves with its carrier; a brake holds a "
                                 "body on the central axis or on a fixed axis", e.name, t.bodies[e.first].name));
      } else {
        const toml::node* b = et.get("bodies");
        if (!b || !b->is_array() || b->as_array()->size() != 2)
          r.fail(b ? *b : static_cast<const toml::node&>(et),
                 fmt::format("clutch '{}' needs the two bodies it joins, e.g. bodies = [\"s\", \"c\"]", e.name));
        const toml::array& pair = *b->as_array();
        e.first = body_of(pair[0]);
        e.second = body_of(pair[1]);
        e.bodies_where = r.loc(pair[1]);
        const Body& f = t.bodies[e.first];
        const Body& g = t.bodies[e.second];
        if (e.first == e.second) r.fail(pair[1], fmt::format("clutch '{}' joins body '{}' to itself; name two bodies", e.name, f.name));
        for (const std::size_t k : {0u, 1u})
          if (const Body& x = t.bodies[k == 0 ? e.first : e.second]; x.fixed)
            r.fail(pair[k], fmt::format("clutch '{}' joins '{}', which is fixed (fixed = true); a clutch to the housing is "
                                      "a [[brake]], and a fixed body needs none", e.name, x.name));
        if (!coaxial(f, g))
          r.fail(pair[1], fmt::format("clutch '{}' joins '{}' on {} and '{}' on {}; a clutch joins two bodies that turn "
                                      "about one axis", e.name, f.name, axis_description(f), g.name, axis_description(g)));
        if (f.axis == AxisKind::fixed)
          if (const std::string why = different_fixed_axes(t, e.first, e.second); !why.empty())
            r.fail(pair[1], fmt::format("clutch '{}' joins '{}' and '{}', which turn about two different fixed axes: {}; "
                                        "a clutch joins two bodies that turn about one axis",
                                        e.name, f.name, g.name, why));
      }
      if (const toml::node* o = et.get("one_way")) {
        if (!o->is_boolean()) r.fail(*o, "one_way must be true or false");
        e.one_way = **o->as_boolean();
      }
      e.capacity_parameter = capacity_parameter_name(e.name);
      if (const toml::node* c = et.get("capacity")) e.capacity_parameter = r.identifier(*c, "capacity");
      if (const toml::node* m = et.get("static_ratio")) {
        e.static_ratio_where = r.loc(*m);
        if (m->is_string()) {
          e.static_ratio = *m->value<std::string>();
          e.static_ratio_column_offset = 1;
        } else if (m->is_integer() || m->is_floating_point()) {
          const double v = *m->value<double>();
          if (!std::isfinite(v)) r.fail(*m, "static_ratio is not finite");
          e.static_ratio = fmt::format("{}", v);
        } else {
          r.fail(*m, "static_ratio must be a number or a string such as \"1.2\" or \"mu_s/mu_k\"");
        }
      } else {
        e.static_ratio_where = e.where;
      }
      if (const toml::node* c = et.get("friction_curve")) read_friction_curve(r, *c, e);
      t.friction_elements.push_back(std::move(e));
      if (t.friction_elements.size() > max_friction_elements)
        r.fail(n, fmt::format("more than {} brakes and clutches; pogear looks at every set of engaged elements, 2^k "
                              "of them; model fewer", max_friction_elements));
    }
  }
  // File order, for deterministic output whichever of [[brake]] and [[clutch]] comes first.
  std::sort(t.friction_elements.begin(), t.friction_elements.end(), [](const FrictionElement& a, const FrictionElement& b) {
    return std::tie(a.where.line, a.where.column) < std::tie(b.where.line, b.where.column);
  });
  std::map<std::string, const FrictionElement*> names;
  std::map<std::pair<int, int>, const FrictionElement*> pairs;
  for (const auto& e : t.friction_elements) {
    // T_<name> is an engaged element's torque and a fixed body's holding torque alike.
    if (const int b = find_body(t, e.name); b >= 0 && t.bodies[b].fixed)
      throw InputError(e.where, fmt::format("'{}' is the name of a fixed body (line {}), whose holding torque is T_{}; "
                                            "give the {} another name", e.name, t.bodies[b].where.line, e.name,
                                            e.is_brake() ? "brake" : "clutch"));
    if (auto [it, fresh] = names.emplace(e.name, &e); !fresh)
      throw InputError(e.where, fmt::format("duplicate name '{}' (brake or clutch); it is already used at line {}", e.name,
                                            it->second->where.line));
    const std::pair<int, int> key{std::min(e.first, e.second), std::max(e.first, e.second)};
    if (auto [it, fresh] = pairs.emplace(key, &e); !fresh)
      throw InputError(e.where, fmt::format("'{}' {} as '{}' (line {}) does; one element per pair of bodies, or remove one",
                                            e.name, e.is_brake() ? fmt::format("holds '{}'", t.bodies[e.first].name)
                                                                 : fmt::format("joins '{}' and '{}'", t.bodies[e.first].name,
                                                                               t.bodies[e.second].name),
                                            it->second->name, it->second->where.line));
  }
}

// Reads [parameters] as written; evaluate_parameters gives them values.
void read_parameters(const TomlReader& r, const toml::table& params, Topology& t) {
  if (params.size() > max_parameters)
    r.fail(params, fmt::format("{} parameters; a model has at most {}", params.size(), max_parameters));
  for (const auto& [key, node] : params) {
    const std::string name(key.str());
    const bool ok = is_name(name);
    if (!ok)
      throw InputError(toml_location(r.file, key.source()),
                       fmt::format("'{}' is not a parameter name; use letters, digits and '_', starting with a letter",
                                   name));
    if (name.size() > max_name_length)
      throw InputError(toml_location(r.file, key.source()), fmt::format("a parameter name is {} characters long; names have at "
                                                             "most {}", name.size(), max_name_length));
    if (is_unit_name(name))
      throw InputError(toml_location(r.file, key.source()), fmt::format("parameter '{}' has the name of a unit; rename it", name));
    Parameter p;
    p.name = name;
    p.where = r.loc(node);
    if (node.is_string()) {
      p.text = *node.value<std::string>();
      p.column_offset = 1;
    } else if (node.is_integer() || node.is_floating_point()) {
      const double v = *node.value<double>();
      if (!std::isfinite(v)) r.fail(node, fmt::format("parameter '{}' is not finite", name));
      p.text = fmt::format("{}", v);
      p.column_offset = 0;
    } else {
      r.fail(node, fmt::format("parameter '{}' must be a number (SI) or a string such as \"4.8*cm\"", name));
    }
    t.parameters.push_back(std::move(p));
  }
  // File order, for deterministic output.
  std::sort(t.parameters.begin(), t.parameters.end(), [](const Parameter& a, const Parameter& b) {
    return std::tie(a.where.line, a.where.column) < std::tie(b.where.line, b.where.column);
  });
}

// The velocity vector holds the bodies that turn; the fixed ones move past them (Topology::grounded)
// and every body index is renumbered to match.
void set_fixed_bodies_apart(Topology& t) {
  std::vector<int> index(t.bodies.size());
  std::vector<Body> turning, fixed;
  for (std::size_t i = 0; i < t.bodies.size(); ++i)
    if (!t.bodies[i].fixed) {
      index[i] = static_cast<int>(turning.size());
      turning.push_back(t.bodies[i]);
    }
  for (std::size_t i = 0; i < t.bodies.size(); ++i)
    if (t.bodies[i].fixed) {
      index[i] = static_cast<int>(turning.size() + fixed.size());
      fixed.push_back(t.bodies[i]);
    }
  for (Mesh& m : t.meshes) {
    m.first.body = index[m.first.body];
    m.second.body = index[m.second.body];
  }
  for (FrictionElement& e : t.friction_elements) {
    e.first = index[e.first];
    if (!e.is_brake()) e.second = index[e.second];
  }
  t.bodies = std::move(turning);
  t.grounded = std::move(fixed);
}

void read_meshes(const TomlReader& r, const toml::table& root, Topology& t) {
  const toml::array& meshes = array_of_tables(
      r, root, "mesh",
      t.bodies.size() < 2 ? std::string("[[mesh]] first = \"p\", second = \"s1\"")
                          : fmt::format("[[mesh]] first = \"{}\", second = \"{}\"", t.bodies[0].name, t.bodies[1].name));
  if (meshes.size() > max_meshes)
    r.fail(meshes, fmt::format("{} meshes; pogear derives gears of at most {} (the symbolic derivation grows steeply "
                               "with the size); model a smaller part of the gear", meshes.size(), max_meshes));
  for (const toml::node& n : meshes) {
    const toml::table& mt = *n.as_table();
    r.only_keys(mt, {"first", "second", "name", "stiffness", "damping", "module", "centre_distance"}, "a [[mesh]]");
    const toml::node* f = mt.get("first");
    const toml::node* s = mt.get("second");
    if (!f || !s) r.fail(mt, "a [[mesh]] needs first = \"<wheel>\" and second = \"<wheel>\"");
    Mesh m;
    m.where = r.loc(*f);
    m.first = resolve_wheel(r, t, *f);
    m.second = resolve_wheel(r, t, *s);
    if (m.first.body == m.second.body) r.fail(*s, "a body cannot mesh with itself");
    if (t.bodies[m.first.body].fixed && t.bodies[m.second.body].fixed)
      r.fail(*s, fmt::format("'{}' and '{}' are both fixed, so their mesh never turns; leave it out, or let one of "
                             "them turn", t.bodies[m.first.body].name, t.bodies[m.second.body].name));
    m.name = t.bodies[m.first.body].name + t.bodies[m.second.body].name;
    if (const toml::node* nn = mt.get("name")) m.name = r.identifier(*nn, "a mesh name");
    m.stiffness_parameter = "K_" + m.name;
    m.damping_parameter = "b_" + m.name;
    if (const toml::node* nn = mt.get("stiffness")) m.stiffness_parameter = r.identifier(*nn, "stiffness");
    if (const toml::node* nn = mt.get("damping")) m.damping_parameter = r.identifier(*nn, "damping");
    if (const toml::node* nn = mt.get("module")) read_module(r, *nn, m.module, m.module_where, m.module_column_offset);
    if (const toml::node* nn = mt.get("centre_distance"))
      read_module(r, *nn, m.centre_distance, m.centre_distance_where, m.centre_distance_column_offset, "centre_distance");
    t.meshes.push_back(std::move(m));
  }
}

}  // namespace

Topology parse_topology_text(const std::string& text, const std::string& path) {
  TomlReader r{path};
  const toml::table root = parse_toml_document(
      text, path, max_model_file_bytes,
      fmt::format("the file is larger than {} bytes; a model or scene file is a few kilobytes", max_model_file_bytes));
  r.only_keys(root, {"name", "title", "keep", "body", "mesh", "shaft", "brake", "clutch", "gears", "parameters"},
              "the model file");

  Topology t;
  t.file = path;
  t.digest = text_digest(text);
  if (const toml::node* n = root.get("name")) t.name = r.identifier(*n, "the model name");
  else t.name = std::filesystem::path(path).stem().string();
  if (auto s = r.optional_string(root, "title", "title")) {
    // The title is quoted in one-line comments of generated code, which a line break would end.
    if (std::any_of(s->begin(), s->end(), [](char c) { return c == '\n' || c == '\r'; }))
      r.fail(*root.get("title"), "the title is one line; remove the line break");
    t.title = *s;
  }

  const toml::array& bodies = array_of_tables(r, root, "body", "[[body]] name = \"c\"");
  if (bodies.size() > max_bodies)
    r.fail(bodies, fmt::format("{} bodies; pogear derives gears of at most {} (the symbolic derivation grows steeply "
                               "with the size); model a smaller part of the gear", bodies.size(), max_bodies));
  for (const toml::node& n : bodies) t.bodies.push_back(read_body(r, *n.as_table()));
  check_unique_names(t, false);
  check_carriers(t);

  // The example names the model's own bodies (a body of one wheel is named by the body).
  if (!root.get("mesh") && !root.get("shaft") && t.bodies.size() < 2)
    throw InputError(SourceLocation{r.file, 0, 0},
                     "no [[mesh]] entries, and one body: a gear is two or more bodies whose wheels mesh; add a second "
                     "[[body]] and a [[mesh]] between them");
  // A driveline of shafts and inertias needs no mesh.
  if (root.get("mesh") || !root.get("shaft")) read_meshes(r, root, t);
  if (const toml::node* shafts = root.get("shaft")) read_shafts(r, *shafts, t);
  check_unique_names(t, true);
  check_lumped_meshes(t);
  read_friction_elements(r, root, t);
  check_shaft_names(t);
  if (const toml::node* g = root.get("gears")) t.gears = read_gears(r, *g, t);

  if (const toml::node* p = root.get("parameters")) read_parameters(r, r.table(*p, "[parameters]"), t);
  evaluate_parameters(t.parameters);
  add_pitch_radii(t);
  add_operating_radii(t);
  check_parameter_roles(t);

  if (const toml::node* k = root.get("keep")) {
    t.keep_where = r.loc(*k);
    if (!k->is_array()) r.fail(*k, "keep must be a list of body names, e.g. keep = [\"c\", \"r\"]");
    for (const toml::node& e : *k->as_array()) {
      std::string name = r.identifier(e, "a kept velocity");
      const int b = find_body(t, name);
      if (b < 0) r.fail(e, fmt::format("keep names '{}', which is not a body", name));
      if (t.bodies[b].fixed)
        r.fail(e, fmt::format("keep names '{}', which is fixed; keep velocities of bodies that turn", name));
      t.default_keep.push_back(std::move(name));
    }
  }
  set_fixed_bodies_apart(t);
  return t;
}

Topology parse_topology(const std::string& path) {
  return parse_topology_text(read_input_file(path, max_model_file_bytes, "file"), path);
}

}  // namespace pogear
