// The clutch schedule needs the rigid motions only: the derivation skips the closed forms.
#include "commands/ratios.hpp"

#include "commands/command_support.hpp"
#include "derive/derivation.hpp"
#include "engage/gear_ratios.hpp"
#include "read/topology.hpp"
#include "report/ratios_report.hpp"

namespace pogear {

int run_ratios(const RatiosCommand& command) {
  const SourceLocation where{command.model, 0, 0};
  const Derivation d = derive_topology(parse_topology(command.model), std::nullopt, where, false);
  const GearRatios g = gear_ratios(d, command.input, command.output, where);
  const std::string text = ratios_report(g, d.topology, command.format, command.all);
  if (command.report_file) refuse_same_file(*command.report_file, command.model, "the model file");
  emit(text, command.report_file);
  return 0;
}

}  // namespace pogear
