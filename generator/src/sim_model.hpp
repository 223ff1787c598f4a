// Specialization: the equations a scene calls for and nothing more. Effects left out leave no
// term, zero inputs are not inputs, unrequested outputs are not computed, and every parameter
// that is not tunable is folded to a number.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "derivation.hpp"
#include "scene.hpp"

namespace pogear {

struct OperationCount {
  int multiplications = 0;  // divisions included
  int additions = 0;        // subtractions included
  int total() const { return multiplications + additions; }
};

// `const double name = value;` in generated code.
struct Assignment {
  std::string name;
  GiNaC::ex value;
};

// How `--param NAME=VALUE` of a generated simulator may write a tunable's value: a plain number
// (SI), or NUMBER*UNIT with one of these units (the model's own spelling and the SI one).
struct UnitSpelling {
  std::string unit;  // e.g. "Newton/mm"
  double si = 1;     // its value in SI, e.g. 1000
};

struct TunableParameter {
  std::string name;
  double value = 0;  // SI, the scene's value
  std::vector<UnitSpelling> units;
  std::string sign;  // "positive", "non-negative", or empty when no role of the model bounds it
};

// L dx/dt = A x + B u, which the generated code solves numerically (L symmetric positive definite).
struct ImplicitForm {
  GiNaC::matrix L, A, B;
};

struct SimSystem {
  std::string kind;       // "elastic" or "rigid"
  std::string equations;  // one line, for the generated header comment
  std::vector<std::string> states, state_units;
  std::vector<double> x0;
  std::vector<std::string> inputs;    // tau_<body> of the nonzero signals
  std::vector<int> input_signal;      // index into Scene::inputs
  std::vector<TunableParameter> params;
  std::vector<Assignment> rhs_temporaries;
  std::vector<GiNaC::ex> rhs;  // dx/dt, one per state
  std::vector<std::string> outputs, output_units;
  std::vector<Assignment> output_temporaries;
  std::vector<GiNaC::ex> output_values;
  GiNaC::matrix M, N;  // dx/dt = M x + N u (every scene pogear knows is linear); 0 x 0 with `implicit`
  // A rigid system with tunables: dx/dt from L1 x1' = A1 x1 + B1 tau, solved by the generated code
  // (rhs and M, N are then empty). The symbolic L1^-1 over one common denominator grew to 21,844
  // operations for 10 tunables of a 2-state system, with exact coefficients beyond doubles.
  std::optional<ImplicitForm> implicit;
  bool output_derivatives = false;  // the outputs read dx/dt as d<state>, computed by rhs
  OperationCount rhs_ops, output_ops;
  GiNaC::matrix L;  // energy E = x^T L x / 2 (symmetric positive definite), for the runner's divergence check
};

struct SimModel {
  Scene scene;
  Derivation derivation;  // with the scene's overrides applied
  SimSystem main;
  std::optional<SimSystem> rigid;  // the comparison, when the scene asks for it
};

SimModel specialize(const Scene& scene);
SimSystem specialize_system(const Scene& scene, Derivation& d, bool elastic);

OperationCount count_operations(const GiNaC::ex& e);

// Numeric (M, N) of the same system built from the derivation's L, A, B instead of the
// specialized expressions: an independent computation for --interpreted and the tests.
struct NumericSystem {
  Eigen::MatrixXd M, N;        // dx/dt = M x + N u
  Eigen::MatrixXd L;           // energy E = x^T L x / 2
  Eigen::MatrixXd C, D, E;     // y = C x + D u + E dx/dt
  Eigen::VectorXd x0;
};
NumericSystem numeric_system(const SimModel& model, const SimSystem& system);

// The state matrix M of a system at the scene's values (every tunable at its value).
Eigen::MatrixXd state_matrix(const SimModel& model, const SimSystem& system);

// Diagnostics of a specialized system (its own M, the scene's values and effects).
Diagnostics system_diagnostics(const SimModel& model, const SimSystem& system);

}  // namespace pogear
