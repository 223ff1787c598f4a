// The run's exit status is the simulator's.
#include "commands/simulate.hpp"

#include <iostream>

#include "read/scene.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

int run_simulate(const SimulateCommand& command) {
  SimulateOptions options = command.options;
  if (!command.solver.empty()) options.solver = rt::parse_solver(command.solver);
  options.repeat = static_cast<int>(command.repeat);
  const SpecializedScene model = specialize(parse_scene(command.scene));
  return simulate_scene(model, options, std::cout);
}

}  // namespace pogear
