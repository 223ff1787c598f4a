// `pogear simulate`: generate, compile (cached) or interpret, and run a scene; CSV files and figures.
#pragma once

#include <string>

#include "run/simulate_scene.hpp"

namespace pogear {

struct SimulateCommand {
  std::string scene;   // the scene file
  std::string solver;  // instead of the scene's; empty: the scene's
  long repeat = 1;     // runs, for the median time
  SimulateOptions options;  // its solver and repeat are set from the two above
};

int run_simulate(const SimulateCommand& command);

}  // namespace pogear
