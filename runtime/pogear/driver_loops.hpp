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
#include "pogear/solver.hpp"
#include "pogear/steppers.hpp"

namespace pogear::rt {

struct RunStatus {
  bool ok = true;
  std::string message;
  double t_reached = 0;  // time of the last state computed (accepted)
  long steps = 0, rhs_evals = 0, jac_evals = 0, lu_decompositions = 0;
};

// Observers are obs(double t, const X& x); one returning bool can stop the run by returning false
// (e.g. when its output file cannot be written).
namespace detail {

// The sample times, computed as t0 + k dt rather than accumulated so that late samples are as exact
// as early ones. The last sample is t_end itself, also when (t_end - t0) / dt is not a whole number.
struct Grid {
  double t0 = 0, dt = 1, t_end = 0;
  long count = 1;
  double at(long k) const { return k + 1 == count ? t_end : t0 + static_cast<double>(k) * dt; }
};

// The samples from t0 to t_end every dt: a whole number of periods when (t_end - t0) / dt is one up
// to 1e-9, else one more (the last at t_end). (t_end - t0) / dt must be below 2^62.
inline Grid sample_grid(double t0, double t_end, double dt) {
  const double n = (t_end - t0) / dt;
  auto steps = std::llround(n);
  if (std::abs(n - static_cast<double>(steps)) > 1e-9 * std::max(1.0, n)) steps = std::llround(std::ceil(n));
  return {t0, dt, t_end, static_cast<long>(steps) + 1};
}

// Failure paths are kept out of the templates' bodies, [[gnu::cold]] and not inlined: built once per
// program instead of once per driver and model size, they cost no compile time per simulator, and
// the step loops stay small.
#define POGEAR_RT_COLD [[gnu::cold, gnu::noinline]]

// Bookkeeping common to all drivers: status, sample grid, the breakpoints still ahead.
struct Run {
  RunStatus st;
  Grid grid;
  std::vector<double> breaks;  // sorted, inside (t0, t_end)
  std::size_t next_break = 0;
  long k = 0;  // next sample to emit
  double last_sample = std::numeric_limits<double>::quiet_NaN();

  POGEAR_RT_COLD RunStatus fail(std::string message) {
    st.ok = false;
    st.message = std::move(message);
    return st;
  }
  POGEAR_RT_COLD bool refuse(std::string message) {
    fail(std::move(message));
    return false;
  }
  POGEAR_RT_COLD RunStatus non_finite(double t) {
    return fail("non-finite state at t = " + num(t) + "; last finite sample at t = " + num(last_sample));
  }
  POGEAR_RT_COLD RunStatus stopped_by_observer(double t) { return fail("stopped by the observer at t = " + num(t)); }
  // A fixed-step method asked for more than max_steps steps over [te - len, te].
  POGEAR_RT_COLD RunStatus too_many_steps(const char* name, double te, double h_max, double count, double len,
                                          long max_steps) {
    return fail(std::string(name) + " cannot reach t = " + num(te) + ": steps of at most " + num(h_max) + " s need " +
                num(count) + " steps over " + num(len) + " s, more than max_steps = " + std::to_string(max_steps) +
                "; raise the step or max_steps");
  }
  POGEAR_RT_COLD RunStatus max_steps_reached(const char* name, double t, long max_steps) {
    return fail(std::string(name) + " stopped at t = " + num(t) + ": max_steps = " + std::to_string(max_steps) +
                " reached");
  }
  POGEAR_RT_COLD RunStatus stalled(const char* name, double t, const std::string& why, const char* advice) {
    return fail(std::string(name) + " stalled at t = " + num(t) + ": " + why + "; " + advice);
  }
  template <class X>
  bool setup(const X& x, double t0, double t_end, double dt, const SolverOptions& opt,
             const std::vector<double>& bps) {
    return setup_grid(x.allFinite(), t0, t_end, dt, opt, bps);
  }
  bool setup_grid(bool x_finite, double t0, double t_end, double dt, const SolverOptions& opt,
                                 const std::vector<double>& bps) {
    st.t_reached = t0;
    if (!std::isfinite(t0) || !std::isfinite(t_end) || !(t_end >= t0) || !(dt > 0))
      return refuse("invalid time span: t0 = " + num(t0) + ", t_end = " + num(t_end) + ", dt = " + num(dt));
    if (!(opt.h > 0) || !(opt.h_max > 0)) return refuse("invalid step size h = " + num(opt.h));
    if (!x_finite) return refuse("non-finite initial state at t = " + num(t0));
    const double n = (t_end - t0) / dt;
    // llround is undefined beyond a long long; far fewer samples than that could ever be written.
    if (!(n < 0x1p62)) return refuse("too many samples: (t_end - t0) / dt = " + num(n));
    grid = sample_grid(t0, t_end, dt);
    for (double b : bps)
      if (b > t0 && b < t_end) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    return true;
  }
  template <class Obs, class X>
  POGEAR_RT_INLINE bool emit(Obs& obs, double t, const X& x) {
    ++k;
    last_sample = t;
    if constexpr (std::is_convertible_v<std::invoke_result_t<Obs&, double, const X&>, bool>) {
      if (!obs(t, x)) {
        stopped_by_observer(t);
        return false;
      }
    } else {
      obs(t, x);
    }
    return true;
  }
};

// Every entry finite, checked after each fixed step: x - x is 0 for a finite entry and NaN for an
// infinite or NaN one, so the sum is 0 exactly when all are finite. One vectorized pass, where
// Eigen's allFinite() compares and branches entry by entry (a third of the exact driver's per-step
// instructions for the 10-state paper model).
template <class X>
POGEAR_RT_INLINE bool all_finite(const X& x) {
  return (x - x).sum() == 0;
}

// Fixed steps: each interval between consecutive stops (samples and breakpoints) is cut into the
// fewest equal steps not longer than h, so that steps land exactly on both. The counters live in
// locals, written back to run on the way out: run's address escapes into the error paths, so its
// members would go through memory on every step (a good part of a batched step's instructions).
template <class X, class Advance, class Obs>
POGEAR_RT_INLINE RunStatus run_fixed(const char* name, Advance&& advance, X& x, double t0, double t_end, double dt,
                                     const SolverOptions& opt, Obs& obs, const std::vector<double>& bps) {
  Run run;
  if (!run.setup(x, t0, t_end, dt, opt, bps) || !run.emit(obs, t0, x)) return run.st;
  const Grid grid = run.grid;
  const double* const breaks = run.breaks.data();
  const std::size_t n_breaks = run.breaks.size();
  const long max_steps = opt.max_steps;
  const double h_max = opt.h;
  std::size_t next_break = 0;
  long k = run.k, steps = 0;
  double t = t0, t_reached = t0, last_sample = t0;
  auto finish = [&]() -> RunStatus& {
    run.k = k;
    run.next_break = next_break;
    run.last_sample = last_sample;
    run.st.steps = steps;
    run.st.t_reached = t_reached;
    return run.st;
  };
  // The step count of the previous interval: consecutive sample intervals differ by rounding only,
  // so the division and ceil (a libm call without SSE4.1) are done once, not on every sample.
  double last_len = -1;
  long n = 1;
  while (k < grid.count) {
    const double ts = grid.at(k);
    const bool brk = next_break < n_breaks && breaks[next_break] <= ts;
    const double te = brk ? breaks[next_break++] : ts;
    const double len = te - t;
    if (!(std::abs(len - last_len) <= 1e-9 * last_len)) {
      // Counted in double and checked before the conversion: a count beyond a long's range used to
      // wrap to 1, so a 1e-30 s step became one 10 ms step per sample, past rk4's stability check.
      const double count = std::ceil(len / h_max - 1e-9);
      if (!(count <= static_cast<double>(std::min(max_steps, 1L << 62)))) {
        finish();
        return run.too_many_steps(name, te, h_max, count, len, max_steps);
      }
      n = std::max(1L, static_cast<long>(count));
      last_len = len;
    }
    const double hs = n == 1 ? len : len / static_cast<double>(n);
    for (long i = 0; i < n; ++i) {
      if (steps >= max_steps) {
        finish();
        return run.max_steps_reached(name, t_reached, max_steps);
      }
      const double ta = t + static_cast<double>(i) * hs, tb = i + 1 == n ? te : ta + hs;
      advance(ta, tb - ta, brk && i + 1 == n, x);
      ++steps;
      if (!all_finite(x)) {
        finish();
        return run.non_finite(tb);
      }
      t_reached = tb;
    }
    t = te;
    if (te == ts) {
      ++k;
      last_sample = ts;
      if constexpr (std::is_convertible_v<std::invoke_result_t<Obs&, double, const X&>, bool>) {
        if (!obs(ts, static_cast<const X&>(x))) {
          finish();
          return run.stopped_by_observer(ts);
        }
      } else {
        obs(ts, static_cast<const X&>(x));
      }
    }
  }
  return finish();
}

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
    // one). Relative to the time reached, not to the horizon: 1e-14 of a 1e8 s horizon (1e-6 s) was
    // above the steps an honest transient at t = 0 needs, so long horizons stalled at once.
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
