// Emits the specialized C++ simulator of a scene: a header that needs Eigen alone (the parameter
// table, one struct per system: sizes, names and units, tunables, rhs, outputs, (M, N), (C, D)),
// and a main with the input signals that runs them.
#pragma once

#include <string>
#include <vector>

#include "specialize/specialization.hpp"

namespace pogear {

struct GeneratedSources {
  std::string header_name, header;  // <scene>.hpp
  std::string main_name, main;      // <scene>_main.cpp
};

// The simulator's sources, with the drivers of `solvers` compiled in (each costs compile time);
// none given: the scene's solver only.
GeneratedSources generate_sources(const SpecializedScene& model, std::vector<rt::Solver> solvers = {});

}  // namespace pogear
