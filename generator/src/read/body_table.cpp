// Reads one [[body]] table of a model file, each complaint located at the value it concerns.
#include "read/body_table.hpp"

#include <cmath>

#include <fmt/format.h>

namespace pogear {
namespace {

// `teeth` and `module` of a wheel (or of a body's one wheel): a whole tooth count, and its module.
void read_teeth(const TomlReader& r, const toml::table& t, Wheel& w) {
  const toml::node* z = t.get("teeth");
  const toml::node* m = t.get("module");
  if (m && !z) r.fail(*m, "a module without teeth; give the tooth count too, e.g. teeth = 30");
  if (!z) return;
  if (const toml::node* radius = t.get("radius"))
    r.fail(*radius, "a wheel is given by its radius or by its teeth, not both; leave out the radius");
  constexpr int fewest = 3, most = 10000;
  if (!z->is_integer() || **z->as_integer() < fewest || **z->as_integer() > most)
    r.fail(*z, fmt::format("teeth is a whole number of teeth from {} to {}", fewest, most));
  w.teeth = static_cast<int>(**z->as_integer());
  w.teeth_where = r.loc(*z);
  if (m) read_module(r, *m, w.module, w.module_where, w.module_column_offset);
}

}  // namespace

void read_module(const TomlReader& r, const toml::node& n, std::string& text, SourceLocation& where, int& column_offset,
                 std::string_view key) {
  where = r.loc(n);
  if (n.is_string()) {
    text = *n.value<std::string>();
    column_offset = 1;
  } else if ((n.is_integer() || n.is_floating_point()) && std::isfinite(*n.value<double>())) {
    text = fmt::format("{}", *n.value<double>());
    column_offset = 0;
  } else {
    r.fail(n, fmt::format("a {} is a length, e.g. {} = \"{}\"", key, key, key == "module" ? "2*mm" : "60*mm"));
  }
}

Body read_body(const TomlReader& r, const toml::table& t) {
  r.only_keys(t, {"name", "axis", "arrow", "inertia", "friction", "wheels", "teeth", "module", "count", "fixed"},
              "a [[body]]");
  Body b;
  b.where = r.loc(t);
  const toml::node* name = t.get("name");
  if (!name) r.fail(t, "a [[body]] needs a name, e.g. name = \"c\"");
  b.name = r.identifier(*name, "a body name");
  b.where = r.loc(*name);

  if (const toml::node* axis = t.get("axis")) {
    if (axis->is_string()) {
      const std::string a = r.string(*axis, "axis");
      if (a != "central")
        r.fail(*axis, fmt::format("axis \"{}\" is not known; write \"central\", {{ fixed = \"below\" }} or "
                                  "{{ carrier = \"c\", distance = \"r_c\" }}", a));
      b.axis = AxisKind::central;
    } else {
      const toml::table& at = r.table(*axis, "axis");
      r.only_keys(at, {"carrier", "distance", "side", "fixed"}, "an axis");
      if (const toml::node* f = at.get("fixed")) {
        if (at.get("carrier") || at.get("distance"))
          r.fail(*axis, "an axis is either fixed or carried, not both");
        b.axis = AxisKind::fixed;
        const std::string side = r.string(*f, "fixed");
        if (side != "above" && side != "below")
          r.fail(*f, "fixed must be \"above\" or \"below\": where the axis is drawn relative to the wheels it meshes with");
        b.side = side == "above" ? +1 : -1;
      } else {
        const toml::node* c = at.get("carrier");
        const toml::node* d = at.get("distance");
        if (!c || !d) r.fail(*axis, "a carried axis needs carrier = \"<body>\" and distance = \"<parameter>\"");
        b.axis = AxisKind::carried;
        b.carrier = r.identifier(*c, "carrier");
        b.distance_parameter = r.identifier(*d, "distance");
        if (const toml::node* s = at.get("side")) {
          const std::string side = r.string(*s, "side");
          if (side != "above" && side != "below") r.fail(*s, "side must be \"above\" or \"below\"");
          b.side = side == "above" ? +1 : -1;
        }
      }
    }
  }
  if (const toml::node* arrow = t.get("arrow")) {
    const std::string a = r.string(*arrow, "arrow");
    if (a != "right" && a != "left")
      r.fail(*arrow, "arrow must be \"right\" or \"left\": the positive direction of omega as drawn");
    b.arrow = a == "right" ? +1 : -1;
  }
  if (const toml::node* n = t.get("count")) {
    constexpr int most = 64;
    if (b.axis != AxisKind::carried)
      r.fail(*n, "count lumps identical planets; it goes on a body with a carried axis (a planet)");
    if (!n->is_integer() || **n->as_integer() < 1 || **n->as_integer() > most)
      r.fail(*n, fmt::format("count is the number of identical planets, a whole number from 1 to {}", most));
    b.count = static_cast<int>(**n->as_integer());
    b.count_where = r.loc(*n);
  }
  if (const toml::node* f = t.get("fixed")) {
    if (!f->is_boolean()) r.fail(*f, "fixed must be true or false: true when the housing holds the body");
    b.fixed = **f->as_boolean();
    if (b.fixed && b.axis == AxisKind::carried)
      r.fail(*f, fmt::format("body '{}' is a planet, whose axis moves with its carrier; fixed = true holds a body on "
                             "the central axis (a ring, sun or carrier): fix its carrier instead", b.name));
    if (b.fixed && b.axis == AxisKind::fixed)
      r.fail(*f, fmt::format("body '{}' turns about a fixed parallel axis; fixed = true holds a body on the central "
                             "axis (a ring, sun or carrier): hold '{}' with a [[brake]]", b.name, b.name));
    // A body that never turns has no inertia or bearing friction in the model: naming them is a mistake.
    for (std::string_view key : {"inertia", "friction"})
      if (const toml::node* n = t.get(key); n && b.fixed)
        r.fail(*n, fmt::format("body '{}' is fixed: it does not turn, so its {} plays no part; leave it out", b.name, key));
  }
  if (!b.fixed) {
    b.inertia_parameter = "J_" + b.name;
    b.friction_parameter = "b_" + b.name;
    if (const toml::node* n = t.get("inertia")) b.inertia_parameter = r.identifier(*n, "inertia");
    if (const toml::node* n = t.get("friction")) b.friction_parameter = r.identifier(*n, "friction");
  }

  if (const toml::node* wheels = t.get("wheels")) {
    if (!wheels->is_array()) r.fail(*wheels, "wheels must be a list: [ { name = \"s1\", radius = \"r_s1\" } ]");
    for (const toml::node& w : *wheels->as_array()) {
      const toml::table& wt = r.table(w, "a wheel");
      r.only_keys(wt, {"name", "radius", "internal", "teeth", "module"}, "a wheel");
      Wheel wheel;
      const toml::node* wn = wt.get("name");
      if (!wn) r.fail(w, "a wheel needs a name, e.g. { name = \"s1\", radius = \"r_s1\" }");
      wheel.name = r.identifier(*wn, "a wheel name");
      wheel.where = r.loc(*wn);
      wheel.radius_parameter = "r_" + wheel.name;
      if (const toml::node* rn = wt.get("radius")) wheel.radius_parameter = r.identifier(*rn, "radius");
      if (const toml::node* in = wt.get("internal")) {
        if (!in->is_boolean()) r.fail(*in, "internal must be true or false");
        wheel.internal = **in->as_boolean();
      }
      read_teeth(r, wt, wheel);
      b.wheels.push_back(std::move(wheel));
    }
    if (b.wheels.empty()) r.fail(*wheels, "an empty wheel list; leave 'wheels' out for a body without teeth");
    for (std::string_view key : {"teeth", "module"})
      if (const toml::node* n = t.get(key))
        r.fail(*n, fmt::format("the {} of a body with a wheel list goes on its wheel: wheels = [ {{ name = \"{}\", "
                               "teeth = 30, module = \"2*mm\" }} ]", key, b.wheels[0].name));
  } else {
    // The common case: one wheel named like its body, radius r_<body>. A carrier without
    // teeth simply never appears in a mesh, so its default wheel is harmless.
    Wheel w;
    w.name = b.name;
    w.radius_parameter = "r_" + b.name;
    w.where = b.where;
    b.wheels.push_back(std::move(w));
    read_teeth(r, t, b.wheels.back());
  }
  return b;
}


}  // namespace pogear
