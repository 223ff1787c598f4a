// The ranges of a run's settings, shared by the scene reader ([simulation] in generator/src/scene.cpp)
// and the generated simulators' command line (command_line.hpp), so both accept the same values.
#pragma once

namespace pogear::rt::limits {

// Relative tolerance of the adaptive methods. Below 1e-14 the local error test asks for less than
// ~50 ulps of the state, which rounding in the stages alone exceeds, so a run only stalls. Above
// 1e-2 the error estimate is no longer in its asymptotic range: dopri5 at 0.2 diverged to 3.8e10
// rad/s on the paper's one-stage gear (exact 26.4) while every step passed its test. The tests and
// benchmarks use 1e-12 ... 1e-3.
inline constexpr double min_tolerance = 1e-14;
inline constexpr double max_tolerance = 1e-2;

// Step in seconds (rk4's step, the exact method's hold for sine inputs, the adaptive methods' first
// step): the range of the model's parameters (1e-30 ... 1e30 SI). A step far below the sample
// period costs steps, which max_steps bounds.
inline constexpr double min_step = 1e-30;
inline constexpr double max_step = 1e30;

// Steps of one run (rejected attempts included for the adaptive methods). 1e12 steps of the
// cheapest method (~10 ns each) are hours; beyond that a run is a mistake, and the count stays far
// inside a long and a double's exact integers.
inline constexpr long min_max_steps = 1;
inline constexpr long max_max_steps = 1000000000000;

// Repetitions of a run for timing (--repeat): the median of up to a million runs.
inline constexpr long max_repeat = 1000000;

// Samples of a run: a CSV of more rows than this is a mistake, not a scene.
inline constexpr double max_samples = 1e7;

}  // namespace pogear::rt::limits
