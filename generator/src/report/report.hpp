// The derive reports: text for terminals, LaTeX and Markdown for papers, JSON for programs.
#pragma once

#include <string>

#include "derive/derivation.hpp"
#include "report/report_format.hpp"
#include "vibrate/diagnostics.hpp"

namespace pogear {

std::string report_text(const Derivation& d, const Diagnostics& diagnostics);
std::string report_latex(const Derivation& d, const Diagnostics& diagnostics);
std::string report_markdown(const Derivation& d, const Diagnostics& diagnostics);
std::string report_json(const Derivation& d, const Diagnostics& diagnostics);
// The one of the four that `format` names.
std::string derive_report(const Derivation& d, const Diagnostics& diagnostics, ReportFormat format);

}  // namespace pogear
