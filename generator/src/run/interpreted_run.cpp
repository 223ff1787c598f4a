// The interpreted path: the numeric model's matrices wrapped in the members run_system and
// simulate_system expect of a generated system.
#include "run/interpreted_run.hpp"

#include <algorithm>
#include <cmath>
#include <string>
#include <utility>

#include <Eigen/SparseCore>
#include <fmt/format.h>

#include "pogear/hybrid_run.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/element_thermal.hpp"
#include "specialize/torque_limits.hpp"
#include "specialize/triggered_signals.hpp"

namespace pogear {
namespace {

// A system with the generated structs' members, on dynamic matrices, from the numeric model.
// The output maps are sparse, as the generated expressions are: a structural zero must not turn
// an overflowed (infinite) rate into NaN through 0 * inf, where the compiled path writes inf.
struct InterpretedSystem {
  InterpretedSystem(NumericSystem numeric, std::vector<std::string> names, std::vector<std::string> units)
      : ns(std::move(numeric)), output_names(std::move(names)), output_units(std::move(units)),
        C(ns.C.sparseView()), D(ns.D.sparseView()), E(ns.E.sparseView()) {}

  using State = Eigen::VectorXd;
  using Input = Eigen::VectorXd;
  using Output = Eigen::VectorXd;
  using StateMatrix = Eigen::MatrixXd;
  using InputMatrix = Eigen::MatrixXd;
  struct Params {};
  NumericSystem ns;
  std::vector<std::string> output_names, output_units, state_units;
  Eigen::SparseMatrix<double> C, D, E;

  // A quadratic load's torque -c s |s| at the state x.
  static double load_torque(const QuadraticLoad& q, const State& x) {
    const double s = q.speed_row.dot(x);
    return -q.coefficient * s * std::abs(s);
  }
  void rhs(const Params&, const State& x, const Input& u, State& dx) const {
    dx.noalias() = ns.M * x;
    if (u.size()) dx.noalias() += ns.N * u;
    for (const QuadraticLoad& q : ns.quadratic) dx += load_torque(q, x) * q.state_column;
  }
  void outputs(const Params&, const State& x, const Input& u, Output& y) const {
    State dx(x.size());
    rhs({}, x, u, dx);
    y.noalias() = C * x;
    y.noalias() += E * dx;
    if (u.size()) y.noalias() += D * u;
    for (const QuadraticLoad& q : ns.quadratic) {
      y += load_torque(q, x) * q.output_column;
      y += -2 * q.coefficient * std::abs(q.speed_row.dot(x)) * q.speed_row.dot(dx) * q.rate_output_column;
    }
  }
  void matrices(const Params&, StateMatrix& M, InputMatrix& N) const {
    M = ns.M;
    N = ns.N;
  }
  void energy_matrix(const Params&, StateMatrix& L) const { L = ns.L; }  // empty: no bound (controllers)
  bool nonlinear = !ns.quadratic.empty();
  void quadratic_loads(const Params&, Eigen::MatrixXd& columns, Eigen::MatrixXd& speeds, Eigen::VectorXd& c) const {
    const auto nq = static_cast<Eigen::Index>(ns.quadratic.size());
    columns.resize(ns.M.rows(), nq);
    speeds.resize(nq, ns.M.rows());
    c.resize(nq);
    for (Eigen::Index i = 0; i < nq; ++i) {
      const QuadraticLoad& q = ns.quadratic[static_cast<std::size_t>(i)];
      columns.col(i) = q.state_column;
      speeds.row(i) = q.speed_row.transpose();
      c(i) = q.coefficient;
    }
  }
  void slip_matrix(const Params&, Eigen::MatrixXd& S) const { S = ns.S; }
  rt::DrivelineData driveline_data;  // a converter's and an engine's
  const rt::DrivelineData& driveline(const Params&) const { return driveline_data; }
  void torque_limit_laws(const Params&, Eigen::MatrixXd& X, Eigen::MatrixXd& W) const {
    X = ns.limit_x;
    W = ns.limit_u;
  }
};

std::vector<rt::FrictionElementData> friction_data(const SpecializedScene& model) {
  std::vector<rt::FrictionElementData> out;
  for (const FrictionRun& f : model.friction) out.push_back(element_data(f));
  return out;
}

int run_one_interpreted(const SpecializedScene& model, const SpecializedSystem& sys, const rt::SceneRun& run,
                        const std::string& suffix) {
  InterpretedSystem is{numeric_system(model, sys), port_names(model.derivation.symbols, output_variables(sys)),
                       output_units(model.derivation.topology, sys)};
  is.state_units = state_units(model.derivation.topology, sys);
  is.driveline_data = driveline_data(model.scene, sys, is.ns.driveline_speeds);
  if (!sys.friction_elements.empty() || !sys.limited_controllers.empty() || !sys.driveline.empty()) {
    std::vector<rt::TriggeredSignal> triggered = triggered_signals(model, sys);
    std::vector<rt::TorqueLimitData> limits = torque_limit_data(model, sys, triggered);
    return rt::run_hybrid_system(is, {}, input_signals(sys), friction_data(model), std::move(limits), is.ns.x0, run,
                                 suffix, std::move(triggered), element_thermal(model));
  }
  return rt::run_system(is, {}, input_signals(sys), is.ns.x0, run, suffix);
}

}  // namespace

int run_interpreted(const SpecializedScene& model, const rt::SceneRun& run) {
  int status = run_one_interpreted(model, model.main, run, "");
  if (status == 0 && model.rigid) status = run_one_interpreted(model, *model.rigid, run, ".rigid");
  return status;
}

Trajectory interpret_trajectory(const SpecializedScene& model, const SpecializedSystem& sys, const rt::SceneRun& run) {
  const InterpretedSystem is{numeric_system(model, sys), port_names(model.derivation.symbols, output_variables(sys)),
                             output_units(model.derivation.topology, sys)};
  const std::vector<rt::Signal> signals = input_signals(sys);
  Eigen::VectorXd u(static_cast<Eigen::Index>(signals.size())), y(sys.outputs.size());
  auto f = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    rt::input_values(signals, t, u);
    is.rhs({}, x, u, dx);
  };
  Trajectory tr;
  if (const auto refusal = rt::solver_refusal(run.solver, {.nonlinear = is.nonlinear})) {
    tr.status = {false, fmt::format("the scene is nonlinear (a quadratic load), {}", refusal->reason), 0.0};
    return tr;
  }
  auto obs = [&](double t, const Eigen::VectorXd& x) {
    rt::input_values(signals, t, u);
    is.outputs({}, x, u, y);
    tr.t.push_back(t);
    tr.x.push_back(x);
    tr.y.push_back(y);
  };
  tr.status = rt::simulate_system(run, signals, is.ns.M, is.ns.N, f, is.ns.x0, obs);
  return tr;
}

}  // namespace pogear
