// A driver's run status, its sample grid and bookkeeping, and the fixed-step driver loop (rk4 and
// the exact method's steps) that driver_loops.hpp's drivers share.
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
    // A breakpoint at t_end itself too: the last step then ends on the input's value before it,
    // not on the jump's (which would smear a step at t_end over the last step).
    for (double b : bps)
      if (b > t0 && b <= t_end) breaks.push_back(b);
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
// Eigen's allFinite() compares and branches entry by entry.
template <class X>
POGEAR_RT_INLINE bool all_finite(const X& x) {
  return (x - x).sum() == 0;
}

// Fixed steps: each interval between consecutive stops (samples and breakpoints) is cut into the
// fewest equal steps not longer than h, so that steps land exactly on both. The counters live in
// locals, written back to run on the way out: run's address escapes into the error paths, so its
// members would go through memory on every step.
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
      // Counted in double and checked before the conversion: a count beyond a long's range would
      // wrap, and a tiny step become one long step per sample, past rk4's stability check.
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

}  // namespace detail

}  // namespace pogear::rt
