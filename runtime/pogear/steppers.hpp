// Time steppers shared by generated simulators (fixed-size Eigen vectors) and the interpreted mode
// (Eigen::VectorXd): RK4, Dormand-Prince 5(4) with dense output, and TR-BDF2 for stiff scenes.
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

namespace pogear::rt {

// The system is any callable f(double t, const X& x, X& dx); the steppers keep their stage vectors as
// members sized once from the initial state, so a step never allocates when X is fixed-size.

// Time at which a step [t0, t1] evaluates its end stages. Inputs are right-continuous, so when t1 is a
// breakpoint the step must see the input just before it, or the jump leaks into the step (and into
// the error estimate, which would then reject the step over and over).
inline double stage_end(double t0, double t1, bool ends_on_break) {
  return ends_on_break ? std::nextafter(t1, t0) : t1;
}

// Weighted RMS norm of the usual ODE codes: 1 means "exactly at tolerance". A plain loop: as fast as
// an Eigen reduction at these sizes, and it avoids the vectorized reductions that GCC 12 flags with
// false -Wuninitialized warnings under AVX-512 (Eigen's products still trigger them).
template <class X>
double error_norm(const X& e, const X& a, const X& b, double rtol, double atol) {
  double sum = 0;
  for (Eigen::Index i = 0; i < e.size(); ++i) {
    const double r = e[i] / (atol + rtol * std::max(std::abs(a[i]), std::abs(b[i])));
    sum += r * r;
  }
  return e.size() == 0 ? 0 : std::sqrt(sum / static_cast<double>(e.size()));
}

template <class X>
struct Rk4 {
  X k1, k2, k3, k4, tmp;
  long rhs_evals = 0;

  explicit Rk4(const X& x) : k1(x), k2(x), k3(x), k4(x), tmp(x) {}

  template <class F>
  void step(F& f, double t, double h, X& x, bool ends_on_break = false) {
    f(t, x, k1);
    tmp = x + (0.5 * h) * k1;
    f(t + 0.5 * h, tmp, k2);
    tmp = x + (0.5 * h) * k2;
    f(t + 0.5 * h, tmp, k3);
    tmp = x + h * k3;
    f(stage_end(t, t + h, ends_on_break), tmp, k4);
    x += (h / 6) * (k1 + 2 * k2 + 2 * k3 + k4);
    rhs_evals += 4;
  }
};

// Adaptive steppers share one protocol, driven by run_adaptive in drivers.hpp:
//   start(t, x)            derivative at the start (again after each breakpoint: f jumps there)
//   attempt(t, x, h, brk)  trial step; returns its error norm: <= 1 accept, NaN the trial is not
//                          finite, +inf its stage equations could not be solved
//   accept(t, x, h)        x becomes the trial result; sets up dense output over [t, t+h]
//   dense(t, out)          state at t inside the last accepted step
//   next_h(err, h)         step size controller, after a trial with error err

// Dormand-Prince 5(4) (Hairer, Norsett & Wanner, "Solving ODEs I", code DOPRI5): FSAL, 5th-order
// result, 4th-order embedded estimate, 4th-order continuous extension.
//
// Written as plain loops over the components rather than Eigen expressions: GCC does not inline
// Eigen's assignment loops for the longer stage sums, so each stage cost a call plus a walk through
// the expression tree, and allFinite() another call. Each loop evaluates every component with the
// same operations in the same order as the Eigen expression it replaces, so stages, result and error
// estimate are bit for bit those of the expression form.
template <class X, class F>
struct Dopri5 {
  F& f;
  double rtol, atol;
  // k1 is the stage at the start of the step. accept() swaps k1 and k7 (first same as last), so until
  // the next attempt the accepted step's own k1 sits in k7 and its k7 in k1.
  X k1, k2, k3, k4, k5, k6, k7, y1, tmp, r1, r2, r3, r4, r5;
  double t_old = 0, h_old = 1, facold = 1e-4;
  // log(facold): the controller needs err^0.17 / facold^0.04; from logs that is one exp per step
  // instead of two pow calls (each several times an exp), and log(err) of this step is the next
  // step's log(facold).
  double log_facold = std::log(1e-4);
  // The dense-output coefficients are built on the first dense() after accept(), not in accept():
  // at tight tolerances most steps contain no sample and never need them.
  bool rejected = false, dense_pending = false;
  long rhs_evals = 0;

  Dopri5(F& f_, const X& x, double rtol_, double atol_)
      : f(f_), rtol(rtol_), atol(atol_), k1(x), k2(x), k3(x), k4(x), k5(x), k6(x), k7(x), y1(x),
        tmp(x), r1(x), r2(x), r3(x), r4(x), r5(x) {}

  void start(double t, const X& x) {
    build_dense();  // f overwrites k1, which holds the last step's k7: keep dense() valid
    f(t, x, k1);
    ++rhs_evals;
  }

  double attempt(double t, const X& x, double h, bool ends_on_break) {
    constexpr double a21 = 1.0 / 5, a31 = 3.0 / 40, a32 = 9.0 / 40, a41 = 44.0 / 45, a42 = -56.0 / 15,
                     a43 = 32.0 / 9, a51 = 19372.0 / 6561, a52 = -25360.0 / 2187, a53 = 64448.0 / 6561,
                     a54 = -212.0 / 729, a61 = 9017.0 / 3168, a62 = -355.0 / 33, a63 = 46732.0 / 5247,
                     a64 = 49.0 / 176, a65 = -5103.0 / 18656, a71 = 35.0 / 384, a73 = 500.0 / 1113,
                     a74 = 125.0 / 192, a75 = -2187.0 / 6784, a76 = 11.0 / 84;
    constexpr double e1 = 71.0 / 57600, e3 = -71.0 / 16695, e4 = 71.0 / 1920, e5 = -17253.0 / 339200,
                     e6 = 22.0 / 525, e7 = -1.0 / 40;
    dense_pending = false;  // the stages are about to change: the last step's dense output is gone
    const Eigen::Index n = x.size();
    const double t_end = stage_end(t, t + h, ends_on_break), ha21 = h * a21;
    for (Eigen::Index i = 0; i < n; ++i) tmp[i] = x[i] + ha21 * k1[i];
    f(t + 0.2 * h, tmp, k2);
    for (Eigen::Index i = 0; i < n; ++i) tmp[i] = x[i] + h * (a31 * k1[i] + a32 * k2[i]);
    f(t + 0.3 * h, tmp, k3);
    for (Eigen::Index i = 0; i < n; ++i) tmp[i] = x[i] + h * (a41 * k1[i] + a42 * k2[i] + a43 * k3[i]);
    f(t + 0.8 * h, tmp, k4);
    for (Eigen::Index i = 0; i < n; ++i)
      tmp[i] = x[i] + h * (a51 * k1[i] + a52 * k2[i] + a53 * k3[i] + a54 * k4[i]);
    f(t + (8.0 / 9) * h, tmp, k5);
    for (Eigen::Index i = 0; i < n; ++i)
      tmp[i] = x[i] + h * (a61 * k1[i] + a62 * k2[i] + a63 * k3[i] + a64 * k4[i] + a65 * k5[i]);
    f(t_end, tmp, k6);
    for (Eigen::Index i = 0; i < n; ++i)
      y1[i] = x[i] + h * (a71 * k1[i] + a73 * k3[i] + a74 * k4[i] + a75 * k5[i] + a76 * k6[i]);
    f(t_end, y1, k7);
    rhs_evals += 6;
    // The error estimate and its scaled components in one vectorizable pass; the sum of squares is
    // then taken in the same order as error_norm(), so the norm is error_norm()'s to the last bit.
    // v - v is 0 for finite v and NaN otherwise: one sum checks y1 and the estimate for non-finite
    // entries (a NaN or inf in y1 could otherwise vanish from the norm through the max()).
    double finite = 0;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double e = h * (e1 * k1[i] + e3 * k3[i] + e4 * k4[i] + e5 * k5[i] + e6 * k6[i] + e7 * k7[i]);
      finite += (y1[i] - y1[i]) + (e - e);
      tmp[i] = e / (atol + rtol * std::max(std::abs(x[i]), std::abs(y1[i])));
    }
    if (!(finite == 0)) return std::numeric_limits<double>::quiet_NaN();
    double sum = 0;
    for (Eigen::Index i = 0; i < n; ++i) sum += tmp[i] * tmp[i];
    return n == 0 ? 0 : std::sqrt(sum / static_cast<double>(n));
  }

  void accept(double t, X& x, double h) {
    r1 = x;
    x = y1;
    k1.swap(k7);  // first same as last
    t_old = t;
    h_old = h;
    dense_pending = true;
  }

  // The coefficients of the continuous extension of the last accepted step, as DOPRI5 computes them
  // (r1 = x_old, r2 = y1 - x_old, r3 = h k1 - r2, r4 = r2 - h k7 - r3, r5 = h sum d_j k_j) with k1 and
  // k7 in each other's place (see accept()); y1 still holds the step's result. With out, also the
  // state at theta = th, in the same pass: evaluating from the registers avoids reloading the
  // coefficients right after storing them (GCC 12 does not vectorize this loop, and packed loads of
  // just-stored scalars stall on store forwarding).
  void build_dense(double th = 0, X* out = nullptr) {
    if (!dense_pending) return;
    constexpr double d1 = -12715105075.0 / 11282082432, d3 = 87487479700.0 / 32700410799,
                     d4 = -10690763975.0 / 1880347072, d5 = 701980252875.0 / 199316789632,
                     d6 = -1453857185.0 / 822651844, d7 = 69997945.0 / 29380423;
    const double h = h_old, th1 = 1 - th;
    for (Eigen::Index i = 0; i < r1.size(); ++i) {  // k7[i] is the step's k1, k1[i] its k7
      const double c2 = y1[i] - r1[i], c3 = h * k7[i] - c2, c4 = c2 - h * k1[i] - c3,
                   c5 = h * (d1 * k7[i] + d3 * k3[i] + d4 * k4[i] + d5 * k5[i] + d6 * k6[i] + d7 * k1[i]);
      r2[i] = c2;
      r3[i] = c3;
      r4[i] = c4;
      r5[i] = c5;
      if (out) (*out)[i] = r1[i] + th * (c2 + th1 * (c3 + th * (c4 + th1 * c5)));
    }
    dense_pending = false;
  }

  void dense(double t, X& out) {
    const double th = (t - t_old) / h_old, th1 = 1 - th;
    out.resize(r1.size());
    if (dense_pending) return build_dense(th, &out);
    for (Eigen::Index i = 0; i < r1.size(); ++i)
      out[i] = r1[i] + th * (r2[i] + th1 * (r3[i] + th * (r4[i] + th1 * r5[i])));
  }

  // DOPRI5's PI controller (beta = 0.04, safety 0.9, step ratio within [0.2, 10]); after a rejection
  // the step may not grow, which avoids reject/accept ping-pong. err^0.17 / facold^0.04 is taken as
  // exp(0.17 log err - 0.04 log facold): the same quantity, rounded differently (relative
  // differences of a few 1e-16 in h, far below anything the controller responds to).
  double next_h(double err, double h) {
    if (std::isnan(err)) {
      rejected = true;
      return 0.1 * h;
    }
    const double log_err = std::log(err);
    if (err > 1) {
      rejected = true;
      return h / std::min(5.0, std::exp((0.2 - 0.04 * 0.75) * log_err) / 0.9);
    }
    double hnew = h / std::clamp(std::exp((0.2 - 0.04 * 0.75) * log_err - 0.04 * log_facold) / 0.9, 0.1, 5.0);
    if (err > 1e-4) {
      facold = err;
      log_facold = log_err;
    } else {
      facold = 1e-4;
      log_facold = std::log(1e-4);
    }
    if (rejected) hnew = std::min(hnew, h);
    rejected = false;
    return hnew;
  }
};

}  // namespace pogear::rt

// TR-BDF2, after the helpers it shares.
#include "pogear/trbdf2.hpp"
