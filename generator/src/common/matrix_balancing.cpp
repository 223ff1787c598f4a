// See matrix_balancing.hpp.
#include "common/matrix_balancing.hpp"

#include "pogear/balancing.hpp"

namespace pogear {

Eigen::VectorXd balancing_scales(const Eigen::MatrixXd& M) {
  Eigen::MatrixXd A = M;
  return rt::balance(A);
}

Eigen::MatrixXd balanced(const Eigen::MatrixXd& M) {
  const Eigen::VectorXd d = balancing_scales(M);
  return d.cwiseInverse().asDiagonal() * M * d.asDiagonal();
}

}  // namespace pogear
