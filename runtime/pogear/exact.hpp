// Exact discretization of linear models dx/dt = M x + N u with a first-order hold on the inputs:
// one matrix exponential per step size at setup, then each step is three matrix-vector products
// (exact_kernel.hpp).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <limits>

#include "pogear/balancing.hpp"
#include "pogear/exact_kernel.hpp"

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
// accumulate over thousands of steps, drops from ~1e-14 to ~1e-16 relative.
namespace detail {
// A B for dynamic matrices of a few rows (the compiled runtime's exact_matrices): each pair of rows of
// a column of the product is one 2-lane sum over k, A read down its contiguous columns, where Eigen's
// lazy product on dynamic sizes runs its inner products along strided rows. Blocks of up to 8 rows
// and 2 columns share their loads of A and B (R pairs of rows, C columns, all in registers). Each
// entry is summed over k in order, as Eigen's is, so both give the same bits.
#if defined(__GNUC__)
template <int R, int C>
POGEAR_RT_INLINE void small_product_block(const double* a, const double* b, double* c, Eigen::Index n,
                                          Eigen::Index m) {
  Lanes2 s[C][R] = {};
  for (Eigen::Index k = 0; k < m; ++k) {
    Lanes2 v[R];
    for (int r = 0; r < R; ++r) load(v[r], a + k * n + 2 * r);
    for (int q = 0; q < C; ++q) {
      const double w = b[q * m + k];
      for (int r = 0; r < R; ++r) s[q][r] += v[r] * w;
    }
  }
  for (int q = 0; q < C; ++q)
    for (int r = 0; r < R; ++r) store(c + q * n + 2 * r, s[q][r]);
}
template <int C>
POGEAR_RT_INLINE void small_product_columns(const double* a, const double* b, double* c, Eigen::Index n,
                                            Eigen::Index m) {
  Eigen::Index i = 0;
  for (; i + 8 <= n; i += 8) small_product_block<4, C>(a + i, b, c + i, n, m);
  if (i + 4 <= n) small_product_block<2, C>(a + i, b, c + i, n, m), i += 4;
  if (i + 2 <= n) small_product_block<1, C>(a + i, b, c + i, n, m), i += 2;
  if (i < n)
    for (int q = 0; q < C; ++q) {
      double s0 = 0;
      for (Eigen::Index k = 0; k < m; ++k) s0 += a[k * n + i] * b[q * m + k];
      c[q * n + i] = s0;
    }
}
#endif
inline Eigen::MatrixXd small_product(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  const Eigen::Index n = A.rows(), m = A.cols(), p = B.cols();
  Eigen::MatrixXd C(n, p);
  const double* a = A.data();
  Eigen::Index j = 0;
#if defined(__GNUC__)
  for (; j + 2 <= p; j += 2) small_product_columns<2>(a, B.data() + j * m, C.data() + j * n, n, m);
  if (j < p) small_product_columns<1>(a, B.data() + j * m, C.data() + j * n, n, m), ++j;
#endif
  for (; j < p; ++j) {
    const double* b = B.data() + j * m;
    double* c = C.data() + j * n;
    for (Eigen::Index i = 0; i < n; ++i) {
      double s0 = 0;
      for (Eigen::Index k = 0; k < m; ++k) s0 += a[k * n + i] * b[k];
      c[i] = s0;
    }
  }
  return C;
}

// A B: a lazy product up to 24 rows (for the 12x12 augmented matrix of the 10-state paper model,
// Eigen's blocked products (packing, kernels) made up half of the setup), a blocked one for larger.
template <class Mat>
Mat mat_mul(const Mat& A, const Mat& B) {
  if constexpr (Mat::RowsAtCompileTime != Eigen::Dynamic && Mat::RowsAtCompileTime <= 24)
    return A.lazyProduct(B);
  else if constexpr (std::is_same_v<Mat, Eigen::MatrixXd>)
    return A.rows() <= 24 ? small_product(A, B) : Eigen::MatrixXd(A * B);
  else
    return A * B;
}

// The even powers of the scaled matrix an evaluation formed (count: A2, A2 and A4, or A2, A4 and A6)
// and its scaling A / 2^scale. A second evaluation of the same A with more squarings (balanced_exp's
// estimate) takes them scaled by powers of 2 instead of forming them again: (A 2^-d)^2k = A^2k 2^-2dk
// in every rounding as long as no product or sum falls below the normal range, which `reusable`
// makes sure of (every nonzero entry of the scaled matrices is at least 2^-400, so every product is
// a normal number, and so is every nonzero sum of them). The same bits, up to three products fewer.
template <class Mat>
struct ExpPowers {
  Mat A2, A4, A6;
  int count = 0, scale = 0;
};
template <class Mat>
bool reusable(const Mat& X, double f) {
  for (Eigen::Index j = 0; j < X.cols(); ++j)
    for (Eigen::Index i = 0; i < X.rows(); ++i)
      if (const double x = X(i, j); x != 0 && !(std::abs(x) * f >= 0x1p-400 && std::abs(x) <= 0x1p400)) return false;
  return true;
}

// e^A by Eigen's own method (MatrixExponential.h: Higham's scaling and squaring with the Pade
// approximant its 1-norm calls for; the same coefficients and the same steps), with one change
// in the squaring: it squares D = e^(A/2^s) - I as D <- 2 D + D^2 instead of E <- E^2. Squaring E
// turns a rounding error of one ulp in an eigenvalue 1 of e^(A/2^s) into (1 - 2^-53)^(2^s): the
// modes that do not move (a frictionless rotation, the input hold of the augmented matrix) lose
// e^(-2^s eps) of their value, and 2^s ~ ||A||, which for very long steps is all of it. In D those
// eigenvalues are 0 and stay 0. extra_squarings > 0 takes the degree-13 approximant with that many
// more squarings (the independent evaluation ExactDiscretization checks against). Without squarings
// E is (V-U)^-1 (U+V), Eigen's own bits. keep receives the powers this evaluation formed; reuse
// offers an earlier evaluation's (ExpPowers).
template <class Mat>
Mat small_exp(const Mat& A, int extra_squarings = 0, ExpPowers<Mat>* keep = nullptr,
              const ExpPowers<Mat>* reuse = nullptr) {
  const Mat I = Mat::Identity(A.rows(), A.cols());
  Mat U, V;
  int squarings = 0;
  const double l1norm = A.cwiseAbs().colwise().sum().maxCoeff();
  if (extra_squarings > 0) {
    // below: the degree-13 branch
  } else if (l1norm < 1.495585217958292e-002) {
    const double b[] = {120., 60., 12., 1.};
    const Mat A2 = mat_mul(A, A);
    const Mat tmp = b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[2] * A2 + b[0] * I;
    if (keep) keep->A2 = A2, keep->count = 1;
  } else if (l1norm < 2.539398330063230e-001) {
    const double b[] = {30240., 15120., 3360., 420., 30., 1.};
    const Mat A2 = mat_mul(A, A), A4 = mat_mul(A2, A2);
    const Mat tmp = b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[4] * A4 + b[2] * A2 + b[0] * I;
    if (keep) keep->A2 = A2, keep->A4 = A4, keep->count = 2;
  } else if (l1norm < 9.504178996162932e-001) {
    const double b[] = {17297280., 8648640., 1995840., 277200., 25200., 1512., 56., 1.};
    const Mat A2 = mat_mul(A, A), A4 = mat_mul(A2, A2), A6 = mat_mul(A4, A2);
    const Mat tmp = b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * I;
    if (keep) keep->A2 = A2, keep->A4 = A4, keep->A6 = A6, keep->count = 3;
  } else if (l1norm < 2.097847961257068e+000) {
    const double b[] = {17643225600., 8821612800., 2075673600., 302702400., 30270240.,
                        2162160.,     110880.,     3960.,       90.,        1.};
    const Mat A2 = mat_mul(A, A), A4 = mat_mul(A2, A2), A6 = mat_mul(A4, A2), A8 = mat_mul(A6, A2);
    const Mat tmp = b[9] * A8 + b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[8] * A8 + b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * I;
    if (keep) keep->A2 = A2, keep->A4 = A4, keep->A6 = A6, keep->count = 3;
  }
  if (extra_squarings > 0 || !(l1norm < 2.097847961257068e+000)) {
    std::frexp(l1norm / 5.371920351148152, &squarings);
    squarings = std::max(squarings, 0) + extra_squarings;
    const Mat As = A * std::ldexp(1.0, -squarings);
    const double b[] = {64764752532480000., 32382376266240000., 7771770303897600., 1187353796428800.,
                        129060195264000.,   10559470521600.,    670442572800.,     33522128640.,
                        1323241920.,        40840800.,          960960.,           16380.,
                        182.,               1.};
    // The powers of As: those of an earlier evaluation scaled by 2^-d where that is exact, else formed.
    const int d = reuse ? squarings - reuse->scale : 0;
    const double f = std::ldexp(1.0, -d);
    int have = 0;
    if (reuse && d >= 0 && reusable(As, 1.0)) {
      have = reuse->count >= 1 && reusable(reuse->A2, f * f) ? 1 : 0;
      if (have == 1 && reuse->count >= 2 && reusable(reuse->A4, f * f * f * f)) have = 2;
      if (have == 2 && reuse->count >= 3) have = 3;
    }
    const Mat A2 = have >= 1 ? Mat(reuse->A2 * (f * f)) : mat_mul(As, As);
    const Mat A4 = have >= 2 ? Mat(reuse->A4 * (f * f * f * f)) : mat_mul(A2, A2);
    const Mat A6 = have >= 3 ? Mat(reuse->A6 * (f * f * f * f * f * f)) : mat_mul(A4, A2);
    if (keep) keep->A2 = A2, keep->A4 = A4, keep->A6 = A6, keep->count = 3, keep->scale = squarings;
    V = b[13] * A6 + b[11] * A4 + b[9] * A2;
    Mat tmp = mat_mul(A6, V);
    tmp += b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(As, tmp);
    tmp = b[12] * A6 + b[10] * A4 + b[8] * A2;
    V = mat_mul(A6, tmp);
    V += b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * I;
  }
  const Mat denom = V - U;
  if (squarings == 0) return denom.partialPivLu().solve(U + V);
  Mat D = 2 * denom.partialPivLu().solve(U);  // (V-U)^-1 (U+V) - I
  for (int i = 0; i < squarings; ++i) D = (2 * D + mat_mul(D, D)).eval();
  return D + I;
}
}  // namespace detail

// Every size goes through detail::small_exp, dynamic ones too (the interpreted mode), so that both
// square e^A - I. Fixed-size matrices keep the setup off the heap, and up to 24x24 their products
// lazy: a sixth of a whole 2000-step run of the 10-state paper scene went into Eigen's dynamic
// exponential.
// With rounding given, it also receives an estimate of the relative error of e^C: the difference
// of e^C' and a second evaluation with three more squarings (another scaled matrix, other roundings,
// so errors that do not cancel), over max(1, ||e^C'||_1), both balanced so that velocities and
// forces weigh alike. Scaling and squaring amplifies rounding by about 2^s ~ ||C||: a mode turning
// by 1e13 rad per step carries phase errors of ~1e-3, and at 1e25 rad the computed e^C overflows.
// The second evaluation, with 8 times the amplification, errs about as much as the first or more,
// so the difference is the size of the error (measured over 100 steps of stiff scenes against
// 80-digit references: each step errs by 1 to 11 times it undamped, up to 25 times with bearing
// friction).
template <class Mat>
Mat balanced_exp(Mat C, double* rounding = nullptr, Eigen::Index measured_rows = -1) {
  const Eigen::Index n = C.rows();
  const auto d = balance(C);
  detail::ExpPowers<Mat> powers;
  Mat E = detail::small_exp(C, 0, rounding ? &powers : nullptr);
  if (rounding) {
    const Eigen::Index r = measured_rows < 0 ? n : std::min(measured_rows, n);
    const double norm = E.topRows(r).cwiseAbs().colwise().sum().maxCoeff();
    const Mat E3 = detail::small_exp<Mat>(C, 3, nullptr, &powers);
    *rounding = (E - E3).topRows(r).cwiseAbs().colwise().sum().maxCoeff() / std::max(1.0, norm);
    if (!E.allFinite()) *rounding = std::numeric_limits<double>::infinity();
  }
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) E(i, j) *= d(i) / d(j);
  return E;
}
template <int NX, int NU>
ExactDiscretization<NX, NU>::ExactDiscretization(const StateMatrix& M, const InputMatrix& N, double h_,
                                                 Eigen::Index measured_rows)
    : h(h_) {
  eigen_assert(M.rows() == M.cols() && N.rows() == M.rows());
  const Eigen::Index n = M.rows(), m = N.cols();
  constexpr int NA = NX == Eigen::Dynamic || NU == Eigen::Dynamic ? Eigen::Dynamic : NX + 2 * NU;
  using Aug = Eigen::Matrix<double, NA, NA>;
  Aug C = Aug::Zero(n + 2 * m, n + 2 * m);
  C.topLeftCorner(n, n) = M * h;
  C.block(0, n, n, m) = N * h;
  C.block(n, n + m, m, m).setIdentity();
  const Aug E = balanced_exp(C, &rounding, measured_rows);
  Phi = E.topLeftCorner(n, n);
  Gamma0 = E.block(0, n, n, m);
  Gamma1 = E.block(0, n + m, n, m);
  GammaD = Gamma0 - Gamma1;
  pack();
}

}  // namespace pogear::rt
