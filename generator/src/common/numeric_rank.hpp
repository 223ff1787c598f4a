// Ranks and independent row/column choices of R, taken numerically at the model's parameter
// values (which satisfy the geometry relations): the decisions of the reduction, not its algebra.
#pragma once

#include <vector>

#include <Eigen/Dense>

namespace pogear {

// Relative threshold for numeric rank: R's entries are radii of one scale, and a genuine
// dependency cancels to rounding (~1e-16 relative), far below 1e-9.
int numeric_rank(const Eigen::MatrixXd& m);

Eigen::MatrixXd columns(const Eigen::MatrixXd& m, const std::vector<int>& cols);

// Rows of R that are independent on the eliminated columns, as many as there are eliminated.
std::vector<int> independent_rows(const Eigen::MatrixXd& Rn, const std::vector<int>& elim);

}  // namespace pogear
