// The report formats' names, in one table that the parse and the command line's check share.
#include "report/report_format.hpp"

#include <array>
#include <utility>

namespace pogear {
namespace {

constexpr std::array<std::pair<std::string_view, ReportFormat>, 4> format_names{{
    {"text", ReportFormat::text},
    {"latex", ReportFormat::latex},
    {"markdown", ReportFormat::markdown},
    {"json", ReportFormat::json},
}};

}  // namespace

std::optional<ReportFormat> parse_report_format(std::string_view name) {
  for (const auto& [text, format] : format_names)
    if (text == name) return format;
  return std::nullopt;
}

std::vector<std::string> report_format_names() {
  std::vector<std::string> names;
  for (const auto& entry : format_names) names.emplace_back(entry.first);
  return names;
}

}  // namespace pogear
