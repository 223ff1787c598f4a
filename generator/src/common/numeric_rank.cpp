// See numeric_rank.hpp: column-pivoted QR with a fixed relative threshold.
#include "common/numeric_rank.hpp"

namespace pogear {

int numeric_rank(const Eigen::MatrixXd& m) {
  if (m.size() == 0) return 0;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  qr.setThreshold(1e-9);
  return static_cast<int>(qr.rank());
}

Eigen::MatrixXd columns(const Eigen::MatrixXd& m, const std::vector<int>& cols) {
  Eigen::MatrixXd out(m.rows(), cols.size());
  for (std::size_t j = 0; j < cols.size(); ++j) out.col(j) = m.col(cols[j]);
  return out;
}

// Rows of R that are independent on the eliminated columns, as many as there are eliminated.
std::vector<int> independent_rows(const Eigen::MatrixXd& Rn, const std::vector<int>& elim) {
  const Eigen::MatrixXd sub = columns(Rn, elim);
  std::vector<int> rows;
  Eigen::MatrixXd picked(0, sub.cols());
  for (int i = 0; i < sub.rows() && rows.size() < elim.size(); ++i) {
    Eigen::MatrixXd trial(picked.rows() + 1, sub.cols());
    trial << picked, sub.row(i);
    if (numeric_rank(trial) == trial.rows()) {
      picked = trial;
      rows.push_back(i);
    }
  }
  return rows;
}

}  // namespace pogear
