// Drivers, header-only: every method of driver_loops.hpp, with the exact method's discretizations
// computed here (exact.hpp), and the rk4 stability limit.
#pragma once

#include <utility>
#include <vector>

#include "pogear/driver_loops.hpp"
#include "pogear/exact.hpp"
#include "pogear/stability_limit.hpp"

namespace pogear::rt {

// As simulate_exact below, with the discretization of the nominal step (exact_nominal_step(dt,
// opt.h)) computed beforehand: a sweep that runs one model many times pays for the matrix
// exponential once. M and N serve the other step sizes (next to breakpoints, a partial last interval).
template <int NX, int NU, class UFun, class Obs>
RunStatus simulate_exact(const ExactDiscretization<NX, NU>& nominal, const Eigen::Matrix<double, NX, NX>& M,
                         const Eigen::Matrix<double, NX, NU>& N, UFun&& u, Eigen::Matrix<double, NX, 1> x, double t0,
                         double t_end, double dt, const SolverOptions& opt, Obs&& obs,
                         const std::vector<double>& breaks = {}) {
  auto discretize = [&](double h) { return ExactDiscretization<NX, NU>(M, N, h); };
  return simulate_exact_with(nominal, discretize, u, std::move(x), t0, t_end, dt, opt, obs, breaks);
}

// dx/dt = M x + N u with u(t, U& out) filling the inputs, by ExactDiscretization steps of at most
// opt.h: exact for inputs linear between breakpoints (Constant, Step, Ramp, Table), so set h = dt
// for those; for a Sine the first-order hold costs O(h^2). NX, NU may be Eigen::Dynamic.
template <int NX, int NU, class UFun, class Obs>
RunStatus simulate_exact(const Eigen::Matrix<double, NX, NX>& M, const Eigen::Matrix<double, NX, NU>& N, UFun&& u,
                         Eigen::Matrix<double, NX, 1> x, double t0, double t_end, double dt,
                         const SolverOptions& opt, Obs&& obs, const std::vector<double>& breaks = {}) {
  if (!(dt > 0) || !(opt.h > 0)) return detail::Run{}.fail("invalid step: dt = " + detail::num(dt));
  const ExactDiscretization<NX, NU> nominal(M, N, exact_nominal_step(dt, opt.h));
  return simulate_exact(nominal, M, N, u, std::move(x), t0, t_end, dt, opt, obs, breaks);
}

}  // namespace pogear::rt
