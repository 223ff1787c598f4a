// The largest step at which rk4 is stable for a linear model, from its eigenvalues: what a run
// checks before it steps with rk4.
#pragma once

#include <Eigen/Eigenvalues>
#include <limits>
#include <numbers>

namespace pogear::rt {

// Largest stable RK4 step for x' = A x, as 2.785 / max|lambda(A)|. 2.785 is where RK4's stability
// region crosses the negative real axis (overdamped, stiff modes); on the imaginary axis (undamped
// gear oscillations) it reaches 2.83. In between the boundary dips to 2.62 near 122 degrees (damping
// ratio ~0.5), so for such modes this limit is up to 6% optimistic: it is meant to refuse steps far
// beyond stability, not to put h on the edge.
inline double rk4_stability_limit(const Eigen::MatrixXd& a) {
  if (a.rows() == 0) return std::numeric_limits<double>::infinity();
  Eigen::EigenSolver<Eigen::MatrixXd> es(a, false);
  // Any induced norm bounds the spectral radius: a safe fallback if the QR iteration fails.
  const double rho = es.info() == Eigen::Success ? es.eigenvalues().cwiseAbs().maxCoeff()
                                                 : a.cwiseAbs().rowwise().sum().maxCoeff();
  if (!(rho >= 0)) return 0;  // NaN in A: refuse every step
  return rho > 0 ? 2.785 / rho : std::numeric_limits<double>::infinity();
}

// The longest step over which an event function of x' = A x + B u (a linear function of x) is
// judged from its values and rates at the step's ends: an eighth of the period of A's fastest
// oscillation. The cubic through those values and rates then follows each oscillating component to
// about 0.1 % of its amplitude, so a slip that swings back through zero within a step is not missed;
// over a whole period the ends could show no sign of it. Infinite when A does not oscillate.
inline double event_check_step(const Eigen::MatrixXd& a) {
  if (a.rows() == 0) return std::numeric_limits<double>::infinity();
  Eigen::EigenSolver<Eigen::MatrixXd> es(a, false);
  const double omega = es.info() == Eigen::Success ? es.eigenvalues().imag().cwiseAbs().maxCoeff()
                                                   : a.cwiseAbs().rowwise().sum().maxCoeff();
  if (!(omega >= 0)) return 0;
  return omega > 0 ? std::numbers::pi / (4 * omega) : std::numeric_limits<double>::infinity();
}

}  // namespace pogear::rt
