// `pogear derive`: R, the elastic and the rigid reduced model of a gear, as a report.
#pragma once

#include <optional>
#include <string>

#include "report/report_format.hpp"

namespace pogear {

struct DeriveCommand {
  std::string model;                   // the model file
  std::string keep;                    // kept velocities, comma-separated; empty: the model's choice
  std::optional<std::string> engaged;  // brakes and clutches stuck, comma-separated
  ReportFormat format = ReportFormat::text;
  std::optional<std::string> output;   // the report's file; none: standard output
};

int run_derive(const DeriveCommand& command);

}  // namespace pogear
