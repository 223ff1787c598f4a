// Balancing of a matrix by a diagonal similarity of powers of 2 (exact): the exact method's
// exponentials, the hybrid engine's modal flows and pogear's frequency responses all need rows and
// columns of comparable size where forces in N sit next to speeds in rad/s.
#pragma once

#include <Eigen/Core>
#include <cmath>

namespace pogear::rt {

// Osborne's iteration with powers of 2, as LAPACK's gebal without its permutations: column i times
// f, row i over f, until each row and column have about the same absolute sum (off the diagonal).
// A becomes D^-1 A D and the diagonal of D is returned. Each accepted scaling lowers the norm by 5 %
// at least; the bounded sweeps and factors (2^-64 ... 2^64 per pass) keep non-finite or extreme
// entries from looping or overflowing.
template <class Mat>
Eigen::Matrix<double, Mat::RowsAtCompileTime, 1> balance(Mat& A, int max_sweeps = 50) {
  const Eigen::Index n = A.rows();
  Eigen::Matrix<double, Mat::RowsAtCompileTime, 1> d = Eigen::Matrix<double, Mat::RowsAtCompileTime, 1>::Ones(n);
  bool done = false;
  for (int sweep = 0; sweep < max_sweeps && !done; ++sweep) {
    done = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double c = A.col(i).cwiseAbs().sum() - std::abs(A(i, i));
      const double r = A.row(i).cwiseAbs().sum() - std::abs(A(i, i));
      if (!(c > 0) || !(r > 0) || !std::isfinite(c) || !std::isfinite(r)) continue;  // nothing to balance
      double f = 1, cs = c;
      for (int k = 0; k < 64 && cs < r / 2; ++k) f *= 2, cs *= 4;
      for (int k = 0; k < 64 && cs > 2 * r; ++k) f /= 2, cs /= 4;
      if ((cs + r) / f < 0.95 * (c + r)) {  // row i scaled by 1/f, column i by f
        done = false;
        d(i) *= f;
        A.row(i) /= f;
        A.col(i) *= f;
      }
    }
  }
  return d;
}

}  // namespace pogear::rt
