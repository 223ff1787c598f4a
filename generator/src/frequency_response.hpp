// Frequency response of a scene's linear system (docs/vibration.md): H(jw) = C (jw I - M)^-1 N + D,
// from the Hessenberg form of M computed once, then one O(n^2) solve per frequency.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "reference_model.hpp"
#include "scene.hpp"

namespace pogear {

struct FrequencyGrid {
  double from_hz = 1, to_hz = 1e4;
  int points = 1000;  // logarithmically spaced, both ends included
};

// A resonance: a local maximum of |H|, located to rounding between its grid neighbours.
struct ResonancePeak {
  double frequency_hz = 0;
  double magnitude = 0;
  std::optional<double> over_rigid;  // |H| / |H of the rigid model| there, when the scene is elastic
};

// H of one input (a torque) to one output (a velocity or a mesh force).
struct TransferFunction {
  Variable input, output;
  std::string input_name, output_name, unit;  // unit of H, e.g. "(rad/s)/(N m)"
  std::vector<double> frequency_hz;
  std::vector<std::complex<double>> value;
  std::vector<std::complex<double>> rigid;  // the rigid model's H on the same grid; empty for a rigid scene
  std::vector<ResonancePeak> peaks;
};

// x' = M x + N u, y = C x + D u in the coordinates of M's Hessenberg form: M = Q H Q^T, N~ = Q^T N,
// C~ = C Q.
struct HessenbergSystem {
  Eigen::MatrixXd H, N, C, D;
};
// The system y = C x + D u + E x' of `s` (E reads x' of a rigid model's mesh forces) as above.
HessenbergSystem hessenberg_system(const NumericSystem& s);
// H(j omega), outputs x inputs.
Eigen::MatrixXcd transfer_matrix(const HessenbergSystem& s, double omega);

// One TransferFunction per (input, output) pair, input-major, of the scene's own system (elastic
// or rigid) with these inputs and outputs instead of the scene's.
std::vector<TransferFunction> frequency_response(const Scene& scene, const std::vector<Variable>& inputs,
                                                 const std::vector<Variable>& outputs, const FrequencyGrid& grid);

}  // namespace pogear
