// Emits the specialized C++ simulator of a scene: a header with one struct per system (sizes,
// names and units as constexpr metadata, tunable parameters, rhs, outputs, (M, N)), and a main.
#pragma once

#include <string>

#include "sim_model.hpp"

namespace pogear {

struct GeneratedSources {
  std::string header_name, header;  // <scene>.hpp
  std::string main_name, main;      // <scene>_main.cpp
};

GeneratedSources generate_sources(const SimModel& model);

// "rhs: 38 operations (24 multiplications, 14 additions); outputs: ..." for each system.
std::string operation_summary(const SimModel& model);

}  // namespace pogear
