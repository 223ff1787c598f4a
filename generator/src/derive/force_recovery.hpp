// The mesh forces of the rigid model, recovered from its accelerations: eq. (8), or the
// stiffness-weighted split when the meshes are redundant.
#pragma once

#include <vector>

#include <Eigen/Dense>
#include <ginac/ginac.h>

#include "derive/elastic_model.hpp"

namespace pogear {

// See RigidModel::force_recovery: one expression per mesh, the bodies S of eq. (8) (empty when
// the meshes are redundant) and whether they are.
struct ForceRecovery {
  std::vector<GiNaC::ex> forces;
  std::vector<int> force_bodies;
  bool redundant_meshes = false;
};

// For the rigid model omega = Q1 x1 with x1 the velocities of the bodies `kept`; `rank` is R's
// rank, `Rn` R at the model's `values`.
ForceRecovery recover_mesh_forces(const Topology& t, const ElasticModel& e, const GiNaC::matrix& Q1,
                                  const std::vector<int>& kept, int rank, const Eigen::MatrixXd& Rn,
                                  const GiNaC::exmap& values, const SymbolTable& s);

// The torque each fixed body puts on the housing, as a stuck brake holding it would take it (T in
// one rotation sense, acting as -T on the body): the meshes' torque on it, -a column . F, a its
// arrow, with F the recovered `forces` (meshes first).
std::vector<GiNaC::ex> fixed_body_torques(const Topology& t, const std::vector<GiNaC::exvector>& fixed_columns,
                                          const std::vector<GiNaC::ex>& forces);

// m bodies whose columns of R are independent, preferring sparse columns (short expressions).
std::vector<int> force_recovery_bodies(const Eigen::MatrixXd& R_numeric);

}  // namespace pogear
