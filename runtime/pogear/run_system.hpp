// Runs one system of a scene with the run's solver (simulate_system, the one place that picks the
// driver) and writes its CSV (run_system): what every generated main calls, and pogear's interpreted
// mode. Only the drivers of the solvers a simulator is compiled with are instantiated, for its
// fixed sizes; everything that does not depend on the model's size is in run_support.hpp, compiled
// once into libpogear_runtime.
#pragma once

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pogear/driver_loops.hpp"
#include "pogear/run_support.hpp"
#include "pogear/scene_run.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

// The solvers a simulator is compiled with: simulate_system and run_system instantiate the drivers
// of these only (each costs compile time: the exact driver twice, for SSE2 and AVX2).
template <Solver... S>
struct Solvers {
  static constexpr std::array<Solver, sizeof...(S)> list{S...};
  static constexpr bool has(Solver s) { return ((s == S) || ...); }
};
using AllSolvers = Solvers<Solver::exact, Solver::rk4, Solver::dopri5, Solver::implicit>;

// The exact method is exact for inputs linear between breakpoints, so it steps a whole sample
// period; a sine or a grade's load is held linear over the scene's `step` instead.
inline double exact_step(const SceneRun& run, const std::vector<Signal>& signals) {
  const bool piecewise_linear = std::none_of(signals.begin(), signals.end(), [](const Signal& s) {
    return std::holds_alternative<Sine>(s) || std::holds_alternative<GradeLoad>(s);
  });
  return piecewise_linear ? run.sample : std::min(run.sample, run.options.h);
}

// The signals' values at t, into u (one entry per signal).
template <class Input>
void input_values(const std::vector<Signal>& signals, double t, Input& u) {
  for (std::size_t i = 0; i < signals.size(); ++i) u(static_cast<Eigen::Index>(i)) = value(signals[i], t);
}

// Integrates dx/dt = M x + N u(t), u from `signals`, from x0 at t = 0 to run.horizon with run.solver,
// calling obs at every sample: the one place that maps a Solver to its driver. `rhs(t, x, dx)` is
// the same right-hand side with the inputs applied (a generated rhs costs less than M x + N u); the
// exact method uses M and N (discretized by the compiled runtime), the implicit one M as its constant
// Jacobian. A solver outside `Compiled` fails the run.
template <class Compiled = AllSolvers, class StateMatrix, class InputMatrix, class Rhs, class State, class Obs>
RunStatus simulate_system(const SceneRun& run, const std::vector<Signal>& signals, const StateMatrix& M,
                          const InputMatrix& N, Rhs&& rhs, const State& x0, Obs&& obs) {
  // The horizon itself among them: a step there must not be smeared over the last step.
  const std::vector<double> breaks =
      breakpoints(signals, 0.0, std::nextafter(run.horizon, std::numeric_limits<double>::infinity()));
  SolverOptions opt = run.options;
  if constexpr (Compiled::has(Solver::exact)) {
    if (run.solver == Solver::exact) {
      opt.h = exact_step(run, signals);
      if (!(run.sample > 0) || !(opt.h > 0)) return detail::Run{}.fail("invalid step: dt = " + detail::num(run.sample));
      using D = ExactDiscretization<StateMatrix::RowsAtCompileTime, InputMatrix::ColsAtCompileTime>;
      const Eigen::MatrixXd Md = M, Nd = N;
      auto discretize = [&](double h) {
        const ExactMatrices e = exact_matrices(Md, Nd, h);
        return D(e.Phi, e.Gamma0, e.Gamma1, h, e.rounding);
      };
      auto inputs = [&](double t, auto& u) { input_values(signals, t, u); };
      return simulate_exact_with(discretize(exact_nominal_step(run.sample, opt.h)), discretize, inputs, x0, 0.0,
                                 run.horizon, run.sample, opt, obs, breaks);
    }
  }
  if constexpr (Compiled::has(Solver::rk4))
    if (run.solver == Solver::rk4) return simulate_rk4(rhs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
  if constexpr (Compiled::has(Solver::dopri5))
    if (run.solver == Solver::dopri5) return simulate_dopri5(rhs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
  if constexpr (Compiled::has(Solver::implicit)) {
    if (run.solver == Solver::implicit) {
      auto jac = [&](double, const State&, StateMatrix& J) { J = M; };
      return simulate_implicit(rhs, jac, true, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    }
  }
  return RunStatus{false, "the solver " + std::string(solver_name(run.solver)) + " is not compiled in", 0.0};
}

// A divergence check from the power balance of the POG models, which are passive. With the stored
// energy E = x^T L x / 2 (L = diag(J, K^-1) elastic, L1 rigid) and L dx/dt = A x + B u, dE/dt =
// x^T A x + x^T B u <= x^T B u, as A's symmetric part is negative semidefinite (friction and damping
// only dissipate). With N = L^-1 B, Cauchy-Schwarz in the L inner product gives x^T B u =
// x^T L (N u) <= sqrt(2E) |N u|_L, so d sqrt(E)/dt <= |N u|_L / sqrt(2) and
//   sqrt(E(t)) <= sqrt(E(0)) + t W / sqrt(2),   W = sum_i |N e_i|_L max|u_i| >= max |N u(s)|_L.
// Checking it costs one quadratic form per sample, nothing per step.
template <class StateMatrix, class InputMatrix>
struct EnergyBound {
  StateMatrix L;
  // L = diag(J, K^-1) of the elastic model: E from its diagonal, contiguous, n products and not n^2.
  bool diagonal = false;
  Eigen::Matrix<double, StateMatrix::RowsAtCompileTime, 1> half_diagonal;
  double root_e0 = 0, rate = 0;  // sqrt(E(0)); W / sqrt(2)

  // sqrt(E(0)) and W / sqrt(2) from the compiled runtime (energy_bound_terms), on dynamic matrices.
  template <class State>
  EnergyBound(StateMatrix L_, const InputMatrix& N, const std::vector<Signal>& signals, const State& x0,
              double horizon)
      : L(std::move(L_)), diagonal(L.isDiagonal(0.0)), half_diagonal(0.5 * L.diagonal()) {
    const EnergyBoundTerms terms = energy_bound_terms(L, N, signals, x0, horizon);
    root_e0 = terms.root_e0;
    rate = terms.rate;
  }

  template <class State>
  double energy(const State& x) const {
    const double e = diagonal ? (x.array().square() * half_diagonal.array()).sum() : 0.5 * x.dot(L * x);
    return std::max(0.0, e);
  }

  // Whether E(t) <= (factor * bound(t))^2: one quadratic form, no square root or division.
  template <class State>
  bool within(double t, const State& x, double factor) const {
    const double bound = factor * (root_e0 + t * rate);
    return energy(x) <= bound * bound;
  }

  // sqrt(E(t)) over the bound at t: at most 1 for the exact solution.
  template <class State>
  double ratio(double t, const State& x) const {
    const double root_e = std::sqrt(energy(x)), bound = root_e0 + t * rate;
    return bound > 0 ? root_e / bound : (root_e > 0 ? std::numeric_limits<double>::infinity() : 0.0);
  }
};

// A run whose sqrt(E) exceeds the bound by this factor has diverged. The bound holds for the exact
// solution; a method's honest error at the loosest tolerance allowed (1e-2) or at a stable rk4 step
// changes sqrt(E) by a few percent, and the bound itself is loose (every input at its largest, all
// pushing the same way), while a diverging run grows without limit (3.8e10 rad/s against 26.4 for
// dopri5 at tolerance 0.2). A factor of 2, the amplitude doubled, separates the two with margin.
inline constexpr double energy_bound_safety_factor = 2;

// Runs `sys` (a generated system struct, or any object with the same members) and writes
// OUT/<name><suffix>.csv. Returns 0, or 3 when the run failed (the CSV is kept, marked incomplete).
template <class Compiled = AllSolvers, class System>
int run_system(const System& sys, const typename System::Params& p, const std::vector<Signal>& signals,
               const typename System::State& x0, const SceneRun& run, const std::string& suffix) {
  using State = typename System::State;
  using Input = typename System::Input;
  using Output = typename System::Output;
  const Eigen::Index nx = x0.size();
  const auto nu = static_cast<Eigen::Index>(signals.size());
  const auto ny = static_cast<Eigen::Index>(std::size(sys.output_names));

  typename System::StateMatrix M(nx, nx);
  typename System::InputMatrix N(nx, nu);
  sys.matrices(p, M, N);
  Input u(nu);
  Output y(ny);
  auto f = [&](double t, const State& x, State& dx) {
    input_values(signals, t, u);
    sys.rhs(p, x, u, dx);
  };

  SystemRunLog log(run, suffix, std::vector<std::string>(std::begin(sys.output_names), std::end(sys.output_names)),
                   std::vector<std::string>(std::begin(sys.output_units), std::end(sys.output_units)));
  // A generated system says whether it is nonlinear; its events are the hybrid runs' (hybrid_run.hpp).
  if constexpr (requires { bool(sys.nonlinear); }) {
    if (const auto refusal = solver_refusal(run.solver, SystemTraits{.nonlinear = bool(sys.nonlinear)})) {
      std::fprintf(stderr, "%s%s: error: the scene is nonlinear (a quadratic load), %.*s; use --solver dopri5 or implicit\n",
                   run.name.c_str(), suffix.c_str(), static_cast<int>(refusal->reason.size()), refusal->reason.data());
      return 3;
    }
  }
  if (run.solver == Solver::rk4 && !log.rk4_step_stable(M)) return 3;

  // Systems without energy_matrix (written by hand against this interface) are not checked.
  std::optional<EnergyBound<typename System::StateMatrix, typename System::InputMatrix>> energy_bound;
  if constexpr (requires(typename System::StateMatrix& L) { sys.energy_matrix(p, L); }) {
    typename System::StateMatrix L(nx, nx);
    sys.energy_matrix(p, L);
    if (L.size() > 0)  // an empty L: no bound (a speed controller feeds in power)
      energy_bound.emplace(std::move(L), N, signals, x0, run.horizon);
  }

  bool linear = true;
  if constexpr (requires { bool(sys.nonlinear); }) linear = !bool(sys.nonlinear);
  RunStatus st;
  for (int rep = 0; rep < run.repeat; ++rep) {
    if (!log.begin()) return 3;
    auto obs = [&](double t, const State& x) {
      if (energy_bound && !energy_bound->within(t, x, energy_bound_safety_factor)) {
        log.diverged(t, energy_bound->ratio(t, x), linear);
        return false;
      }
      input_values(signals, t, u);
      sys.outputs(p, x, u, y);
      if (log.writes_csv()) log.row(t, y.data(), static_cast<long>(ny));
      return true;
    };
    st = simulate_system<Compiled>(run, signals, M, N, f, x0, obs);
    if (!log.end(st)) return 3;
    if (!st.ok) break;
  }
  return log.finish(st);
}

}  // namespace pogear::rt
