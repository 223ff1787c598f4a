// Vibration modes of the elastic model (docs/vibration.md): natural frequencies and mode shapes
// from the symmetric problem R^T K R phi = lambda J phi, modal energies, damping ratios from M.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <Eigen/Dense>
#include <ginac/ginac.h>

#include "derive/derivation.hpp"

namespace pogear {

enum class ModeKind {
  rigid,    // a motion of ker R: frequency 0, no mesh is strained
  planet,   // the central members (sun, ring, carrier: bodies on the central axis) stay at rest
  elastic,  // any other elastic mode
};
std::string_view mode_kind_name(ModeKind kind);

struct VibrationMode {
  double frequency_hz = 0;               // undamped natural frequency; 0 for a rigid mode
  std::optional<double> damping_ratio;   // none for a rigid mode, or when M's eigenvalues do not pair (see note)
  int multiplicity = 1;                  // modes of this frequency, within degenerate_tolerance
  ModeKind kind = ModeKind::elastic;
  Eigen::VectorXd shape;                 // per body; the largest |entry| is 1, and positive
  Eigen::VectorXd strain_energy;         // share of each mesh, summing to 1; empty for a rigid mode
  Eigen::VectorXd kinetic_energy;        // share of each body, summing to 1
};

// An oscillating eigenvalue s of the damped state matrix M: |s| / 2 pi and -Re s / |s|.
struct DampedMode {
  double frequency_hz = 0;
  double damping_ratio = 0;
};

struct VibrationModes {
  std::string model;
  std::vector<std::string> engaged;  // brakes and clutches stuck, in file order; empty: all open
  std::vector<std::string> held;     // bodies held at rest (a Campbell diagram's operating line)
  std::vector<std::string> bodies, meshes;
  std::vector<VibrationMode> modes;  // ascending frequency; a degenerate cluster is one entry per mode
  std::string damping;               // which damping the ratios are of, e.g. "none", "mesh damping"
  std::string damping_note;          // why damping ratios are missing, when they are
  std::vector<std::string> open_in_scene;  // a scene's brakes and clutches left open (no --engaged)
  std::vector<DampedMode> damped;    // every oscillating eigenvalue of M, by ascending |s|; empty undamped
  // det(R^T K R - lambda J) / lambda^(n - rank R) = sum_k characteristic[k] lambda^k when rank R <= 3
  // (three elastic modes), and its roots in closed form, ascending at the model's values, when
  // rank R <= 2.
  GiNaC::symbol lambda{"lambda"};
  std::vector<GiNaC::ex> characteristic;
  std::vector<GiNaC::ex> closed_form;
};

// Two frequencies closer than this, relative, are one degenerate frequency: rounding leaves equal
// frequencies ~1e-14 apart, and a mistuning a designer means is far above 1e-6.
inline constexpr double degenerate_tolerance = 1e-6;
// lambda is computed to about eps * lambda_max absolute, so the smallest nonzero one to eps times
// this ratio relative: above 1e8 (a frequency ratio of 1e4) that is over ~1e-8, and it is refused.
inline constexpr double max_eigenvalue_spread = 1e8;

// Modes of the elastic model at `values` (exact numbers for every parameter; damping parameters
// at zero for damping left out), with the friction elements `engaged` (indices) stuck: the bodies
// they tie move as one, the bodies a brake holds and the `held` bodies stay at rest (shape 0). Shapes, energies and the
// kinds are per body and mesh of the gear; the closed forms are of the engaged model's
// det(R_q^T K R_q - lambda J_q). Throws std::domain_error when the frequencies cannot be computed
// to the accuracy above, when the model has no mesh, and when the brakes hold every body.
VibrationModes vibration_modes(const Derivation& d, const GiNaC::exmap& values, std::string damping,
                               const std::vector<int>& engaged = {}, const std::vector<int>& held = {});

// The lowest nonzero natural frequency [Hz] at `values`, by the same computation, with the
// derivation's engaged elements stuck.
double lowest_natural_frequency(const Derivation& d, const GiNaC::exmap& values);

}  // namespace pogear
