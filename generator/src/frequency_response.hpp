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

// Values of H whose rounding bound exceeds this, relative, are not written (the CSV leaves their
// cells empty): the 6 digits printed are then not all right.
inline constexpr double response_accuracy = 1e-6;

// A resonance: a local maximum of |H|, located to rounding between its grid neighbours.
struct ResonancePeak {
  double frequency_hz = 0;
  double magnitude = 0;              // infinite at the pole of an undamped scene
  std::optional<double> over_rigid;  // |H| / |H of the rigid model| there, when the scene is elastic
};

// H of one input (a torque) to one output (a velocity or a mesh force).
struct TransferFunction {
  Variable input, output;
  std::string input_name, output_name, unit;  // unit of H, e.g. "(rad/s)/(N m)"
  std::vector<double> frequency_hz;
  std::vector<std::complex<double>> value;
  std::vector<bool> accurate;               // value within response_accuracy (transfer_matrix's bound)
  std::vector<std::complex<double>> rigid;  // the rigid model's H on the same grid; empty for a rigid scene
  std::vector<bool> rigid_accurate;
  bool undamped = false;                    // no damping at all: the resonances are poles
  std::vector<ResonancePeak> peaks;
};

// x' = M x + N u, y = C x + D u in the coordinates of the Hessenberg form of balanced M:
// D^-1 M D = Q H Q^T, N~ = Q^T D^-1 N, C~ = C D Q.
struct HessenbergSystem {
  Eigen::MatrixXd H, N, C, D;
  double norm_M = 0;  // Frobenius, of the balanced M
};
// The system y = C x + D u + E x' of `s` (E reads x' of a rigid model's mesh forces) as above.
HessenbergSystem hessenberg_system(const NumericSystem& s);
// H(j omega), outputs x inputs, and a first-order bound of its rounding error per entry: the
// Hessenberg form and the Givens solve are backward stable, so H is exact for M + dM with
// |dM| <= gamma (|M| + |jwI - M|), gamma = 8 n eps, and |dH| <= |C (jwI - M)^-1| |dM| |X| plus the
// rounding of the last product (C R^-1 from the triangular factor R, whose norm equals it).
struct TransferValues {
  Eigen::MatrixXcd H;
  Eigen::MatrixXd error;
};
TransferValues transfer_matrix(const HessenbergSystem& s, double omega);
// Whether |H| is nonzero, finite and its error bound within response_accuracy of it.
bool accurate(std::complex<double> h, double error);

// One TransferFunction per (input, output) pair, input-major, of the scene's own system (elastic
// or rigid) with these inputs and outputs instead of the scene's.
std::vector<TransferFunction> frequency_response(const Scene& scene, const std::vector<Variable>& inputs,
                                                 const std::vector<Variable>& outputs, const FrequencyGrid& grid);

}  // namespace pogear
