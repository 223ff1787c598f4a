// The compiled simulator is cached by a hash of everything that goes into it (its sources, the
// runtime headers, the compiler and its flags), so that running a scene a second time starts at
// once; a stale binary can never be picked up for new sources or an edited runtime.
#include "simulation.hpp"

#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <Eigen/SparseCore>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include "child_process.hpp"
#include "output_file.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

rt::Signal to_signal(const SignalSpec& g) {
  switch (g.kind) {
    case SignalKind::constant: return rt::Constant{g.value};
    case SignalKind::step: return rt::Step{g.before, g.value, g.time};
    case SignalKind::ramp: return rt::Ramp{g.time, g.value, g.before};
    case SignalKind::sine: return rt::Sine{g.value, g.frequency, g.phase, g.offset};
    case SignalKind::table: return rt::Table{g.table_t, g.table_v};
  }
  return rt::Constant{0};
}

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
  std::vector<std::string> output_names, output_units;
  Eigen::SparseMatrix<double> C, D, E;

  void rhs(const Params&, const State& x, const Input& u, State& dx) const {
    dx.noalias() = ns.M * x;
    if (u.size()) dx.noalias() += ns.N * u;
  }
  void outputs(const Params&, const State& x, const Input& u, Output& y) const {
    State dx(x.size());
    rhs({}, x, u, dx);
    y.noalias() = C * x;
    y.noalias() += E * dx;
    if (u.size()) y.noalias() += D * u;
  }
  void matrices(const Params&, StateMatrix& M, InputMatrix& N) const {
    M = ns.M;
    N = ns.N;
  }
  void energy_matrix(const Params&, StateMatrix& L) const { L = ns.L; }
};

std::vector<rt::Signal> signals_of(const SimModel& model, const SimSystem& sys) {
  std::vector<rt::Signal> signals;
  for (int i : sys.input_signal) signals.push_back(to_signal(model.scene.inputs[i].signal));
  return signals;
}

int run_one_interpreted(const SimModel& model, const SimSystem& sys, const rt::SceneRun& run,
                        const std::string& suffix) {
  InterpretedSystem is{numeric_system(model, sys), sys.outputs, sys.output_units};
  return rt::run_system(is, {}, signals_of(model, sys), is.ns.x0, run, suffix);
}

}  // namespace

void write_sources(const GeneratedSources& g, const std::string& dir) {
  write_file_atomically((fs::path(dir) / g.header_name).string(), g.header);
  write_file_atomically((fs::path(dir) / g.main_name).string(), g.main);
}

std::uintmax_t csv_bytes_bound(const SimModel& model) {
  const double samples = std::ceil(model.scene.horizon / model.scene.sample) + 1;
  double numbers = samples * static_cast<double>(model.main.outputs.size() + 1);
  if (model.rigid) numbers += samples * static_cast<double>(model.rigid->outputs.size() + 1);
  return static_cast<std::uintmax_t>(std::min(numbers * 25, 1e18));
}

void check_output_size(const SimModel& model, bool allow_large) {
  const std::uintmax_t bytes = csv_bytes_bound(model);
  if (allow_large || bytes <= max_csv_bytes) return;
  const Scene& sc = model.scene;
  throw InputError(sc.sample_where.file.empty() ? SourceLocation{sc.file, 0, 0} : sc.sample_where,
                   fmt::format("the CSV files of this scene may take up to {:.3g} GB ({:.4g} samples of {} columns); "
                               "the limit is {:.3g} GB: raise sample, shorten the horizon or list fewer outputs, or "
                               "pass --large-output to write them all the same",
                               static_cast<double>(bytes) / 1e9, std::ceil(sc.horizon / sc.sample) + 1,
                               model.main.outputs.size() + 1, static_cast<double>(max_csv_bytes) / 1e9));
}

int run_compiled(const std::string& exe, const rt::SceneRun& run) {
  ChildRequest request;
  request.argv = {exe, "--solver", run.solver, "--out", run.out_dir, "--tolerance", fmt::format("{}", run.options.rtol),
                  "--step", fmt::format("{}", run.options.h), "--repeat", std::to_string(run.repeat),
                  "--max-steps", std::to_string(run.options.max_steps)};
  if (!run.csv) request.argv.push_back("--no-csv");
  if (run.quiet) request.argv.push_back("--quiet");
  std::fflush(stdout);
  const ChildResult result = run_child(request);
  if (result.signal != 0)
    throw std::runtime_error(fmt::format("the simulator {} died of {}; run it by hand to see why", exe, result.describe()));
  return result.exit_code;
}

int run_interpreted(const SimModel& model, const rt::SceneRun& run) {
  int status = run_one_interpreted(model, model.main, run, "");
  if (status == 0 && model.rigid) status = run_one_interpreted(model, *model.rigid, run, ".rigid");
  return status;
}

Trajectory interpret_trajectory(const SimModel& model, const SimSystem& sys, const rt::SceneRun& run) {
  const InterpretedSystem is{numeric_system(model, sys), sys.outputs, sys.output_units};
  const std::vector<rt::Signal> signals = signals_of(model, sys);
  const auto nu = static_cast<Eigen::Index>(signals.size());
  auto inputs = [&](double t, Eigen::VectorXd& u) {
    for (Eigen::Index i = 0; i < nu; ++i) u(i) = rt::value(signals[static_cast<std::size_t>(i)], t);
  };
  Eigen::VectorXd u(nu), y(sys.outputs.size());
  auto f = [&](double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    inputs(t, u);
    is.rhs({}, x, u, dx);
  };
  auto jac = [&](double, const Eigen::VectorXd&, Eigen::MatrixXd& J) { J = is.ns.M; };
  Trajectory tr;
  auto obs = [&](double t, const Eigen::VectorXd& x) {
    inputs(t, u);
    is.outputs({}, x, u, y);
    tr.t.push_back(t);
    tr.x.push_back(x);
    tr.y.push_back(y);
  };
  const std::vector<double> breaks = rt::breakpoints(signals, 0.0, run.horizon);
  rt::SolverOptions opt = run.options;
  if (run.solver == "exact") {
    opt.h = rt::exact_step(run, signals);
    tr.status = rt::simulate_exact(is.ns.M, is.ns.N, inputs, is.ns.x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
  } else if (run.solver == "rk4") {
    tr.status = rt::simulate_rk4(f, is.ns.x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
  } else if (run.solver == "dopri5") {
    tr.status = rt::simulate_dopri5(f, is.ns.x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
  } else {
    tr.status = rt::simulate_implicit(f, jac, true, is.ns.x0, 0.0, run.horizon, run.sample, opt, obs, breaks);
  }
  return tr;
}

}  // namespace pogear
