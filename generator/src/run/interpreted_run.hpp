// Running a scene without compiling: the reference numeric model (numeric_system) behind the
// generated systems' interface, driven by the same runtime as a compiled simulator.
#pragma once

#include <vector>

#include <Eigen/Core>

#include "pogear/run_system.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// Runs the scene's systems as the generated main does (writes their CSV files; returns 0, or 3 when
// a run failed).
int run_interpreted(const SpecializedScene& model, const rt::SceneRun& run);

// A run kept in memory: samples of the state and the outputs (for tests and benchmarks).
struct Trajectory {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, y;
  rt::RunStatus status;
};
Trajectory interpret_trajectory(const SpecializedScene& model, const SpecializedSystem& system, const rt::SceneRun& run);

}  // namespace pogear
