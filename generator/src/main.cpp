// The pogear command line: the table of subcommands and options, parsed by CLI11; each subcommand
// is one function of commands/.
#include <charconv>
#include <optional>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "build_config/build_config.hpp"
#include "commands/command_support.hpp"
#include "commands/derive.hpp"
#include "commands/generate.hpp"
#include "commands/modes.hpp"
#include "commands/ratios.hpp"
#include "commands/response.hpp"
#include "commands/simulate.hpp"
#include "common/interrupts.hpp"
#include "pogear/run_limits.hpp"

namespace {

// "-o ''" would otherwise mean standard output (derive) or the root of the file system.
CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& value) {
        return value.empty() ? std::string("the path is empty; give a file or directory name") : std::string();
      },
      "PATH");
}

// --format of every report, read into `format` by the one parse of report_format.hpp.
CLI::Option* add_format_option(CLI::App* command, pogear::ReportFormat& format) {
  return command
      ->add_option_function<std::string>(
          "--format", [&format](const std::string& name) { format = *pogear::parse_report_format(name); },
          "Report format")
      ->check(CLI::IsMember(pogear::report_format_names()));
}

// An option whose presence matters even when its value is empty.
CLI::Option* add_given_option(CLI::App* command, const std::string& name, std::optional<std::string>& value,
                              const std::string& description) {
  return command->add_option_function<std::string>(
      name, [&value](const std::string& text) { value = text; }, description);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pogear: planetary gear models by the Power-Oriented Graphs method"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("pogear ") + pogear::build_config::version);

  pogear::DeriveCommand derive_command;
  CLI::App* derive = app.add_subcommand("derive", "Derive R, the elastic and the rigid reduced model of a gear");
  derive->add_option("MODEL", derive_command.model, "Model file (TOML)")->required();
  derive->add_option("--keep", derive_command.keep, "Velocities kept in the rigid model, e.g. c,r");
  add_given_option(derive, "--engaged", derive_command.engaged,
                   "Brakes and clutches stuck: the rigid model of that mode, e.g. B1,C2");
  add_format_option(derive, derive_command.format);
  derive->add_option("-o,--output", derive_command.output, "Write the report to FILE instead of standard output")
      ->check(non_empty_path());

  pogear::GenerateCommand generate_command;
  CLI::App* generate = app.add_subcommand("generate", "Write the specialized C++ simulator of a scene");
  generate->add_option("SCENE", generate_command.scene, "Scene file (TOML)")->required();
  generate->add_option("-o,--output", generate_command.directory, "Directory for <scene>.hpp and <scene>_main.cpp")
      ->check(non_empty_path());
  generate->add_flag("--list-outputs", generate_command.list_outputs,
                     "Print the files it would write, one per line; write nothing");
  generate->add_option("--solvers", generate_command.solvers,
                       "Solvers to compile into the simulator, comma-separated, or 'all' (default: the scene's)")
      ->check(CLI::Validator(
          [](std::string& value) {
            if (value == "all") return std::string();
            for (const std::string& name : pogear::split_list(value))
              if (!pogear::rt::parse_solver(name))
                return fmt::format("unknown solver '{}' in '{}'; give some of {}, comma-separated, or all", name, value,
                                   pogear::rt::solver_names(", "));
            return std::string();
          },
          "LIST"));

  pogear::SimulateCommand simulate_command;
  CLI::App* simulate = app.add_subcommand("simulate", "Generate, compile and run a scene; write CSV and plots");
  simulate->add_option("SCENE", simulate_command.scene, "Scene file (TOML)")->required();
  simulate->add_option("-o,--output", simulate_command.options.out_dir, "Directory for the CSV files and plots")
      ->check(non_empty_path());
  std::vector<std::string> solver_names;
  for (pogear::rt::Solver s : pogear::rt::all_solvers) solver_names.emplace_back(pogear::rt::solver_name(s));
  simulate->add_option("--solver", simulate_command.solver, "Override the scene's solver")
      ->check(CLI::IsMember(solver_names));
  simulate->add_option("--tolerance", simulate_command.options.tolerance,
                       "Relative tolerance of the adaptive solvers instead of the scene's, e.g. 1e-10")
      ->check(CLI::Validator(
          [](std::string& value) {
            const std::optional<double> r = pogear::rt::detail::parse_finite(value);
            if (r && *r >= pogear::rt::limits::min_tolerance && *r <= pogear::rt::limits::max_tolerance)
              return std::string();
            return fmt::format("'{}' is not a tolerance from {:g} to {:g}; give a relative tolerance, e.g. "
                               "--tolerance 1e-10", value, pogear::rt::limits::min_tolerance,
                               pogear::rt::limits::max_tolerance);
          },
          "R"));
  simulate->add_option("--param", simulate_command.options.params,
                       "A tunable parameter's value for this run, NAME=VALUE (e.g. K_ps=2000*N/mm); repeatable")
      ->allow_extra_args(false);
  simulate->add_flag("--interpreted", simulate_command.options.interpreted,
                     "Run from the numeric matrices, without compiling");
  simulate->add_option("--repeat", simulate_command.repeat, "Run N times and report the median time")
      ->check(CLI::Validator(
          [](std::string& value) {
            long n = 0;
            const auto [end, ec] = std::from_chars(value.data(), value.data() + value.size(), n);
            if (ec == std::errc() && end == value.data() + value.size() && n >= 1 && n <= pogear::rt::limits::max_repeat)
              return std::string();
            return fmt::format("'{}' is not a whole number from 1 to {}; give how many times to run, e.g. --repeat 5",
                               value, pogear::rt::limits::max_repeat);
          },
          "N"));
  simulate->add_flag("--large-output", simulate_command.options.large_output,
                     fmt::format("Write CSV files even when they may exceed {} GB", pogear::max_csv_bytes >> 30));

  pogear::ModesCommand modes_command;
  CLI::App* modes =
      app.add_subcommand("modes", "Natural frequencies, mode shapes and modal energies of the elastic model");
  modes->add_option("MODEL_OR_SCENE", modes_command.model_or_scene,
                    "Model file, or scene file (its parameters and damping)")
      ->required();
  modes->add_option("--engaged", modes_command.engaged, "Brakes and clutches stuck (the others open), e.g. B1,C2");
  add_format_option(modes, modes_command.format);
  modes->add_option("-o,--output", modes_command.output, "Write the report to FILE instead of standard output")
      ->check(non_empty_path());
  modes->add_option("--campbell", modes_command.campbell,
                    "Also draw the Campbell diagram as an SVG FILE (needs tooth counts)")
      ->check(non_empty_path());
  add_given_option(modes, "--input", modes_command.input, "Campbell: the input body whose speed is the axis, e.g. s");
  add_given_option(modes, "--hold", modes_command.hold, "Campbell: bodies held at rest on the operating line, e.g. r");
  modes->add_option("--to", modes_command.to, "Campbell: the highest input speed, e.g. 6000*rpm");
  modes->add_option("--harmonics", modes_command.harmonics, "Campbell: harmonics of each mesh frequency (default 3)");

  pogear::ResponseCommand response_command;
  pogear::ResponseRequest& response_request = response_command.request;
  CLI::App* response =
      app.add_subcommand("response", "Frequency response of a scene: CSV, Bode figure, resonance peaks");
  response->add_option("SCENE", response_request.scene_file, "Scene file (TOML)")->required();
  response->add_option("--input", response_command.inputs, "Input torques, comma-separated, e.g. tau_c")->required();
  response->add_option("--output", response_command.outputs, "Outputs, comma-separated: omega_<body>, F_<mesh> or T_<shaft>")
      ->required();
  response->add_option("--from", response_request.from, "Lowest frequency, e.g. 1*Hz (default)");
  response->add_option("--to", response_request.to, "Highest frequency, e.g. 10*kHz (default)");
  response->add_option("--engaged", response_request.engaged, "Brakes and clutches stuck (the others open), e.g. B1,C2");
  response->add_option("--points", response_request.points, "Frequencies, logarithmically spaced (default 1000)")
      ->check(CLI::Range(2, 1000000));
  response->add_option("-o,--output-dir", response_command.directory,
                       "Directory for the CSV files and figures (default out)")
      ->check(non_empty_path());

  pogear::RatiosCommand ratios_command;
  CLI::App* ratios = app.add_subcommand("ratios", "Gear ratio of every set of engaged brakes and clutches");
  ratios->add_option("MODEL", ratios_command.model, "Model file (TOML)")->required();
  ratios->add_option("--input", ratios_command.input, "Input body, e.g. i")->required();
  ratios->add_option("--output", ratios_command.output, "Output body, e.g. o")->required();
  add_format_option(ratios, ratios_command.format);
  ratios->add_flag("--all", ratios_command.all, "With the model's [gears]: every other engagement too");
  ratios->add_option("-o,--output-file", ratios_command.report_file, "Write the report to FILE instead of standard output")
      ->check(non_empty_path());

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

  pogear::install_interrupt_cleanup();  // Ctrl-C leaves no temporary file and no running child behind
  return pogear::exit_status_of([&] {
    if (*derive) return pogear::run_derive(derive_command);
    if (*generate) return pogear::run_generate(generate_command);
    if (*modes) return pogear::run_modes(modes_command);
    if (*ratios) return pogear::run_ratios(ratios_command);
    if (*response) return pogear::run_response(response_command);
    return pogear::run_simulate(simulate_command);
  });
}
