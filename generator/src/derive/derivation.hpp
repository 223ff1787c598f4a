// The derive pipeline end to end: model file -> topology -> R -> elastic model -> rigid model.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "derive/parameter_table.hpp"
#include "derive/rigid_model.hpp"

namespace pogear {

struct Derivation {
  Topology topology;
  SymbolTable symbols;  // made once from the topology; no stage adds to it
  RadiusMatrix radius;
  std::vector<ParameterValue> parameters;  // the parameter table, the derived radii included
  GiNaC::exmap values;  // every parameter of the table as its exact number
  ElasticModel elastic;
  RigidModel rigid;
  std::vector<int> engaged;      // brakes and clutches stuck (indices, ascending); the rigid model is theirs
  GiNaC::matrix constraints;     // the rigid model's: R, or [R; E_S] with elements S engaged
  std::vector<std::string> keep;
  RigidValues rigid_values;  // Q1, L1, A1 at the model's values, exact
};

// `keep` overrides the model's default; `keep_where` locates it in messages. Without
// `closed_forms` the rigid model's L1, A1, B1 are left empty (see reduce_to_rigid).
Derivation derive_model(const std::string& model_path, const std::optional<std::vector<std::string>>& keep,
                        const SourceLocation& keep_where);
// With `engaged` (friction element indices) the rigid model is that mode's: constraints
// [R; E_S], its Q1 and closed forms, the mesh forces and the engaged elements' torques; the
// default kept set is then the first valid one. Throws InputError at `keep_where` when the
// engaged elements lock the gear, when one of them adds no constraint to the others (its torque
// is then not determined), or when the meshes are redundant (their split with stuck elements is
// not derived).
Derivation derive_topology(Topology topology, const std::optional<std::vector<std::string>>& keep,
                           const SourceLocation& keep_where, bool closed_forms = true,
                           const std::vector<int>& engaged = {});

}  // namespace pogear
