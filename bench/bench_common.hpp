// Shared by the benchmark harnesses (bench/*.cpp): one system of a generated scene as a problem,
// its exact reference in long double, the error measure, the timing loop, the results CSV.
#pragma once

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <limits>
#include <string>
#include <string_view>
#include <variant>
#include <vector>

#include <Eigen/Dense>
#include <unsupported/Eigen/MatrixFunctions>

#include <pogear/signals.hpp>
#include <pogear/solver.hpp>

namespace bench {

namespace rt = pogear::rt;

// The input of every scene the benchmarks run (models/scenes/paper_*.toml and their variants): one
// constant torque of 100 N m. The generated headers leave the signals to the generated main.
inline std::vector<rt::Signal> paper_scene_signals() { return {rt::Constant{100.0}}; }

inline constexpr double NaN = std::numeric_limits<double>::quiet_NaN();

// ---------------------------------------------------------------------------------------------
// Command line shared by all harnesses: --out DIR --quick --check

struct Options {
  std::string out = ".";
  bool quick = false;
  bool check = false;      // verify the numbers (errors finite, within bounds); never the speed
  double min_batch = 0.05;  // s: a timed batch repeats the run until it lasts this long
  int batches = 5;          // the median, min and max are taken over batches
  double max_run = 20;      // s: a method's tighter settings are skipped once one run takes longer
};

inline Options parse_options(int argc, char** argv) {
  Options o;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--out" && i + 1 < argc) o.out = argv[++i];
    else if (a == "--quick") o.quick = true;
    else if (a == "--check") o.check = true;
    else {
      std::fprintf(stderr, "%s: error: unknown option '%s'; options are --out DIR, --quick, --check\n", argv[0],
                   a.c_str());
      std::exit(1);
    }
  }
  if (o.quick) {  // a smoke test of the whole pipeline, well under a minute: timings are rough
    o.min_batch = 0.002;
    o.batches = 3;
    o.max_run = 2;
  }
  std::filesystem::create_directories(o.out);
  return o;
}

// ---------------------------------------------------------------------------------------------
// Samples of a run on the sample grid t_k = k dt, k = 0..count-1 (the runtime's grid: t_end = (count-1) dt)

struct Samples {
  int nx = 0;
  long count = 0, filled = 0;
  std::vector<double> v;  // v[k * nx + i]

  void reset(int nx_, long count_) {
    nx = nx_;
    count = count_;
    filled = 0;
    v.assign(static_cast<std::size_t>(nx * count), NaN);
  }
  void restart() { filled = 0; }
  // Stores the next sample; beyond count it is ignored (and the run's sample count says so).
  template <class X>
  void push(const X& x) {
    if (filled < count) {
      double* p = v.data() + filled * nx;
      for (int i = 0; i < nx; ++i) p[i] = x[i];
    }
    ++filled;
  }
  double at(long k, int i) const { return v[static_cast<std::size_t>(k * nx + i)]; }
  bool complete() const { return filled == count; }
};

// The largest deviation over the samples k in [k0, k1) and all components, each component relative
// to its largest magnitude over the whole reference (velocities and forces have different scales,
// and every state starts at zero, so a pointwise relative error would divide by zero). NaN when the
// run did not produce every sample.
inline double max_rel_error(const Samples& a, const Samples& ref, long k0 = 0, long k1 = -1) {
  if (!a.complete() || a.nx != ref.nx || a.count != ref.count) return NaN;
  if (k1 < 0) k1 = ref.count;
  double worst = 0;
  for (int i = 0; i < ref.nx; ++i) {
    double scale = 0;
    for (long k = 0; k < ref.count; ++k) scale = std::max(scale, std::abs(ref.at(k, i)));
    if (scale == 0) scale = 1;  // a component identically zero: measure absolutely
    for (long k = k0; k < k1; ++k) {
      const double e = std::abs(a.at(k, i) - ref.at(k, i)) / scale;
      if (!(e <= worst)) worst = e;  // also propagates NaN
    }
  }
  return worst;
}

// ---------------------------------------------------------------------------------------------
// One system (Elastic or Rigid) of a generated scene, with its exact reference

template <class Sys>
struct Problem {
  using State = typename Sys::State;
  using Input = typename Sys::Input;
  std::string scene, model;  // model: "elastic" or "rigid"
  std::vector<rt::Signal> signals;
  State x0;
  double horizon = 1, dt = 1e-3, first_step = 1e-4;
  typename Sys::StateMatrix M;
  typename Sys::InputMatrix N;
  typename Sys::Params params{};
  long count = 0;
  Samples ref;

  void inputs(double t, Input& u) const {
    for (int i = 0; i < Sys::nu; ++i) u[i] = rt::value(signals[static_cast<std::size_t>(i)], t);
  }
  // The generated right-hand side, with the scene's inputs: every method, pogear's and the peers',
  // calls exactly this.
  void rhs(double t, const State& x, State& dx) const {
    Input u;
    inputs(t, u);
    Sys::rhs(params, x, u, dx);
  }
  double time(long k) const { return k + 1 == count ? horizon : static_cast<double>(k) * dt; }
  std::string label() const { return scene + "/" + model; }
};

// Exact reference on the sample grid: the inputs of the paper scenes are constant, so
// x(t + dt) = Phi x(t) + Gamma u exactly, with Phi and Gamma from one matrix exponential taken in
// long double (64-bit mantissa) and the stepping done in long double too: its rounding (~1e-19 per
// step, 2000 steps) is far below the 1e-13 that double-precision exact stepping can reach.
template <class Sys>
Samples exact_reference(const Problem<Sys>& pb) {
  using LD = long double;
  using MatL = Eigen::Matrix<LD, Eigen::Dynamic, Eigen::Dynamic>;
  using VecL = Eigen::Matrix<LD, Eigen::Dynamic, 1>;
  const int n = Sys::nx;
  for (const auto& s : pb.signals)
    if (!std::holds_alternative<rt::Constant>(s)) {
      std::fprintf(stderr, "%s: error: the benchmark reference needs constant inputs\n", pb.label().c_str());
      std::exit(2);
    }
  typename Sys::Input u;
  pb.inputs(0, u);
  // Augmented system (x, 1)' = [[M, N u], [0, 0]] (x, 1).
  MatL C = MatL::Zero(n + 1, n + 1);
  for (int i = 0; i < n; ++i) {
    for (int j = 0; j < n; ++j) C(i, j) = static_cast<LD>(pb.M(i, j)) * static_cast<LD>(pb.dt);
    LD nu = 0;
    for (int j = 0; j < Sys::nu; ++j) nu += static_cast<LD>(pb.N(i, j)) * static_cast<LD>(u[j]);
    C(i, n) = nu * static_cast<LD>(pb.dt);
  }
  const MatL E = C.exp();
  VecL x(n + 1);
  for (int i = 0; i < n; ++i) x(i) = static_cast<LD>(pb.x0[i]);
  x(n) = 1;
  Samples ref;
  ref.reset(n, pb.count);
  std::vector<double> xd(static_cast<std::size_t>(n));
  for (long k = 0; k < pb.count; ++k) {
    for (int i = 0; i < n; ++i) xd[static_cast<std::size_t>(i)] = static_cast<double>(x(i));
    ref.push(xd);
    x = (E * x).eval();
  }
  return ref;
}

template <class Sys>
Problem<Sys> make_problem(std::string_view scene, const char* model, std::vector<rt::Signal> signals,
                          const typename Sys::State& x0, double horizon, double dt, double first_step) {
  Problem<Sys> pb;
  pb.scene = scene;
  pb.model = model;
  pb.signals = std::move(signals);
  pb.x0 = x0;
  pb.horizon = horizon;
  pb.dt = dt;
  pb.first_step = first_step;
  Sys::matrices(pb.params, pb.M, pb.N);
  const double n = horizon / dt;
  pb.count = std::lround(n) + 1;
  if (std::abs(n - std::round(n)) > 1e-9 * n) {
    std::fprintf(stderr, "%s: error: the horizon must be a whole number of samples\n", pb.label().c_str());
    std::exit(2);
  }
  pb.ref = exact_reference(pb);
  return pb;
}

// ---------------------------------------------------------------------------------------------
// Timing

struct Timing {
  double median = NaN, min = NaN, max = NaN;  // seconds per run
  long runs_per_batch = 0;
  int batches = 0;
};

inline double seconds_since(std::chrono::steady_clock::time_point t0) {
  return std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
}

// Times run(): batches of n runs, n chosen so that a batch lasts at least o.min_batch; per-run
// times are batch time / n, and the median, min and max are over batches. A run slower than 1 s
// gets 3 batches, slower than o.max_run 1: the error does not need them and the table stays honest
// (runs, batches are reported).
template <class F>
Timing measure(F&& run, const Options& o) {
  auto t0 = std::chrono::steady_clock::now();
  run();
  const double one = seconds_since(t0);
  Timing tm;
  tm.runs_per_batch = std::max(1L, static_cast<long>(std::ceil(o.min_batch / std::max(one, 1e-9))));
  int batches = o.batches;
  if (one > 1) batches = std::min(batches, 3);
  if (one > o.max_run) batches = 1;
  std::vector<double> per_run;
  for (int b = 0; b < batches; ++b) {
    t0 = std::chrono::steady_clock::now();
    for (long i = 0; i < tm.runs_per_batch; ++i) run();
    per_run.push_back(seconds_since(t0) / static_cast<double>(tm.runs_per_batch));
  }
  std::sort(per_run.begin(), per_run.end());
  tm.batches = batches;
  tm.min = per_run.front();
  tm.max = per_run.back();
  const std::size_t m = per_run.size();
  tm.median = m % 2 ? per_run[m / 2] : 0.5 * (per_run[m / 2 - 1] + per_run[m / 2]);
  return tm;
}

// ---------------------------------------------------------------------------------------------
// Results: one CSV per harness; run.sh merges them

inline std::string fmt_double(double v) {
  if (std::isnan(v)) return "nan";
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.6g", v);
  return buf;
}

// Work-precision rows. Times are seconds of wall time per simulated second.
struct Row {
  std::string scene, model, family, method, knob;  // knob: "rtol", "h" or "" (no setting)
  double value = NaN;
  std::string status = "ok";  // ok, failed, refused, skipped
  long steps = -1, rhs_evals = -1;
  double error = NaN;
  Timing time;
  double horizon = 1;
  std::string note;
  std::string label_scene() const { return scene + "/" + model; }
};

class Results {
 public:
  Results(const std::string& path, const char* header) : f_(std::fopen(path.c_str(), "w")), path_(path) {
    if (!f_) {
      std::fprintf(stderr, "error: cannot write %s\n", path.c_str());
      std::exit(2);
    }
    std::fprintf(f_, "%s\n", header);
  }
  Results(const Results&) = delete;
  Results& operator=(const Results&) = delete;
  ~Results() { std::fclose(f_); }
  void line(const std::string& s) {
    std::fprintf(f_, "%s\n", s.c_str());
    std::fflush(f_);
  }
  const std::string& path() const { return path_; }

 private:
  std::FILE* f_;
  std::string path_;
};

inline constexpr const char* kWpHeader =
    "scene,model,family,method,knob,value,status,steps,rhs_evals,max_rel_error,time_median,time_min,time_max,"
    "runs_per_batch,batches,note";

inline void write_row(Results& res, const Row& r) {
  const double s = r.horizon;
  auto per = [&](double t) { return fmt_double(t / s); };
  std::string note = r.note;
  std::replace(note.begin(), note.end(), ',', ';');
  res.line(r.scene + "," + r.model + "," + r.family + "," + r.method + "," + r.knob + "," + fmt_double(r.value) + "," +
           r.status + "," + std::to_string(r.steps) + "," + std::to_string(r.rhs_evals) + "," +
           fmt_double(r.error) + "," + per(r.time.median) + "," + per(r.time.min) + "," + per(r.time.max) + "," +
           std::to_string(r.time.runs_per_batch) + "," + std::to_string(r.time.batches) + "," + note);
  std::printf("  %-22s %-12s %-5s %-9s %-8s err %-10s %s s/s%s%s\n", r.label_scene().c_str(), r.method.c_str(),
              r.knob.c_str(), fmt_double(r.value).c_str(), r.status.c_str(), fmt_double(r.error).c_str(),
              per(r.time.median).c_str(), note.empty() ? "" : "  ", note.c_str());
  std::fflush(stdout);
}

// ---------------------------------------------------------------------------------------------
// Correctness checks (--check): numbers only, never speed

struct Checker {
  bool enabled = false;
  int failures = 0, passed = 0;
  void expect(bool ok, const std::string& what) {
    if (!enabled) return;
    if (ok) {
      ++passed;
      return;
    }
    ++failures;
    std::fprintf(stderr, "CHECK FAILED: %s\n", what.c_str());
  }
  int exit_code(const char* who) const {
    if (!enabled) return 0;
    std::printf("%s: %d checks passed, %d failed\n", who, passed, failures);
    return failures ? 1 : 0;
  }
};

// Bound on the sampled error of an adaptive method run at relative tolerance rtol (absolute
// tolerance 1e-2 rtol). Local error control does not bound the global error: over the ~100
// oscillation periods of the paper scenes and with dense output between steps it exceeds the
// tolerance by factors up to a few hundred, so the check allows 1e3 rtol. Below rtol = 1e-8 the
// error no longer follows the tolerance reliably for every code (rounding in the error estimate,
// the order of the dense output, steps limited by stability: SciPy's DOP853 stalls near 1e-6 on
// the two-stage scene, CVODE's BDF reaches 2800 rtol at 1e-12), so there only the 1e-8 level's bound
// (1e-5) is required. These checks guard the harness (same problem, same reference), not a ranking.
inline double adaptive_bound(double rtol) { return 1e3 * std::max(rtol, 1e-8) + 1e-11; }

// The same for 2nd-order methods (pogear's TR-BDF2): a step of size h commits a local error ~ h^3
// held at rtol, so h ~ rtol^(1/3) and the error summed over the T/h steps grows like rtol^(2/3);
// measured on the paper scenes the factor stays below 30.
inline double low_order_bound(double rtol) { return 100 * std::pow(rtol, 2.0 / 3.0) + 1e-11; }

// --check of a run at tolerance rtol: it succeeded and its error is within `bound`.
inline void expect_error_within(Checker& chk, const std::string& label, const Row& r, bool ok, double rtol,
                                double bound) {
  chk.expect(ok && r.error <= bound, label + ": " + r.method + " rtol " + fmt_double(rtol) + ": error " +
                                         fmt_double(r.error) + " <= " + fmt_double(bound));
}

// The tolerances of the work-precision curves over rtol (two in --quick mode).
inline std::vector<double> wp_tolerances(const Options& o) {
  return o.quick ? std::vector<double>{1e-4, 1e-8}
                 : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
}

// What another library's integrator reports of one run.
struct IntegratorRun {
  bool ok = true;
  std::string message;
  long steps = 0, rhs_evals = 0;
};

// The work-precision rows of another library's `method` over wp_tolerances: run(rtol) simulates
// into `s` and returns its IntegratorRun. Once a tolerance takes longer than --max-run the tighter
// ones are skipped. These codes' global error tracks the tolerance like dopri5's does: each run is
// checked against adaptive_bound.
template <class P, class Run>
void integrator_rows(const P& pb, const std::string& family, const std::string& method, const Samples& s,
                     const Options& o, Results& res, Checker& chk, Run run) {
  bool slow = false;
  for (double rtol : wp_tolerances(o)) {
    Row r;
    r.scene = pb.scene;
    r.model = pb.model;
    r.family = family;
    r.method = method;
    r.knob = "rtol";
    r.value = rtol;
    r.horizon = pb.horizon;
    if (slow) {
      r.status = "skipped";
      r.note = "a looser tolerance already took longer than " + fmt_double(o.max_run) + " s";
      write_row(res, r);
      continue;
    }
    IntegratorRun ir;
    auto once = [&] { ir = run(rtol); };
    once();
    r.error = max_rel_error(s, pb.ref);
    r.steps = ir.steps;
    r.rhs_evals = ir.rhs_evals;
    if (!ir.ok) {
      r.status = "failed";
      r.note = ir.message;
    }
    r.time = measure(once, o);
    slow = r.time.median > o.max_run;
    write_row(res, r);
    expect_error_within(chk, pb.label(), r, ir.ok, rtol, adaptive_bound(rtol));
  }
}

}  // namespace bench
