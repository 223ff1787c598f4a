// Drivers: integrate a model from t0 to t_end with one of the methods and hand the state to an
// observer exactly at the sample times t0 + k dt, landing on input breakpoints on the way.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <limits>
#include <string>
#include <type_traits>
#include <vector>

#include "pogear/exact.hpp"
#include "pogear/steppers.hpp"

namespace pogear::rt {

struct SolverOptions {
  double rtol = 1e-8, atol = 1e-10;
  double h = 1e-4;  // rk4 and exact: largest step; dopri5 and implicit: first step
  double h_max = std::numeric_limits<double>::infinity();
  long max_steps = 100000000;  // adaptive methods count rejected attempts too
};

struct RunStatus {
  bool ok = true;
  std::string message;
  double t_reached = 0;  // time of the last state computed (accepted)
  long steps = 0, rhs_evals = 0, jac_evals = 0, lu_decompositions = 0;
};

// Observers are obs(double t, const X& x); one returning bool can stop the run by returning false
// (e.g. when its output file cannot be written).
namespace detail {

inline std::string num(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 10).ptr);
}

// The sample times, computed as t0 + k dt rather than accumulated so that late samples are as exact
// as early ones. The last sample is t_end itself, also when (t_end - t0) / dt is not a whole number.
struct Grid {
  double t0 = 0, dt = 1, t_end = 0;
  long count = 1;
  double at(long k) const { return k + 1 == count ? t_end : t0 + static_cast<double>(k) * dt; }
};

// Bookkeeping common to all drivers: status, sample grid, the breakpoints still ahead.
struct Run {
  RunStatus st;
  Grid grid;
  std::vector<double> breaks;  // sorted, inside (t0, t_end)
  std::size_t next_break = 0;
  long k = 0;  // next sample to emit
  double last_sample = std::numeric_limits<double>::quiet_NaN();

  RunStatus fail(std::string message) {
    st.ok = false;
    st.message = std::move(message);
    return st;
  }
  bool refuse(std::string message) {
    fail(std::move(message));
    return false;
  }
  RunStatus non_finite(double t) {
    return fail("non-finite state at t = " + num(t) + "; last finite sample at t = " + num(last_sample));
  }
  template <class X>
  bool setup(const X& x, double t0, double t_end, double dt, const SolverOptions& opt,
             const std::vector<double>& bps) {
    st.t_reached = t0;
    if (!std::isfinite(t0) || !std::isfinite(t_end) || !(t_end >= t0) || !(dt > 0))
      return refuse("invalid time span: t0 = " + num(t0) + ", t_end = " + num(t_end) + ", dt = " + num(dt));
    if (!(opt.h > 0) || !(opt.h_max > 0)) return refuse("invalid step size h = " + num(opt.h));
    if (!x.allFinite()) return refuse("non-finite initial state at t = " + num(t0));
    const double n = (t_end - t0) / dt;
    auto steps = std::llround(n);
    if (std::abs(n - static_cast<double>(steps)) > 1e-9 * std::max(1.0, n)) steps = std::llround(std::ceil(n));
    grid = {t0, dt, t_end, static_cast<long>(steps) + 1};
    for (double b : bps)
      if (b > t0 && b < t_end) breaks.push_back(b);
    std::sort(breaks.begin(), breaks.end());
    breaks.erase(std::unique(breaks.begin(), breaks.end()), breaks.end());
    return true;
  }
  template <class Obs, class X>
  bool emit(Obs& obs, double t, const X& x) {
    ++k;
    last_sample = t;
    if constexpr (std::is_convertible_v<std::invoke_result_t<Obs&, double, const X&>, bool>) {
      if (!obs(t, x)) return refuse("stopped by the observer at t = " + num(t));
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
bool all_finite(const X& x) {
  return (x - x).sum() == 0;
}

// Fixed steps: each interval between consecutive stops (samples and breakpoints) is cut into the
// fewest equal steps not longer than h, so that steps land exactly on both.
template <class X, class Advance, class Obs>
RunStatus run_fixed(const char* name, Advance&& advance, X& x, double t0, double t_end, double dt,
                    const SolverOptions& opt, Obs& obs, const std::vector<double>& bps) {
  Run run;
  if (!run.setup(x, t0, t_end, dt, opt, bps) || !run.emit(obs, t0, x)) return run.st;
  double t = t0;
  // The step count of the previous interval: consecutive sample intervals differ by rounding only,
  // so the division and ceil (a libm call without SSE4.1) are done once, not on every sample.
  double last_len = -1;
  long n = 1;
  while (run.k < run.grid.count) {
    const double ts = run.grid.at(run.k);
    const bool brk = run.next_break < run.breaks.size() && run.breaks[run.next_break] <= ts;
    const double te = brk ? run.breaks[run.next_break++] : ts;
    const double len = te - t;
    if (!(std::abs(len - last_len) <= 1e-9 * last_len)) {
      n = std::max(1L, static_cast<long>(std::ceil(len / opt.h - 1e-9)));
      last_len = len;
    }
    const double hs = n == 1 ? len : len / static_cast<double>(n);
    for (long i = 0; i < n; ++i) {
      if (run.st.steps >= opt.max_steps)
        return run.fail(std::string(name) + " stopped at t = " + num(run.st.t_reached) +
                        ": max_steps = " + std::to_string(opt.max_steps) + " reached");
      const double ta = t + static_cast<double>(i) * hs, tb = i + 1 == n ? te : ta + hs;
      advance(ta, tb - ta, brk && i + 1 == n, x);
      ++run.st.steps;
      if (!all_finite(x)) return run.non_finite(tb);
      run.st.t_reached = tb;
    }
    t = te;
    if (te == ts && !run.emit(obs, ts, x)) return run.st;
  }
  return run.st;
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
  auto stalled = [&](const std::string& why) {
    return run.fail(std::string(name) + " stalled at t = " + num(t) + ": " + why + "; " + advice);
  };
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
    const double hmin = 1e-14 * std::max(std::abs(t), t_end - t0);
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

// As simulate_exact below, with the discretization of the nominal step (exact_nominal_step(dt,
// opt.h)) computed beforehand: a sweep that runs one model many times pays for the matrix
// exponential once. M and N serve the other step sizes (next to breakpoints, a partial last interval).
template <int NX, int NU, class UFun, class Obs>
RunStatus simulate_exact(const ExactDiscretization<NX, NU>& nominal, const Eigen::Matrix<double, NX, NX>& M,
                         const Eigen::Matrix<double, NX, NU>& N, UFun&& u, Eigen::Matrix<double, NX, 1> x, double t0,
                         double t_end, double dt, const SolverOptions& opt, Obs&& obs,
                         const std::vector<double>& breaks = {}) {
  using D = ExactDiscretization<NX, NU>;
  if (!(dt > 0) || !(opt.h > 0)) return detail::Run{}.fail("invalid step: dt = " + detail::num(dt));
  // Step lengths within 1e-9 of each other differ by rounding of the grid times only.
  auto same = [](double a, double b) { return std::abs(a - b) <= 1e-9 * b; };
  const double h_nom = nominal.h;
  if (!same(h_nom, exact_nominal_step(dt, opt.h)))
    return detail::Run{}.fail("the discretization's step " + detail::num(h_nom) + " is not the nominal step " +
                              detail::num(exact_nominal_step(dt, opt.h)) + " of dt and h");
  D odd;  // the last other step size (next to breakpoints, the final partial interval)
  typename D::Input u0 = D::Input::Zero(N.cols()), u1 = u0;
  typename D::State xn = x;
  bool u0_valid = false;
  auto advance = [&](double t, double h, bool brk, typename D::State& xs) {
    const D* disc = &nominal;
    if (!same(h, h_nom)) {
      if (!same(h, odd.h)) odd = D(M, N, h);
      disc = &odd;
    }
    if (!u0_valid) u(t, u0);
    u(stage_end(t, t + h, brk), u1);
    disc->step(xs, u0, u1, xn);
    xs = xn;
    u0 = u1;
    u0_valid = !brk;  // after a breakpoint the input restarts from its new (right) value
  };
  return detail::run_fixed("exact", advance, x, t0, t_end, dt, opt, obs, breaks);
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
