// The modal bound that proves a step of one linear mode free of events (docs/friction-elements.md,
// "Events and how they are located"): per mode and step length, linear maps from the step's data
// to the fast part of the motion and to the fast modes' amplitudes: a step's proof is two products.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cmath>
#include <complex>
#include <numbers>
#include <vector>

#include "pogear/exact_kernel.hpp"
#include "pogear/run_support.hpp"

namespace pogear::rt {

// Whether the cubic through g0, g1 with slopes r0, r1 (over a step h) dips to zero or below between
// its ends: then a function positive at both ends may cross zero twice within the step.
inline bool cubic_dips(double g0, double g1, double r0, double r1, double h) {
  if (!(g0 > 0 && g1 > 0) || !std::isfinite(g0) || !std::isfinite(g1)) return false;
  if (r0 >= 0 && r1 <= 0) return false;  // rises then falls: no interior minimum
  // Hermite form on s in [0, 1]: q(s) = h00 g0 + h10 h r0 + h01 g1 + h11 h r1.
  const double d0 = h * r0, d1 = h * r1;
  // q'(s) = a s^2 + b s + c
  const double a = 6 * g0 + 3 * d0 - 6 * g1 + 3 * d1, b = -6 * g0 - 4 * d0 + 6 * g1 - 2 * d1, c = d0;
  auto q = [&](double s) {
    const double s2 = s * s, s3 = s2 * s;
    return (2 * s3 - 3 * s2 + 1) * g0 + (s3 - 2 * s2 + s) * d0 + (-2 * s3 + 3 * s2) * g1 + (s3 - s2) * d1;
  };
  double roots[2];
  int n = 0;
  if (std::abs(a) < 1e-300) {
    if (b != 0) roots[n++] = -c / b;
  } else {
    const double disc = b * b - 4 * a * c;
    if (disc >= 0) {
      const double sq = std::sqrt(disc);
      roots[n++] = (-b - sq) / (2 * a);
      roots[n++] = (-b + sq) / (2 * a);
    }
  }
  for (int i = 0; i < n; ++i)
    if (roots[i] > 0 && roots[i] < 1 && q(roots[i]) <= 0) return true;
  return false;
}

// A mode x' = A x + B w with modal form A = V diag(lambda) V^-1, over steps of h with inputs linear
// in time, w(s) = v0 + v' s. Each modal coordinate is xi_j(s) = r_j e^(lambda_j s) + a_j + b_j s, the
// second part the particular solution of the inputs, r_j = (W x0)_j + (W B v0)_j / lambda_j +
// (W B v')_j / lambda_j^2. The modes too fast for a cubic over h (|lambda| h > pi/4) are the fast
// part of the motion, sum over them of V_j r_j e^(lambda_j s); the rest (slow modes, particular
// solutions) is the slow part, which a cubic through its ends' values and rates follows. A function
// c x + d w then never differs from its slow part by more than sum_j |c V_j| |r_j| grow_j,
// grow_j = max(1, |e^(lambda_j h)|). All of it is linear in the step's data z = [x0; v0; v1; x1].
struct StepProof {
  Eigen::MatrixXd slow;       // rows 4i..4i+3: function i's slow part at both ends, then its rates there
  Eigen::MatrixXd amplitude;  // rows 2j, 2j+1: Re and Im of r_j, from [x0; v0; v1] (a complex pair: one of it)
  Eigen::MatrixXd reach;  // functions x amplitudes: sum over the modes of amplitude j of |c V_j| grow_j
};

// The proof's maps for the mode x' = A x + B w with modal form f (f.WB = W B), the functions
// C x + D w, and the step h.
inline StepProof step_proof(const ModalForm& f, const Eigen::MatrixXd& A, const Eigen::MatrixXd& B,
                            const Eigen::MatrixXd& C, const Eigen::MatrixXd& D, double h) {
  using Cx = std::complex<double>;
  const Eigen::Index n = A.rows(), nw = B.cols(), nz = 2 * n + 2 * nw, nc = C.rows();
  const double fast = std::numbers::pi / 4 / h;
  std::vector<Eigen::Index> F;  // the fast modes
  for (Eigen::Index j = 0; j < f.lambda.size(); ++j)
    if (std::abs(f.lambda(j)) > fast) F.push_back(j);
  const auto nf = static_cast<Eigen::Index>(F.size());
  // [x0; v0; v'] = Y z, r = R Y z.
  Eigen::MatrixXd Y = Eigen::MatrixXd::Zero(n + 2 * nw, nz);
  Y.topLeftCorner(n + nw, n + nw).setIdentity();
  Y.block(n + nw, n, nw, nw) = -Eigen::MatrixXd::Identity(nw, nw) / h;
  Y.block(n + nw, n + nw, nw, nw) = Eigen::MatrixXd::Identity(nw, nw) / h;
  Eigen::MatrixXcd R(nf, n + 2 * nw), VF(n, nf);
  Eigen::VectorXcd e(nf), lambda(nf);
  Eigen::VectorXd grow(nf);
  for (Eigen::Index i = 0; i < nf; ++i) {
    const Eigen::Index j = F[static_cast<std::size_t>(i)];
    const Cx inv = 1.0 / f.lambda(j);
    R.row(i) << f.W.row(j), f.WB.row(j) * inv, f.WB.row(j) * (inv * inv);
    VF.col(i) = f.V.col(j);
    lambda(i) = f.lambda(j);
    e(i) = std::exp(f.lambda(j) * h);
    grow(i) = std::max(1.0, std::abs(e(i)));
  }
  const Eigen::MatrixXcd Rz = R * Y.cast<Cx>(), CV = C.cast<Cx>() * VF;
  // Each function's value and rate at both ends, whole: x0, x1, x'(0) = A x0 + B v0, x'(h) = A x1 + B v1.
  const Eigen::MatrixXd I = Eigen::MatrixXd::Identity(n, n), Iw = Eigen::MatrixXd::Identity(nw, nw);
  const Eigen::MatrixXd Zn = Eigen::MatrixXd::Zero(n, n), Znw = Eigen::MatrixXd::Zero(n, nw), Zwn = Znw.transpose(),
                        Zw = Eigen::MatrixXd::Zero(nw, nw);
  Eigen::MatrixXd X0(n, nz), X1(n, nz), dX0(n, nz), dX1(n, nz), W0(nw, nz), W1(nw, nz), dW(nw, nz);
  X0 << I, Znw, Znw, Zn;
  X1 << Zn, Znw, Znw, I;
  dX0 << A, B, Znw, Zn;
  dX1 << Zn, Znw, B, A;
  W0 << Zwn, Iw, Zw, Zwn;
  W1 << Zwn, Zw, Iw, Zwn;
  dW = (W1 - W0) / h;
  // Less their fast parts, sum_j c V_j r_j (1, e^(lambda h), lambda, lambda e^(lambda h)).
  const Eigen::MatrixXd g0 = C * X0 + D * W0 - (CV * Rz).real();
  const Eigen::MatrixXd g1 = C * X1 + D * W1 - (CV * e.asDiagonal() * Rz).real();
  const Eigen::MatrixXd r0 = C * dX0 + D * dW - (CV * lambda.asDiagonal() * Rz).real();
  const Eigen::MatrixXd r1 = C * dX1 + D * dW - (CV * lambda.cwiseProduct(e).asDiagonal() * Rz).real();
  StepProof p;
  p.slow.resize(4 * nc, nz);
  for (Eigen::Index i = 0; i < nc; ++i) {
    p.slow.row(4 * i) = g0.row(i);
    p.slow.row(4 * i + 1) = g1.row(i);
    p.slow.row(4 * i + 2) = r0.row(i);
    p.slow.row(4 * i + 3) = r1.row(i);
  }
  // Amplitudes: a complex pair (Eigen's solver gives its two consecutive, exactly conjugate) has
  // conjugate amplitudes of equal size, so one of it serves both.
  const Eigen::MatrixXd bound = CV.cwiseAbs() * grow.asDiagonal();
  std::vector<Eigen::Index> kept;
  std::vector<Eigen::Index> partner;
  for (Eigen::Index i = 0; i < nf; ++i) {
    const bool pair = i + 1 < nf && lambda(i).imag() > 0 && lambda(i + 1) == std::conj(lambda(i)) &&
                      VF.col(i + 1) == VF.col(i).conjugate();
    kept.push_back(i);
    partner.push_back(pair ? i + 1 : -1);
    if (pair) ++i;
  }
  const auto na = static_cast<Eigen::Index>(kept.size());
  p.amplitude.resize(2 * na, n + 2 * nw);
  p.reach.resize(nc, na);
  for (Eigen::Index a = 0; a < na; ++a) {
    const Eigen::Index i = kept[static_cast<std::size_t>(a)], q = partner[static_cast<std::size_t>(a)];
    p.amplitude.row(2 * a) = Rz.row(i).head(n + 2 * nw).real();
    p.amplitude.row(2 * a + 1) = Rz.row(i).head(n + 2 * nw).imag();
    p.reach.col(a) = bound.col(i);
    if (q >= 0) p.reach.col(a) += bound.col(q);
  }
  return p;
}

// One step's slow parts and fast amplitudes (scratch reused from step to step). The fast modes'
// count differs from step length to step length: parts and amplitude keep the largest size met
// (at most 2 n and n), their heads in use, so that steps of other lengths stay off the heap.
struct SlowMotion {
  Eigen::VectorXd z, slow, parts, amplitude;
};

// Fills s for the step from x0 to x1 under inputs linear from v0 to v1.
inline void slow_motion(const StepProof& p, const Eigen::VectorXd& x0, const Eigen::VectorXd& x1,
                        const Eigen::VectorXd& v0, const Eigen::VectorXd& v1, SlowMotion& s) {
  s.z.resize(2 * x0.size() + 2 * v0.size());
  s.z << x0, v0, v1, x1;
  s.slow.setZero(p.slow.rows());
  detail::small_matvec_add(p.slow, p.slow.cols(), s.z.data(), s.slow.data());
  const Eigen::Index na = p.amplitude.rows() / 2;
  if (s.parts.size() < 2 * na) s.parts.resize(2 * na);
  if (s.amplitude.size() < na) s.amplitude.resize(na);
  s.parts.head(2 * na).setZero();
  detail::small_matvec_add(p.amplitude, p.amplitude.cols(), s.z.data(), s.parts.data());
  for (Eigen::Index a = 0; a < na; ++a)
    s.amplitude(a) = std::sqrt(s.parts(2 * a) * s.parts(2 * a) + s.parts(2 * a + 1) * s.parts(2 * a + 1));
}

// Whether function i of the proof, times sign, plus the known values b0, b1 at the ends (linear
// between them) stays positive over the step h: its slow cubic less the fast part's bound does.
inline bool stays_positive(const StepProof& p, const SlowMotion& s, Eigen::Index i, double sign, double b0, double b1,
                           double h) {
  const double omega = p.reach.row(i).dot(s.amplitude.head(p.reach.cols())), db = (b1 - b0) / h;
  const double s0 = sign * s.slow(4 * i) + b0 - omega, s1 = sign * s.slow(4 * i + 1) + b1 - omega;
  return s0 > 0 && s1 > 0 && !cubic_dips(s0, s1, sign * s.slow(4 * i + 2) + db, sign * s.slow(4 * i + 3) + db, h);
}

}  // namespace pogear::rt
