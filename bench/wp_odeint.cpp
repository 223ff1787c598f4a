// Work-precision of Boost.Odeint on the same generated right-hand sides: runge_kutta_dopri5 and
// rosenbrock4 (with the Jacobian M), each as a dense-output stepper driven by integrate_times onto
// the sample grid.
#include <boost/numeric/odeint.hpp>
#include <boost/numeric/odeint/external/eigen/eigen.hpp>
#include <boost/version.hpp>

#include "odeint_rosenbrock4.hpp"
#include "paper_scenes.hpp"

namespace {

using namespace bench;
namespace odeint = boost::numeric::odeint;

struct OdeintRun {
  bool ok = true;
  std::string message;
  long steps = 0, rhs_evals = 0;
};

// runge_kutta_dopri5 on the generated fixed-size Eigen State itself (odeint's Eigen support, vector
// space algebra): no copies between odeint and the generated code.
template <class Sys>
OdeintRun run_dopri5(const Problem<Sys>& pb, double rtol, const std::vector<double>& times, Samples& s) {
  using State = typename Sys::State;
  OdeintRun r;
  auto sys = [&](const State& x, State& dx, double t) {
    pb.rhs(t, x, dx);
    ++r.rhs_evals;
  };
  auto obs = [&](const State& x, double) { s.push(x); };
  s.restart();
  State x = pb.x0;
  auto stepper = odeint::make_dense_output(1e-2 * rtol, rtol, odeint::runge_kutta_dopri5<State, double, State, double,
                                                                                           odeint::vector_space_algebra>());
  try {
    r.steps = static_cast<long>(odeint::integrate_times(stepper, sys, x, times.begin(), times.end(), pb.first_step, obs));
  } catch (const std::exception& e) {  // odeint throws when it exceeds its step limits
    r.ok = false;
    r.message = e.what();
  }
  return r;
}

// rosenbrock4 runs behind a C++17 boundary (odeint_rosenbrock4.hpp); the generated rhs is called
// through a function pointer on the uBLAS vectors' storage.
template <class Sys>
OdeintRun run_rosenbrock4(const Problem<Sys>& pb, double rtol, const std::vector<double>& times, Samples& s) {
  using State = typename Sys::State;
  struct Context {
    const Problem<Sys>* pb;
    Samples* s;
    long rhs_evals = 0;
  } c{&pb, &s};
  LinearOde ode;
  ode.n = Sys::nx;
  ode.context = &c;
  ode.rhs = [](void* p, double t, const double* x, double* dx) {
    auto* cx = static_cast<Context*>(p);
    State xs = Eigen::Map<const State>(x), dxs;
    cx->pb->rhs(t, xs, dxs);
    Eigen::Map<State> out(dx);
    out = dxs;
    ++cx->rhs_evals;
  };
  ode.jacobian = pb.M.data();  // Eigen's default storage is column-major
  ode.observe = [](void* p, double, const double* x) {
    static_cast<Context*>(p)->s->push(Eigen::Map<const State>(x));
  };
  s.restart();
  const Rosenbrock4Result rr = integrate_rosenbrock4(ode, pb.x0.data(), times, 1e-2 * rtol, rtol, pb.first_step);
  OdeintRun r;
  r.ok = rr.ok;
  r.message = rr.message;
  r.steps = rr.steps;
  r.rhs_evals = c.rhs_evals;
  return r;
}

template <class Sys>
void bench_odeint(const Problem<Sys>& pb, const Options& o, Results& res, Checker& chk) {
  const std::vector<double> tolerances =
      o.quick ? std::vector<double>{1e-4, 1e-8}
              : std::vector<double>{1e-3, 1e-4, 1e-5, 1e-6, 1e-7, 1e-8, 1e-9, 1e-10, 1e-11, 1e-12};
  std::vector<double> times(static_cast<std::size_t>(pb.count));
  for (long k = 0; k < pb.count; ++k) times[static_cast<std::size_t>(k)] = pb.time(k);
  Samples s;
  s.reset(Sys::nx, pb.count);
  for (const char* method : {"odeint_dopri5", "odeint_rosenbrock4"}) {
    const bool rosenbrock = std::string_view(method) == "odeint_rosenbrock4";
    bool slow = false;
    for (double rtol : tolerances) {
      Row r;
      r.scene = pb.scene;
      r.model = pb.model;
      r.family = "odeint";
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
      OdeintRun orun;
      auto run = [&] { orun = rosenbrock ? run_rosenbrock4(pb, rtol, times, s) : run_dopri5(pb, rtol, times, s); };
      run();
      r.error = max_rel_error(s, pb.ref);
      r.steps = orun.steps;
      r.rhs_evals = orun.rhs_evals;
      if (!orun.ok) {
        r.status = "failed";
        r.note = orun.message;
      }
      r.time = measure(run, o);
      slow = r.time.median > o.max_run;
      write_row(res, r);
      // odeint's error test uses the max norm (stricter than an RMS norm); rosenbrock4 is 4th order.
      expect_error_within(chk, pb.label(), r, orun.ok, rtol, adaptive_bound(rtol));
    }
  }
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk;
  chk.enabled = o.check;
  Results res(o.out + "/wp_odeint.csv", kWpHeader);
  std::printf("Boost.Odeint (Boost %d.%d)\n", BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000);
  for_each_paper_scene([&](const auto& elastic, const auto& rigid) {
    bench_odeint(elastic, o, res, chk);
    bench_odeint(rigid, o, res, chk);
  });
  return chk.exit_code("wp_odeint");
}
