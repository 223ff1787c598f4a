// `pogear generate`: the specialized C++ simulator of a scene, <scene>.hpp and <scene>_main.cpp.
#pragma once

#include <string>

namespace pogear {

struct GenerateCommand {
  std::string scene;             // the scene file
  std::string directory = ".";  // where the two files go
  bool list_outputs = false;     // print the files it would write, write nothing
  std::string solvers;           // compiled in, comma-separated, or "all"; empty: the scene's
};

int run_generate(const GenerateCommand& command);

}  // namespace pogear
