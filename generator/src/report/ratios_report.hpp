// `pogear ratios` reports: the clutch schedule of a gear as text, Markdown, LaTeX and JSON.
#pragma once

#include <string>

#include "engage/gear_ratios.hpp"

namespace pogear {

std::string ratios_text(const GearRatios& g, const Topology& t);
std::string ratios_markdown(const GearRatios& g, const Topology& t);
std::string ratios_latex(const GearRatios& g, const Topology& t);
std::string ratios_json(const GearRatios& g, const Topology& t);

}  // namespace pogear
