// The names of a specialized system's states, inputs and outputs, as the generated code and the CSV
// files write them, for tests that find a port by its name.
#pragma once

#include <string>
#include <vector>

#include "specialize/specialization.hpp"

namespace pogear::test {

inline std::vector<std::string> state_names(const SpecializedScene& m, const SpecializedSystem& sys) {
  return port_names(m.derivation.symbols, state_variables(sys));
}
inline std::vector<std::string> input_names(const SpecializedScene& m, const SpecializedSystem& sys) {
  return port_names(m.derivation.symbols, input_variables(sys));
}
inline std::vector<std::string> output_names(const SpecializedScene& m, const SpecializedSystem& sys) {
  return port_names(m.derivation.symbols, output_variables(sys));
}

}  // namespace pogear::test
