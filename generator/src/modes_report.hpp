// The vibration modes as `pogear modes` writes them: text, Markdown, LaTeX (a whole document) and JSON.
#pragma once

#include <string>

#include "vibration_modes.hpp"

namespace pogear {

std::string modes_text(const VibrationModes& m);
std::string modes_markdown(const VibrationModes& m);
std::string modes_latex(const VibrationModes& m);
std::string modes_json(const VibrationModes& m);

}  // namespace pogear
