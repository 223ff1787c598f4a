// Parameters that follow a scene's tunable parameters: those defined through a tunable, kept as
// expressions in it, and the units the model wrote, which a simulator's --param accepts.
#pragma once

#include <map>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "names/symbols.hpp"
#include "read/topology.hpp"

namespace pogear {

// The parameters defined, directly or through others, by one of `tunables` (not the tunables
// themselves), each as an expression in the tunables' symbols with every other parameter and unit
// at its exact value: `K_pr = "K_ps"` with K_ps tunable is the symbol K_ps, not its number.
std::map<std::string, GiNaC::ex> tunable_dependents(const std::vector<Parameter>& parameters,
                                                    const std::vector<std::string>& tunables, const SymbolTable& symbols);

// The unit a parameter's text multiplies its leading number by, as written ("Newton/mm" in
// "1000*Newton/mm"), with its value in SI; nothing when the text is not NUMBER*UNITS.
std::optional<std::pair<std::string, double>> written_unit(const Parameter& parameter);

// The engineering spellings `--param` accepts besides the model's own and the SI one, for a
// parameter of `dimension` ("N/mm" and "kN/mm" for a stiffness the model wrote in "Newton/mm"),
// each with its value in SI, in a fixed order.
std::vector<std::pair<std::string, double>> common_unit_spellings(const Dimension& dimension);

}  // namespace pogear
