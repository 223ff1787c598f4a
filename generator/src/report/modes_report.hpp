// The vibration modes as `pogear modes` writes them: text, Markdown, LaTeX (a whole document) and JSON.
#pragma once

#include <string>
#include <string_view>

#include "vibrate/campbell.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear {

std::string modes_text(const VibrationModes& m);
std::string modes_markdown(const VibrationModes& m);
// `extra`: more of the document before its end (the Campbell diagram's section).
std::string modes_latex(const VibrationModes& m, const std::string& extra = "");
// `extra_member`: one more member of the top-level object, e.g. "campbell": {...}.
std::string modes_json(const VibrationModes& m, const std::string& extra_member = "");

// The report in `format` ("text", "markdown", "latex", "json"), with the Campbell diagram's section
// when one is given.
std::string modes_report(const VibrationModes& m, std::string_view format, const CampbellDiagram* campbell = nullptr);

}  // namespace pogear
