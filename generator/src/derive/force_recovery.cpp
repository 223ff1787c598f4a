// See force_recovery.hpp: eq. (8) through the sparsest bodies S, or F = K R (R^T K R)^+ g with
// its weights as numbers (docs/design.md §4).
#include "derive/force_recovery.hpp"

#include <algorithm>
#include <numeric>

#include "common/block_triangular_solve.hpp"
#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"

namespace pogear {

using GiNaC::ex;

ForceRecovery recover_mesh_forces(const Topology& t, const ElasticModel& e, const GiNaC::matrix& Q1,
                                  const std::vector<int>& kept, int rank, const Eigen::MatrixXd& Rn,
                                  const GiNaC::exmap& values, const SymbolTable& s) {
  const int n = static_cast<int>(t.bodies.size());
  const unsigned k = kept.size();
  ForceRecovery out;
  // Eq. (8) needs R R^T invertible; with redundant meshes it is not (docs/design.md §4).
  const int m = static_cast<int>(e.R.rows());  // meshes, and stuck elements when engaged
  out.redundant_meshes = rank < m;
  if (out.redundant_meshes) {
    // docs/design.md §4: the elastic model's limit splits the load as F = K R (R^T K R)^+ g. On the
    // rigid model g is orthogonal to ker R = span Q1, and on that subspace (R^T K R)^+ equals
    // (R^T K R + Q1 Q1^T)^-1, an ordinary inverse. The split depends on stiffness ratios, so
    // its weights are numbers at the model's values, computed exactly and then rounded.
    const GiNaC::matrix Kx = exact_matrix(e.K, values);
    const GiNaC::matrix Rx = exact_matrix(e.R, values);
    const GiNaC::matrix Qx = exact_matrix(Q1, values);
    const GiNaC::matrix S = Rx.transpose().mul(Kx).mul(Rx).add(Qx.mul(Qx.transpose()));
    const GiNaC::matrix W = Kx.mul(Rx).mul(S.inverse());  // m x n
    for (int i = 0; i < m; ++i) {
      ex f = 0;
      for (int b = 0; b < n; ++b) {
        const ex& w = W(i, b);
        if (W(i, b).is_zero()) continue;
        ex g = variable_symbol(s, {VariableKind::torque, b});
        for (unsigned j = 0; j < k; ++j)
          g -= e.J(b, b) * Q1(b, j) * variable_symbol(s, {VariableKind::acceleration, kept[j]}) +
               e.B_J(b, b) * Q1(b, j) * variable_symbol(s, {VariableKind::velocity, kept[j]});
        f += w * g;
      }
      out.forces.push_back(f);
    }
  } else {
    out.force_bodies = force_recovery_bodies(Rn);
    // On the rigid model g = tau - J Q1 x1' - B_J Q1 x1 lies in range(R^T), so eq. (8)'s
    // (R R^T)^-1 R g equals (R_S^T)^-1 g_S for any m bodies S with independent columns of R.
    // The sparsest S gives the shortest expressions, e.g. F_sg = -g_g/r_g.
    GiNaC::matrix RSt(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) RSt(i, j) = e.R(j, out.force_bodies[i]);
    // (R_S^T)^-1; R_S^T is as sparse as R (block triangular along a chain).
    const GiNaC::matrix P = block_triangular_solve(RSt, GiNaC::ex_to<GiNaC::matrix>(GiNaC::unit_matrix(m)));
    for (int i = 0; i < m; ++i) {
      ex f = 0;
      std::vector<ex> inertial(k, 0), friction(k, 0);
      for (int a = 0; a < m; ++a) {
        const int b = out.force_bodies[a];
        const ex p = P(i, a).normal();
        if (p.is_zero()) continue;
        f += p * variable_symbol(s, {VariableKind::torque, b});
        for (unsigned j = 0; j < k; ++j) {
          inertial[j] += p * e.J(b, b) * Q1(b, j);
          friction[j] += p * e.B_J(b, b) * Q1(b, j);
        }
      }
      for (unsigned j = 0; j < k; ++j) {
        f -= inertial[j].normal() * variable_symbol(s, {VariableKind::acceleration, kept[j]});
        f -= friction[j].normal() * variable_symbol(s, {VariableKind::velocity, kept[j]});
      }
      out.forces.push_back(f);
    }
  }
  return out;
}

std::vector<int> force_recovery_bodies(const Eigen::MatrixXd& Rn) {
  std::vector<int> order(Rn.cols());
  std::iota(order.begin(), order.end(), 0);
  auto nonzeros = [&](int j) { return (Rn.col(j).array() != 0.0).count(); };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return nonzeros(a) < nonzeros(b); });
  std::vector<int> picked;
  for (int j : order) {
    picked.push_back(j);
    if (numeric_rank(columns(Rn, picked)) < static_cast<int>(picked.size())) picked.pop_back();
    if (picked.size() == static_cast<std::size_t>(Rn.rows())) break;
  }
  std::sort(picked.begin(), picked.end());
  return picked;
}

std::vector<GiNaC::ex> fixed_body_torques(const Topology& t, const std::vector<GiNaC::exvector>& fixed_columns,
                                          const std::vector<GiNaC::ex>& forces) {
  std::vector<GiNaC::ex> torques;
  for (std::size_t k = 0; k < fixed_columns.size(); ++k) {
    GiNaC::ex torque = 0;
    for (std::size_t i = 0; i < fixed_columns[k].size(); ++i) torque -= fixed_columns[k][i] * forces[i];
    torques.push_back((t.grounded[k].arrow * torque).expand());
  }
  return torques;
}

}  // namespace pogear
