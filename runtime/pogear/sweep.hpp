// Design sweeps: B runs of one linear model (different inputs and initial states) stepped exactly
// in lockstep, and their outputs computed together, so that the independent runs fill the pipeline.
#pragma once

#include <algorithm>
#include <cmath>
#include <type_traits>
#include <utility>
#include <vector>

#include "pogear/drivers.hpp"

namespace pogear::rt {

// Batches are row-major: entry (i, s) is state (input, output) i of run s, and row i of all runs is
// contiguous, so that one vector operation serves several runs.
template <int NX, int B>
using BatchState = Eigen::Matrix<double, NX, B, Eigen::RowMajor>;
template <int NU, int B>
using BatchInput = Eigen::Matrix<double, NU, B, Eigen::RowMajor>;
template <int NY, int B>
using BatchOutput = Eigen::Matrix<double, NY, B, Eigen::RowMajor>;

// Outputs y = C x + D u of a generated system, from its output_matrices(p, C, D): the generator
// reads them off the output expressions (eq. 8's mesh forces, which read dx/dt = M x + N u, too).
template <int NY, int NX, int NU>
struct LinearOutputs {
  Eigen::Matrix<double, NY, NX> C;
  Eigen::Matrix<double, NY, NU> D;
};

// C and D of a system with fixed sizes (System::nx, nu, ny and output_matrices(p, C, D)).
template <class System>
LinearOutputs<System::ny, System::nx, System::nu> linear_outputs(const System& sys,
                                                                const typename System::Params& p) {
  LinearOutputs<System::ny, System::nx, System::nu> lo;
  sys.output_matrices(p, lo.C, lo.D);
  return lo;
}

namespace detail {
// Y = C X + D U over B runs, W runs per operation. Each output adds its terms to 0 in operand order.
// |v|: the sign bit (that of -0.0) cleared, one operation.
template <class V>
POGEAR_RT_INLINE void abs_lanes(V& v) {
#if defined(__GNUC__)
  if constexpr (sizeof(V) > sizeof(double)) {
    typedef long long Bits __attribute__((vector_size(sizeof(V))));
    v = (V)((Bits)v & ~(Bits)(-V{}));
    return;
  }
#endif
  if constexpr (sizeof(V) == sizeof(double)) v = std::abs(v);
}

// Peak = true: Y holds running peaks, Y = max(Y, |C X + D U|), and the outputs are never stored.
template <int W, int B, bool Peak = false, int NY, int NX, int NU>
POGEAR_RT_INLINE void batch_outputs_lanes(const LinearOutputs<NY, NX, NU>& lo, const double* X, const double* U,
                                          double* Y) {
  using V = Lanes<W>;
  constexpr int L = B / W;
  static_assert(B % W == 0, "the batch must be a whole number of lanes");
#pragma GCC unroll 64
  for (int i = 0; i < NY; ++i) {
    V acc[L];
    for (int s = 0; s < L; ++s) acc[s] = V{};
#pragma GCC unroll 40
    for (int j = 0; j < NX + NU; ++j) {
      const double c = j < NX ? lo.C(i, j) : lo.D(i, j - NX);
      // A zero input coefficient is skipped (once for all the runs), so that an infinite input
      // cannot turn an output that does not depend on it into NaN. The states need no test: the
      // driver stops at the first non-finite state, before any output of it is computed, and 0 x
      // adds nothing to a finite sum.
      if (j >= NX && c == 0) continue;
      for (int s = 0; s < L; ++s) {
        V v;  // loaded where used: a local copy of the operands may be stored in halves and stall
        if (j < NX) load(v, X + j * B + s * W);
        else load_pairs(v, U + (j - NX) * B + s * W);
        acc[s] = acc[s] + c * v;
      }
    }
    for (int s = 0; s < L; ++s) {
      if constexpr (Peak) {
        V p;
        load(p, Y + i * B + s * W);
        abs_lanes(acc[s]);
        acc[s] = p < acc[s] ? acc[s] : p;
      }
      store(Y + i * B + s * W, acc[s]);
    }
  }
}
}  // namespace detail

// Y = C X + D U for a batch. It agrees with the system's own outputs to rounding, not to the bit:
// the generated code groups the same terms differently (eq. 8 through the derivatives).
template <int NY, int NX, int NU, int B>
void batch_outputs(const LinearOutputs<NY, NX, NU>& lo, const BatchState<NX, B>& X, const BatchInput<NU, B>& U,
                   BatchOutput<NY, B>& Y) {
  detail::batch_outputs_lanes<B % detail::kDefaultLanes == 0 ? detail::kDefaultLanes : 1, B>(lo, X.data(), U.data(),
                                                                                             Y.data());
}

// peak(i, s) = max(peak(i, s), |Y(i, s)|): the usual reduction of a sweep, for an observer of
// simulate_exact_batch. Written on 4-double lanes, so that inlined into the AVX2 driver it runs in
// AVX2 registers (Eigen's own expressions stay at SSE2 width there).
template <int NY, int B>
POGEAR_RT_INLINE void update_peaks(const BatchOutput<NY, B>& Y, BatchOutput<NY, B>& peak) {
  constexpr int W = B % 4 == 0 ? 4 : B % 2 == 0 ? 2 : 1;
  using V = detail::Lanes<W>;
#pragma GCC unroll 64
  for (int i = 0; i < NY * B; i += W) {
    V y, p;
    detail::load(y, Y.data() + i);
    detail::load(p, peak.data() + i);
    detail::abs_lanes(y);
    if constexpr (W > 1) p = p < y ? y : p;
    else p = std::max(p, y);
    detail::store(peak.data() + i, p);
  }
}

namespace detail {

// What sweep_exact_peaks hands the batch driver: the outputs to reduce, and where.
template <int NY, int NX, int NU, int B>
struct PeakOutputs {
  const LinearOutputs<NY, NX, NU>* lo;
  BatchOutput<NY, B>* peak;
};
template <class T>
inline constexpr bool is_peak_outputs = false;
template <int NY, int NX, int NU, int B>
inline constexpr bool is_peak_outputs<PeakOutputs<NY, NX, NU, B>> = true;

// simulate_exact_batch's body; W is the lane width. Lo is std::nullptr_t (obs sees the states) or
// LinearOutputs (obs also sees the outputs, computed here so that they get the same lanes).
template <int W, int B, int NX, int NU, class Lo, class UFun, class Obs>
POGEAR_RT_INLINE RunStatus simulate_exact_batch_lanes(const ExactDiscretization<NX, NU>& nominal,
                                                      const Eigen::Matrix<double, NX, NX>& M,
                                                      const Eigen::Matrix<double, NX, NU>& N, const Lo& lo, UFun& u,
                                                      BatchState<NX, B>& X, double t0, double t_end, double dt,
                                                      const SolverOptions& opt, Obs& obs,
                                                      const std::vector<double>& breaks) {
  using D = ExactDiscretization<NX, NU>;
  D odd;
  // The inputs at the start and at the end of a step, swapped rather than copied after each step.
  BatchInput<NU, B> Ua = BatchInput<NU, B>::Zero(), Ub = Ua;
  BatchInput<NU, B>*U0 = &Ua, *U1 = &Ub;
  bool u0_valid = false;
  const double h_nom = nominal.h, tol_nom = 1e-9 * nominal.h;
  auto discretize = [&](double h) { return D(M, N, h); };
  auto advance = [&](double t, double h, bool brk, BatchState<NX, B>& xs) POGEAR_RT_LAMBDA_INLINE {
    const D* disc = &nominal;
    if (!(std::abs(h - h_nom) <= tol_nom)) {
      refresh_odd(odd, discretize, h, xs);
      disc = &odd;
    }
    if (!u0_valid) u(t, *U0);
    u(stage_end(t, t + h, brk), *U1);
    exact_step_batch<W, B>(disc->kernel, xs.data(), U0->data(), U1->data(), xs.data());
    std::swap(U0, U1);
    u0_valid = !brk;  // after a breakpoint the input restarts from its new (right) value
  };
  // A step size whose discretization cannot be trusted stops the run (refresh_odd): say so.
  auto reported = [&](RunStatus st) {
    if (!st.ok && odd.h > 0 && !odd.accurate()) st.message = inaccurate_exact_step(odd.h, odd.rounding);
    return st;
  };
  if constexpr (std::is_same_v<Lo, std::nullptr_t>) {
    return reported(run_fixed("exact", advance, X, t0, t_end, dt, opt, obs, breaks));
  } else if constexpr (is_peak_outputs<Lo>) {
    auto peaks = [&](double t, const BatchState<NX, B>& xs) POGEAR_RT_LAMBDA_INLINE {
      if (!u0_valid) {
        u(t, *U0);
        u0_valid = true;
      }
      batch_outputs_lanes<W, B, true>(*lo.lo, xs.data(), U0->data(), lo.peak->data());
    };
    return reported(run_fixed("exact", advance, X, t0, t_end, dt, opt, peaks, breaks));
  } else {
    constexpr int NY = std::remove_cvref_t<decltype(lo.C)>::RowsAtCompileTime;
    BatchOutput<NY, B> Y;
    // The outputs at a sample take the inputs at that time, right-continuous: U0 holds them after
    // a step that ends on the sample, except at t0 and after a breakpoint, where they are asked
    // for (the next step then reuses them, as it would ask for them too).
    auto with_outputs = [&](double t, const BatchState<NX, B>& xs) POGEAR_RT_LAMBDA_INLINE {
      if (!u0_valid) {
        u(t, *U0);
        u0_valid = true;
      }
      batch_outputs_lanes<W, B>(lo, xs.data(), U0->data(), Y.data());
      return obs(t, xs, static_cast<const BatchOutput<NY, B>&>(Y));
    };
    return reported(run_fixed("exact", advance, X, t0, t_end, dt, opt, with_outputs, breaks));
  }
}

#if defined(POGEAR_RT_AVX2_DISPATCH)
template <int B, int NX, int NU, class Lo, class UFun, class Obs>
POGEAR_RT_TARGET_AVX2 RunStatus simulate_exact_batch_avx2(const ExactDiscretization<NX, NU>& nominal,
                                                          const Eigen::Matrix<double, NX, NX>& M,
                                                          const Eigen::Matrix<double, NX, NU>& N, const Lo& lo,
                                                          UFun& u, BatchState<NX, B>& X, double t0, double t_end,
                                                          double dt, const SolverOptions& opt, Obs& obs,
                                                          const std::vector<double>& breaks) {
  // The user's functions entered clean (CleanUpperCall); sweep_exact_peaks has no observer to call.
  CleanUpperCall<UFun> clean_u{u};
  CleanUpperCall<Obs> clean_obs{obs};
  return simulate_exact_batch_lanes<B % 4 == 0 ? 4 : 2, B>(nominal, M, N, lo, clean_u, X, t0, t_end, dt, opt, clean_obs,
                                                           breaks);
}
#endif

template <int B, int NX, int NU, class Lo, class UFun, class Obs>
RunStatus simulate_exact_batch(const ExactDiscretization<NX, NU>& nominal, const Eigen::Matrix<double, NX, NX>& M,
                               const Eigen::Matrix<double, NX, NU>& N, const Lo& lo, UFun& u, BatchState<NX, B>& X,
                               double t0, double t_end, double dt, const SolverOptions& opt, Obs& obs,
                               const std::vector<double>& breaks) {
  static_assert(ExactKernel<NX, NU>::enabled, "batches need fixed sizes of at most 32 states and 8 inputs");
  static_assert(B > 0 && B % 2 == 0, "the batch size must be even");
  if (RunStatus bad = check_nominal(nominal, dt, opt); !bad.ok) return bad;
#if defined(POGEAR_RT_AVX2_DISPATCH)
  if (cpu_has_avx2()) return simulate_exact_batch_avx2<B>(nominal, M, N, lo, u, X, t0, t_end, dt, opt, obs, breaks);
#endif
  return simulate_exact_batch_lanes<B % kDefaultLanes == 0 ? kDefaultLanes : 1, B>(nominal, M, N, lo, u, X, t0, t_end,
                                                                                  dt, opt, obs, breaks);
}

}  // namespace detail

// B runs of dx/dt = M x + N u in lockstep, exactly as simulate_exact steps each of them: the same
// grid, breakpoints and step sizes, the same discretizations, and per run the same arithmetic in
// the same order, so run s of the batch gives the bits simulate_exact gives for it alone. The runs
// share the model and the time grid; they differ in X (column s: the initial state of run s) and in
// their inputs: u(t, BatchInput<NU, B>& U) fills column s with run s's inputs at t.
// obs(t, const BatchState<NX, B>& X) sees every run's state at each sample, and may stop the runs by
// returning false. B must be even; 8 suits 2-state models (4 independent chains per AVX2 lane hide
// the latency of a step). Fixed sizes of at most 32 states and 8 inputs. A non-finite state in any
// run stops them all. On x86-64 CPUs with AVX2 the batch runs in AVX2 registers, with the same bits.
template <int B, int NX, int NU, class UFun, class Obs>
RunStatus simulate_exact_batch(const ExactDiscretization<NX, NU>& nominal, const Eigen::Matrix<double, NX, NX>& M,
                               const Eigen::Matrix<double, NX, NU>& N, UFun&& u, BatchState<NX, B> X, double t0,
                               double t_end, double dt, const SolverOptions& opt, Obs&& obs,
                               const std::vector<double>& breaks = {}) {
  return detail::simulate_exact_batch<B>(nominal, M, N, nullptr, u, X, t0, t_end, dt, opt, obs, breaks);
}

// The reduction most design sweeps want, fused into the stepping: peak(i, s) becomes the largest
// of peak(i, s) and |y_i| of run s over all samples (start from zero). The outputs are reduced as
// they are computed, never stored; they are those simulate_exact_batch with lo would give.
template <int B, int NX, int NU, int NY, class UFun>
RunStatus sweep_exact_peaks(const ExactDiscretization<NX, NU>& nominal, const Eigen::Matrix<double, NX, NX>& M,
                            const Eigen::Matrix<double, NX, NU>& N, const LinearOutputs<NY, NX, NU>& lo, UFun&& u,
                            BatchState<NX, B> X, double t0, double t_end, double dt, const SolverOptions& opt,
                            BatchOutput<NY, B>& peak, const std::vector<double>& breaks = {}) {
  const detail::PeakOutputs<NY, NX, NU, B> po{&lo, &peak};
  int no_observer = 0;
  return detail::simulate_exact_batch<B>(nominal, M, N, po, u, X, t0, t_end, dt, opt, no_observer, breaks);
}

// The same with the outputs y = C x + D u of every run at each sample (linear_outputs gives lo):
// obs(t, const BatchState<NX, B>& X, const BatchOutput<NY, B>& Y). They are computed with the
// inputs at the sample time, as the generated main computes them.
template <int B, int NX, int NU, int NY, class UFun, class Obs>
RunStatus simulate_exact_batch(const ExactDiscretization<NX, NU>& nominal, const Eigen::Matrix<double, NX, NX>& M,
                               const Eigen::Matrix<double, NX, NU>& N, const LinearOutputs<NY, NX, NU>& lo, UFun&& u,
                               BatchState<NX, B> X, double t0, double t_end, double dt, const SolverOptions& opt,
                               Obs&& obs, const std::vector<double>& breaks = {}) {
  return detail::simulate_exact_batch<B>(nominal, M, N, lo, u, X, t0, t_end, dt, opt, obs, breaks);
}

}  // namespace pogear::rt
