// Numbers that tell, before a run, whether a scene is hard: the stiffness ratio and time
// constants of the elastic model, the conditioning of L1 and R R^T, the largest stable rk4
// step, and the solver to use.
#pragma once

#include <optional>
#include <string>

#include <Eigen/Dense>

namespace pogear {

struct Derivation;         // derive/derivation.hpp
struct SpecializedScene;   // specialize/specialization.hpp
struct SpecializedSystem;  // specialize/specialization.hpp

// How strongly a scene's inputs excite an oscillation of angular frequency omega, against the
// quasi-static response to their own size: fully by anything that reaches the gear as a jump (a
// step, a table's repeated time, a start out of equilibrium, a brake, clutch or torque limit
// switching); by |slope change| / (omega U) at a corner of an input of size U (the free
// oscillation a ramp leaves behind is its slope over omega); by Omega / omega for a sine of angular
// frequency Omega (the transient of its start). Unknown inputs excite everything.
struct InputExcitation {
  bool jumps = true;
  double corner_rate = 0;  // max |slope change| / U over the inputs' corners [1/s]
  double sine_rate = 0;    // the fastest sine's angular frequency [rad/s]
  double of(double omega) const { return jumps ? 1.0 : std::max(corner_rate, sine_rate) / omega; }
};

struct Diagnostics {
  double fastest_rate = 0;            // largest |lambda| of M [1/s]
  double fastest_time_constant = 0;   // 1 / fastest_rate [s]
  double slowest_time_constant = 0;   // 1 / smallest decay rate among decaying modes [s]; 0 if none
  double stiffness_ratio = 1;         // fastest_rate / smallest decay rate among decaying modes
  int undecaying_modes = 0;           // |Re lambda| below rounding: free rotation, undamped motion
  int growing_modes = 0;              // Re lambda above rounding: an unstable scene (a controller feeding back positively)
  double fastest_growth_rate = 0;     // largest Re lambda of those [1/s]
  double cond_L1 = 0;                 // 2-norm condition number of the reduced inertia
  std::optional<double> cond_RRt;     // of R R^T; none when singular (redundant meshes)
  double rk4_max_step = 0;            // largest stable rk4 step [s]
  // The fastest oscillation of M, max |Im lambda| / 2 pi [Hz] (0: none), and with a sample period
  // the most its sampled peaks can read low, 1 - cos(pi f T): a peak midway between two samples.
  double fastest_oscillation_hz = 0;
  // The fastest oscillation the inputs excite above 1 % (InputExcitation), which the sampled-peak
  // shortfall is of: a faster one they leave below 1 % does not show in the samples.
  double excited_oscillation_hz = 0;
  double sampled_peak_shortfall = 0;
  double sample = 0;
  std::string suggested_solver;
  std::string adaptive_solver;        // the adaptive method to use: "dopri5", or "implicit" when stiff
  std::string reason;
  // Of the undamped elastic model (vibration_modes.hpp), at the parameters' values: below it the
  // rigid model holds. None, with the reason, when it cannot be computed accurately.
  std::optional<double> lowest_natural_frequency_hz;
  std::string natural_frequency_note;
  std::string natural_frequency_of;   // the gear it is of, when not the free one: 'C1, B1 engaged'
};

// M: the system matrix of the simulated model (elastic or rigid); L1, R: numeric. sample: the
// scene's sample period [s], which the fastest time scale is compared with; 0 when there is no
// scene (derive), and only the stiffness ratio decides.
Diagnostics diagnose(const Eigen::MatrixXd& M, const Eigen::MatrixXd& L1, const Eigen::MatrixXd& R,
                     double sample = 0, const InputExcitation& excitation = {});

// What excites a specialized system's oscillations: its input signals over the scene's horizon,
// its start, and the switching of its brakes, clutches and torque limits.
InputExcitation input_excitation(const SpecializedScene& model, const SpecializedSystem& system);

// Of a derivation's elastic model with every effect, at the model's values, with the lowest natural
// frequency of its gear (the derivation's engaged elements stuck): what `pogear derive` prints.
Diagnostics derivation_diagnostics(const Derivation& d);
// Of a specialized system: its own M, the scene's values and effects.
Diagnostics system_diagnostics(const SpecializedScene& model, const SpecializedSystem& system);

std::string diagnostics_text(const Diagnostics& d, const std::string& indent);
std::string diagnostics_json(const Diagnostics& d, const std::string& indent);

}  // namespace pogear
