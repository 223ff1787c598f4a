// Runs one system of a scene with the run's solver (simulate_system, the one place that picks the
// driver) and writes its CSV (run_system): the part of every generated main that does not depend
// on the model, shared with pogear's interpreted mode.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <variant>
#include <vector>

#include "pogear/command_line.hpp"
#include "pogear/csv.hpp"
#include "pogear/drivers.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

// The exact method is exact for inputs linear between breakpoints, so it steps a whole sample
// period; a sine is held linear over the scene's `step` instead.
inline double exact_step(const SceneRun& run, const std::vector<Signal>& signals) {
  const bool piecewise_linear = std::none_of(signals.begin(), signals.end(),
                                             [](const Signal& s) { return std::holds_alternative<Sine>(s); });
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
// exact method uses M and N, the implicit one M as its constant Jacobian.
template <class StateMatrix, class InputMatrix, class Rhs, class State, class Obs>
RunStatus simulate_system(const SceneRun& run, const std::vector<Signal>& signals, const StateMatrix& M,
                          const InputMatrix& N, Rhs&& rhs, const State& x0, Obs&& obs) {
  const std::vector<double> breaks = breakpoints(signals, 0.0, run.horizon);
  SolverOptions opt = run.options;
  switch (run.solver) {
    case Solver::exact: {
      opt.h = exact_step(run, signals);
      auto inputs = [&](double t, auto& u) { input_values(signals, t, u); };
      return simulate_exact(M, N, inputs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    }
    case Solver::rk4: return simulate_rk4(rhs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    case Solver::dopri5: return simulate_dopri5(rhs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    case Solver::implicit: {
      auto jac = [&](double, const State&, StateMatrix& J) { J = M; };
      return simulate_implicit(rhs, jac, true, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    }
  }
  return RunStatus{false, "unknown solver", 0.0};
}

// The largest |u(t)| of a signal over [t0, t1]: a sine's offset plus its amplitude; every other
// signal is linear between its breakpoints, so its extremes are at the ends and on either side of a
// breakpoint.
inline double input_bound(const Signal& s, double t0, double t1) {
  if (const auto* sine = std::get_if<Sine>(&s)) return std::abs(sine->offset) + std::abs(sine->amplitude);
  double m = std::max(std::abs(value(s, t0)), std::abs(value(s, t1)));
  for (double b : breakpoints(s, t0, t1))
    m = std::max({m, std::abs(value(s, b)), std::abs(value(s, std::nextafter(b, t0)))});
  return m;
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

  template <class State>
  EnergyBound(StateMatrix L_, const InputMatrix& N, const std::vector<Signal>& signals, const State& x0,
              double horizon)
      : L(std::move(L_)), diagonal(L.isDiagonal(0.0)), half_diagonal(0.5 * L.diagonal()) {
    root_e0 = std::sqrt(energy(x0));
    double w = 0;
    for (Eigen::Index i = 0; i < N.cols(); ++i)
      w += std::sqrt(std::max(0.0, N.col(i).dot(L * N.col(i)))) *
           input_bound(signals[static_cast<std::size_t>(i)], 0.0, horizon);
    rate = w / std::sqrt(2.0);
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
template <class System>
int run_system(const System& sys, const typename System::Params& p, const std::vector<Signal>& signals,
               const typename System::State& x0, const SceneRun& run, const std::string& suffix) {
  using State = typename System::State;
  using Input = typename System::Input;
  using Output = typename System::Output;
  const Eigen::Index nx = x0.size();
  const auto nu = static_cast<Eigen::Index>(signals.size());
  const auto ny = static_cast<Eigen::Index>(std::size(sys.output_names));
  const std::string label = run.name + suffix;

  typename System::StateMatrix M(nx, nx);
  typename System::InputMatrix N(nx, nu);
  sys.matrices(p, M, N);
  Input u(nu);
  Output y(ny);
  auto f = [&](double t, const State& x, State& dx) {
    input_values(signals, t, u);
    sys.rhs(p, x, u, dx);
  };

  if (run.solver == Solver::rk4) {
    const double limit = rk4_stability_limit(M);
    if (run.options.h > limit) {
      std::fprintf(stderr,
                   "%s: error: rk4 step %g s is above its stability limit %g s for this scene (fastest mode); "
                   "use --step %g or smaller, or --solver exact or implicit\n",
                   label.c_str(), run.options.h, limit, 0.9 * limit);
      return 3;
    }
  }

  std::vector<std::string> columns{"t [s]"};
  for (Eigen::Index i = 0; i < ny; ++i)
    columns.push_back(std::string(sys.output_names[static_cast<std::size_t>(i)]) + " [" +
                      std::string(sys.output_units[static_cast<std::size_t>(i)]) + "]");

  // Systems without energy_matrix (written by hand against this interface) are not checked.
  std::optional<EnergyBound<typename System::StateMatrix, typename System::InputMatrix>> energy_bound;
  if constexpr (requires(typename System::StateMatrix& L) { sys.energy_matrix(p, L); }) {
    typename System::StateMatrix L(nx, nx);
    sys.energy_matrix(p, L);
    energy_bound.emplace(std::move(L), N, signals, x0, run.horizon);
  }
  std::string diverged;

  std::vector<double> seconds;
  RunStatus st;
  for (int rep = 0; rep < run.repeat; ++rep) {
    std::optional<CsvWriter> csv;
    if (run.csv) {
      csv.emplace(run.out_dir + "/" + label + ".csv", columns);
      if (!csv->ok()) {
        std::fprintf(stderr, "%s: error: %s\n", label.c_str(), csv->error().c_str());
        return 3;
      }
    }
    auto obs = [&](double t, const State& x) {
      if (energy_bound && !energy_bound->within(t, x, energy_bound_safety_factor)) {
        const double r = energy_bound->ratio(t, x);
        char times[32];
        std::snprintf(times, sizeof times, "%.3g", r * r);
        diverged = "the solution diverged at t = " + detail::num(t) + ": its energy is " + times +
                   " times what the initial state and the inputs can supply; use a tighter --tolerance (or a "
                   "smaller --step for rk4), or --solver exact or implicit";
        return false;
      }
      input_values(signals, t, u);
      sys.outputs(p, x, u, y);
      if (csv) csv->row(t, y);
      return true;
    };
    const auto start = std::chrono::steady_clock::now();
    st = simulate_system(run, signals, M, N, f, x0, obs);
    if (!diverged.empty()) st.message = diverged;
    if (csv) {
      if (st.ok ? !csv->commit() : !csv->commit_incomplete(st.message)) {
        std::fprintf(stderr, "%s: error: %s\n", label.c_str(), csv->error().c_str());
        return 3;
      }
    }
    seconds.push_back(std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count());
    if (!st.ok) break;
  }
  if (!st.ok) {
    std::fprintf(stderr, "%s: error: %s%s\n", label.c_str(), st.message.c_str(),
                 run.csv ? "; the CSV keeps what was computed and is marked incomplete" : "");
    return 3;
  }
  std::sort(seconds.begin(), seconds.end());
  if (!run.quiet)
    std::printf("%s: %s, %ld steps, %ld rhs evaluations, %.6g s wall (median of %d)%s\n", label.c_str(),
                std::string(solver_name(run.solver)).c_str(), st.steps, st.rhs_evals, seconds[seconds.size() / 2], run.repeat,
                run.csv ? (", wrote " + run.out_dir + "/" + label + ".csv").c_str() : "");
  return 0;
}

}  // namespace pogear::rt
