// Composes the derive stages; each stage only sees the plain results of the ones before it.
#include "derive/derivation.hpp"

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"
#include "names/model_variables.hpp"

namespace pogear {

namespace {

// The gear's elastic model with the engaged elements' rows under R: what the rigid reduction of
// that mode reads (its constraints, and the names of what they recover).
ElasticModel engaged_constraints(const Derivation& d, const std::vector<int>& engaged, const SourceLocation& where) {
  const Topology& t = d.topology;
  const GiNaC::matrix E = engagement_rows(t, engaged);
  const Eigen::MatrixXd Rn = evaluate_matrix(d.elastic.R, d.values);
  const int gear_rank = numeric_rank(Rn);
  const int n = static_cast<int>(t.bodies.size());
  const std::string names = engaged_names(t, engaged, ", ");
  // Rigid shafts join their bodies as meshes do: a clutch across one adds nothing in the rigid model.
  const std::string rows = has_shafts(t) ? "the meshes and rigid shafts" : "the meshes";
  // Element by element, so that the message names the first one that adds nothing.
  for (std::size_t k = 1; k <= engaged.size(); ++k) {
    const std::vector<int> first(engaged.begin(), engaged.begin() + k);
    if (numeric_rank(stacked_for_rank(Rn, engagement_rows(t, first))) < gear_rank + static_cast<int>(k))
      throw InputError(where, fmt::format("engaging {} adds no constraint that {} do not already impose, so its torque "
                                          "is not determined; engage fewer elements (pogear ratios lists the sets)",
                                          t.friction_elements[engaged[k - 1]].name,
                                          k == 1 ? rows : engaged_names(t, std::vector<int>(first.begin(), first.end() - 1), ", ") + " and " + rows));
  }
  if (gear_rank + static_cast<int>(engaged.size()) == n)
    throw InputError(where, fmt::format("engaging {} locks the gear: no body can turn, so there is no rigid model; "
                                        "engage fewer elements (pogear ratios lists the sets)", names));
  if (gear_rank < static_cast<int>(t.meshes.size()))
    throw InputError(where, fmt::format("the gear's meshes are redundant (rank of R {} for {} meshes), and pogear does "
                                        "not split their load with brakes or clutches engaged; leave --engaged out",
                                        gear_rank, t.meshes.size()));
  ElasticModel c = d.elastic;
  c.R = stacked(d.elastic.R, E);
  for (int k : engaged) c.forces.push_back(element_torque_name(t.friction_elements[k].name));
  return c;
}

}  // namespace

Derivation derive_topology(Topology topology, const std::optional<std::vector<std::string>>& keep,
                           const SourceLocation& keep_where, bool closed_forms, const std::vector<int>& engaged) {
  Derivation d;
  d.topology = std::move(topology);
  d.symbols = make_symbol_table(d.topology);
  d.radius = derive_radius_matrix(d.topology, d.symbols);
  d.parameters = parameter_table(d.topology, d.radius);
  for (const ParameterValue& p : d.parameters) d.values[parameter_symbol(d.symbols, p.name)] = p.exact;
  d.elastic = assemble_elastic_model(d.topology, d.radius, d.symbols);
  d.engaged = engaged;
  const ElasticModel constrained = engaged.empty() ? d.elastic : engaged_constraints(d, engaged, keep_where);
  d.constraints = constrained.R;
  SourceLocation where = keep_where;
  if (keep) {
    d.keep = *keep;
  } else if (!d.topology.default_keep.empty() && engaged.empty()) {
    d.keep = d.topology.default_keep;
    where = d.topology.keep_where;
  } else {
    // No choice made: take the first valid set, so derive always shows a reduced model.
    const auto valid = valid_keep_sets(evaluate_matrix(d.constraints, d.values), 1);
    if (!valid.empty())
      for (int b : valid[0]) d.keep.push_back(d.topology.bodies[b].name);
  }
  d.rigid = reduce_to_rigid(d.topology, constrained, d.values, d.keep, where, d.symbols, closed_forms);
  d.rigid_values = exact_rigid_values(d.rigid, d.elastic, d.values);
  return d;
}

Derivation derive_model(const std::string& model_path, const std::optional<std::vector<std::string>>& keep,
                        const SourceLocation& keep_where) {
  return derive_topology(parse_topology(model_path), keep, keep_where);
}

}  // namespace pogear
