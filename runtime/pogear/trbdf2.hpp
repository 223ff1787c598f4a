// TR-BDF2, the implicit stepper for stiff scenes, with the stepper protocol of steppers.hpp (which
// includes this file: steppers.hpp is the one to include).
#pragma once

#include <Eigen/Core>
#include <Eigen/LU>
#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include "pogear/steppers.hpp"

namespace pogear::rt {

// TR-BDF2 (Bank et al. 1985; Hosea & Shampine 1996, the method of MATLAB's ode23tb) for stiff
// scenes. Chosen because it is L-stable (stiff modes are damped, never ring), both implicit stages
// share one iteration matrix I - d h J (one LU per step size), it has a cheap embedded 3rd-order
// error estimate, and it is short. As a 3-stage ESDIRK with gamma = 2 - sqrt(2), d = gamma/2,
// w = sqrt(2)/4:  c = (0, gamma, 1),  A = [[0], [d, d], [w, w, d]],  b = (w, w, d),
// b_hat = ((1 - w)/3, (3w + 1)/3, d/3). 2nd order, so suited to moderate tolerances.
// jac(t, x, J) fills the Jacobian df/dx. constant_jacobian says f is affine in x (a linear model):
// J is then evaluated once and every Newton solve is exact in one iteration.
template <class X, class F, class JacF>
struct TrBdf2 {
  using Jac = Eigen::Matrix<double, X::RowsAtCompileTime, X::RowsAtCompileTime>;
  static constexpr double gamma = 2 - std::numbers::sqrt2, d = gamma / 2, w = std::numbers::sqrt2 / 4;

  F& f;
  JacF& jac;
  bool constant_jacobian;
  double rtol, atol;
  Jac J, G;
  Eigen::PartialPivLU<Jac> lu;
  X f0, zg, fg, y1, f1, rhs, dz, tmp, est, qy, qh, qa, qb;
  double lu_h = 0, t_old = 0, h_old = 1;
  bool have_jac = false, jac_fresh = false, slow_newton = false, rejected = false;
  long rhs_evals = 0, jac_evals = 0, lu_decompositions = 0;

  TrBdf2(F& f_, JacF& jac_, bool constant_jacobian_, const X& x, double rtol_, double atol_)
      : f(f_), jac(jac_), constant_jacobian(constant_jacobian_), rtol(rtol_), atol(atol_),
        J(Jac::Zero(x.size(), x.size())), G(J), lu(x.size()), f0(x), zg(x), fg(x), y1(x), f1(x),
        rhs(x), dz(x), tmp(x), est(x), qy(x), qh(x), qa(x), qb(x) {}

  void update_jacobian(double t, const X& x) {
    jac(t, x, J);
    ++jac_evals;
    have_jac = jac_fresh = true;
    lu_h = 0;  // forces a refactorization
  }

  void start(double t, const X& x) {
    f(t, x, f0);
    ++rhs_evals;
    if (!have_jac || !constant_jacobian) update_jacobian(t, x);
  }

  // Simplified Newton for z - d h f(ts, z) = rhs. The stopping test keeps the iteration error far
  // below the local error tolerance; a ratio of successive corrections above 0.9 means the iteration
  // does not contract (stale J or h too large), and the caller retries.
  bool solve_stage(double ts, double dh, X& z) {
    double prev = 0;
    for (int it = 0; it < 10; ++it) {
      f(ts, z, tmp);
      ++rhs_evals;
      tmp = rhs - z + dh * tmp;
      dz = lu.solve(tmp);
      z += dz;
      if (!dz.allFinite()) return false;
      if (constant_jacobian) return true;  // f affine in x: this iterate is the exact solution
      const double nd = error_norm(dz, z, z, rtol, atol);
      if (it > 2) slow_newton = true;
      if (nd <= 1e-2) return true;
      if (it > 0 && nd > 0.9 * prev) return false;
      prev = nd;
    }
    return false;
  }

  double attempt(double t, const X& x, double h, bool ends_on_break) {
    const double dh = d * h;
    for (;;) {
      if (lu_h != h) {
        G = Jac::Identity(x.size(), x.size()) - dh * J;
        lu.compute(G);
        ++lu_decompositions;
        lu_h = h;
      }
      rhs = x + dh * f0;  // trapezoidal stage to t + gamma h
      zg = x + (gamma * h) * f0;
      bool ok = solve_stage(t + gamma * h, dh, zg);
      if (ok) {
        // Stage derivatives from the stage equations rather than from f: f would amplify the Newton
        // error of a stiff component by |lambda|.
        fg = (zg - rhs) / dh;
        rhs = x + (w * h) * (f0 + fg);  // BDF2 stage to t + h
        y1 = zg + ((1 - gamma) * h) * fg;
        ok = solve_stage(stage_end(t, t + h, ends_on_break), dh, y1);
      }
      if (ok) break;
      if (!zg.allFinite() || !y1.allFinite()) return std::numeric_limits<double>::quiet_NaN();
      if (constant_jacobian || jac_fresh) return std::numeric_limits<double>::infinity();
      update_jacobian(t, x);  // a stale Jacobian is the usual cause: retry once with a fresh one
    }
    f1 = (y1 - rhs) / dh;
    est = h * (((4 * w - 1) / 3) * f0 - (1.0 / 3) * fg + (2 * d / 3) * f1);
    // Shampine's filter: (I - d h J)^-1 keeps the estimate of converged stiff components bounded
    // instead of growing like h |lambda|, which would force explicit-sized steps.
    tmp = lu.solve(est);
    if (!y1.allFinite() || !tmp.allFinite()) return std::numeric_limits<double>::quiet_NaN();
    return error_norm(tmp, x, y1, rtol, atol);
  }

  // Dense output: the cubic through x(t), the stage value at t + gamma h and x(t + h), with slope f1
  // at t + h. Unlike the cubic Hermite through (x, f0, y1, f1) it avoids h f0, which for a stiff mode
  // that has not yet decayed is h |lambda| times the state and makes the interpolant overshoot.
  // Writing s = theta - 1: p = y1 + s h f1 + s^2 (a + b s), with a, b fixed by p(0) = x, p(gamma) = zg.
  void accept(double t, X& x, double h) {
    const double g = gamma - 1;
    qy = y1;
    qh = h * f1;
    tmp = x - y1 + qh;                      // a - b
    est = (zg - y1 - g * qh) / (g * g);     // a + g b
    qb = (est - tmp) / gamma;
    qa = tmp + qb;
    x = y1;
    f0.swap(f1);
    t_old = t;
    h_old = h;
    jac_fresh = false;
    if (slow_newton && !constant_jacobian) update_jacobian(t + h, x);
    slow_newton = false;
  }

  void dense(double t, X& out) const {
    const double s = (t - t_old) / h_old - 1;
    out = qy + s * qh + (s * s) * (qa + s * qb);
  }

  // I controller for a local error of order h^3; new step sizes cost an LU, so small increases wait.
  double next_h(double err, double h) {
    if (std::isnan(err) || std::isinf(err)) {
      rejected = true;
      return (std::isnan(err) ? 0.1 : 0.25) * h;
    }
    double fac = std::clamp(0.9 * std::pow(err, -1.0 / 3), 0.2, 5.0);
    if (err > 1) {
      rejected = true;
      return fac * h;
    }
    if (rejected) fac = std::min(fac, 1.0);
    if (fac >= 1 && fac < 1.2) fac = 1;
    rejected = false;
    return fac * h;
  }
};

}  // namespace pogear::rt
