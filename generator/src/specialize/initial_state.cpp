// See initial_state.hpp. The named speeds are conditions on x1 (rows of Q1); their consistency is
// judged on the least-squares residual, which lies in the left null space of those rows: its
// direction is the kinematic relation the named speeds violate.
#include "specialize/initial_state.hpp"

#include <algorithm>
#include <cmath>

#include <Eigen/QR>
#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"
#include "specialize/parameter_folding.hpp"
#include "names/model_variables.hpp"

namespace pogear {

namespace {

// The residual y of the least-squares solve satisfies y^T A = 0: sum_i y_i omega_i = 0 is a relation
// of the gear's kinematics among the named bodies, and y^T b != 0 is by how much the named speeds miss it.
InputError contradicted_kinematics(const Scene& scene, const Topology& t, const std::vector<int>& named,
                                   const Eigen::VectorXd& residual, const Eigen::VectorXd& b) {
  Eigen::VectorXd y = residual / residual.cwiseAbs().maxCoeff();
  std::string relation, bodies;
  for (std::size_t i = 0; i < named.size(); ++i) {
    const double c = y(static_cast<Eigen::Index>(i));
    if (std::abs(c) < 1e-9) continue;
    const std::string name = variable_name(t, {VariableKind::velocity, named[i]});
    bodies += (bodies.empty() ? "" : ", ") + name;
    const std::string coefficient = std::abs(std::abs(c) - 1) < 1e-12 ? "" : fmt::format("{:.6g}*", std::abs(c));
    relation += relation.empty() ? (c < 0 ? "-" : "") : (c < 0 ? " - " : " + ");
    relation += coefficient + name;
  }
  return InputError(scene.initial_where,
                    fmt::format("the initial speeds {} contradict the gear's kinematics, which require {} = 0 (with these "
                                "speeds it is {:.6g} rad/s); give speeds that satisfy it, or name fewer bodies",
                                bodies, relation, y.dot(b)));
}

}  // namespace

std::vector<double> rigid_initial_state(const Scene& scene, const Derivation& d, const GiNaC::exmap& values) {
  const Topology& t = d.topology;
  const std::vector<int>& kept = d.rigid.kept;
  const int k1 = static_cast<int>(kept.size());
  std::vector<int> named;  // bodies, ascending
  for (const auto& [v, value] : scene.initial)
    if (v.kind == VariableKind::velocity) named.push_back(v.index);
  if (named.empty()) return std::vector<double>(k1, 0.0);

  const Eigen::MatrixXd Q1 = evaluate_matrix(d.rigid.Q1, values);
  const int g = static_cast<int>(named.size());
  Eigen::MatrixXd A(g, k1);
  Eigen::VectorXd b(g);
  for (int i = 0; i < g; ++i) {
    A.row(i) = Q1.row(named[i]);
    b(i) = scene.initial.at(Variable{VariableKind::velocity, named[i]});
  }
  // Q1's rows are exact ratios of radii, of order one: a genuine dependency cancels to ~1e-16,
  // and speeds that agree with the kinematics leave a residual of that order times the speeds.
  const Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(A);
  const Eigen::VectorXd x = qr.solve(b);
  const Eigen::VectorXd residual = b - A * x;
  const double scale = b.cwiseAbs().maxCoeff();
  if (residual.cwiseAbs().maxCoeff() > 1e-9 * std::max(scale, 1e-300) && scale > 0)
    throw contradicted_kinematics(scene, t, named, residual, b);
  if (qr.rank() == k1) return std::vector<double>(x.data(), x.data() + k1);

  // Freedom left: kept bodies not named at rest, in the kept order, each only if it adds a condition.
  Eigen::MatrixXd Aa = A;
  Eigen::VectorXd ba = b;
  int rank = static_cast<int>(qr.rank());
  for (int j = 0; j < k1 && rank < k1; ++j) {
    if (std::find(named.begin(), named.end(), kept[j]) != named.end()) continue;
    Eigen::MatrixXd trial(Aa.rows() + 1, k1);
    trial << Aa, Eigen::RowVectorXd::Unit(k1, j);
    const int r = numeric_rank(trial);
    if (r == rank) continue;
    Aa = trial;
    ba.conservativeResize(ba.size() + 1);
    ba(ba.size() - 1) = 0;
    rank = r;
  }
  Eigen::VectorXd xa = Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(Aa).solve(ba);
  // Kept bodies at rest by the rule are exactly at rest (the solve leaves ~1e-16 of the speeds).
  for (Eigen::Index r = g; r < Aa.rows(); ++r) {
    Eigen::Index j = 0;
    Aa.row(r).cwiseAbs().maxCoeff(&j);
    xa(j) = 0;
  }
  return std::vector<double>(xa.data(), xa.data() + k1);
}

std::string initial_deflection_note(const SpecializedScene& model) {
  const SpecializedSystem& sys = model.main;
  if (sys.kind != SystemKind::elastic) return "";
  const Derivation& d = model.derivation;
  const GiNaC::exmap& values = model.values.numbers;
  const Eigen::MatrixXd R = evaluate_matrix(d.elastic.R, values);
  const Eigen::VectorXd J = evaluate_matrix(d.elastic.J, values).diagonal();
  const Eigen::VectorXd K = evaluate_matrix(d.elastic.K, values).diagonal();
  Eigen::VectorXd omega = Eigen::VectorXd::Zero(R.cols());
  for (const StatePort& x : sys.states)
    if (x.variable.kind == VariableKind::velocity) omega(x.variable.index) = x.initial;
  const Eigen::VectorXd rate = R * omega;
  // R's rows are radii: rates below 1e-12 of the largest |r omega| are the rounding of consistent speeds.
  const double scale = (R.cwiseAbs() * omega.cwiseAbs()).maxCoeff();
  std::string s;
  for (Eigen::Index i = 0; i < rate.size(); ++i) {
    if (!(std::abs(rate(i)) > 1e-12 * scale)) continue;
    // The mesh alone between its bodies: effective mass 1 / (R_i J^-1 R_i^T), and the spring force
    // that stops a relative speed v on it is v sqrt(K m) (undamped, the other meshes left out).
    // A lumped planet's mesh carries its planets' sum; the note gives one planet's share.
    const double mass = 1 / R.row(i).cwiseAbs2().dot(J.cwiseInverse());
    const Mesh& m = d.topology.meshes[static_cast<std::size_t>(i)];
    const double count = mesh_count(d.topology, m);
    const double force = std::abs(rate(i)) * std::sqrt(K(i) * mass) / count;
    if (m.shaft)  // a twist rate and a torque, on the shaft's effective inertia
      s += fmt::format("initial speeds twist shaft {} at {:.4g} rad/s (they break the rigid kinematics): a torque of "
                       "the order of {:.3g} N m, w sqrt(K J) on the shaft's effective inertia; name the speeds of a "
                       "rigid motion, or start from the rigid model's state (compare_rigid = true, or start = "
                       "\"rigid\")\n", m.name, rate(i), force * m.output_scale);
    else
      s += fmt::format("initial speeds deflect mesh {} at {:.4g} m/s (they break the rigid kinematics): a force of the "
                       "order of {:.3g} N, v sqrt(K m) on the mesh's effective mass; name the speeds of a rigid motion, "
                       "or start from the rigid model's state (compare_rigid = true, or start = \"rigid\")\n",
                       m.name, rate(i), force);
  }
  return s;
}

}  // namespace pogear
