// Boost.Odeint's rosenbrock4 with dense output, compiled as C++17 (see odeint_rosenbrock4.hpp).
#include "odeint_rosenbrock4.hpp"

#include <boost/numeric/odeint.hpp>
#include <exception>
#include <utility>

namespace bench {

namespace odeint = boost::numeric::odeint;
namespace ublas = boost::numeric::ublas;

Rosenbrock4Result integrate_rosenbrock4(const LinearOde& ode, const double* x0, const std::vector<double>& times,
                                        double atol, double rtol, double first_step) {
  using V = ublas::vector<double>;
  using Mat = ublas::matrix<double>;
  Rosenbrock4Result r;
  // uBLAS vectors store their elements contiguously, so the callbacks see plain arrays.
  auto sys = [&](const V& x, V& dx, double t) { ode.rhs(ode.context, t, &x.data()[0], &dx.data()[0]); };
  auto jac = [&](const V&, Mat& J, const double&, V& dfdt) {
    for (int i = 0; i < ode.n; ++i) {
      for (int j = 0; j < ode.n; ++j) J(i, j) = ode.jacobian[j * ode.n + i];
      dfdt[i] = 0;  // constant inputs: f does not depend on t explicitly
    }
  };
  auto obs = [&](const V& x, double t) { ode.observe(ode.context, t, &x.data()[0]); };
  V x(ode.n);
  for (int i = 0; i < ode.n; ++i) x[i] = x0[i];
  auto stepper = odeint::make_dense_output(atol, rtol, odeint::rosenbrock4<double>());
  try {
    r.steps = static_cast<long>(
        odeint::integrate_times(stepper, std::make_pair(sys, jac), x, times.begin(), times.end(), first_step, obs));
  } catch (const std::exception& e) {  // odeint throws when it exceeds its step limits
    r.ok = false;
    r.message = e.what();
  }
  return r;
}

}  // namespace bench
