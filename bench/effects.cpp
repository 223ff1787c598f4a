// Each effect on and off: for the scene variants generated at build time (bench/CMakeLists.txt),
// the operation counts `pogear generate` printed and what they cost in time — per call of the
// generated rhs and outputs, and per simulated second with rk4 (fixed steps: time follows the op
// count), dopri5 (adaptive: time also follows the dynamics) and exact (time follows the state count).
#include <pogear/drivers.hpp>

#include "bench_common.hpp"
#include "variants.hpp"

namespace {

using namespace bench;

struct Ops {
  long rhs = -1, rhs_mul = -1, rhs_add = -1, outputs = -1;
};

// From the line `pogear generate` printed for the system, e.g. "elastic (10 states, 1 inputs,
// 10 outputs): rhs 56 operations (35 multiplications, 21 additions); outputs 0 operations (...)".
Ops read_ops(const std::string& name, const char* system) {
  Ops ops;
  std::ifstream in(std::string(BENCH_GEN_DIR) + "/" + name + ".ops.txt");
  const std::string prefix = std::string_view(system) == "Elastic" ? "elastic (" : "rigid (";
  std::string line;
  while (std::getline(in, line)) {
    if (line.rfind(prefix, 0) != 0) continue;
    const auto r = line.find("rhs ");
    const auto o = line.find("outputs ", line.find("):"));
    if (r != std::string::npos) std::sscanf(line.c_str() + r, "rhs %ld operations (%ld multiplications, %ld additions)",
                                            &ops.rhs, &ops.rhs_mul, &ops.rhs_add);
    if (o != std::string::npos) std::sscanf(line.c_str() + o, "outputs %ld operations", &ops.outputs);
  }
  return ops;
}

template <class Sys>
void bench_variant(const Problem<Sys>& pb, const std::string& name, const char* variant, const char* system,
                   const char* effects,
                   const Options& o, Results& res, Checker& chk) {
  using State = typename Sys::State;
  using Input = typename Sys::Input;
  const Ops ops = read_ops(name, system);
  chk.expect(ops.rhs >= 0, name + ": operation counts found in " + name + ".ops.txt");

  // Per call: the generated functions on the states of the reference trajectory.
  std::vector<State> states(static_cast<std::size_t>(pb.count));
  for (long k = 0; k < pb.count; ++k)
    for (int i = 0; i < Sys::nx; ++i) states[static_cast<std::size_t>(k)][i] = pb.ref.at(k, i);
  Input u;
  pb.inputs(0, u);
  // The generated functions are called through pointers the compiler cannot see through: inlined
  // into the loop, GCC vectorizes some variants across calls and not others, which measures its
  // choices rather than the operation counts. Every component is summed, so none of the generated
  // arithmetic can be dropped as unused.
  using RhsFn = void (*)(const typename Sys::Params&, const State&, const Input&, State&);
  using OutFn = void (*)(const typename Sys::Params&, const State&, const Input&, typename Sys::Output&);
  volatile RhsFn rhs_fn = &Sys::rhs;
  volatile OutFn out_fn = &Sys::outputs;
  double sink = 0;
  auto rhs_calls = [&] {
    const RhsFn fn = rhs_fn;
    State dx;
    for (const State& x : states) {
      fn(pb.params, x, u, dx);
      sink += dx.sum();
    }
  };
  auto output_calls = [&] {
    const OutFn fn = out_fn;
    typename Sys::Output y;
    for (const State& x : states) {
      fn(pb.params, x, u, y);
      sink += y.sum();
    }
  };
  const double calls = static_cast<double>(states.size());
  const Timing t_rhs = measure(rhs_calls, o), t_out = measure(output_calls, o);

  Samples s;
  s.reset(Sys::nx, pb.count);
  auto obs = [&](double, const State& x) { s.push(x); };
  auto f = [&](double t, const State& x, State& dx) { pb.rhs(t, x, dx); };
  auto inputs = [&](double t, Input& uu) { pb.inputs(t, uu); };
  const std::vector<double> breaks = rt::breakpoints(pb.signals, 0.0, pb.horizon);

  rt::SolverOptions rk;
  rk.h = pb.dt / 20;
  Timing t_rk4;
  double rk4_error = NaN;
  if (rk.h <= rt::rk4_stability_limit(pb.M)) {
    auto run = [&] {
      s.restart();
      rt::simulate_rk4(f, pb.x0, 0.0, pb.horizon, pb.dt, rk, obs, breaks);
    };
    run();
    rk4_error = max_rel_error(s, pb.ref);
    t_rk4 = measure(run, o);
  }
  rt::SolverOptions ex;
  ex.h = pb.dt;
  auto run_exact = [&] {
    s.restart();
    rt::simulate_exact(pb.M, pb.N, inputs, pb.x0, 0.0, pb.horizon, pb.dt, ex, obs, breaks);
  };
  run_exact();
  const double exact_error = max_rel_error(s, pb.ref);
  const Timing t_exact = measure(run_exact, o);
  rt::SolverOptions dp;
  dp.rtol = 1e-8;
  dp.atol = 1e-10;
  dp.h = pb.first_step;
  rt::RunStatus st;
  auto run_dopri5 = [&] {
    s.restart();
    st = rt::simulate_dopri5(f, pb.x0, 0.0, pb.horizon, pb.dt, dp, obs, breaks);
  };
  run_dopri5();
  const double dopri5_error = max_rel_error(s, pb.ref);
  const Timing t_dopri5 = measure(run_dopri5, o);

  auto per_s = [&](const Timing& t) { return fmt_double(t.median / pb.horizon); };
  std::string eff = effects;
  std::replace(eff.begin(), eff.end(), ',', ' ');
  res.line(pb.scene + "," + variant + "," + eff + "," + system + "," +
           std::to_string(Sys::nx) + "," + std::to_string(Sys::ny) + "," + std::to_string(ops.rhs) + "," +
           std::to_string(ops.rhs_mul) + "," + std::to_string(ops.rhs_add) + "," + std::to_string(ops.outputs) + "," +
           fmt_double(1e9 * t_rhs.median / calls) + "," + fmt_double(1e9 * t_out.median / calls) + "," +
           per_s(t_rk4) + "," + fmt_double(rk4_error) + "," + per_s(t_exact) + "," + fmt_double(exact_error) + "," +
           per_s(t_dopri5) + "," + std::to_string(st.steps) + "," + fmt_double(dopri5_error));
  std::printf("  %-40s %-7s rhs %3ld ops %6s ns, outputs %3ld ops %6s ns; rk4 %s, exact %s, dopri5 %s s/s (%ld steps)\n",
              name.c_str(), system, ops.rhs, fmt_double(1e9 * t_rhs.median / calls).c_str(), ops.outputs,
              fmt_double(1e9 * t_out.median / calls).c_str(), per_s(t_rk4).c_str(), per_s(t_exact).c_str(),
              per_s(t_dopri5).c_str(), st.steps);
  // Every variant is a valid scene: the methods must agree with its own exact reference.
  chk.expect(exact_error <= 1e-11, name + ": exact error " + fmt_double(exact_error) + " <= 1e-11");
  chk.expect(st.ok && dopri5_error <= adaptive_bound(1e-8),
             name + ": dopri5 error " + fmt_double(dopri5_error) + " <= " + fmt_double(adaptive_bound(1e-8)));
  if (sink == 42.4242) std::printf(" ");  // keeps the calls alive
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk;
  chk.enabled = o.check;
  Results res(o.out + "/effects.csv",
              "scene,variant,effects,system,nx,ny,rhs_ops,rhs_multiplications,rhs_additions,outputs_ops,rhs_ns,"
              "outputs_ns,rk4_s_per_s,rk4_error,exact_s_per_s,exact_error,dopri5_s_per_s,dopri5_steps,dopri5_error");
  std::printf("effects on/off (rk4 h = dt/20, dopri5 rtol 1e-8; wall time per simulated second)\n");
#define BENCH_RUN_VARIANT(ns, System, scene, variant, effects)                                                    \
  {                                                                                                               \
    namespace g = pogear_generated::ns;                                                                           \
    const auto pb = make_problem<g::System>(scene, #System, bench::paper_scene_signals(), g::System::initial_state(),    \
                                            g::horizon, g::sample_period, g::default_step);                       \
    bench_variant(pb, #ns, variant, #System, effects, o, res, chk);                                                        \
  }
  BENCH_FOR_EACH_VARIANT(BENCH_RUN_VARIANT)
  return chk.exit_code("effects");
}
