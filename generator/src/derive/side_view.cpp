// The side view of the toothed meshes: each contact's velocity u_k(y) = s_k omega_k (y - a_k) +
// u_carrier(a_k) read off the drawing, the axis heights it implies, pinion pairs at an angle.
#include "derive/side_view.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <optional>

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "derive/derivation_errors.hpp"
#include "read/model_parameters.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// Axis heights in the side view. A fixed axis has an unknown height until a mesh places it: a
// symbol of this stage alone, never in the model's symbol table.
struct Heights {
  std::vector<ex> symbolic;                  // per body
  std::vector<std::optional<double>> value;  // per body, numeric when known
  std::vector<ex> unknowns;                  // the fixed axes' height symbols
};

bool is_height(const Heights& h, const ex& e) {
  return std::any_of(h.unknowns.begin(), h.unknowns.end(), [&](const ex& u) { return u.is_equal(e); });
}

// `values`: numeric_substitutions of the parameters known so far, built once (a chain of 40
// stages has 500 of them, and every axis and mesh asks).
std::optional<double> value_of(const ex& e, const GiNaC::exmap& values) {
  const ex v = exact_value(e, values).evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v)) return std::nullopt;
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

Heights axis_heights(const Topology& t, const SymbolTable& s, const GiNaC::exmap& values) {
  const std::size_t n = t.bodies.size();
  Heights h{std::vector<ex>(n), std::vector<std::optional<double>>(n), {}};
  std::vector<bool> placed(n, false);
  // Carriers may themselves be carried; resolve in dependency order (no cycles: checked on parse).
  std::function<void(int)> place = [&](int k) {
    if (placed[k]) return;
    placed[k] = true;
    const Body& b = t.bodies[k];
    switch (b.axis) {
      case AxisKind::central:
        h.symbolic[k] = 0;
        break;
      case AxisKind::fixed:
        // Named so that it sorts among the radii as it always has (the solver below takes
        // unknowns in name order); the name never leaves this stage.
        h.symbolic[k] = GiNaC::realsymbol("__height_" + b.name);
        h.unknowns.push_back(h.symbolic[k]);
        break;
      case AxisKind::carried: {
        const int c = find_body(t, b.carrier);
        place(c);
        h.symbolic[k] = h.symbolic[c] + b.side * parameter_symbol(s, b.distance_parameter);
        break;
      }
    }
    h.value[k] = value_of(h.symbolic[k], values);
  };
  for (std::size_t k = 0; k < n; ++k) place(static_cast<int>(k));
  return h;
}

// The sign of a height difference, when the numbers are missing, from lengths being positive.
std::optional<int> sign_of(const ex& diff, const GiNaC::exmap& values) {
  if (auto v = value_of(diff, values)) return *v > 0 ? 1 : (*v < 0 ? -1 : 0);
  const ex e = diff.subs(values).expand();
  int sign = 0;
  const auto terms = GiNaC::is_a<GiNaC::add>(e) ? GiNaC::exvector(e.begin(), e.end()) : GiNaC::exvector{e};
  for (const ex& term : terms) {
    ex coeff = term;
    if (GiNaC::is_a<GiNaC::mul>(term)) {
      coeff = 1;
      for (const ex& f : term)
        if (GiNaC::is_a<GiNaC::numeric>(f)) coeff *= f;
    } else if (!GiNaC::is_a<GiNaC::numeric>(term)) {
      coeff = 1;
    }
    const int c = GiNaC::ex_to<GiNaC::numeric>(coeff.evalf()).to_double() > 0 ? 1 : -1;
    if (sign != 0 && c != sign) return std::nullopt;
    sign = c;
  }
  return sign;
}

bool pinions_of_one_carrier(const Topology& t, int bi, int bj) {
  const Body& a = t.bodies[bi];
  const Body& b = t.bodies[bj];
  return a.axis == AxisKind::carried && b.axis == AxisKind::carried && a.carrier == b.carrier;
}

// Which side of each axis a mesh's contact lies on. `solved`: the relations of the meshes before it,
// asked only when the given values cannot tell; with `may_wait`, an undecided mesh is left for later
// (nullopt) instead of being an error.
std::optional<ContactSides> contact_sides(const Topology& t, int mi, Heights& h, const SymbolTable& s,
                                          const GiNaC::exmap& values, const GiNaC::exmap& solved, bool may_wait) {
  const Mesh& m = t.meshes[mi];
  const int bi = m.first.body;
  const int bj = m.second.body;
  const Wheel& wi = wheel(t, m.first);
  const Wheel& wj = wheel(t, m.second);
  if (wi.internal && wj.internal)
    throw InputError(m.where, fmt::format("{}: two internal wheels cannot mesh; one of {} and {} must have "
                                          "external teeth", describe_mesh(t, mi), wi.name, wj.name));
  // is_j_above: +1 when body j's axis is drawn above body i's.
  std::optional<int> j_above;
  const bool fi = t.bodies[bi].axis == AxisKind::fixed && !h.value[bi];
  const bool fj = t.bodies[bj].axis == AxisKind::fixed && !h.value[bj];
  if (fj && !fi) j_above = t.bodies[bj].side;
  else if (fi && !fj) j_above = -t.bodies[bi].side;
  else if (fi && fj)
    throw InputError(m.where, fmt::format("{}: neither axis height is known yet; mesh a fixed-axis gear with a "
                                          "central or carried wheel first", describe_mesh(t, mi)));
  else
    j_above = sign_of(h.symbolic[bj] - h.symbolic[bi], values);
  if (!j_above && !fi && !fj) j_above = sign_of((h.symbolic[bj] - h.symbolic[bi]).subs(solved), values);
  if (!j_above && may_wait) return std::nullopt;
  if (!j_above)
    throw InputError(m.where, fmt::format("{}: cannot tell which axis is drawn higher; give the numeric values "
                                          "of the axis distances", describe_mesh(t, mi)));
  // Two pinions at one distance from the central axis are at an angle to each other: by
  // convention the second is drawn higher, which fixes only the sign of F.
  if (*j_above == 0 && pinions_of_one_carrier(t, bi, bj)) j_above = +1;
  if (*j_above == 0)
    throw InputError(m.where, fmt::format("{}: {} and {} turn about the same axis, so they cannot mesh; put one "
                                          "on a carrier or a fixed axis", describe_mesh(t, mi),
                                          wheel_label(t, m.first), wheel_label(t, m.second)));
  ContactSides c;
  if (wi.internal) {
    c.first = c.second = *j_above;  // contact on the far side of j, seen from the ring's axis
  } else if (wj.internal) {
    c.first = c.second = -*j_above;
  } else {
    c.first = *j_above;  // external pair: they touch between their axes
    c.second = -*j_above;
  }
  // A fixed axis is placed by its first mesh: contact heights must agree.
  auto place = [&](int fixed_body, int other_body, int side_fixed, int side_other, const std::string& rf,
                   const std::string& ro) {
    h.symbolic[fixed_body] = h.symbolic[other_body] + side_other * parameter_symbol(s, ro) - side_fixed * parameter_symbol(s, rf);
    h.value[fixed_body] = value_of(h.symbolic[fixed_body], values);
  };
  if (fi) place(bi, bj, c.first, c.second, contact_radius(t, m, m.first), contact_radius(t, m, m.second));
  if (fj) place(bj, bi, c.second, c.first, contact_radius(t, m, m.second), contact_radius(t, m, m.first));
  return c;
}

// Velocity of body k's material point at `offset` from its own axis, as coefficients of omega.
void add_point_velocity(const Topology& t, const SymbolTable& s, int k, const ex& offset, const ex& factor,
                        std::vector<ex>& row) {
  const Body& b = t.bodies[k];
  row[k] += factor * b.arrow * offset;
  if (b.axis == AxisKind::carried) {
    const int c = find_body(t, b.carrier);
    add_point_velocity(t, s, c, b.side * parameter_symbol(s, b.distance_parameter), factor, row);
  }
}

// A pinion pair's row in its carrier's frame, where both axes are fixed: each wheel's contact point
// moves at side * r * (a omega - a_c omega_c) relative to the carrier, whatever the angle between
// the axes. For pinions drawn on one line with the central axis it equals the side-view row.
std::vector<ex> carrier_frame_row(const Topology& t, const SymbolTable& s, int mi, const ContactSides& c) {
  const Mesh& m = t.meshes[mi];
  const int carrier = find_body(t, t.bodies[m.first.body].carrier);
  std::vector<ex> row(t.bodies.size(), ex(0));
  auto add = [&](WheelRef w, const std::string& radius, int side, int sign) {
    const ex r = parameter_symbol(s, radius);
    row[w.body] += sign * side * r * t.bodies[w.body].arrow;
    row[carrier] -= sign * side * r * t.bodies[carrier].arrow;
  };
  add(m.first, contact_radius(t, m, m.first), c.first, +1);
  add(m.second, contact_radius(t, m, m.second), c.second, -1);
  for (ex& e : row) e = e.expand();
  return row;
}

// Priority when solving the contact equations: what a designer reads as derived comes first.
int unknown_rank(const Topology& t, const std::string& name, int& order) {
  for (int k = static_cast<int>(t.bodies.size()) - 1; k >= 0; --k) {
    const Body& b = t.bodies[k];
    order = k;
    if (b.axis == AxisKind::carried && b.distance_parameter == name) return 2;
    for (const auto& w : b.wheels)
      if (w.radius_parameter == name) return w.internal ? 1 : 0;
  }
  // An operating pitch radius ranks as its wheel's radius.
  for (const Mesh& m : t.meshes)
    for (const bool first : {true, false})
      if (const WheelRef ref = first ? m.first : m.second; contact_radius(t, m, ref) == name) {
        order = ref.body;
        return wheel(t, ref).internal ? 1 : 0;
      }
  order = -1;
  return -1;
}

// The angle between two pinions' axes from the triangle of their axis distances and their centre
// distance; a triangle that cannot close is a layout no carrier can hold.
double pinion_angle(const Topology& t, const SymbolTable& s, int mi, const RadiusMatrix& rm, const GiNaC::exmap& known) {
  const Mesh& mesh = t.meshes[mi];
  const Wheel& wi = wheel(t, mesh.first);
  const Wheel& wj = wheel(t, mesh.second);
  const Body& bi = t.bodies[mesh.first.body];
  const Body& bj = t.bodies[mesh.second.body];
  const ex ri = parameter_symbol(s, contact_radius(t, mesh, mesh.first));
  const ex rj = parameter_symbol(s, contact_radius(t, mesh, mesh.second));
  const ex centre = wi.internal ? ri - rj : (wj.internal ? rj - ri : ri + rj);
  const auto d = value_of(centre, known);
  const auto ai = value_of(parameter_symbol(s, bi.distance_parameter), known);
  const auto aj = value_of(parameter_symbol(s, bj.distance_parameter), known);
  if (!d || !ai || !aj) return 0;  // a missing value is reported where it is missing
  auto origin = [&](const std::string& parameter) {
    for (const auto& g : rm.relations)
      if (g.parameter == parameter) return t.meshes[g.mesh].name;
    return std::string{};
  };
  const double lo = std::abs(*ai - *aj);
  const double hi = *ai + *aj;
  // Tolerance as for the relations: values typed to a few digits close a collinear layout to ~1e-15.
  const double tol = 1e-9 * hi;
  if (*d < lo - tol || *d > hi + tol || !(*d > 0))
    throw GeometryConflict(mesh.where,
                           PinionsOutOfReach{describe_mesh(t, mi), bi.carrier,
                                             {bi.name, bi.distance_parameter, *ai, origin(bi.distance_parameter)},
                                             {bj.name, bj.distance_parameter, *aj, origin(bj.distance_parameter)},
                                             centre, *d, lo, hi});
  if (!(*ai > 0) || !(*aj > 0)) return 0;
  const double c = (*ai * *ai + *aj * *aj - *d * *d) / (2 * *ai * *aj);
  return std::acos(std::clamp(c, -1.0, 1.0));
}

// A clutch joins two bodies on one axis: two fixed axes that the meshes place at different heights
// of the side view are two axes, whichever way the chain of meshes between them runs (a countershaft's
// input and output gears are coaxial only when their centre distances agree).
void check_clutches_on_one_axis(const Topology& t, const Heights& h, const GiNaC::exmap& solved,
                                const GiNaC::exmap& known) {
  for (const FrictionElement& e : t.friction_elements) {
    if (e.is_brake() || t.bodies[e.first].axis != AxisKind::fixed || t.bodies[e.second].axis != AxisKind::fixed)
      continue;
    const auto a = value_of(h.symbolic[e.first].subs(solved), known);
    const auto b = value_of(h.symbolic[e.second].subs(solved), known);
    if (!a || !b) continue;  // a missing radius is reported where it is missing
    // The heights are sums of radii typed to a few digits: equal axes agree to ~1e-15 relative,
    // so 1e-9 (the tolerance of the geometry relations) only separates axes that differ.
    if (std::abs(*a - *b) <= 1e-9 * std::max(std::abs(*a), std::abs(*b))) continue;
    throw InputError(e.bodies_where,
                     fmt::format("clutch '{}' joins '{}' and '{}', whose meshes place their fixed axes at heights "
                                 "{:.6g} m and {:.6g} m of the side view; a clutch joins two bodies that "
                                 "turn about one axis",
                                 e.name, t.bodies[e.first].name, t.bodies[e.second].name, *a, *b));
  }
}

}  // namespace

// The side view of every body, the fixed ones among them (after the turning ones, as their
// indices say): the layout and the contact rows do not care which bodies turn.
RadiusMatrix derive_side_view(const Topology& t, const SymbolTable& s) {
  const auto n = t.bodies.size();
  const auto m = t.meshes.size();
  RadiusMatrix rm;
  std::map<std::string, double> given;
  for (const auto& p : t.parameters) given[p.name] = p.value.si;
  GiNaC::exmap known = numeric_substitutions(s, given);
  Heights h = axis_heights(t, s, known);

  rm.R = GiNaC::matrix(m, n);
  rm.sides.resize(m);
  std::vector<ex> contact_equations(m);  // a_i + side_i r_i - (a_j + side_j r_j) == 0, per mesh
  // Solve the contact equations one at a time for the most "derived" unknown in each.
  GiNaC::exmap solved;
  std::map<std::string, int> solved_by;
  auto solve = [&](std::size_t mi) {
    const ex e = contact_equations[mi].subs(solved).expand();
    if (e.is_zero()) return;
    std::optional<ex> best;
    int best_rank = -2;
    int best_order = -2;
    // The symbols of e, in the order of their names (as a walk over every symbol would meet them).
    std::map<std::string, ex> in_e;
    for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
      if (GiNaC::is_a<GiNaC::symbol>(*it)) {
        const std::string& name = GiNaC::ex_to<GiNaC::symbol>(*it).get_name();
        in_e.emplace(name, *it);
      }
    for (const auto& [name, sym] : in_e) {
      int order = -1;
      const int r = is_height(h, sym) ? 3 : unknown_rank(t, name, order);
      if (std::tie(r, order) > std::tie(best_rank, best_order)) {
        best = sym;
        best_rank = r;
        best_order = order;
      }
    }
    if (!best || !GiNaC::is_a<GiNaC::numeric>(e.coeff(*best, 1)) || e.degree(*best) != 1)
      throw InputError(t.meshes[mi].where, fmt::format("{}: its contact geometry cannot be satisfied",
                                                       describe_mesh(t, static_cast<int>(mi))));
    const ex value = (-e.coeff(*best, 0) / e.coeff(*best, 1)).expand();
    for (auto& [sym, v] : solved)
      if (v.has(*best)) v = v.subs(*best == value).expand();
    solved[*best] = value;
    solved_by[GiNaC::ex_to<GiNaC::symbol>(*best).get_name()] = static_cast<int>(mi);
  };
  // A pinion pair is on the side view's line when its numbers satisfy its contact equation, and at
  // an angle otherwise; the numbers may come from later meshes, so an undecided pair waits for them
  // (and, still undecided, is taken as drawn).
  auto angled_pair = [&](std::size_t mi) -> std::optional<bool> {
    const Mesh& mesh = t.meshes[mi];
    const auto residual = value_of(contact_equations[mi].subs(solved), known);
    const auto scale = value_of((parameter_symbol(s, contact_radius(t, mesh, mesh.first)) + parameter_symbol(s, contact_radius(t, mesh, mesh.second))).subs(solved),
                                known);
    if (!residual || !scale) return std::nullopt;
    // The same 1e-9 relative as the check of given radii against the relations below.
    return std::abs(*residual) > 1e-9 * std::abs(*scale);
  };
  // Each mesh in turn: its contact sides, its side-view row and contact equation, then that
  // equation solved, unless it is a pinion pair at an angle. A pinion pair that earlier meshes do
  // not yet place waits until every other mesh is laid out.
  std::vector<int> angled;
  auto lay_out = [&](std::size_t mi, bool may_wait) {
    const Mesh& mesh = t.meshes[mi];
    const bool pinions = pinions_of_one_carrier(t, mesh.first.body, mesh.second.body);
    const auto c = contact_sides(t, static_cast<int>(mi), h, s, known, solved, pinions && may_wait);
    if (!c) return false;
    rm.sides[mi] = *c;
    const ex ri = parameter_symbol(s, contact_radius(t, mesh, mesh.first));
    const ex rj = parameter_symbol(s, contact_radius(t, mesh, mesh.second));
    std::vector<ex> row(n, ex(0));
    add_point_velocity(t, s, mesh.first.body, c->first * ri, +1, row);
    add_point_velocity(t, s, mesh.second.body, c->second * rj, -1, row);
    for (std::size_t k = 0; k < n; ++k) rm.R(mi, k) = row[k].expand();
    contact_equations[mi] =
        (h.symbolic[mesh.first.body] + c->first * ri - h.symbolic[mesh.second.body] - c->second * rj).expand();
    if (pinions) {
      const auto a = angled_pair(mi);
      if (!a && may_wait) return false;
      if (a.value_or(false)) {
        angled.push_back(static_cast<int>(mi));
        return true;
      }
    }
    solve(mi);
    return true;
  };
  std::vector<std::size_t> waiting;
  for (std::size_t mi = 0; mi < m; ++mi)
    if (!lay_out(mi, true)) waiting.push_back(mi);
  for (std::size_t mi : waiting) lay_out(mi, false);
  std::sort(angled.begin(), angled.end());
  for (int mi : angled) {
    const auto row = carrier_frame_row(t, s, mi, rm.sides[mi]);
    for (std::size_t k = 0; k < n; ++k) rm.R(mi, k) = row[k];
  }

  for (const auto& [sym, rhs] : solved) {
    if (is_height(h, sym)) continue;
    const std::string name = GiNaC::ex_to<GiNaC::symbol>(sym).get_name();
    rm.relations.push_back(GeometryRelation{name, rhs, solved_by[name]});
  }
  // Report relations in mesh order, which follows the drawing.
  std::stable_sort(rm.relations.begin(), rm.relations.end(),
                   [](const GeometryRelation& a, const GeometryRelation& b) { return a.mesh < b.mesh; });

  // Every radius the relations leave free must be given; the dependent ones may be omitted.
  for (std::size_t mi = 0; mi < m; ++mi)
    for (const bool first : {true, false}) {
      const WheelRef w = first ? t.meshes[mi].first : t.meshes[mi].second;
      const std::string r = contact_radius(t, t.meshes[mi], w);
      const bool dependent = std::any_of(rm.relations.begin(), rm.relations.end(),
                                         [&](const GeometryRelation& g) { return g.parameter == r; });
      if (!dependent && !given.count(r))
        throw InputError(t.meshes[mi].where, fmt::format("missing parameter '{}' (the radius of {}); add it under "
                                                         "[parameters], e.g. {} = \"10*cm\"",
                                                         r, wheel_label(t, w), r));
    }
  for (const auto& b : t.bodies)
    if (b.axis == AxisKind::carried && !given.count(b.distance_parameter) &&
        std::none_of(rm.relations.begin(), rm.relations.end(),
                     [&](const GeometryRelation& g) { return g.parameter == b.distance_parameter; }))
      throw InputError(b.where, fmt::format("missing parameter '{}' (the axis distance of {}); add it under "
                                            "[parameters]", b.distance_parameter, b.name));

  for (const auto& g : rm.relations) {
    const auto implied = value_of(g.rhs, known);
    if (!implied) continue;  // depends on a missing free radius: reported above
    const Parameter* p = find_parameter(t, g.parameter);
    if (!p) {
      if (!(*implied > 0))
        throw InputError(t.meshes[g.mesh].where,
                         fmt::format("{} makes '{}' = {:.6g} m, which is not positive; check the layout",
                                     describe_mesh(t, g.mesh), g.parameter, *implied));
      known[parameter_symbol(s, g.parameter)] = exact_number(*implied);
      rm.derived.push_back({g.parameter, *implied});
      continue;
    }
    const double given = p->value.si;
    const double gap = std::abs(given - *implied);
    // The relations are exact identities of the drawing; values typed to a few digits still
    // reproduce them to ~1e-15 relative, so 1e-9 only catches real inconsistencies.
    if (gap > 1e-9 * std::max(std::abs(given), std::abs(*implied)))
      throw GeometryConflict(p->where, ContradictedLength{g.parameter, p->text, given, describe_mesh(t, g.mesh), g.rhs,
                                                          *implied});
  }
  check_clutches_on_one_axis(t, h, solved, known);
  for (int mi : angled) rm.angled.push_back({mi, pinion_angle(t, s, mi, rm, known)});
  // With pinions at an angle, axis distances no longer describe the layout: every row is taken in
  // the frame where both its axes are fixed, in wheel radii alone (for a planet and a central wheel
  // that is the side-view row with its centre distance written out, a_p = r_s + r_p).
  if (!angled.empty()) {
    GiNaC::exmap distances;
    for (const auto& g : rm.relations)
      for (const auto& b : t.bodies)
        if (b.axis == AxisKind::carried && b.distance_parameter == g.parameter)
          distances[parameter_symbol(s, g.parameter)] = g.rhs;
    rm.R = GiNaC::ex_to<GiNaC::matrix>(rm.R.subs(distances).expand());
  }
  return rm;
}

}  // namespace pogear
