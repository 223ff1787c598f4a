// The derive reports: text for terminals, LaTeX and Markdown for papers, JSON for programs.
#pragma once

#include <string>

#include "derive/derivation.hpp"

namespace pogear {

std::string report_text(const Derivation& d);
std::string report_latex(const Derivation& d);
std::string report_markdown(const Derivation& d);
std::string report_json(const Derivation& d);

}  // namespace pogear
