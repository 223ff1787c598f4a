// Runs one system of a scene with the chosen method and writes its CSV: the part of every
// generated main that does not depend on the model, shared with the interpreted mode.
#pragma once

#include <algorithm>
#include <charconv>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <limits>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <variant>
#include <vector>

#include "pogear/csv.hpp"
#include "pogear/run_limits.hpp"
#include "pogear/signals.hpp"
#include "pogear/simulate.hpp"

namespace pogear::rt {

struct SceneRun {
  std::string name;
  double horizon = 1, sample = 1e-3;
  std::string solver = "exact";
  SolverOptions options;
  std::string out_dir = ".";
  bool csv = true;
  int repeat = 1;  // > 1 for timing: the median is reported
  bool quiet = false;
  // --param NAME=VALUE as given, in order; the generated main resolves them against its Params.
  std::vector<std::pair<std::string, std::string>> params;
};

namespace detail {

// The whole of `text` as a finite number, or nothing: "1e-6x", "0.05ms", "", "inf" and "nan" are
// not numbers here (atof would have read a prefix, or 0).
inline std::optional<double> parse_finite(std::string_view text) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc{} || ptr != end || !std::isfinite(v)) return std::nullopt;
  return v;
}

}  // namespace detail

// Reads the generated simulator's options into `run`; on bad usage prints
// `PROGRAM: error: what; what to do` and returns false (the caller exits with 1). Every number
// must be all of its argument and inside the ranges of run_limits.hpp, which the scene file obeys too.
inline bool parse_command_line(int argc, char** argv, SceneRun& run) {
  const char* program = argv[0];
  auto usage_error = [&](const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
    return false;
  };
  // A number in [lo, hi]; `what` says what the option takes, for the message.
  auto number = [&](const char* option, const char* text, double lo, double hi, const std::string& what,
                    bool whole, double& out) {
    const std::optional<double> v = detail::parse_finite(text);
    if (!v) return usage_error(std::string(option) + " '" + text + "' is not a finite number; give " + what);
    if (!(*v >= lo && *v <= hi) || (whole && *v != std::floor(*v)))
      return usage_error(std::string(option) + " " + text + " is out of range; give " + what);
    out = *v;
    return true;
  };
  const std::string tolerance_range = "a relative tolerance from " + detail::num(limits::min_tolerance) + " to " +
                                      detail::num(limits::max_tolerance) + ", e.g. 1e-8";
  const std::string step_range = "a step in seconds as a plain number (no unit), from " +
                                 detail::num(limits::min_step) + " to " + detail::num(limits::max_step) +
                                 ", e.g. 5e-05";
  const std::string max_steps_range = "a whole number from " + std::to_string(limits::min_max_steps) + " to " +
                                      std::to_string(limits::max_max_steps) + ", e.g. 10000000";
  const std::string repeat_range = "a whole number from 1 to " + std::to_string(limits::max_repeat) + ", e.g. 10";
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const bool takes_value = a == "--solver" || a == "--tolerance" || a == "--step" || a == "--out" ||
                             a == "--repeat" || a == "--max-steps" || a == "--param";
    if (takes_value && i + 1 >= argc) return usage_error(a + " needs a value");
    const char* v = takes_value ? argv[++i] : nullptr;
    double x = 0;
    if (a == "--solver") {
      run.solver = v;
    } else if (a == "--tolerance") {
      if (!number("--tolerance", v, limits::min_tolerance, limits::max_tolerance, tolerance_range, false, x))
        return false;
      run.options.rtol = x;
      run.options.atol = x * 1e-2;
    } else if (a == "--step") {
      if (!number("--step", v, limits::min_step, limits::max_step, step_range, false, x)) return false;
      run.options.h = x;
    } else if (a == "--max-steps") {
      if (!number("--max-steps", v, static_cast<double>(limits::min_max_steps),
                  static_cast<double>(limits::max_max_steps), max_steps_range, true, x))
        return false;
      run.options.max_steps = static_cast<long>(x);
    } else if (a == "--repeat") {
      if (!number("--repeat", v, 1, static_cast<double>(limits::max_repeat), repeat_range, true, x)) return false;
      run.repeat = static_cast<int>(x);
    } else if (a == "--out") {
      if (!*v) return usage_error("--out needs a directory name, not an empty one; give e.g. --out results");
      run.out_dir = v;
    } else if (a == "--param") {
      const std::string_view pv = v;
      const auto eq = pv.find('=');
      if (eq == std::string_view::npos || eq == 0)
        return usage_error("--param '" + std::string(pv) + "' is not NAME=VALUE; give a tunable parameter and "
                           "its value, e.g. --param J_c=0.5");
      run.params.emplace_back(std::string(pv.substr(0, eq)), std::string(pv.substr(eq + 1)));
    } else if (a == "--no-csv") {
      run.csv = false;
    } else if (a == "--quiet") {
      run.quiet = true;
    } else {
      return usage_error("unknown option '" + a + "'; options are --solver, --tolerance, --step, --out, --repeat, "
                         "--max-steps, --param, --no-csv, --quiet");
    }
  }
  if (run.solver != "exact" && run.solver != "rk4" && run.solver != "dopri5" && run.solver != "implicit")
    return usage_error("unknown solver '" + run.solver + "'; the solvers are exact, rk4, dopri5, implicit");
  if (run.csv) {
    std::error_code ec;
    std::filesystem::create_directories(run.out_dir, ec);
    if (ec)
      return usage_error("cannot create the output directory '" + run.out_dir + "' (" + ec.message() +
                         "); give --out a directory you can create or write to");
  }
  return true;
}

// The exact method is exact for inputs linear between breakpoints, so it steps a whole sample
// period; a sine is held linear over the scene's `step` instead.
inline double exact_step(const SceneRun& run, const std::vector<Signal>& signals) {
  const bool piecewise_linear = std::none_of(signals.begin(), signals.end(),
                                             [](const Signal& s) { return std::holds_alternative<Sine>(s); });
  return piecewise_linear ? run.sample : std::min(run.sample, run.options.h);
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
  const std::vector<double> breaks = breakpoints(signals, 0.0, run.horizon);
  auto inputs = [&](double t, Input& u) {
    for (Eigen::Index i = 0; i < nu; ++i) u(i) = value(signals[static_cast<std::size_t>(i)], t);
  };
  Input u(nu);
  Output y(ny);
  auto f = [&](double t, const State& x, State& dx) {
    inputs(t, u);
    sys.rhs(p, x, u, dx);
  };
  auto jac = [&](double, const State&, typename System::StateMatrix& J) { J = M; };

  SolverOptions opt = run.options;
  if (run.solver == "exact") opt.h = exact_step(run, signals);
  if (run.solver == "rk4") {
    const double limit = rk4_stability_limit(M);
    if (opt.h > limit) {
      std::fprintf(stderr,
                   "%s: error: rk4 step %g s is above its stability limit %g s for this scene (fastest mode); "
                   "use --step %g or smaller, or --solver exact or implicit\n",
                   label.c_str(), opt.h, limit, 0.9 * limit);
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
      inputs(t, u);
      sys.outputs(p, x, u, y);
      if (csv) csv->row(t, y);
      return true;
    };
    const auto start = std::chrono::steady_clock::now();
    if (run.solver == "exact") st = simulate_exact(M, N, inputs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    else if (run.solver == "rk4") st = simulate_rk4(f, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    else if (run.solver == "dopri5") st = simulate_dopri5(f, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    else st = simulate_implicit(f, jac, true, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
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
                run.solver.c_str(), st.steps, st.rhs_evals, seconds[seconds.size() / 2], run.repeat,
                run.csv ? (", wrote " + run.out_dir + "/" + label + ".csv").c_str() : "");
  return 0;
}

}  // namespace pogear::rt
