// Specializes the scene, writes its simulator's sources and prints what they cost.
#include "commands/generate.hpp"

#include <iostream>

#include "codegen/codegen.hpp"
#include "commands/command_support.hpp"
#include "common/output_file.hpp"
#include "read/scene.hpp"
#include "report/run_summary.hpp"
#include "run/simulator_cache.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

int run_generate(const GenerateCommand& command) {
  const SpecializedScene model = specialize(parse_scene(command.scene));
  std::vector<rt::Solver> solvers;
  if (command.solvers == "all") {  // those that can run the scene
    solvers = rt::admissible_solvers(solver_traits(model));
  } else if (!command.solvers.empty()) {
    for (const std::string& name : split_list(command.solvers)) solvers.push_back(*rt::parse_solver(name));
  }
  const GeneratedSources sources = generate_sources(model, solvers);
  if (command.list_outputs) {
    for (const std::string& path : source_paths(sources, command.directory)) std::cout << path << "\n";
    return 0;
  }
  ensure_directory(command.directory);
  write_sources(sources, command.directory);
  std::cout << "wrote " << command.directory << "/" << sources.header_name << " and " << command.directory << "/"
            << sources.main_name << "\n"
            << operation_summary(model);
  return 0;
}

}  // namespace pogear
