// Exact discretization of linear models dx/dt = M x + N u with a first-order hold on the inputs:
// one matrix exponential per step size at setup, then each step is three matrix-vector products.
#pragma once

#include <Eigen/Dense>
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
template <int NX, int NU>
struct ExactDiscretization {
  using State = Eigen::Matrix<double, NX, 1>;
  using Input = Eigen::Matrix<double, NU, 1>;
  using StateMatrix = Eigen::Matrix<double, NX, NX>;
  using InputMatrix = Eigen::Matrix<double, NX, NU>;

  StateMatrix Phi;
  InputMatrix Gamma0, Gamma1;
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
    const Eigen::MatrixXd E = C.exp();
    Phi = E.topLeftCorner(n, n);
    Gamma0 = E.block(0, n, n, m);
    Gamma1 = E.block(0, n + m, n, m);
  }

  // out must not alias x. No allocation for fixed sizes (and none for dynamic ones once out is sized).
  void step(const State& x, const Input& u0, const Input& u1, State& out) const {
    out.noalias() = Phi * x;
    if constexpr (NU != 0) {
      if (Gamma0.cols() == 0) return;
      out.noalias() += Gamma0 * u0;
      out.noalias() += Gamma1 * u1;
      out.noalias() -= Gamma1 * u0;
    }
  }
  State step(const State& x, const Input& u0, const Input& u1) const {
    State out(x.size());
    step(x, u0, u1, out);
    return out;
  }
};

}  // namespace pogear::rt
