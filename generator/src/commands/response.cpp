// The peaks go to standard output first; the files follow, each named as it is written.
#include "commands/response.hpp"

#include <iostream>

#include "commands/command_support.hpp"
#include "common/output_file.hpp"
#include "report/response_report.hpp"

namespace pogear {

int run_response(const ResponseCommand& command) {
  ResponseRequest request = command.request;
  request.inputs = split_list(command.inputs);
  request.outputs = split_list(command.outputs);
  const SceneResponse h = response_of(request);
  std::cerr << open_elements_warning(h.open_in_scene, "responses");
  std::cout << response_summary(h.pairs);
  ensure_directory(command.directory);
  for (const std::string& path : write_response_files(h.scene_name, h.pairs, command.directory))
    std::cout << "wrote " << path << "\n";
  return 0;
}

}  // namespace pogear
