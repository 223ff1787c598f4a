// `pogear simulate` as a library function: the run a scene asks for, the size check of its CSV
// files, the compiled or the interpreted run, and the figures of what it wrote.
#pragma once

#include <cstdint>
#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "common/output_file.hpp"
#include "pogear/command_line.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// What the command line adds to the scene.
struct SimulateOptions {
  std::string out_dir = "out";
  std::optional<rt::Solver> solver;  // instead of the scene's
  std::optional<double> tolerance;   // instead of the scene's
  std::vector<std::string> params;   // --param NAME=VALUE, as given
  bool interpreted = false;          // from the numeric matrices, without compiling
  int repeat = 1;
  bool large_output = false;  // write CSV files above max_csv_bytes all the same
};

// The scene's settings as a run: its name, horizon, sample, solver, tolerances (the runtime's rule
// for atol), step and max_steps; output to "." as the SceneRun default.
rt::SceneRun scene_run(const Scene& scene);

// An upper bound of the bytes the scene's CSV files take: samples x columns x 25 (a double in its
// shortest round-trip form has at most 24 characters, then a separator).
std::uintmax_t csv_bytes_bound(const SpecializedScene& model);

// Throws an InputError at the scene's `sample` when csv_bytes_bound exceeds max_csv_bytes and
// `allow_large` is false.
void check_output_size(const SpecializedScene& model, bool allow_large);

// Runs the compiled simulator with rt::command_line(run) as its arguments (no shell); returns its
// exit status (0 success, 3 failed run). Throws std::runtime_error when it dies of a signal.
int run_compiled(const std::string& executable, const rt::SceneRun& run);

// Checks the output size, creates options.out_dir, writes the operation summary to `out`, runs the
// scene (compiled, through the simulator cache, or interpreted) and plots its CSV files, naming
// each figure on `out`. Returns the run's exit status (0, or 3 when a run failed: then no figure).
// Throws InputError for a scene that cannot run, std::runtime_error for a failing system.
int simulate_scene(const SpecializedScene& model, const SimulateOptions& options, std::ostream& out);

}  // namespace pogear
