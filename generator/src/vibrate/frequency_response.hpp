// Frequency response of a scene's linear system (docs/vibration.md): H(jw) = C (jw I - M)^-1 N + D,
// from the Hessenberg form of M computed once, then one O(n^2) solve per frequency.
#pragma once

#include <complex>
#include <optional>
#include <string>
#include <vector>

#include <Eigen/Dense>

#include "specialize/reference_model.hpp"
#include "read/scene.hpp"

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
// Bounds on the absolute errors of a system's matrices, entry by entry, when they carry rounding
// from their own computation (a mode's matrices, formed from the system's by solving for the stuck
// elements' torques, have exact zeros that come out as rounding).
struct MatrixErrors {
  Eigen::MatrixXd M, N, C, D;
};
struct HessenbergSystem {
  Eigen::MatrixXd H, N, C, D;
  double norm_M = 0;  // Frobenius, of the balanced M
  // The MatrixErrors in the same coordinates: of M (Frobenius), of each column of N and each row
  // of C (2-norms), and of D.
  double error_M = 0;
  Eigen::VectorXd error_N, error_C;
  Eigen::MatrixXd error_D;
};
// The system y = C x + D u + E x' of `s` (E reads x' of a rigid model's mesh forces) as above, with
// the errors of its matrices when they have some.
HessenbergSystem hessenberg_system(const NumericSystem& s, const MatrixErrors* errors = nullptr);
// The same balanced by the scales `d` (balancing_scales of another matrix: a mode's A is balanced
// as its system's M).
HessenbergSystem hessenberg_system(const NumericSystem& s, const MatrixErrors* errors, const Eigen::VectorXd& d);
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

// The scene whose system the response is of: unit constant inputs on `inputs`, the `outputs`, the
// `engaged` brakes and clutches commanded stuck throughout and the others out of it.
Scene response_scene(const Scene& scene, const std::vector<Variable>& inputs, const std::vector<Variable>& outputs,
                     const std::vector<int>& engaged);

// One TransferFunction per (input, output) pair, input-major, of the scene's own system (elastic
// or rigid) with these inputs and outputs instead of the scene's, and the `engaged` brakes and
// clutches (friction element indices) stuck, the others open.
std::vector<TransferFunction> frequency_response(const Scene& scene, const std::vector<Variable>& inputs,
                                                 const std::vector<Variable>& outputs, const FrequencyGrid& grid,
                                                 const std::vector<int>& engaged = {});

}  // namespace pogear
