// Work-precision of pogear's own methods (exact, rk4, dopri5, implicit) on the checked-in generated
// simulators of the two paper scenes, plus the rigid-vs-elastic comparison, the cost of one exact
// step, and the problem files (matrices, inputs, exact reference) that the SciPy script reads.
#include <pogear/drivers.hpp>
#include <pogear/run_system.hpp>

#include "paper_scenes.hpp"

namespace {

using namespace bench;

// Times of the exact and dopri5 runs, kept for the rigid-vs-elastic table.
struct Kept {
  Timing exact, dopri5_1e8;
  double exact_error = NaN, dopri5_1e8_error = NaN;
};

template <class Sys>
Kept bench_methods(const Problem<Sys>& pb, const Options& o, Results& res, Checker& chk) {
  using State = typename Sys::State;
  using Input = typename Sys::Input;
  Kept kept;
  Samples s;
  s.reset(Sys::nx, pb.count);
  auto obs = [&](double, const State& x) { s.push(x); };
  auto inputs = [&](double t, Input& u) { pb.inputs(t, u); };
  auto f = [&](double t, const State& x, State& dx) { pb.rhs(t, x, dx); };
  auto jac = [&](double, const State&, typename Sys::StateMatrix& J) { J = pb.M; };
  const std::vector<double> breaks = rt::breakpoints(pb.signals, 0.0, pb.horizon);
  auto row = [&](const char* method, const char* knob, double value) {
    Row r;
    r.scene = pb.scene;
    r.model = pb.model;
    r.family = "pogear";
    r.method = method;
    r.knob = knob;
    r.value = value;
    r.horizon = pb.horizon;
    return r;
  };
  auto finish = [&](Row& r, const rt::RunStatus& st) {
    r.steps = st.steps;
    r.rhs_evals = st.rhs_evals;
    if (!st.ok) {
      r.status = "failed";
      r.note = st.message;
    }
  };

  // exact: what the generated main does for constant inputs, one step per sample, the matrix
  // exponential included in every run (the matrices come from the generated code each time).
  {
    Row r = row("exact", "", NaN);
    rt::RunStatus st;
    rt::SolverOptions opt;
    opt.h = pb.dt;
    auto run = [&] {
      s.restart();
      typename Sys::StateMatrix M;
      typename Sys::InputMatrix N;
      Sys::matrices(pb.params, M, N);
      st = rt::simulate_exact(M, N, inputs, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs, breaks);
    };
    run();
    r.error = max_rel_error(s, pb.ref);
    finish(r, st);
    r.time = measure(run, o);
    write_row(res, r);
    kept.exact = r.time;
    kept.exact_error = r.error;
    // The exact method is exact up to rounding: Phi = e^{M dt} carries a relative rounding error of
    // a few eps times |M dt| (~200 here: stiff mesh rows), which the lightly damped oscillations of
    // the one-stage gear accumulate over 2000 steps to a few 1e-12; hence 1e-11, not eps.
    chk.expect(st.ok && r.error <= 1e-11, pb.label() + ": exact error " + fmt_double(r.error) + " <= 1e-11");

    // The same through the generated main's path (run_system.hpp's run_system), computing the outputs at
    // every sample, without and with writing the CSV: the cost of formatting shows.
    for (const bool csv : {false, true}) {
      Row rc = row(csv ? "exact_csv" : "exact_outputs", "", NaN);
      rt::SceneRun sr;
      sr.name = pb.scene;
      sr.horizon = pb.horizon;
      sr.sample = pb.dt;
      sr.solver = rt::Solver::exact;
      sr.options.h = pb.first_step;
      sr.out_dir = o.out + "/csv";
      sr.csv = csv;
      sr.quiet = true;
      std::filesystem::create_directories(sr.out_dir);
      int status = 0;
      auto run_sys = [&] {
        status = rt::run_system(Sys{}, pb.params, pb.signals, pb.x0, sr, pb.model == "rigid" ? ".rigid" : "");
      };
      run_sys();
      rc.error = r.error;  // the same computation; the CSV holds the shortest round-trip form
      rc.steps = r.steps;
      rc.rhs_evals = 0;
      rc.status = status == 0 ? "ok" : "failed";
      rc.note = csv ? "run_system with CSV (outputs formatted and written)" : "run_system without CSV (outputs computed)";
      rc.time = measure(run_sys, o);
      write_row(res, rc);
      chk.expect(status == 0, pb.label() + ": run_system " + (csv ? "with" : "without") + " CSV succeeds");
    }
  }

  // rk4 over steps h = dt / n; the scene runner refuses steps above the stability limit, and so do we.
  {
    const double limit = rt::rk4_stability_limit(pb.M);
    const std::vector<int> subdivisions =
        o.quick ? std::vector<int>{1, 20} : std::vector<int>{1, 2, 5, 10, 20, 50, 100, 200, 500, 1000};
    bool slow = false;
    double smallest_h_error = NaN;
    for (int n : subdivisions) {
      const double h = pb.dt / n;
      Row r = row("rk4", "h", h);
      if (h > limit) {
        r.status = "refused";
        r.note = "above the rk4 stability limit " + fmt_double(limit) + " s";
      } else if (slow) {
        r.status = "skipped";
        r.note = "a larger step already took longer than " + fmt_double(o.max_run) + " s";
      } else {
        rt::RunStatus st;
        rt::SolverOptions opt;
        opt.h = h;
        auto run = [&] {
          s.restart();
          st = rt::simulate_rk4(f, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs, breaks);
        };
        run();
        r.error = max_rel_error(s, pb.ref);
        finish(r, st);
        r.time = measure(run, o);
        slow = r.time.median > o.max_run;
        smallest_h_error = r.error;
        chk.expect(st.ok && std::isfinite(r.error), pb.label() + ": rk4 h = " + fmt_double(h) + " gives a finite error");
      }
      write_row(res, r);
    }
    // RK4's global error is O(h^4): at the smallest step it must be small (1e-6 is loose on purpose:
    // the quick mode's smallest step is only dt/20).
    chk.expect(smallest_h_error <= 1e-6, pb.label() + ": rk4 error at the smallest step " +
                                             fmt_double(smallest_h_error) + " <= 1e-6");
  }

  // dopri5 and implicit (TR-BDF2) over tolerances; atol = 1e-2 rtol as the generated main sets it.
  for (const char* method : {"dopri5", "implicit"}) {
    bool slow = false;
    for (double rtol : wp_tolerances(o)) {
      Row r = row(method, "rtol", rtol);
      if (slow) {
        r.status = "skipped";
        r.note = "a looser tolerance already took longer than " + fmt_double(o.max_run) + " s";
        write_row(res, r);
        continue;
      }
      rt::RunStatus st;
      rt::SolverOptions opt;
      rt::set_tolerance(opt, rtol);
      opt.h = pb.first_step;
      auto run = [&] {
        s.restart();
        if (std::string_view(method) == "dopri5")
          st = rt::simulate_dopri5(f, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs, breaks);
        else
          st = rt::simulate_implicit(f, jac, true, pb.x0, 0.0, pb.horizon, pb.dt, opt, obs, breaks);
      };
      run();
      r.error = max_rel_error(s, pb.ref);
      finish(r, st);
      r.time = measure(run, o);
      slow = r.time.median > o.max_run;
      write_row(res, r);
      if (std::string_view(method) == "dopri5" && rtol == 1e-8) {
        kept.dopri5_1e8 = r.time;
        kept.dopri5_1e8_error = r.error;
      }
      const double bound = std::string_view(method) == "dopri5" ? adaptive_bound(rtol) : low_order_bound(rtol);
      expect_error_within(chk, pb.label(), r, st.ok, rtol, bound);
    }
  }
  return kept;
}

// The problem file of one system for the SciPy script: the generated M and N (to check that SciPy's
// matrices, built from `pogear derive`, are the same), the inputs, and the exact reference.
template <class Sys>
void write_problem(const Problem<Sys>& pb, const Options& o) {
  const std::string dir = o.out + "/problems";
  std::filesystem::create_directories(dir);
  const std::string base = pb.scene + "." + pb.model;
  {
    std::ofstream ref(dir + "/" + base + ".ref.csv");
    char buf[40];
    for (long k = 0; k < pb.count; ++k) {
      for (int i = 0; i < Sys::nx; ++i) {
        std::snprintf(buf, sizeof buf, "%.17g", pb.ref.at(k, i));
        ref << (i ? "," : "") << buf;
      }
      ref << '\n';
    }
  }
  std::ofstream js(dir + "/" + base + ".json");
  auto num = [](double v) {
    char buf[40];
    std::snprintf(buf, sizeof buf, "%.17g", v);
    return std::string(buf);
  };
  js << "{\n  \"scene\": \"" << pb.scene << "\",\n  \"model\": \"" << pb.model << "\",\n";
  js << "  \"scene_file\": \"" << POGEAR_ROOT << "/models/scenes/" << pb.scene << ".toml\",\n";
  js << "  \"horizon\": " << num(pb.horizon) << ",\n  \"sample\": " << num(pb.dt) << ",\n";
  js << "  \"states\": [";
  for (int i = 0; i < Sys::nx; ++i) js << (i ? ", " : "") << '"' << Sys::state_names[i] << '"';
  js << "],\n  \"inputs\": {";
  typename Sys::Input u;
  pb.inputs(0, u);
  for (int j = 0; j < Sys::nu; ++j) js << (j ? ", " : "") << '"' << Sys::input_names[j] << "\": " << num(u[j]);
  js << "},\n  \"x0\": [";
  for (int i = 0; i < Sys::nx; ++i) js << (i ? ", " : "") << num(pb.x0[i]);
  js << "],\n  \"M\": [";
  for (int i = 0; i < Sys::nx; ++i) {
    js << (i ? ",\n        [" : "[");
    for (int j = 0; j < Sys::nx; ++j) js << (j ? ", " : "") << num(pb.M(i, j));
    js << "]";
  }
  js << "],\n  \"N\": [";
  for (int i = 0; i < Sys::nx; ++i) {
    js << (i ? ", [" : "[");
    for (int j = 0; j < Sys::nu; ++j) js << (j ? ", " : "") << num(pb.N(i, j));
    js << "]";
  }
  js << "],\n  \"reference\": \"" << base << ".ref.csv\"\n}\n";
}

// Outputs of a system along a trajectory of states (constant inputs).
template <class Sys>
Samples outputs_along(const Problem<Sys>& pb, const Samples& states) {
  Samples y;
  y.reset(Sys::ny, states.count);
  typename Sys::State x;
  typename Sys::Input u;
  typename Sys::Output out;
  for (long k = 0; k < states.count; ++k) {
    for (int i = 0; i < Sys::nx; ++i) x[i] = states.at(k, i);
    pb.inputs(pb.time(k), u);
    Sys::outputs(pb.params, x, u, out);
    y.push(out);
  }
  return y;
}

// The rigid model against the elastic one (both exact): each output of the rigid model relative to
// the largest magnitude of the same elastic output, during the transient (t <= 0.3 s) and after it.
template <class E, class R>
void rigid_vs_elastic(const Problem<E>& pe, const Problem<R>& pr, const Kept& ke, const Kept& kr, Results& err_res,
                      Results& time_res, Checker& chk) {
  const Samples ye = outputs_along(pe, pe.ref), yr = outputs_along(pr, pr.ref);
  const long k_split = std::lround(0.3 / pe.dt) + 1;  // samples with t <= 0.3 s
  double group[2][2] = {{0, 0}, {0, 0}};           // [velocity/force][transient/after]
  for (int i = 0; i < E::ny; ++i) {
    int j = 0;
    while (j < R::ny && R::output_names[j] != E::output_names[i]) ++j;
    if (j == R::ny) continue;
    double scale = 0;
    for (long k = 0; k < ye.count; ++k) scale = std::max(scale, std::abs(ye.at(k, i)));
    if (scale == 0) scale = 1;
    double e[2] = {0, 0};
    for (long k = 0; k < ye.count; ++k) {
      const double d = std::abs(yr.at(k, j) - ye.at(k, i)) / scale;
      double& w = e[k < k_split ? 0 : 1];
      w = std::max(w, d);
    }
    const std::string name(E::output_names[i]);
    const int g = name.rfind("F_", 0) == 0 ? 1 : 0;
    for (int w = 0; w < 2; ++w) {
      group[g][w] = std::max(group[g][w], e[w]);
      err_res.line(pe.scene + "," + name + "," + (w ? "after" : "transient") + "," + fmt_double(e[w]) + "," +
                   fmt_double(scale));
    }
  }
  for (int g = 0; g < 2; ++g)
    for (int w = 0; w < 2; ++w)
      err_res.line(pe.scene + "," + (g ? "all forces" : "all velocities") + "," + (w ? "after" : "transient") + "," +
                   fmt_double(group[g][w]) + ",");
  std::printf("  %s rigid vs elastic: velocities %s (transient) %s (after), forces %s / %s\n", pe.scene.c_str(),
              fmt_double(group[0][0]).c_str(), fmt_double(group[0][1]).c_str(), fmt_double(group[1][0]).c_str(),
              fmt_double(group[1][1]).c_str());
  // A model difference, not a numerical error: only its sanity is checked (finite, and the rigid
  // velocities within 10% of the elastic ones once the transient is over).
  chk.expect(group[0][1] < 0.1, pe.scene + ": rigid velocities within 10% of the elastic ones after 0.3 s");
  auto trow = [&](const char* method, const Timing& te, const Timing& tr, double ee, double er) {
    time_res.line(pe.scene + "," + method + "," + fmt_double(te.median / pe.horizon) + "," +
                  fmt_double(tr.median / pr.horizon) + "," + fmt_double(te.median / tr.median) + "," +
                  fmt_double(ee) + "," + fmt_double(er));
  };
  trow("exact", ke.exact, kr.exact, ke.exact_error, kr.exact_error);
  trow("dopri5 rtol 1e-8", ke.dopri5_1e8, kr.dopri5_1e8, ke.dopri5_1e8_error, kr.dopri5_1e8_error);
}

// The cost of one exact step: the kernel alone (Phi x + Gamma0 u0 + Gamma1 (u1 - u0) on a fixed
// discretization) and through the driver simulate_exact over a long run (setup amortized), with an
// observer that only keeps one number.
template <class Sys>
void exact_step_cost(const Problem<Sys>& pb, const Options& o, Results& res) {
  using State = typename Sys::State;
  using Input = typename Sys::Input;
  const rt::ExactDiscretization<Sys::nx, Sys::nu> disc(pb.M, pb.N, pb.dt);
  Input u0, u1;
  pb.inputs(0, u0);
  u1 = u0;
  const long steps = o.quick ? 20000 : 1000000;
  State x = pb.x0, xn;
  double sink = 0;
  auto kernel = [&] {
    x = pb.x0;
    for (long i = 0; i < steps; ++i) {
      disc.step(x, u0, u1, xn);
      x = xn;
    }
    sink += x[0];
  };
  const Timing tk = measure(kernel, o);
  const double horizon = static_cast<double>(steps) * pb.dt;
  rt::SolverOptions opt;
  opt.h = pb.dt;
  auto inputs = [&](double t, Input& u) { pb.inputs(t, u); };
  auto obs = [&](double, const State& xs) { sink += xs[0]; };
  auto driver = [&] { rt::simulate_exact(pb.M, pb.N, inputs, pb.x0, 0.0, horizon, pb.dt, opt, obs); };
  const Timing td = measure(driver, o);
  auto line = [&](const char* what, const Timing& t) {
    const double n = static_cast<double>(steps);
    res.line(pb.scene + "," + pb.model + "," + std::to_string(Sys::nx) + "," + what + "," +
             fmt_double(1e9 * t.median / n) + "," + fmt_double(1e9 * t.min / n) + "," + fmt_double(1e9 * t.max / n) +
             "," + std::to_string(steps));
    std::printf("  %s exact step (%s): %s ns (min %s)\n", pb.label().c_str(), what,
                fmt_double(1e9 * t.median / n).c_str(), fmt_double(1e9 * t.min / n).c_str());
  };
  line("kernel", tk);
  line("simulate_exact", td);
  if (sink == 42.4242) std::printf(" ");  // keeps the results alive
}

template <class E, class R>
void bench_scene(const Problem<E>& pe, const Problem<R>& pr, const Options& o, Results& res, Results& rve_err,
                 Results& rve_time, Results& step_res, Checker& chk) {
  write_problem(pe, o);
  write_problem(pr, o);
  const Kept ke = bench_methods(pe, o, res, chk);
  const Kept kr = bench_methods(pr, o, res, chk);
  rigid_vs_elastic(pe, pr, ke, kr, rve_err, rve_time, chk);
  exact_step_cost(pe, o, step_res);
  exact_step_cost(pr, o, step_res);
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk{o.check};
  Results res(o.out + "/wp_pogear.csv", kWpHeader);
  Results rve_err(o.out + "/rigid_vs_elastic_error.csv", "scene,output,window,max_rel_error,elastic_scale");
  Results rve_time(o.out + "/rigid_vs_elastic_time.csv",
                   "scene,method,elastic_s_per_s,rigid_s_per_s,speedup,elastic_error,rigid_error");
  Results step_res(o.out + "/exact_step.csv", "scene,model,nx,what,ns_per_step_median,ns_min,ns_max,steps");
  std::printf("pogear methods (wall time per simulated second)\n");
  for_each_paper_scene([&](const auto& elastic, const auto& rigid) {
    bench_scene(elastic, rigid, o, res, rve_err, rve_time, step_res, chk);
  });
  return chk.exit_code("wp_pogear");
}
