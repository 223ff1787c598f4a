// The formats every report comes in (derive, ratios, modes): one list, one parse, for every
// command that takes --format.
#pragma once

#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace pogear {

enum class ReportFormat { text, latex, markdown, json };

// "text", "latex", "markdown", "json"; nothing for any other name.
std::optional<ReportFormat> parse_report_format(std::string_view name);
// The names parse_report_format takes, in the order --help lists them.
std::vector<std::string> report_format_names();

}  // namespace pogear
