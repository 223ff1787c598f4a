// `pogear ratios` reports: the clutch schedule of a gear as text, Markdown, LaTeX and JSON.
#pragma once

#include <string>

#include "engage/gear_ratios.hpp"
#include "report/report_format.hpp"

namespace pogear {

// A model with [gears] lists its named gears (i = omega_in / omega_out, steps, spread), and every
// engagement too with `all`; one without lists every engagement. JSON always holds both.
std::string ratios_text(const GearRatios& g, const Topology& t, bool all);
std::string ratios_markdown(const GearRatios& g, const Topology& t, bool all);
std::string ratios_latex(const GearRatios& g, const Topology& t, bool all);
std::string ratios_json(const GearRatios& g, const Topology& t);
// The one of the four that `format` names.
std::string ratios_report(const GearRatios& g, const Topology& t, ReportFormat format, bool all);

}  // namespace pogear
