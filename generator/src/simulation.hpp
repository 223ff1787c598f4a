// Running scenes: the compiled simulator (see simulator_cache.hpp for how it is built) and the
// interpreted path (the same runtime on Eigen dynamic matrices).
#pragma once

#include <cstdint>
#include <string>

#include "codegen.hpp"
#include "pogear/scene_runner.hpp"

namespace pogear {

// Writes the generated sources into `dir` (atomically, file by file).
void write_sources(const GeneratedSources& sources, const std::string& dir);

// CSV files are refused above this size unless the user opts in (`simulate --large-output`): a
// sample period chosen by mistake would otherwise fill the disk before the run fails.
inline constexpr std::uintmax_t max_csv_bytes = std::uintmax_t{1} << 30;

// An upper bound of the bytes the scene's CSV files take: samples x columns x 25 (a double in its
// shortest round-trip form has at most 24 characters, then a separator).
std::uintmax_t csv_bytes_bound(const SimModel& model);

// Throws an InputError at the scene's `sample` when csv_bytes_bound exceeds max_csv_bytes and
// `allow_large` is false.
void check_output_size(const SimModel& model, bool allow_large);

// Runs the compiled simulator (no shell: the options are its arguments as they are); returns its
// exit status (0 success, 3 failed run). Throws std::runtime_error when it dies of a signal.
int run_compiled(const std::string& executable, const rt::SceneRun& run);

// Runs the same scene from the numeric matrices of the derivation, without compiling.
int run_interpreted(const SimModel& model, const rt::SceneRun& run);

// A run kept in memory: samples of the state and the outputs (for tests and benchmarks).
struct Trajectory {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, y;
  rt::RunStatus status;
};
Trajectory interpret_trajectory(const SimModel& model, const SimSystem& system, const rt::SceneRun& run);

}  // namespace pogear
