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

// runge_kutta_dopri5 on the generated fixed-size Eigen State itself (odeint's Eigen support, vector
// space algebra): no copies between odeint and the generated code.
template <class Sys>
IntegratorRun run_dopri5(const Problem<Sys>& pb, double rtol, const std::vector<double>& times, Samples& s) {
  using State = typename Sys::State;
  IntegratorRun r;
  auto sys = [&](const State& x, State& dx, double t) {
    pb.rhs(t, x, dx);
    ++r.rhs_evals;
  };
  auto obs = [&](const State& x, double) { s.push(x); };
  s.restart();
  State x = pb.x0;
  const double atol = rt::absolute_per_relative_tolerance * rtol;  // as pogear's runs
  auto stepper = odeint::make_dense_output(atol, rtol, odeint::runge_kutta_dopri5<State, double, State, double,
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
IntegratorRun run_rosenbrock4(const Problem<Sys>& pb, double rtol, const std::vector<double>& times, Samples& s) {
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
  const Rosenbrock4Result rr = integrate_rosenbrock4(ode, pb.x0.data(), times,
                                                     rt::absolute_per_relative_tolerance * rtol, rtol, pb.first_step);
  IntegratorRun r;
  r.ok = rr.ok;
  r.message = rr.message;
  r.steps = rr.steps;
  r.rhs_evals = c.rhs_evals;
  return r;
}

template <class Sys>
void bench_odeint(const Problem<Sys>& pb, const Options& o, Results& res, Checker& chk) {
  std::vector<double> times(static_cast<std::size_t>(pb.count));
  for (long k = 0; k < pb.count; ++k) times[static_cast<std::size_t>(k)] = pb.time(k);
  Samples s;
  s.reset(Sys::nx, pb.count);
  // odeint's error test uses the max norm (stricter than an RMS norm); rosenbrock4 is 4th order.
  integrator_rows(pb, "odeint", "odeint_dopri5", s, o, res, chk,
                  [&](double rtol) { return run_dopri5(pb, rtol, times, s); });
  integrator_rows(pb, "odeint", "odeint_rosenbrock4", s, o, res, chk,
                  [&](double rtol) { return run_rosenbrock4(pb, rtol, times, s); });
}

}  // namespace

int main(int argc, char** argv) {
  const Options o = parse_options(argc, argv);
  Checker chk{o.check};
  Results res(o.out + "/wp_odeint.csv", kWpHeader);
  std::printf("Boost.Odeint (Boost %d.%d)\n", BOOST_VERSION / 100000, BOOST_VERSION / 100 % 1000);
  for_each_paper_scene([&](const auto& elastic, const auto& rigid) {
    bench_odeint(elastic, o, res, chk);
    bench_odeint(rigid, o, res, chk);
  });
  return chk.exit_code("wp_odeint");
}
