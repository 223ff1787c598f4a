// Balancing of a state matrix by an exact diagonal similarity, so that normwise rounding bounds and
// eigenvalues are not ruled by the rows of the stiffest states (mesh forces beside speeds).
#pragma once

#include <Eigen/Dense>

namespace pogear {

// The diagonal D (powers of 2) that balances M: D^-1 M D has rows and columns of comparable norms,
// the same eigenvalues, and is computed without rounding.
Eigen::VectorXd balancing_scales(const Eigen::MatrixXd& M);

// D^-1 M D for those scales.
Eigen::MatrixXd balanced(const Eigen::MatrixXd& M);

}  // namespace pogear
