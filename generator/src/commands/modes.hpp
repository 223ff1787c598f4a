// `pogear modes`: natural frequencies, mode shapes and modal energies, and on request the Campbell
// diagram as an SVG figure.
#pragma once

#include <optional>
#include <string>

#include "report/report_format.hpp"

namespace pogear {

struct ModesCommand {
  std::string model_or_scene;          // a model file, or a scene file (its parameters and damping)
  std::optional<std::string> engaged;  // brakes and clutches stuck (the others open)
  ReportFormat format = ReportFormat::text;
  std::optional<std::string> output;   // the report's file; none: standard output
  std::optional<std::string> campbell;  // the Campbell diagram's SVG file
  // The diagram's operating line, each only with `campbell`: the input body, the bodies held at
  // rest, the highest input speed, the harmonics of each mesh frequency.
  std::optional<std::string> input, hold, to;
  std::optional<int> harmonics;
};

int run_modes(const ModesCommand& command);

}  // namespace pogear
