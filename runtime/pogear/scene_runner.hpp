// Runs one system of a scene with the chosen method and writes its CSV: the part of every
// generated main that does not depend on the model, shared with the interpreted mode.
#pragma once

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "pogear/csv.hpp"
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
};

inline bool parse_command_line(int argc, char** argv, SceneRun& run) {
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    bool missing_value = false;  // a known option without its value: reported once, not twice
    auto value = [&](const char* what) -> const char* {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "%s: error: %s needs a value\n", argv[0], what);
        missing_value = true;
        return nullptr;
      }
      return argv[++i];
    };
    const char* v = nullptr;
    if (a == "--solver" && (v = value("--solver"))) run.solver = v;
    else if (a == "--tolerance" && (v = value("--tolerance"))) run.options.rtol = std::atof(v), run.options.atol = run.options.rtol * 1e-2;
    else if (a == "--step" && (v = value("--step"))) run.options.h = std::atof(v);
    else if (a == "--out" && (v = value("--out"))) run.out_dir = v;
    else if (a == "--repeat" && (v = value("--repeat"))) run.repeat = std::max(1, std::atoi(v));
    else if (a == "--max-steps" && (v = value("--max-steps"))) run.options.max_steps = std::max(1L, std::atol(v));
    else if (a == "--no-csv") run.csv = false;
    else if (a == "--quiet") run.quiet = true;
    else {
      if (!missing_value) std::fprintf(stderr, "%s: error: unknown option '%s'; options are --solver, --tolerance, --step, "
                                   "--out, --repeat, --max-steps, --no-csv, --quiet\n", argv[0], a.c_str());
      return false;
    }
  }
  if (run.solver != "exact" && run.solver != "rk4" && run.solver != "dopri5" && run.solver != "implicit") {
    std::fprintf(stderr, "%s: error: unknown solver '%s'; the solvers are exact, rk4, dopri5, implicit\n", argv[0],
                 run.solver.c_str());
    return false;
  }
  if (!(run.options.rtol > 0) || !(run.options.h > 0)) {
    std::fprintf(stderr, "%s: error: --tolerance and --step must be positive\n", argv[0]);
    return false;
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

  std::vector<double> seconds;
  RunStatus st;
  for (int rep = 0; rep < run.repeat; ++rep) {
    std::optional<CsvWriter> csv;
    if (run.csv) {
      csv.emplace(run.out_dir + "/" + label + ".csv", columns);
      if (!csv->ok()) {
        std::fprintf(stderr, "%s: error: cannot write %s (%s); check the output directory and the free space\n",
                     label.c_str(), csv->path().c_str(), csv->error().c_str());
        return 3;
      }
    }
    auto obs = [&](double t, const State& x) {
      inputs(t, u);
      sys.outputs(p, x, u, y);
      if (csv) csv->row(t, y);
    };
    const auto start = std::chrono::steady_clock::now();
    if (run.solver == "exact") st = simulate_exact(M, N, inputs, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    else if (run.solver == "rk4") st = simulate_rk4(f, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    else if (run.solver == "dopri5") st = simulate_dopri5(f, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    else st = simulate_implicit(f, jac, true, x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
    if (csv) {
      if (st.ok ? !csv->commit() : !csv->commit_incomplete(st.message)) {
        std::fprintf(stderr, "%s: error: cannot write %s (%s); check the output directory and the free space\n",
                     label.c_str(), csv->path().c_str(), csv->error().c_str());
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
