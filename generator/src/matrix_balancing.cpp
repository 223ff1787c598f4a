// See matrix_balancing.hpp.
#include "matrix_balancing.hpp"

#include <algorithm>
#include <cmath>

namespace pogear {

Eigen::VectorXd balancing_scales(const Eigen::MatrixXd& M) {
  const Eigen::Index n = M.rows();
  Eigen::MatrixXd A = M;
  Eigen::VectorXd d = Eigen::VectorXd::Ones(n);
  // Parlett & Reinsch's sweeps (LAPACK's dgebal without its permutations), in the 2-norm as James,
  // Langou & Lowery (2014) advise: a row and its column are scaled by a power of 2 until their norms
  // are within a factor 2. Each accepted scaling lowers the matrix's norm by 5 % at least, so the
  // sweeps end; the cap only guards against a pathological input.
  for (int sweep = 0; sweep < 200; ++sweep) {
    bool done = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      double c = std::sqrt(std::max(A.col(i).squaredNorm() - A(i, i) * A(i, i), 0.0));
      double r = std::sqrt(std::max(A.row(i).squaredNorm() - A(i, i) * A(i, i), 0.0));
      if (!(c > 0) || !(r > 0) || !std::isfinite(c + r)) continue;
      const double total = c * c + r * r;
      double f = 1;
      while (c < r / 2 && f < 0x1p500) c *= 2, r /= 2, f *= 2;
      while (c >= r * 2 && f > 0x1p-500) c /= 2, r *= 2, f /= 2;
      if (c * c + r * r >= 0.95 * total) continue;
      done = false;
      d(i) *= f;
      A.col(i) *= f;
      A.row(i) /= f;
    }
    if (done) break;
  }
  return d;
}

Eigen::MatrixXd balanced(const Eigen::MatrixXd& M) {
  const Eigen::VectorXd d = balancing_scales(M);
  return d.cwiseInverse().asDiagonal() * M * d.asDiagonal();
}

}  // namespace pogear
