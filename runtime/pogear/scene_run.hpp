// What a run of a scene is set to: the scene's times and solver, and what the command line changed.
#pragma once

#include <string>
#include <utility>
#include <vector>

#include "pogear/solver.hpp"

namespace pogear::rt {

struct SceneRun {
  std::string name;
  double horizon = 1, sample = 1e-3;
  Solver solver = Solver::exact;
  SolverOptions options;
  std::string out_dir = ".";
  bool csv = true;
  int repeat = 1;  // > 1 for timing: the median is reported
  bool quiet = false;
  bool help = false;  // --help: print the usage and the solvers, run nothing
  // speed_unit = "rpm": the system's speed outputs come in rpm already; the brakes' and clutches'
  // slips, which the run computes from the state, are written in rpm too.
  bool speeds_in_rpm = false;
  // --param NAME=VALUE as given, in order; the generated main resolves them against its Params.
  std::vector<std::pair<std::string, std::string>> params;
};

}  // namespace pogear::rt
