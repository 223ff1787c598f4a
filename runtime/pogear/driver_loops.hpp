// Drivers: integrate a model from t0 to t_end with one of the methods and hand the state to an
// observer exactly at the sample times t0 + k dt, landing on input breakpoints on the way. Eigen/Core
// only: the exact driver takes its discretizations from a callable (drivers.hpp passes exact.hpp's,
// generated simulators the compiled runtime's), so a simulator compiles no matrix exponential.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "pogear/exact_kernel.hpp"
#include "pogear/fixed_step_loop.hpp"
#include "pogear/solver.hpp"
#include "pogear/steppers.hpp"

namespace pogear::rt {

namespace detail {

// Adaptive steps (see the stepper protocol in steppers.hpp): steps end on breakpoints and t_end,
// samples in between come from the stepper's dense output.
template <class S, class X, class Obs>
RunStatus run_adaptive(const char* name, const char* advice, S& s, X& x, double t0, double t_end, double dt,
                       const SolverOptions& opt, Obs& obs, const std::vector<double>& bps) {
  Run run;
  if (!run.setup(x, t0, t_end, dt, opt, bps) || !run.emit(obs, t0, x)) return run.st;
  X sample = x;
  double t = t0, h = std::min(opt.h, opt.h_max);
  long attempts = 0;
  auto stalled = [&](const std::string& why) { return run.stalled(name, t, why, advice); };
  if (t_end > t0) s.start(t, x);
  while (run.k < run.grid.count) {
    const bool before_break = run.next_break < run.breaks.size();
    const double t_stop = before_break ? run.breaks[run.next_break] : t_end;
    // A step that would leave a sliver (< 10% of h) before the stop is stretched to end on it.
    const bool clipped = t_stop - t <= std::min(1.1 * h, opt.h_max);
    const double hs = clipped ? t_stop - t : h;
    const bool brk = clipped && before_break;
    if (++attempts > opt.max_steps) return stalled("max_steps = " + std::to_string(opt.max_steps) + " reached");
    const double err = s.attempt(t, x, hs, brk);
    // A stall is a step that t can barely represent: a few ulps of t (or, at t = 0, an underflowing
    // one). Relative to the time reached, not to the horizon: a fraction of a long horizon can exceed
    // the steps an honest transient at t = 0 needs.
    const double hmin = std::max(16 * std::numeric_limits<double>::epsilon() * std::abs(t),
                                 std::numeric_limits<double>::min());
    if (!(err <= 1)) {
      h = std::min(s.next_h(err, hs), opt.h_max);
      if (h < hmin) {
        if (std::isnan(err)) return run.non_finite(t + hs);
        return stalled("step size h = " + num(h) + " below the minimum");
      }
      continue;
    }
    const double t_new = clipped ? t_stop : t + hs;
    s.accept(t, x, hs);
    ++run.st.steps;
    run.st.t_reached = t_new;
    while (run.k < run.grid.count && run.grid.at(run.k) <= t_new) {
      const double ts = run.grid.at(run.k);
      if (ts == t_new) {
        if (!run.emit(obs, ts, x)) return run.st;
      } else {
        s.dense(ts, sample);
        if (!run.emit(obs, ts, sample)) return run.st;
      }
    }
    // A step shortened to end on a stop says nothing against the step size before it.
    const double h_next = s.next_h(err, hs);
    h = std::min(clipped ? std::max(h, h_next) : h_next, opt.h_max);
    t = t_new;
    if (h < hmin) return stalled("step size h = " + num(h) + " below the minimum");
    if (brk) {
      ++run.next_break;
      s.start(t, x);
    }
  }
  return run.st;
}

}  // namespace detail

// Each driver takes the initial state x at t0, calls obs at t0, t0 + dt, ..., t_end, and steps onto
// the breakpoints (see signals.hpp) where the inputs jump or kink.

// f(t, x, dx) with fixed steps of at most opt.h. Refuse h > rk4_stability_limit(A) beforehand.
template <class X0, class F, class Obs>
RunStatus simulate_rk4(F&& f, const X0& x0, double t0, double t_end, double dt, const SolverOptions& opt, Obs&& obs,
                       const std::vector<double>& breaks = {}) {
  using X = typename X0::PlainObject;  // x0 may be an Eigen expression such as VectorXd::Zero(n)
  X x = x0;
  Rk4<X> rk(x);
  auto advance = [&](double t, double h, bool brk, X& xs) { rk.step(f, t, h, xs, brk); };
  RunStatus st = detail::run_fixed("rk4", advance, x, t0, t_end, dt, opt, obs, breaks);
  st.rhs_evals = rk.rhs_evals;
  return st;
}

template <class X0, class F, class Obs>
RunStatus simulate_dopri5(F&& f, const X0& x0, double t0, double t_end, double dt, const SolverOptions& opt, Obs&& obs,
                          const std::vector<double>& breaks = {}) {
  using X = typename X0::PlainObject;
  X x = x0;
  Dopri5<X, std::remove_reference_t<F>> s(f, x, opt.rtol, opt.atol);
  RunStatus st = detail::run_adaptive("dopri5", "the scene is stiff: use --solver exact or --solver implicit", s,
                                      x, t0, t_end, dt, opt, obs, breaks);
  st.rhs_evals = s.rhs_evals;
  return st;
}

// TR-BDF2 with jac(t, x, J); constant_jacobian for linear models (one J, one LU per step size).
template <class X0, class F, class JacF, class Obs>
RunStatus simulate_implicit(F&& f, JacF&& jac, bool constant_jacobian, const X0& x0, double t0, double t_end, double dt,
                            const SolverOptions& opt, Obs&& obs, const std::vector<double>& breaks = {}) {
  using X = typename X0::PlainObject;
  X x = x0;
  TrBdf2<X, std::remove_reference_t<F>, std::remove_reference_t<JacF>> s(f, jac, constant_jacobian, x, opt.rtol,
                                                                         opt.atol);
  RunStatus st = detail::run_adaptive(
      "implicit", "the Newton iteration or the error test keeps failing: check the model for singular or "
      "non-smooth parts, or loosen the tolerances", s, x, t0, t_end, dt, opt, obs, breaks);
  st.rhs_evals = s.rhs_evals;
  st.jac_evals = s.jac_evals;
  st.lu_decompositions = s.lu_decompositions;
  return st;
}

// The step simulate_exact takes between samples when no breakpoint interrupts them: the largest
// dt / n not above h.
inline double exact_nominal_step(double dt, double h) { return dt / std::max(1.0, std::ceil(dt / h - 1e-9)); }

namespace detail {

// Step lengths within 1e-9 of each other differ by rounding of the grid times only.
inline bool same_step(double a, double b) { return std::abs(a - b) <= 1e-9 * b; }

// The refusal of a step size whose discretization cannot be trusted (ExactDiscretization::accurate):
// its fastest modes turn so far per step that scaling and squaring loses them, and with them, through
// rounding, the slow motion too (every velocity 0, or 17 % off).
POGEAR_RT_COLD inline std::string inaccurate_exact_step(double h, double rounding) {
  char err[32];
  std::snprintf(err, sizeof err, "%.2g", rounding);
  return "exact stepping lost accuracy: with steps of " + num(h) +
         " s the scene's fastest modes turn too far per step for double precision (" +
         (std::isfinite(rounding) ? "estimated error per step " + std::string(err) + ", limit " +
                                             num(kExactMaxRounding)
                                       : std::string("the matrix exponential overflows")) +
         "); shorten the sample, or check stiffnesses and inertias (without mesh_compliance the rigid model is "
         "the limit of stiff meshes)";
}

POGEAR_RT_COLD inline RunStatus check_nominal(double nominal_h, bool accurate, double rounding, double dt,
                                              const SolverOptions& opt) {
  if (!(dt > 0) || !(opt.h > 0)) return Run{}.fail("invalid step: dt = " + num(dt));
  if (!same_step(nominal_h, exact_nominal_step(dt, opt.h)))
    return Run{}.fail("the discretization's step " + num(nominal_h) + " is not the nominal step " +
                      num(exact_nominal_step(dt, opt.h)) + " of dt and h");
  if (!accurate) return Run{}.fail(inaccurate_exact_step(nominal_h, rounding));
  return {};
}
template <class D>
RunStatus check_nominal(const D& nominal, double dt, const SolverOptions& opt) {
  return check_nominal(nominal.h, nominal.accurate(), nominal.rounding, dt, opt);
}

// The discretization of a step other than the nominal one, built when the step size changes. When
// it cannot be trusted the state becomes NaN, which stops run_fixed at once; the driver then reports
// inaccurate_exact_step instead of a non-finite state. Out of line: it runs next to breakpoints and
// at the last sample only, and keeps the step loop as small as it was.
template <class D, class Discretize, class X>
[[gnu::noinline]] void refresh_odd(D& odd, Discretize& discretize, double h, X& xs) {
  if (same_step(h, odd.h)) return;
  odd = discretize(h);
  if (!odd.accurate()) xs.setConstant(std::numeric_limits<double>::quiet_NaN());
}

// simulate_exact's body; W is the step kernel's lane width (exact.hpp).
template <int W, int NX, int NU, class Discretize, class UFun, class Obs>
POGEAR_RT_INLINE RunStatus simulate_exact_lanes(const ExactDiscretization<NX, NU>& nominal, Discretize& discretize,
                                                UFun& u, Eigen::Matrix<double, NX, 1>& x, double t0, double t_end,
                                                double dt, const SolverOptions& opt, Obs& obs,
                                                const std::vector<double>& breaks) {
  using D = ExactDiscretization<NX, NU>;
  D odd;  // the last other step size (next to breakpoints, the final partial interval)
  typename D::Input u0 = D::Input::Zero(nominal.Gamma1.cols()), u1 = u0;
  typename D::State xn = x;
  bool u0_valid = false;
  const double h_nom = nominal.h, tol_nom = 1e-9 * nominal.h;
  auto advance = [&](double t, double h, bool brk, typename D::State& xs) POGEAR_RT_LAMBDA_INLINE {
    const D* disc = &nominal;
    if (!(std::abs(h - h_nom) <= tol_nom)) {  // same_step(h, h_nom)
      refresh_odd(odd, discretize, h, xs);
      disc = &odd;
    }
    if (!u0_valid) u(t, u0);
    u(stage_end(t, t + h, brk), u1);
    if constexpr (ExactKernel<NX, NU>::enabled) {
      exact_step<W>(disc->kernel, xs.data(), u0.data(), u1.data(), xs.data());
    } else {
      disc->step(xs, u0, u1, xn);
      xs = xn;
    }
    u0 = u1;
    u0_valid = !brk;  // after a breakpoint the input restarts from its new (right) value
  };
  RunStatus st = run_fixed("exact", advance, x, t0, t_end, dt, opt, obs, breaks);
  if (!st.ok && odd.h > 0 && !odd.accurate()) st.message = inaccurate_exact_step(odd.h, odd.rounding);
  return st;
}

#if defined(POGEAR_RT_AVX2_DISPATCH)
inline bool cpu_has_avx2() { return __builtin_cpu_supports("avx2"); }

// The same run in AVX2 registers: 4 rows per operation (2 for a 2-state model, which has no more),
// the user's functions entered clean (CleanUpperCall).
template <int NX, int NU, class Discretize, class UFun, class Obs>
POGEAR_RT_TARGET_AVX2 RunStatus simulate_exact_avx2(const ExactDiscretization<NX, NU>& nominal, Discretize& discretize,
                                                    UFun& u, Eigen::Matrix<double, NX, 1>& x, double t0, double t_end,
                                                    double dt, const SolverOptions& opt, Obs& obs,
                                                    const std::vector<double>& breaks) {
  CleanUpperCall<Discretize> clean_discretize{discretize};
  CleanUpperCall<UFun> clean_u{u};
  CleanUpperCall<Obs> clean_obs{obs};
  return simulate_exact_lanes<NX <= 2 ? 2 : 4>(nominal, clean_discretize, clean_u, x, t0, t_end, dt, opt, clean_obs,
                                               breaks);
}
#endif

}  // namespace detail

// dx/dt = M x + N u with u(t, U& out) filling the inputs, by exact steps: `nominal` is the
// discretization of the nominal step (exact_nominal_step(dt, opt.h)), computed beforehand, and
// discretize(h) gives that of any other step (next to breakpoints, a partial last interval). On
// x86-64 CPUs with AVX2 a copy of the driver compiled for AVX2 runs; it gives the same bits.
template <int NX, int NU, class Discretize, class UFun, class Obs>
RunStatus simulate_exact_with(const ExactDiscretization<NX, NU>& nominal, Discretize&& discretize, UFun&& u,
                              Eigen::Matrix<double, NX, 1> x, double t0, double t_end, double dt,
                              const SolverOptions& opt, Obs&& obs, const std::vector<double>& breaks = {}) {
  if (!(dt > 0) || !(opt.h > 0) || !detail::same_step(nominal.h, exact_nominal_step(dt, opt.h)) || !nominal.accurate())
    return detail::check_nominal(nominal.h, nominal.accurate(), nominal.rounding, dt, opt);
#if defined(POGEAR_RT_AVX2_DISPATCH)
  if constexpr (detail::ExactKernel<NX, NU>::enabled)
    if (detail::cpu_has_avx2())
      return detail::simulate_exact_avx2(nominal, discretize, u, x, t0, t_end, dt, opt, obs, breaks);
#endif
  return detail::simulate_exact_lanes<detail::kDefaultLanes>(nominal, discretize, u, x, t0, t_end, dt, opt, obs,
                                                             breaks);
}

}  // namespace pogear::rt
