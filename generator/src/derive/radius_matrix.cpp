// R: the toothed meshes' rows from the side view (derive/side_view), a row per shaft, and the fixed
// bodies' columns set apart.
#include "derive/radius_matrix.hpp"

#include <fmt/format.h>

#include "derive/side_view.hpp"

namespace pogear {

std::string describe_mesh(const Topology& t, int mesh) {
  const Mesh& m = t.meshes[mesh];
  if (m.shaft) return fmt::format("shaft {} ({} to {})", m.name, body(t, m.first.body).name, body(t, m.second.body).name);
  return fmt::format("mesh {} ({} with {})", m.name, wheel_label(t, m.first), wheel_label(t, m.second));
}

namespace {

// The toothed meshes' side view, then a row per shaft: its twist rate a_i omega_i - a_j omega_j.
RadiusMatrix with_shaft_rows(const Topology& t, const SymbolTable& s) {
  const std::size_t toothed = toothed_mesh_count(t);
  if (toothed == t.meshes.size()) return derive_side_view(t, s);
  Topology gear = t;
  gear.meshes.resize(toothed);  // the shafts follow the toothed meshes
  RadiusMatrix rm = derive_side_view(gear, s);
  const unsigned m = t.meshes.size(), n = t.bodies.size();
  GiNaC::matrix R(m, n);
  for (unsigned i = 0; i < toothed; ++i)
    for (unsigned k = 0; k < n; ++k) R(i, k) = rm.R(i, k);
  for (unsigned i = toothed; i < m; ++i) {
    const Mesh& shaft = t.meshes[i];
    R(i, static_cast<unsigned>(shaft.first.body)) = t.bodies[static_cast<std::size_t>(shaft.first.body)].arrow;
    R(i, static_cast<unsigned>(shaft.second.body)) = -t.bodies[static_cast<std::size_t>(shaft.second.body)].arrow;
  }
  rm.R = R;
  rm.sides.resize(m);
  return rm;
}

}  // namespace

RadiusMatrix derive_radius_matrix(const Topology& t, const SymbolTable& s) {
  if (t.grounded.empty()) return with_shaft_rows(t, s);
  Topology all = t;
  all.bodies.insert(all.bodies.end(), t.grounded.begin(), t.grounded.end());
  all.grounded.clear();
  RadiusMatrix rm = with_shaft_rows(all, s);
  // A fixed body's omega is 0: its column drops out of every contact velocity.
  const unsigned m = rm.R.rows(), n = t.bodies.size(), g = t.grounded.size();
  GiNaC::matrix turning(m, n);
  rm.fixed_columns.assign(g, GiNaC::exvector(m));
  for (unsigned i = 0; i < m; ++i) {
    for (unsigned k = 0; k < n; ++k) turning(i, k) = rm.R(i, k);
    for (unsigned k = 0; k < g; ++k) rm.fixed_columns[k][i] = rm.R(i, n + k);
  }
  rm.R = turning;
  return rm;
}

GiNaC::exmap geometry_substitutions(const RadiusMatrix& rm, const SymbolTable& s) {
  GiNaC::exmap m;
  for (const auto& g : rm.relations) m[parameter_symbol(s, g.parameter)] = g.rhs;
  return m;
}

}  // namespace pogear
