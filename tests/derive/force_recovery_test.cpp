// The recovered mesh forces put back into the elastic model's body equations: on a rigid motion
// (accelerations from the rigid model L1 x1' = A1 x1 + B1 u) every body's torque balance
// J omega' = -B_J omega + (A's force columns) F + tau holds exactly, at the model's values, for
// arbitrary rational speeds and input torques. Eq. (8) uses only the bodies S; the other bodies'
// equations are the independent check.
#include <gtest/gtest.h>
#include <ginac/ginac.h>

#include "../support/files.hpp"
#include "derive/derivation.hpp"
#include "test_support.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::numeric;

matrix at_values(const matrix& m, const GiNaC::exmap& values) {
  return GiNaC::ex_to<matrix>(GiNaC::ex(m).subs(values).evalm());
}

void expect_body_equations_hold(const Derivation& d) {
  const Topology& t = d.topology;
  const RigidModel& r = d.rigid;
  const ElasticModel& e = d.elastic;
  const unsigned n = t.bodies.size(), m = t.meshes.size(), k = r.kept.size();
  ASSERT_FALSE(r.redundant_meshes) << t.name << ": eq. (8) holds only without redundant meshes";
  GiNaC::exmap at = d.values;
  matrix x1(k, 1), u(n, 1);
  for (unsigned i = 0; i < k; ++i) {
    x1(i, 0) = numeric(3 + 2 * static_cast<int>(i), 7);
    at[variable_symbol(d.symbols, {VariableKind::velocity, r.kept[i]})] = x1(i, 0);
  }
  for (unsigned b = 0; b < n; ++b) {
    u(b, 0) = numeric(static_cast<int>(b) - 2, 5);
    at[variable_symbol(d.symbols, {VariableKind::torque, static_cast<int>(b)})] = u(b, 0);
  }
  const matrix L1 = at_values(r.L1, at), A1 = at_values(r.A1, at), B1 = at_values(r.B1, at);
  const matrix dx1 = L1.inverse().mul(A1.mul(x1).add(B1.mul(u)));
  for (unsigned i = 0; i < k; ++i) at[variable_symbol(d.symbols, {VariableKind::acceleration, r.kept[i]})] = dx1(i, 0);
  const matrix Q1 = at_values(r.Q1, at);
  const matrix omega = Q1.mul(x1), domega = Q1.mul(dx1);
  matrix x(n + m, 1);
  for (unsigned b = 0; b < n; ++b) x(b, 0) = omega(b, 0);
  ASSERT_GE(r.force_recovery.size(), m);
  for (unsigned j = 0; j < m; ++j) x(n + j, 0) = r.force_recovery[j].subs(at);
  const matrix L = at_values(e.L, at), A = at_values(e.A, at), B = at_values(e.B, at);
  for (unsigned b = 0; b < n; ++b) {
    ex residual = 0;
    for (unsigned j = 0; j < n; ++j) residual += L(b, j) * domega(j, 0);
    for (unsigned j = 0; j < m; ++j) ASSERT_TRUE(L(b, n + j).is_zero()) << "L is block diagonal";
    for (unsigned j = 0; j < n + m; ++j) residual -= A(b, j) * x(j, 0);
    for (unsigned j = 0; j < n; ++j) residual -= B(b, j) * u(j, 0);
    EXPECT_TRUE(residual.normal().is_zero()) << t.name << ", body " << t.bodies[b].name << ": " << residual.normal();
  }
}

TEST(ForceRecovery, BodyEquationsHoldOnTheRigidMotionOfThePaperGears) {
  expect_body_equations_hold(derive_file("paper_one_stage"));
  expect_body_equations_hold(derive_file("paper_two_stage"));
}

TEST(ForceRecovery, BodyEquationsHoldForEveryKeptSet) {
  // The same forces whichever velocities the rigid model keeps.
  expect_body_equations_hold(derive_paper("paper_one_stage", {"c", "r"}));
  expect_body_equations_hold(derive_paper("paper_one_stage", {"s", "r"}));
}

TEST(ForceRecovery, OneMeshByHand) {
  // tests/vibration/pair.toml: a (r_a, J_a) meshing b (r_b, J_b), no friction, torque tau_a only.
  // Rigid, omega_b = -(r_a / r_b) omega_a (b turns the other way) and the mesh force accelerates b:
  // |F| r_b = J_b |omega_b'|, with (J_a + J_b r_a^2 / r_b^2) omega_a' = tau_a.
  const std::string path = source_path("tests/vibration/pair.toml");
  const Derivation d = derive_model(path, std::vector<std::string>{"a"}, SourceLocation{path, 0, 0});
  expect_body_equations_hold(d);
  const double r_a = 0.10, r_b = 0.25, J_a = 0.02, J_b = 0.3, tau_a = 1.5;
  GiNaC::exmap at = d.values;
  at[variable_symbol(d.symbols, {VariableKind::torque, 0})] = numeric(3, 2);
  at[variable_symbol(d.symbols, {VariableKind::torque, 1})] = 0;
  at[variable_symbol(d.symbols, {VariableKind::velocity, 0})] = 0;
  const double domega_a = tau_a / (J_a + J_b * r_a * r_a / (r_b * r_b));
  at[variable_symbol(d.symbols, {VariableKind::acceleration, 0})] = exact_number(domega_a);
  const double F = GiNaC::ex_to<numeric>(d.rigid.force_recovery[0].subs(at).evalf()).to_double();
  // Rounding of the double domega_a only.
  EXPECT_NEAR(std::abs(F), J_b * (r_a / r_b) * domega_a / r_b, 1e-12);
}

}  // namespace
}  // namespace pogear::test
