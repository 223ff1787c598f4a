// Relative gaps between computed values and their references, the measure every numeric
// comparison of the tests states its tolerance in.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include <Eigen/Core>

namespace pogear::test {

// The largest |a - b| relative to the largest |b|.
inline double relative_gap(const Eigen::MatrixXd& a, const Eigen::MatrixXd& b) {
  return (a - b).cwiseAbs().maxCoeff() / b.cwiseAbs().maxCoeff();
}

// The largest |a_i - b_i| / scale_i; a zero scale asks for equality (infinity otherwise).
inline double largest_scaled_gap(const Eigen::VectorXd& a, const Eigen::VectorXd& b, const Eigen::VectorXd& scale) {
  double gap = 0;
  for (Eigen::Index i = 0; i < a.size(); ++i) {
    const double d = std::abs(a(i) - b(i));
    gap = std::max(gap, scale(i) > 0 ? d / scale(i) : (d == 0 ? 0.0 : std::numeric_limits<double>::infinity()));
  }
  return gap;
}

// Largest |a - b| over column `col` of two tables of rows, relative to the largest |b| in it.
inline double column_error(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b,
                           std::size_t col) {
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    err = std::max(err, std::abs(a[i][col] - b[i][col]));
    scale = std::max(scale, std::abs(b[i][col]));
  }
  return scale > 0 ? err / scale : err;
}

}  // namespace pogear::test
