// Running scenes: the compiled path (generate, compile once per content hash, run) and the
// interpreted path (the same runtime on Eigen dynamic matrices), plus gnuplot figures.
#pragma once

#include <cstdint>
#include <string>

#include "codegen.hpp"
#include "pogear/scene_runner.hpp"

namespace pogear {

// Writes the generated sources into `dir` (atomically, file by file).
void write_sources(const GeneratedSources& sources, const std::string& dir);

// The cache key of a simulator: a hash of its sources, the runtime headers under
// `runtime_include`/pogear, the compiler (path, size, modification time), flags and version.
std::uint64_t simulator_cache_key(const GeneratedSources& sources, const std::string& runtime_include);

// Compiles the scene's simulator unless a binary for the same sources is cached; returns its path.
// The cache is $POGEAR_CACHE_DIR, else $XDG_CACHE_HOME/pogear, else ~/.cache/pogear.
std::string build_simulator(const GeneratedSources& sources);

// Runs the compiled simulator; returns its exit status (0 success, 3 failed run).
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

// DIR/<scene>.velocities.svg and, with forces, DIR/<scene>.forces.svg: elastic solid, rigid
// dashed on top, as in the paper's Figs. 8-9. Returns the files written.
std::vector<std::string> plot_scene(const SimModel& model, const std::string& dir);

}  // namespace pogear
