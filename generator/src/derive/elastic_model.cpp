// L = diag(J, K^-1), A = [-B_J - R^T B_K R, -R^T; R, 0], B = [I; 0].
#include "derive/elastic_model.hpp"

namespace pogear {

ElasticModel assemble_elastic_model(const Topology& t, const RadiusMatrix& rm, const SymbolTable& s) {
  const unsigned n = t.bodies.size();
  const unsigned m = t.meshes.size();
  ElasticModel e;
  e.J = GiNaC::matrix(n, n);
  e.B_J = GiNaC::matrix(n, n);
  e.K = GiNaC::matrix(m, m);
  e.B_K = GiNaC::matrix(m, m);
  for (unsigned k = 0; k < n; ++k) {
    e.velocities.push_back(variable_name(t, {VariableKind::velocity, static_cast<int>(k)}));
    e.torques.push_back(variable_name(t, {VariableKind::torque, static_cast<int>(k)}));
    // A lumped planet is its count of planets turning together: their inertia and friction add.
    const int count = t.bodies[k].count;
    e.J(k, k) = count * parameter_symbol(s, t.bodies[k].inertia_parameter);
    e.B_J(k, k) = count * parameter_symbol(s, t.bodies[k].friction_parameter);
  }
  for (unsigned i = 0; i < m; ++i) {
    e.forces.push_back(variable_name(t, {VariableKind::force, static_cast<int>(i)}));
    // Its planets' meshes act in parallel, so F_<mesh> here is the sum of their forces.
    const int count = mesh_count(t, t.meshes[i]);
    e.K(i, i) = count * parameter_symbol(s, t.meshes[i].stiffness_parameter);
    e.B_K(i, i) = count * parameter_symbol(s, t.meshes[i].damping_parameter);
  }
  e.R = rm.R;
  const GiNaC::matrix Rt = e.R.transpose();
  const GiNaC::matrix damping = e.B_J.add(Rt.mul(e.B_K).mul(e.R));

  e.L = GiNaC::matrix(n + m, n + m);
  e.A = GiNaC::matrix(n + m, n + m);
  e.B = GiNaC::matrix(n + m, n);
  for (unsigned i = 0; i < n; ++i) {
    e.L(i, i) = e.J(i, i);
    e.B(i, i) = 1;
    for (unsigned j = 0; j < n; ++j) e.A(i, j) = (-damping(i, j)).expand();
    for (unsigned j = 0; j < m; ++j) e.A(i, n + j) = -Rt(i, j);
  }
  for (unsigned i = 0; i < m; ++i) {
    e.L(n + i, n + i) = 1 / e.K(i, i);
    for (unsigned j = 0; j < n; ++j) e.A(n + i, j) = e.R(i, j);
  }
  return e;
}

}  // namespace pogear
