// Composes the derive stages; each stage only sees the plain results of the ones before it.
#include "derivation.hpp"

#include <fmt/format.h>

#include "exact_algebra.hpp"
#include "vibration_modes.hpp"

namespace pogear {

Derivation derive_topology(Topology topology, const std::optional<std::vector<std::string>>& keep,
                           const SourceLocation& keep_where, bool closed_forms) {
  Derivation d;
  d.topology = std::move(topology);
  d.symbols = make_symbol_table(d.topology);
  d.radius = derive_radius_matrix(d.topology, d.symbols);
  d.values = numeric_substitutions(d.symbols, parameter_values(d.topology, d.radius));
  d.elastic = assemble_elastic_model(d.topology, d.radius, d.symbols);
  SourceLocation where = keep_where;
  if (keep) {
    d.keep = *keep;
  } else if (!d.topology.default_keep.empty()) {
    d.keep = d.topology.default_keep;
    where = d.topology.keep_where;
  } else {
    // No choice made: take the first valid set, so derive always shows a reduced model.
    const auto valid = valid_keep_sets(evaluate_matrix(d.elastic.R, d.values), 1);
    if (!valid.empty())
      for (int b : valid[0]) d.keep.push_back(d.topology.bodies[b].name);
  }
  d.rigid = reduce_to_rigid(d.topology, d.elastic, d.values, d.keep, where, d.symbols, closed_forms);
  const GiNaC::exmap& at = d.values;
  const Eigen::MatrixXd L = evaluate_matrix(d.elastic.L, at);
  const Eigen::MatrixXd M = L.diagonal().cwiseInverse().asDiagonal() * evaluate_matrix(d.elastic.A, at);
  d.rigid_values = exact_rigid_values(d.rigid, d.elastic, at);
  d.diagnostics = diagnose(M, evaluate_matrix(d.rigid_values.L1, {}), evaluate_matrix(d.elastic.R, at));
  add_natural_frequency(d.diagnostics, d, at);
  return d;
}

Derivation derive_model(const std::string& model_path, const std::optional<std::vector<std::string>>& keep,
                        const SourceLocation& keep_where) {
  return derive_topology(parse_topology(model_path), keep, keep_where);
}

}  // namespace pogear
