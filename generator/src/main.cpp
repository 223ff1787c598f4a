// The pogear command line: a thin layer that parses options and calls the library.
#include <charconv>
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>
#include <fmt/format.h>

#include "build_config.hpp"
#include "derive/derivation.hpp"
#include "derive/engagement.hpp"
#include "common/interrupts.hpp"
#include "report/modes_report.hpp"
#include "run/plot.hpp"
#include "common/output_file.hpp"
#include "report/ratios_report.hpp"
#include "pogear/run_limits.hpp"
#include "report/response_report.hpp"
#include "report/run_summary.hpp"
#include "report/report.hpp"
#include "run/simulate_scene.hpp"
#include "run/simulator_cache.hpp"
#include "vibrate/vibration_analysis.hpp"

namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

// An output file must not be an input of the command, nor another of its outputs.
void refuse_same_file(const std::string& output, const std::string& other, const std::string& what) {
  std::error_code e1, e2;
  const auto a = std::filesystem::weakly_canonical(output, e1), b = std::filesystem::weakly_canonical(other, e2);
  if (!e1 && !e2 && a == b)
    throw pogear::InputError(pogear::SourceLocation{output, 0, 0},
                             fmt::format("this output is also {}; write it to another file", what));
}

void emit(const std::string& text, const std::optional<std::string>& output) {
  if (!output) std::fwrite(text.data(), 1, text.size(), stdout);
  else pogear::write_file_atomically(*output, text);
}

// "-o ''" would otherwise mean standard output (derive) or the root of the file system.
CLI::Validator non_empty_path() {
  return CLI::Validator(
      [](std::string& value) {
        return value.empty() ? std::string("the path is empty; give a file or directory name") : std::string();
      },
      "PATH");
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pogear: planetary gear models by the Power-Oriented Graphs method"};
  app.require_subcommand(1);
  app.set_version_flag("--version", std::string("pogear ") + pogear::build_config::version);

  std::string model, keep, format = "text";
  std::optional<std::string> output;
  CLI::App* derive = app.add_subcommand("derive", "Derive R, the elastic and the rigid reduced model of a gear");
  derive->add_option("MODEL", model, "Model file (TOML)")->required();
  derive->add_option("--keep", keep, "Velocities kept in the rigid model, e.g. c,r");
  std::string engaged;
  derive->add_option("--engaged", engaged, "Brakes and clutches stuck: the rigid model of that mode, e.g. B1,C2");
  derive->add_option("--format", format, "Report format")
      ->check(CLI::IsMember({"text", "latex", "markdown", "json"}));
  derive->add_option("-o,--output", output, "Write the report to FILE instead of standard output")
      ->check(non_empty_path());

  std::string scene_file, generate_dir = ".", solver;
  bool list_outputs = false;
  pogear::SimulateOptions simulate_options;
  long repeat = 1;
  CLI::App* generate = app.add_subcommand("generate", "Write the specialized C++ simulator of a scene");
  generate->add_option("SCENE", scene_file, "Scene file (TOML)")->required();
  generate->add_option("-o,--output", generate_dir, "Directory for <scene>.hpp and <scene>_main.cpp")
      ->check(non_empty_path());
  generate->add_flag("--list-outputs", list_outputs, "Print the files it would write, one per line; write nothing");
  std::string generate_solvers;
  generate->add_option("--solvers", generate_solvers,
                       "Solvers to compile into the simulator, comma-separated, or 'all' (default: the scene's)")
      ->check(CLI::Validator(
          [](std::string& value) {
            if (value == "all") return std::string();
            for (const std::string& name : split_list(value))
              if (!pogear::rt::parse_solver(name))
                return fmt::format("unknown solver '{}' in '{}'; give some of {}, comma-separated, or all", name, value,
                                   pogear::rt::solver_names(", "));
            return std::string();
          },
          "LIST"));

  CLI::App* simulate = app.add_subcommand("simulate", "Generate, compile and run a scene; write CSV and plots");
  simulate->add_option("SCENE", scene_file, "Scene file (TOML)")->required();
  simulate->add_option("-o,--output", simulate_options.out_dir, "Directory for the CSV files and plots")
      ->check(non_empty_path());
  std::vector<std::string> solver_names;
  for (pogear::rt::Solver s : pogear::rt::all_solvers) solver_names.emplace_back(pogear::rt::solver_name(s));
  simulate->add_option("--solver", solver, "Override the scene's solver")->check(CLI::IsMember(solver_names));
  simulate->add_flag("--interpreted", simulate_options.interpreted, "Run from the numeric matrices, without compiling");
  simulate->add_option("--repeat", repeat, "Run N times and report the median time")
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
  simulate->add_flag("--large-output", simulate_options.large_output,
                     fmt::format("Write CSV files even when they may exceed {} GB", pogear::max_csv_bytes >> 30));

  std::string modes_file, modes_format = "text";
  std::optional<std::string> modes_output;
  CLI::App* modes = app.add_subcommand("modes", "Natural frequencies, mode shapes and modal energies of the elastic model");
  modes->add_option("MODEL_OR_SCENE", modes_file, "Model file, or scene file (its parameters and damping)")->required();
  std::optional<std::string> modes_engaged;
  modes->add_option("--engaged", modes_engaged, "Brakes and clutches stuck (the others open), e.g. B1,C2");
  modes->add_option("--format", modes_format, "Report format")->check(CLI::IsMember({"text", "latex", "markdown", "json"}));
  modes->add_option("-o,--output", modes_output, "Write the report to FILE instead of standard output")
      ->check(non_empty_path());
  std::optional<std::string> campbell_file;
  pogear::CampbellRequest campbell_request;
  std::string campbell_held;
  modes->add_option("--campbell", campbell_file, "Also draw the Campbell diagram as an SVG FILE (needs tooth counts)")
      ->check(non_empty_path());
  modes->add_option("--input", campbell_request.input, "Campbell: the input body whose speed is the axis, e.g. s");
  modes->add_option("--hold", campbell_held, "Campbell: bodies held at rest on the operating line, e.g. r");
  modes->add_option("--to", campbell_request.to, "Campbell: the highest input speed, e.g. 6000*rpm");
  modes->add_option("--harmonics", campbell_request.harmonics, "Campbell: harmonics of each mesh frequency (default 3)");

  pogear::ResponseRequest response_request;
  std::string response_dir = "out";
  std::string response_inputs, response_outputs;
  CLI::App* response = app.add_subcommand("response", "Frequency response of a scene: CSV, Bode figure, resonance peaks");
  response->add_option("SCENE", response_request.scene_file, "Scene file (TOML)")->required();
  response->add_option("--input", response_inputs, "Input torques, comma-separated, e.g. tau_c")->required();
  response->add_option("--output", response_outputs, "Outputs, comma-separated: omega_<body> or F_<mesh>")->required();
  response->add_option("--from", response_request.from, "Lowest frequency, e.g. 1*Hz (default)");
  response->add_option("--to", response_request.to, "Highest frequency, e.g. 10*kHz (default)");
  response->add_option("--engaged", response_request.engaged, "Brakes and clutches stuck (the others open), e.g. B1,C2");
  response->add_option("--points", response_request.points, "Frequencies, logarithmically spaced (default 1000)")
      ->check(CLI::Range(2, 1000000));
  response->add_option("-o,--output-dir", response_dir, "Directory for the CSV files and figures (default out)")
      ->check(non_empty_path());

  std::string ratios_model, ratios_input, ratios_output, ratios_format = "text";
  std::optional<std::string> ratios_file;
  CLI::App* ratios = app.add_subcommand("ratios", "Gear ratio of every set of engaged brakes and clutches");
  ratios->add_option("MODEL", ratios_model, "Model file (TOML)")->required();
  ratios->add_option("--input", ratios_input, "Input body, e.g. i")->required();
  ratios->add_option("--output", ratios_output, "Output body, e.g. o")->required();
  ratios->add_option("--format", ratios_format, "Report format")->check(CLI::IsMember({"text", "latex", "markdown", "json"}));
  ratios->add_option("-o,--output-file", ratios_file, "Write the report to FILE instead of standard output")
      ->check(non_empty_path());

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

  pogear::install_interrupt_cleanup();  // Ctrl-C leaves no temporary file and no running child behind
  try {
    if (*derive) {
      std::optional<std::vector<std::string>> kept;
      if (!keep.empty()) kept = split_list(keep);
      const pogear::SourceLocation where{model, 0, 0};
      pogear::Topology topology = pogear::parse_topology(model);
      std::vector<int> stuck;
      if (derive->count("--engaged")) stuck = pogear::parse_engaged(topology, engaged, where);
      const pogear::Derivation d = pogear::derive_topology(std::move(topology), kept, where, true, stuck);
      std::string text;
      if (format == "json") text = pogear::report_json(d);
      else if (format == "latex") text = pogear::report_latex(d);
      else if (format == "markdown") text = pogear::report_markdown(d);
      else text = pogear::report_text(d);
      if (output) refuse_same_file(*output, model, "the model file");
      emit(text, output);
    } else if (*generate) {
      const pogear::SpecializedScene model = pogear::specialize(pogear::parse_scene(scene_file));
      std::vector<pogear::rt::Solver> solvers;
      if (generate_solvers == "all") {  // those that can run the scene
        solvers = pogear::rt::admissible_solvers(pogear::solver_traits(model));
      } else if (!generate_solvers.empty())
        for (const std::string& name : split_list(generate_solvers)) solvers.push_back(*pogear::rt::parse_solver(name));
      const pogear::GeneratedSources sources = pogear::generate_sources(model, solvers);
      if (list_outputs) {
        for (const std::string& path : pogear::source_paths(sources, generate_dir)) std::cout << path << "\n";
        return 0;
      }
      pogear::ensure_directory(generate_dir);
      pogear::write_sources(sources, generate_dir);
      std::cout << "wrote " << generate_dir << "/" << sources.header_name << " and " << generate_dir << "/"
                << sources.main_name << "\n"
                << pogear::operation_summary(model);
    } else if (*modes) {
      const pogear::SourceLocation where{modes_file, 0, 0};
      for (const char* option : {"--input", "--hold", "--to", "--harmonics"})
        if (!campbell_file && modes->count(option))
          throw pogear::InputError(where, fmt::format("{} belongs to the Campbell diagram; add --campbell FILE.svg", option));
      if (modes_output) refuse_same_file(*modes_output, modes_file, "the model or scene file");
      if (campbell_file) {
        refuse_same_file(*campbell_file, modes_file, "the model or scene file");
        if (modes_output) refuse_same_file(*campbell_file, *modes_output, "the report (-o)");
      }
      if (!campbell_file) {
        const pogear::VibrationModes modes = pogear::modes_of_file(modes_file, modes_engaged);
        std::cerr << pogear::open_elements_warning(modes.open_in_scene, "modes");
        emit(pogear::modes_report(modes, modes_format), modes_output);
        return 0;
      }
      if (campbell_request.input.empty())
        throw pogear::InputError(where, "--campbell needs the input body whose speed is the axis, e.g. --input s");
      if (modes->count("--hold")) campbell_request.hold = campbell_held;
      const pogear::ModesWithCampbell mc = pogear::campbell_of_file(modes_file, modes_engaged, campbell_request);
      std::cerr << pogear::open_elements_warning(mc.modes.open_in_scene, "modes");
      const std::string text = pogear::modes_report(mc.modes, modes_format, &mc.campbell);
      const std::optional<std::string> gnuplot = pogear::gnuplot_program();
      if (!gnuplot)
        throw std::runtime_error("gnuplot is not installed, so the Campbell diagram cannot be drawn; install "
                                 "gnuplot-nox (scripts/install-deps.sh)");
      // Both made before either is written; the report first when it goes to a file, so that a bad -o
      // leaves no figure behind.
      const std::string svg = pogear::render_svg(*gnuplot, pogear::campbell_script(mc.campbell), *campbell_file,
                                                 "nothing was written");
      if (modes_output) {
        emit(text, modes_output);
        try {
          pogear::write_file_atomically(*campbell_file, svg);
        } catch (const std::exception& e) {
          throw std::runtime_error(std::string(e.what()) + " (the report " + *modes_output + " is written)");
        }
        std::cout << "wrote " << *modes_output << " and " << *campbell_file << "\n";
      } else {
        pogear::write_file_atomically(*campbell_file, svg);
        emit(text, modes_output);
      }
    } else if (*ratios) {
      const pogear::SourceLocation where{ratios_model, 0, 0};
      const pogear::Derivation d = pogear::derive_topology(pogear::parse_topology(ratios_model), std::nullopt, where, false);
      const pogear::GearRatios g = pogear::gear_ratios(d, ratios_input, ratios_output, where);
      std::string text;
      if (ratios_format == "json") text = pogear::ratios_json(g, d.topology);
      else if (ratios_format == "latex") text = pogear::ratios_latex(g, d.topology);
      else if (ratios_format == "markdown") text = pogear::ratios_markdown(g, d.topology);
      else text = pogear::ratios_text(g, d.topology);
      if (ratios_file) refuse_same_file(*ratios_file, ratios_model, "the model file");
      emit(text, ratios_file);
    } else if (*response) {
      response_request.inputs = split_list(response_inputs);
      response_request.outputs = split_list(response_outputs);
      const pogear::SceneResponse h = pogear::response_of(response_request);
      std::cerr << pogear::open_elements_warning(h.open_in_scene, "responses");
      std::cout << pogear::response_summary(h.pairs);
      pogear::ensure_directory(response_dir);
      for (const std::string& path : pogear::write_response_files(h.scene_name, h.pairs, response_dir))
        std::cout << "wrote " << path << "\n";
    } else if (*simulate) {
      if (!solver.empty()) simulate_options.solver = pogear::rt::parse_solver(solver);
      simulate_options.repeat = static_cast<int>(repeat);
      const pogear::SpecializedScene model = pogear::specialize(pogear::parse_scene(scene_file));
      return pogear::simulate_scene(model, simulate_options, std::cout);
    }
  } catch (const pogear::InputError& e) {
    std::cerr << e.what() << "\n";
    return 2;
  } catch (const std::exception& e) {
    std::cerr << "pogear: error: " << e.what() << "\n";
    return 2;
  }
  return 0;
}
