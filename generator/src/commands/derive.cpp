// The derivation, the diagnostics of its elastic model, and the report of both.
#include "commands/derive.hpp"

#include "commands/command_support.hpp"
#include "derive/derivation.hpp"
#include "derive/engagement.hpp"
#include "read/topology.hpp"
#include "report/report.hpp"
#include "vibrate/diagnostics.hpp"

namespace pogear {

int run_derive(const DeriveCommand& command) {
  std::optional<std::vector<std::string>> kept;
  if (!command.keep.empty()) kept = split_list(command.keep);
  const SourceLocation where{command.model, 0, 0};
  Topology topology = parse_topology(command.model);
  std::vector<int> stuck;
  if (command.engaged) stuck = parse_engaged(topology, *command.engaged, where);
  const Derivation d = derive_topology(std::move(topology), kept, where, true, stuck);
  const std::string text = derive_report(d, derivation_diagnostics(d), command.format);
  if (command.output) refuse_same_file(*command.output, command.model, "the model file");
  emit(text, command.output);
  return 0;
}

}  // namespace pogear
