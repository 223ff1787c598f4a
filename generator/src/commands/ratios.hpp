// `pogear ratios`: the gear ratio of every set of engaged brakes and clutches, as a report.
#pragma once

#include <optional>
#include <string>

#include "report/report_format.hpp"

namespace pogear {

struct RatiosCommand {
  std::string model;   // the model file
  std::string input;   // the input body
  std::string output;  // the output body
  ReportFormat format = ReportFormat::text;
  std::optional<std::string> report_file;  // none: standard output
  bool all = false;  // with [gears], every other engagement too
};

int run_ratios(const RatiosCommand& command);

}  // namespace pogear
