// The compiled simulator is cached by a hash of everything that goes into it (its sources, the
// runtime headers, the compiler and its flags), so that running a scene a second time starts at
// once; a stale binary can never be picked up for new sources or an edited runtime.
#include "simulation.hpp"

#include <algorithm>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <vector>

#include <Eigen/SparseCore>
#include <fmt/format.h>
#include <sys/wait.h>
#include <unistd.h>

#include "build_config.hpp"
#include "output_file.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

std::uint64_t fnv1a(const std::string& s, std::uint64_t h = 1469598103934665603ull) {
  for (unsigned char c : s) {
    h ^= c;
    h *= 1099511628211ull;
  }
  return h;
}

// The runtime's headers by name and content, in a fixed order, so that editing the runtime (or
// installing another version of it) gives new cache entries.
std::uint64_t hash_runtime_headers(const fs::path& include_dir, std::uint64_t h) {
  std::vector<fs::path> headers;
  std::error_code ec;
  for (const auto& entry : fs::directory_iterator(include_dir / "pogear", ec))
    if (entry.is_regular_file(ec)) headers.push_back(entry.path());
  std::sort(headers.begin(), headers.end());
  for (const fs::path& header : headers) {
    std::ifstream in(header, std::ios::binary);
    std::stringstream text;
    text << in.rdbuf();
    h = fnv1a(header.filename().string(), h);
    h = fnv1a(text.str(), h);
  }
  return h;
}

// The compiler binary itself (behind its symlinks) by size and modification time: an upgraded
// compiler, or another one at the same path, must not reuse binaries built by the old one.
std::uint64_t hash_compiler(const fs::path& compiler, std::uint64_t h) {
  std::error_code ec;
  const fs::path real = fs::canonical(compiler, ec);
  if (ec) return fnv1a(compiler.string(), h);
  const auto size = fs::file_size(real, ec);
  const auto mtime = fs::last_write_time(real, ec).time_since_epoch().count();
  return fnv1a(fmt::format("{}|{}|{}", real.string(), size, mtime), h);
}

fs::path cache_root() {
  if (const char* d = std::getenv("POGEAR_CACHE_DIR"); d && *d) return d;
  if (const char* d = std::getenv("XDG_CACHE_HOME"); d && *d) return fs::path(d) / "pogear";
  if (const char* d = std::getenv("HOME"); d && *d) return fs::path(d) / ".cache" / "pogear";
  return fs::temp_directory_path() / "pogear-cache";
}

std::string shell_quote(const std::string& s) {
  std::string out = "'";
  for (char c : s) out += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return out + "'";
}

int exit_status(int raw) { return raw == -1 ? 127 : (WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw)); }

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

std::string gnuplot_label(const std::string& name) {
  // omega_c -> {/Symbol w}_{c}, F_ps -> F_{ps}
  const auto us = name.find('_');
  std::string base = name.substr(0, us), sub = us == std::string::npos ? "" : name.substr(us + 1);
  if (base == "omega") base = "{/Symbol w}";
  return sub.empty() ? base : base + "_{" + sub + "}";
}

}  // namespace

void write_sources(const GeneratedSources& g, const std::string& dir) {
  write_file_atomically((fs::path(dir) / g.header_name).string(), g.header);
  write_file_atomically((fs::path(dir) / g.main_name).string(), g.main);
}

constexpr const char* simulator_flags = "-std=c++20 -O2 -DNDEBUG -Wall -Wextra";

std::uint64_t simulator_cache_key(const GeneratedSources& g, const std::string& runtime_include) {
  std::uint64_t h = fnv1a(g.header);
  h = fnv1a(g.main, h);
  h = fnv1a(std::string(build_config::cxx_compiler) + simulator_flags + runtime_include + build_config::version, h);
  h = hash_runtime_headers(runtime_include, h);
  return hash_compiler(build_config::cxx_compiler, h);
}

std::string build_simulator(const GeneratedSources& g) {
  const std::string flags = simulator_flags;
  const std::uint64_t h = simulator_cache_key(g, build_config::runtime_include);
  const fs::path dir = cache_root() / fmt::format("{:016x}", h);
  const fs::path exe = dir / "simulator";
  if (fs::exists(exe)) return exe.string();
  fs::create_directories(dir);
  write_sources(g, dir.string());
  const fs::path tmp = dir / fmt::format("simulator.tmp{}", ::getpid());
  const fs::path log = dir / "compile.log";
  const std::string cmd = fmt::format("{} {} -I{} -I{} -I{} {} -o {} >{} 2>&1", shell_quote(build_config::cxx_compiler),
                                      flags, shell_quote(dir.string()), shell_quote(build_config::runtime_include),
                                      shell_quote(build_config::eigen_include),
                                      shell_quote((dir / g.main_name).string()), shell_quote(tmp.string()),
                                      shell_quote(log.string()));
  const int status = exit_status(std::system(cmd.c_str()));
  if (status != 0) {
    std::error_code ec;
    fs::remove(tmp, ec);
    std::ifstream in(log);
    std::stringstream ss;
    ss << in.rdbuf();
    throw std::runtime_error(fmt::format("compiling the simulator failed (status {}); the compiler said:\n{}", status,
                                         ss.str().substr(0, 4000)));
  }
  fs::rename(tmp, exe);  // atomic: a concurrent run sees either no binary or a whole one
  return exe.string();
}

int run_compiled(const std::string& exe, const rt::SceneRun& run) {
  std::string cmd = shell_quote(exe) + " --solver " + shell_quote(run.solver) + " --out " + shell_quote(run.out_dir) +
                    fmt::format(" --tolerance {} --step {} --repeat {} --max-steps {}", run.options.rtol, run.options.h,
                                run.repeat, run.options.max_steps);
  if (!run.csv) cmd += " --no-csv";
  if (run.quiet) cmd += " --quiet";
  std::fflush(stdout);
  return exit_status(std::system(cmd.c_str()));
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

std::vector<std::string> plot_scene(const SimModel& model, const std::string& dir) {
  std::vector<std::string> written;
  const std::string name = model.scene.name;
  const fs::path elastic_csv = fs::path(dir) / (name + ".csv");
  const fs::path rigid_csv = fs::path(dir) / (name + ".rigid.csv");
  for (const std::string kind : {"velocities", "forces"}) {
    const std::string prefix = kind == "velocities" ? "omega_" : "F_";
    std::vector<int> columns;  // 1-based gnuplot columns; column 1 is t
    for (std::size_t i = 0; i < model.main.outputs.size(); ++i)
      if (model.main.outputs[i].rfind(prefix, 0) == 0) columns.push_back(static_cast<int>(i) + 2);
    if (columns.empty()) continue;
    const fs::path svg = fs::path(dir) / fmt::format("{}.{}.svg", name, kind);
    const fs::path tmp = fs::path(dir) / fmt::format(".{}.{}.svg.tmp{}", name, kind, ::getpid());
    std::string script;
    script += "set terminal svg size 900,560 dynamic enhanced font 'Helvetica,13' background rgb 'white'\n";
    script += fmt::format("set output '{}'\n", tmp.string());
    script += "set datafile separator ','\nset grid\nset key outside right top\n";
    script += fmt::format("set title '{}: {}{}' noenhanced\n", name, kind == "velocities" ? "angular velocities" : "mesh forces",
                          model.rigid ? " (rigid model dashed)" : "");
    script += "set xlabel 't [s]'\n";
    script += fmt::format("set ylabel '{}'\n", kind == "velocities" ? "{/Symbol w} [rad/s]" : "F [N]");
    script += "plot ";
    bool first = true;
    for (int c : columns) {
      script += fmt::format("{}'{}' using 1:{} with lines lw 2 title '{}'", first ? "" : ", \\\n     ",
                            elastic_csv.string(), c, gnuplot_label(model.main.outputs[c - 2]));
      first = false;
    }
    if (model.rigid)
      for (std::size_t k = 0; k < columns.size(); ++k)
        script += fmt::format(", \\\n     '{}' using 1:{} with lines dt 2 lw 1.5 lc rgb 'red' {}", rigid_csv.string(),
                              columns[k], k == 0 ? "title 'rigid'" : "notitle");
    script += "\n";
    const fs::path script_file = fs::path(dir) / fmt::format(".{}.{}.gp", name, kind);
    write_file_atomically(script_file.string(), script);
    const int status = exit_status(std::system(fmt::format("gnuplot {} 2>&1", shell_quote(script_file.string())).c_str()));
    std::error_code ec;
    fs::remove(script_file, ec);
    if (status != 0) {
      fs::remove(tmp, ec);
      throw std::runtime_error(fmt::format("gnuplot failed (status {}) drawing {}; is gnuplot-nox installed "
                                           "(scripts/install-deps.sh)?", status, svg.string()));
    }
    fs::rename(tmp, svg);
    written.push_back(svg.string());
  }
  return written;
}

}  // namespace pogear
