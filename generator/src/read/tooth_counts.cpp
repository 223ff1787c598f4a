// Pitch radii from tooth counts and modules. A pitch radius is an ordinary radius parameter from
// here on: R, the geometry checks and the code see radii; only the reports write ratios in Z.
#include "read/tooth_counts.hpp"

#include <cmath>
#include <map>
#include <numeric>
#include <optional>

#include <fmt/format.h>

#include "read/model_parameters.hpp"
#include "common/quantity.hpp"

namespace pogear {
namespace {

struct Module {
  double value = 0;  // m
  std::string text;
};

std::string millimetres(double m) { return fmt::format("{:.6g} mm", m * 1e3); }

// Z_1 + Z_2, or for an internal mesh, whose wheels turn the same way, Z_ring - Z_pinion.
int teeth_span(const Wheel& w1, const Wheel& w2) {
  return w1.internal || w2.internal ? std::abs(w1.teeth - w2.teeth) : w1.teeth + w2.teeth;
}

Module evaluate_module(const std::string& text, const SourceLocation& where, int column_offset,
                       const std::map<std::string, Quantity>& known) {
  const Quantity q = evaluate_quantity(text, known, where, column_offset);
  if (!q.has_unit || !(q.dimension == length_dimension()))
    throw InputError(where, fmt::format("the module '{}' {}; a module is a length, e.g. \"2*mm\"", text,
                                        q.has_unit ? "has unit " + describe(q.dimension) : "has no unit"));
  // Modules of real gears run from 0.05 mm (watches) to about 100 mm (mill drives).
  if (!(q.si >= 1e-6 && q.si <= 1.0))
    throw InputError(where, fmt::format("the module '{}' is {} m; a module is positive and at most 1 m", text, q.si));
  return {q.si, text};
}

}  // namespace

void add_pitch_radii(Topology& t) {
  std::map<std::string, Quantity> known;
  for (const auto& p : t.parameters) known[p.name] = p.value;
  // The module of each toothed wheel: its own, else the first of its meshes that gives one.
  std::map<std::pair<int, int>, Module> modules;
  for (int bi = 0; bi < static_cast<int>(t.bodies.size()); ++bi)
    for (int wi = 0; wi < static_cast<int>(t.bodies[bi].wheels.size()); ++wi) {
      const Wheel& w = t.bodies[bi].wheels[wi];
      if (w.teeth > 0 && !w.module.empty())
        modules[{bi, wi}] = evaluate_module(w.module, w.module_where, w.module_column_offset, known);
    }
  for (int mi = 0; mi < static_cast<int>(t.meshes.size()); ++mi) {
    const Mesh& m = t.meshes[mi];
    if (m.shaft || m.module.empty()) continue;
    const Module given = evaluate_module(m.module, m.module_where, m.module_column_offset, known);
    if (wheel(t, m.first).teeth == 0 && wheel(t, m.second).teeth == 0)
      throw InputError(m.module_where, fmt::format("mesh {} gives a module, but neither {} nor {} has teeth; give "
                                                   "their teeth, or leave the module out",
                                                   m.name, wheel_label(t, m.first), wheel_label(t, m.second)));
    for (WheelRef w : {m.first, m.second})
      if (wheel(t, w).teeth > 0) modules.emplace(std::make_pair(w.body, w.wheel), given);
  }
  for (int bi = 0; bi < static_cast<int>(t.bodies.size()); ++bi)
    for (int wi = 0; wi < static_cast<int>(t.bodies[bi].wheels.size()); ++wi) {
      const Wheel& w = t.bodies[bi].wheels[wi];
      if (w.teeth == 0) continue;
      const WheelRef ref{bi, wi};
      const auto it = modules.find({bi, wi});
      if (it == modules.end())
        throw InputError(w.teeth_where, fmt::format("{} has {} teeth but no module; give module = \"2*mm\" with its "
                                                    "teeth or on one of its meshes",
                                                    wheel_label(t, ref), w.teeth));
      if (const Parameter* p = find_parameter(t, w.radius_parameter))
        throw InputError(p->where, fmt::format("'{}' is the pitch radius of {}, which its {} teeth give; leave it "
                                               "out of [parameters]",
                                               w.radius_parameter, wheel_label(t, ref), w.teeth));
      Parameter p;
      p.name = w.radius_parameter;
      p.text = fmt::format("{}*({})/2", w.teeth, it->second.text);
      p.value = Quantity{w.teeth * it->second.value / 2, length_dimension(), true};
      p.where = w.teeth_where;
      p.column_offset = 0;
      t.parameters.push_back(std::move(p));
    }
  for (const Mesh& m : t.meshes) {
    if (m.shaft) continue;
    const auto a = modules.find({m.first.body, m.first.wheel});
    const auto b = modules.find({m.second.body, m.second.wheel});
    if (a == modules.end() || b == modules.end()) continue;
    // Modules typed as the same text, or as equal lengths in other units, agree to rounding.
    if (std::abs(a->second.value - b->second.value) > 1e-12 * std::max(a->second.value, b->second.value))
      throw InputError(m.where, fmt::format("mesh {}: {} has module {} and {} module {}; meshing wheels share one "
                                            "module",
                                            m.name, wheel_label(t, m.first), millimetres(a->second.value),
                                            wheel_label(t, m.second), millimetres(b->second.value)));
  }
}

namespace {

// Mesh m's centre distance in metres, checked against its teeth: both wheels toothed, a positive
// length, within one module of the reference m (Z_2 +- Z_1) / 2.
double checked_centre_distance(const Topology& t, const Mesh& m, const std::map<std::string, Quantity>& known) {
  const SourceLocation& where = m.centre_distance_where;
  for (const WheelRef w : {m.first, m.second})
    if (wheel(t, w).teeth == 0)
      throw InputError(where, fmt::format("mesh {}: a centre distance sets the operating pitch radii from the teeth, "
                                          "but {} is given by its radius; give its teeth and module",
                                          m.name, wheel_label(t, w)));
  const Quantity a = evaluate_quantity(m.centre_distance, known, where, m.centre_distance_column_offset);
  if (!a.has_unit || !(a.dimension == length_dimension()) || !(a.si > 0))
    throw InputError(where, fmt::format("the centre distance '{}' of mesh {} is {}; it is a positive length, e.g. "
                                        "\"60*mm\"", m.centre_distance, m.name,
                                        !a.has_unit ? std::string("without a unit")
                                        : !(a.dimension == length_dimension()) ? "in " + describe(a.dimension)
                                                                                 : fmt::format("{} m", a.si)));
  const Wheel& w1 = wheel(t, m.first);
  const Wheel& w2 = wheel(t, m.second);
  const bool internal = w1.internal || w2.internal;
  const double r1 = known.at(w1.radius_parameter).si;
  const double r2 = known.at(w2.radius_parameter).si;
  const double reference = internal ? std::abs(r1 - r2) : r1 + r2;
  const double module = 2 * r1 / w1.teeth;
  if (teeth_span(w1, w2) == 0 || !(std::abs(a.si - reference) <= module))
    throw InputError(where, fmt::format("mesh {}: centre distance {} is {} from the reference centre distance of "
                                        "its teeth, m ({} {} {})/2 = {} with module {}; profile shifts move it by a "
                                        "fraction of the module: check the centre distance and the teeth",
                                        m.name, millimetres(a.si), millimetres(std::abs(a.si - reference)),
                                        std::max(w1.teeth, w2.teeth), internal ? "-" : "+",
                                        std::min(w1.teeth, w2.teeth), millimetres(reference), millimetres(module)));
  return a.si;
}

std::map<std::string, Quantity> parameter_values(const Topology& t) {
  std::map<std::string, Quantity> known;
  for (const auto& p : t.parameters) known[p.name] = p.value;
  return known;
}

}  // namespace

void add_operating_radii(Topology& t) {
  const std::map<std::string, Quantity> known = parameter_values(t);
  for (const Mesh& m : t.meshes) {
    if (m.centre_distance.empty()) continue;
    const double a = checked_centre_distance(t, m, known);
    const int span = teeth_span(wheel(t, m.first), wheel(t, m.second));
    auto operating_radius = [&](WheelRef ref) {
      const Wheel& w = wheel(t, ref);
      const std::string name = contact_radius(t, m, ref);
      if (const Parameter* p = find_parameter(t, name))
        throw InputError(p->where, fmt::format("'{}' is the operating pitch radius of {} in mesh {}, which its centre "
                                               "distance gives; leave it out of [parameters]", name, w.name, m.name));
      // As text too: a scene's override of a parameter the centre distance names reaches it.
      Parameter p;
      p.name = name;
      p.text = fmt::format("({})*{}/{}", m.centre_distance, w.teeth, span);
      p.value = Quantity{a * w.teeth / span, length_dimension(), true};
      p.where = m.centre_distance_where;
      p.column_offset = 0;
      t.parameters.push_back(std::move(p));
    };
    operating_radius(m.first);
    operating_radius(m.second);
  }
}

void check_centre_distances(const Topology& t) {
  const std::map<std::string, Quantity> known = parameter_values(t);
  for (const Mesh& m : t.meshes)
    if (!m.centre_distance.empty()) checked_centre_distance(t, m, known);
}

GiNaC::exmap tooth_count_substitutions(const Topology& t, const SymbolTable& s) {
  // Wheels as one index each; meshes between toothed wheels join their sets.
  std::vector<std::pair<int, int>> wheels;
  std::map<std::pair<int, int>, int> index;
  const std::vector<const Body*> bodies = every_body(t);
  for (int bi = 0; bi < static_cast<int>(bodies.size()); ++bi)
    for (int wi = 0; wi < static_cast<int>(bodies[bi]->wheels.size()); ++wi)
      if (bodies[bi]->wheels[wi].teeth > 0) {
        index[{bi, wi}] = static_cast<int>(wheels.size());
        wheels.push_back({bi, wi});
      }
  if (wheels.empty()) return {};
  std::vector<int> parent(wheels.size());
  std::iota(parent.begin(), parent.end(), 0);
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (const Mesh& m : t.meshes) {
    if (m.shaft || !m.centre_distance.empty()) continue;  // rolling on operating circles, written below
    const auto a = index.find({m.first.body, m.first.wheel});
    const auto b = index.find({m.second.body, m.second.wheel});
    if (a != index.end() && b != index.end()) parent[root(a->second)] = root(b->second);
  }
  std::map<int, int> set_number;  // root -> 1, 2, ... in the order of the wheels
  for (std::size_t i = 0; i < wheels.size(); ++i) set_number.emplace(root(static_cast<int>(i)), set_number.size() + 1);
  std::map<int, GiNaC::ex> module;
  for (const auto& [r, k] : set_number)
    module[r] = GiNaC::realsymbol(set_number.size() == 1 ? std::string("m") : fmt::format("m_{}", k));
  GiNaC::exmap out;
  std::map<std::string, GiNaC::realsymbol> teeth;  // one symbol per name: GiNaC compares symbols by identity
  auto tooth_count = [&](const Wheel& w) { return teeth.emplace(w.name, GiNaC::realsymbol("Z_" + w.name)).first->second; };
  for (std::size_t i = 0; i < wheels.size(); ++i) {
    const Wheel& w = bodies[wheels[i].first]->wheels[wheels[i].second];
    out[parameter_symbol(s, w.radius_parameter)] =
        module[root(static_cast<int>(i))] * tooth_count(w) / 2;
  }
  // An operating pitch radius is a Z / (Z_2 +- Z_1): across its mesh the ratio is Z_1 / Z_2. A planet's
  // meshes with central wheels share one centre distance, its axis distance (the geometry checks
  // that they agree), so that it cancels between them: one symbol, named after it, or the reference
  // centre distance m (Z_c +- Z_p) / 2 of a mesh of the planet that is not shifted.
  auto reference_distance = [&](int planet) -> std::optional<GiNaC::ex> {
    for (const Mesh& m : t.meshes) {
      if (m.shaft || !m.centre_distance.empty()) continue;
      for (const bool planet_first : {true, false}) {
        const WheelRef p = planet_first ? m.first : m.second, c = planet_first ? m.second : m.first;
        if (p.body != planet || body(t, c.body).axis != AxisKind::central) continue;
        const auto ip = index.find({p.body, p.wheel});
        if (ip == index.end() || !index.count({c.body, c.wheel})) continue;
        const Wheel& wp = wheel(t, p);
        const Wheel& wc = wheel(t, c);
        return module[root(ip->second)] * (wc.internal ? tooth_count(wc) - tooth_count(wp) : tooth_count(wc) + tooth_count(wp)) / 2;
      }
    }
    return std::nullopt;
  };
  std::map<std::string, GiNaC::ex> distances;
  for (const Mesh& m : t.meshes) {
    if (m.centre_distance.empty()) continue;
    const Wheel& w1 = wheel(t, m.first);
    const Wheel& w2 = wheel(t, m.second);
    std::string distance = "a_" + m.name;
    int planet = -1;
    for (const bool first : {true, false}) {
      const int p = first ? m.first.body : m.second.body, other = first ? m.second.body : m.first.body;
      if (body(t, p).axis == AxisKind::carried && body(t, other).axis == AxisKind::central) {
        distance = body(t, p).distance_parameter;
        planet = p;
      }
    }
    if (!distances.count(distance)) {
      const std::optional<GiNaC::ex> reference = planet < 0 ? std::nullopt : reference_distance(planet);
      distances.emplace(distance, reference ? *reference : GiNaC::ex(GiNaC::realsymbol(distance)));
    }
    const GiNaC::ex a = distances.at(distance);
    const GiNaC::realsymbol z1 = tooth_count(w1), z2 = tooth_count(w2);
    const GiNaC::ex span = w1.internal ? z1 - z2 : w2.internal ? z2 - z1 : z1 + z2;
    out[parameter_symbol(s, contact_radius(t, m, m.first))] = a * z1 / span;
    out[parameter_symbol(s, contact_radius(t, m, m.second))] = a * z2 / span;
  }
  return out;
}

std::optional<GiNaC::ex> in_tooth_numbers(const GiNaC::ex& e, const Topology& t) {
  std::map<std::string, int> teeth;
  for (const Body* b : every_body(t))
    for (const Wheel& w : b->wheels)
      if (w.teeth > 0) teeth["Z_" + w.name] = w.teeth;
  GiNaC::exmap numbers;
  for (GiNaC::const_preorder_iterator i = e.preorder_begin(); i != e.preorder_end(); ++i) {
    if (!GiNaC::is_a<GiNaC::symbol>(*i)) continue;
    const auto it = teeth.find(GiNaC::ex_to<GiNaC::symbol>(*i).get_name());
    if (it == teeth.end()) return std::nullopt;
    numbers[*i] = it->second;
  }
  return e.subs(numbers, GiNaC::subs_options::no_pattern);
}

}  // namespace pogear
