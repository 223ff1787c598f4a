// The reference numeric model: a specialized system's matrices computed from the derivation's
// L, A, B instead of the specialized expressions, for --interpreted runs and the tests.
#pragma once

#include <vector>

#include <Eigen/Dense>

#include "pogear/hybrid_modes.hpp"

namespace pogear {

struct Scene;              // read/scene.hpp
struct SpecializedScene;   // specialization.hpp
struct SpecializedSystem;  // specialization.hpp

// Numeric (M, N) of the same system built from the derivation's L, A, B instead of the
// specialized expressions: an independent computation for --interpreted and the tests.
// A quadratic load's torque q = -c s |s| on the speed s = speed_row x, entering as dx/dt += state_column q
// and y += output_column q.
struct QuadraticLoad {
  Eigen::VectorXd state_column, output_column, speed_row;
  double coefficient = 0;
  // The outputs' term in the torque's rate d(-c s |s|)/dt = -2 c |s| speed_row dx/dt (vehicle_jerk).
  Eigen::VectorXd rate_output_column;
};

struct NumericSystem {
  Eigen::MatrixXd M, N;        // dx/dt = M x + N u (+ the quadratic loads)
  std::vector<QuadraticLoad> quadratic;
  Eigen::MatrixXd L;           // energy E = x^T L x / 2; empty with controllers
  Eigen::MatrixXd C, D, E;     // y = C x + D u + E dx/dt
  Eigen::MatrixXd S;           // slips of the engaged brakes and clutches, s = S x
  Eigen::MatrixXd limit_x, limit_u;  // laws T = limit_x x + limit_u u of the controllers with torque limits
  Eigen::MatrixXd driveline_speeds;  // the speed each driveline torque's body turns at (SpecializedSystem::driveline)
  Eigen::VectorXd x0;
};
NumericSystem numeric_system(const SpecializedScene& model, const SpecializedSystem& system);

// The system as the runtime's hybrid engine takes it: M, N, S, the input signals, the engaged brakes
// and clutches, and the torque-limited controllers with their laws.
// A system's engine and converter as the runtime takes them, their bodies' speeds given (one row each,
// in SpecializedSystem::driveline's order).
rt::DrivelineData driveline_data(const Scene& scene, const SpecializedSystem& sys, const Eigen::MatrixXd& speeds);
rt::HybridSystem hybrid_system(const SpecializedScene& model, const SpecializedSystem& system, const NumericSystem& ns);

// The state matrix M of a system at the scene's values (every tunable at its value).
Eigen::MatrixXd state_matrix(const SpecializedScene& model, const SpecializedSystem& system);
// The same with the torque-limited controllers within their limits, their laws' state rows closed
// through their torques' columns: M + N_c X (M itself without such controllers).
Eigen::MatrixXd state_matrix_within_limits(const SpecializedScene& model, const SpecializedSystem& system);

}  // namespace pogear
