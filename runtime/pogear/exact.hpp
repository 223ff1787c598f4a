// Exact discretization of linear models dx/dt = M x + N u with a first-order hold on the inputs:
// one matrix exponential per step size at setup, then each step is three matrix-vector products.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <unsupported/Eigen/MatrixFunctions>

namespace pogear::rt {

// Over a step [t, t+h] the input is taken as the straight line through u0 = u(t) and u1 = u(t+h):
//   x(t+h) = Phi x(t) + Gamma0 u0 + Gamma1 (u1 - u0)
//   Phi = e^{M h},  Gamma0 = int_0^h e^{M s} ds N,  Gamma1 = (1/h) int_0^h e^{M (h-s)} s ds N.
// This is the exact solution (up to rounding) whenever u is linear over the step, constant included;
// for other inputs the error is that of linear interpolation of u, O(h^2 max|u''|) per unit time.
// All three come from one exponential (Van Loan, 1978) of the augmented system x' = Mx + Nu,
// u' = w/h, w' = 0, whose start value w = u1 - u0 makes u the line above:
//   exp([[M h, N h, 0], [0, 0, I], [0, 0, 0]]) = [[Phi, Gamma0, Gamma1], [0, I, I], [0, 0, I]].
// NU may be 0 (no inputs); NX and NU may be Eigen::Dynamic for the interpreted mode.
// e^C through a balanced matrix: C' = D^-1 C D with D diagonal, powers of 2 chosen so that each
// row and column of C' have about the same norm (Parlett & Reinsch 1969, LAPACK's dgebal without
// permutations), then e^C = D e^C' D^-1. The scaling is exact in floating point. It matters for gear
// models: their states mix velocities (rad/s) and mesh forces (N), so M h has entries from ~1e-3 to
// ~200 (the stiff K rows) while its eigenvalues are O(1). Balanced, the norm drops to O(1): scaling
// and squaring needs fewer squarings, and Phi's rounding error, which the lightly damped modes
// accumulate over thousands of steps, drops from ~1e-14 to ~1e-16 relative (on the one-stage paper
// scene the sampled error of exact stepping falls from 6e-12 to ~1e-13).
inline Eigen::MatrixXd balanced_exp(Eigen::MatrixXd C) {
  const Eigen::Index n = C.rows();
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  // Bounded passes and factors (2^-64 ... 2^64 per pass): balancing converges in a few passes, and
  // the bounds keep non-finite or extreme entries from looping or overflowing.
  bool done = false;
  for (int pass = 0; pass < 50 && !done; ++pass) {
    done = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double c = C.col(i).cwiseAbs().sum() - std::abs(C(i, i));
      const double r = C.row(i).cwiseAbs().sum() - std::abs(C(i, i));
      if (!(c > 0) || !(r > 0) || !std::isfinite(c) || !std::isfinite(r)) continue;  // nothing to balance
      double f = 1, cs = c;
      for (int k = 0; k < 64 && cs < r / 2; ++k) f *= 2, cs *= 4;
      for (int k = 0; k < 64 && cs > 2 * r; ++k) f /= 2, cs /= 4;
      if ((cs + r) / f < 0.95 * (c + r)) {  // row i scaled by 1/f, column i by f
        done = false;
        d(i) *= f;
        C.row(i) /= f;
        C.col(i) *= f;
      }
    }
  }
  Eigen::MatrixXd E = C.exp();
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) E(i, j) *= d(i) / d(j);
  return E;
}

template <int NX, int NU>
struct ExactDiscretization {
  using State = Eigen::Matrix<double, NX, 1>;
  using Input = Eigen::Matrix<double, NU, 1>;
  using StateMatrix = Eigen::Matrix<double, NX, NX>;
  using InputMatrix = Eigen::Matrix<double, NX, NU>;

  StateMatrix Phi;
  InputMatrix Gamma0, Gamma1;
  InputMatrix GammaD;  // Gamma0 - Gamma1, the weight of u0 in step()
  double h = 0;

  ExactDiscretization() = default;
  ExactDiscretization(const StateMatrix& M, const InputMatrix& N, double h_) : h(h_) {
    eigen_assert(M.rows() == M.cols() && N.rows() == M.rows());
    const Eigen::Index n = M.rows(), m = N.cols();
    // Built dynamic: this runs once per step size, and MatrixFunctions is best exercised on MatrixXd.
    Eigen::MatrixXd C = Eigen::MatrixXd::Zero(n + 2 * m, n + 2 * m);
    C.topLeftCorner(n, n) = M * h;
    C.block(0, n, n, m) = N * h;
    C.block(n, n + m, m, m).setIdentity();
    const Eigen::MatrixXd E = balanced_exp(C);
    Phi = E.topLeftCorner(n, n);
    Gamma0 = E.block(0, n, n, m);
    Gamma1 = E.block(0, n + m, n, m);
    GammaD = Gamma0 - Gamma1;
  }

  // out must not alias x. No allocation for fixed sizes (and none for dynamic ones once out is sized).
  // Computed as Phi x + (Gamma0 - Gamma1) u0 + Gamma1 u1. Consecutive steps form a chain of dependent
  // sums, so for small fixed sizes the latency of the sum over Phi's columns, not the arithmetic,
  // bounds the speed: it runs as two independent halves, each a coefficient-wise (lazy, inlined)
  // product, added at the end. That takes 46 instead of 69 cycles per step for the 10-state paper
  // model (SSE2); beyond 16 states Eigen's blocked matrix-vector product is faster again. Always
  // inlined: as a call, the driver's state round-trips through memory (87 instead of 63 cycles per
  // step of simulate_exact on that model).
  EIGEN_ALWAYS_INLINE void step(const State& x, const Input& u0, const Input& u1, State& out) const {
    if constexpr (NX == Eigen::Dynamic || NX < 2 || NX > 16) {
      out.noalias() = Phi * x;
      if (GammaD.cols() == 0) return;
      out.noalias() += GammaD * u0;
      out.noalias() += Gamma1 * u1;
    } else {
      constexpr int H = NX / 2;
      const auto first = Phi.template leftCols<H>().lazyProduct(x.template head<H>());
      const auto second = Phi.template rightCols<NX - H>().lazyProduct(x.template tail<NX - H>());
      if constexpr (NU == 0)
        out.noalias() = first + second;
      else
        out.noalias() = (first + GammaD.lazyProduct(u0)) + (second + Gamma1.lazyProduct(u1));
    }
  }
  State step(const State& x, const Input& u0, const Input& u1) const {
    State out(x.size());
    step(x, u0, u1, out);
    return out;
  }
};

}  // namespace pogear::rt
