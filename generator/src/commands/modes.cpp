// The report and the figure are both made before either is written, so that a failure leaves
// neither half behind.
#include "commands/modes.hpp"

#include <iostream>
#include <stdexcept>

#include <fmt/format.h>

#include "commands/command_support.hpp"
#include "common/gnuplot.hpp"
#include "common/input_error.hpp"
#include "common/output_file.hpp"
#include "report/modes_report.hpp"
#include "vibrate/vibration_analysis.hpp"

namespace pogear {
namespace {

void check_campbell_options(const ModesCommand& command, const SourceLocation& where) {
  if (command.campbell) return;
  const std::pair<const char*, bool> options[] = {{"--input", command.input.has_value()},
                                                  {"--hold", command.hold.has_value()},
                                                  {"--to", command.to.has_value()},
                                                  {"--harmonics", command.harmonics.has_value()}};
  for (const auto& [option, given] : options)
    if (given) throw InputError(where, fmt::format("{} belongs to the Campbell diagram; add --campbell FILE.svg", option));
}

int write_modes_with_campbell(const ModesCommand& command, const SourceLocation& where) {
  const std::string& campbell_file = *command.campbell;
  if (!command.input || command.input->empty())
    throw InputError(where, "--campbell needs the input body whose speed is the axis, e.g. --input s");
  CampbellRequest request;
  request.input = *command.input;
  request.hold = command.hold;
  request.to = command.to;
  if (command.harmonics) request.harmonics = *command.harmonics;
  const ModesWithCampbell mc = campbell_of_file(command.model_or_scene, command.engaged, request);
  std::cerr << open_elements_warning(mc.modes.open_in_scene, "modes");
  const std::string text = modes_report(mc.modes, command.format, &mc.campbell);
  const std::optional<std::string> gnuplot = gnuplot_program();
  if (!gnuplot)
    throw std::runtime_error("gnuplot is not installed, so the Campbell diagram cannot be drawn; install "
                             "gnuplot-nox (scripts/install-deps.sh)");
  // The report first when it goes to a file, so that a bad -o leaves no figure behind.
  const std::string svg = render_svg(*gnuplot, campbell_script(mc.campbell), campbell_file, "nothing was written");
  if (command.output) {
    emit(text, command.output);
    try {
      write_file_atomically(campbell_file, svg);
    } catch (const std::exception& e) {
      throw std::runtime_error(std::string(e.what()) + " (the report " + *command.output + " is written)");
    }
    std::cout << "wrote " << *command.output << " and " << campbell_file << "\n";
  } else {
    write_file_atomically(campbell_file, svg);
    emit(text, command.output);
  }
  return 0;
}

}  // namespace

int run_modes(const ModesCommand& command) {
  const SourceLocation where{command.model_or_scene, 0, 0};
  check_campbell_options(command, where);
  if (command.output) refuse_same_file(*command.output, command.model_or_scene, "the model or scene file");
  if (command.campbell) {
    refuse_same_file(*command.campbell, command.model_or_scene, "the model or scene file");
    if (command.output) refuse_same_file(*command.campbell, *command.output, "the report (-o)");
    return write_modes_with_campbell(command, where);
  }
  const VibrationModes modes = modes_of_file(command.model_or_scene, command.engaged);
  std::cerr << open_elements_warning(modes.open_in_scene, "modes");
  emit(modes_report(modes, command.format), command.output);
  return 0;
}

}  // namespace pogear
