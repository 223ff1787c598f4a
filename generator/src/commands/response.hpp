// `pogear response`: the frequency response of a scene as CSV files, Bode figures and the
// resonance peaks.
#pragma once

#include <string>

#include "vibrate/vibration_analysis.hpp"

namespace pogear {

struct ResponseCommand {
  ResponseRequest request;       // its inputs and outputs are filled from the two lists below
  std::string inputs, outputs;   // comma-separated, as given
  std::string directory = "out";  // for the CSV files and figures
};

int run_response(const ResponseCommand& command);

}  // namespace pogear
