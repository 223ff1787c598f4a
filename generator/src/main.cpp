// The pogear command line: a thin layer that parses options and calls the library.
#include <cstdio>
#include <filesystem>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "derivation.hpp"
#include "output_file.hpp"
#include "report.hpp"
#include "simulation.hpp"

namespace {

std::vector<std::string> split_list(const std::string& s) {
  std::vector<std::string> out;
  std::stringstream ss(s);
  std::string item;
  while (std::getline(ss, item, ','))
    if (!item.empty()) out.push_back(item);
  return out;
}

void emit(const std::string& text, const std::string& output) {
  if (output.empty()) std::fwrite(text.data(), 1, text.size(), stdout);
  else pogear::write_file_atomically(output, text);
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"pogear: planetary gear models by the Power-Oriented Graphs method"};
  app.require_subcommand(1);
  app.set_version_flag("--version", "pogear 0.1.0");

  std::string model, keep, format = "text", output;
  CLI::App* derive = app.add_subcommand("derive", "Derive R, the elastic and the rigid reduced model of a gear");
  derive->add_option("MODEL", model, "Model file (TOML)")->required();
  derive->add_option("--keep", keep, "Velocities kept in the rigid model, e.g. c,r");
  derive->add_option("--format", format, "Report format")
      ->check(CLI::IsMember({"text", "latex", "markdown", "json"}));
  derive->add_option("-o,--output", output, "Write the report to FILE instead of standard output");

  std::string scene_file, generate_dir = ".", simulate_dir = "out", solver;
  bool interpreted = false;
  int repeat = 1;
  CLI::App* generate = app.add_subcommand("generate", "Write the specialized C++ simulator of a scene");
  generate->add_option("SCENE", scene_file, "Scene file (TOML)")->required();
  generate->add_option("-o,--output", generate_dir, "Directory for <scene>.hpp and <scene>_main.cpp");

  CLI::App* simulate = app.add_subcommand("simulate", "Generate, compile and run a scene; write CSV and plots");
  simulate->add_option("SCENE", scene_file, "Scene file (TOML)")->required();
  simulate->add_option("-o,--output", simulate_dir, "Directory for the CSV files and plots");
  simulate->add_option("--solver", solver, "Override the scene's solver")
      ->check(CLI::IsMember({"exact", "rk4", "dopri5", "implicit"}));
  simulate->add_flag("--interpreted", interpreted, "Run from the numeric matrices, without compiling");
  simulate->add_option("--repeat", repeat, "Run N times and report the median time")->check(CLI::PositiveNumber);

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

  pogear::install_interrupt_cleanup();  // Ctrl-C leaves no temporary file behind
  try {
    if (*derive) {
      std::optional<std::vector<std::string>> kept;
      if (!keep.empty()) kept = split_list(keep);
      const pogear::Derivation d = pogear::derive_model(model, kept, pogear::SourceLocation{model, 0, 0});
      std::string text;
      if (format == "json") text = pogear::report_json(d);
      else if (format == "latex") text = pogear::report_latex(d);
      else if (format == "markdown") text = pogear::report_markdown(d);
      else text = pogear::report_text(d);
      emit(text, output);
    } else if (*generate) {
      const pogear::SimModel model = pogear::specialize(pogear::parse_scene(scene_file));
      const pogear::GeneratedSources sources = pogear::generate_sources(model);
      pogear::write_sources(sources, generate_dir);
      std::cout << "wrote " << generate_dir << "/" << sources.header_name << " and " << generate_dir << "/"
                << sources.main_name << "\n"
                << pogear::operation_summary(model);
    } else if (*simulate) {
      const pogear::SimModel model = pogear::specialize(pogear::parse_scene(scene_file));
      pogear::rt::SceneRun run;
      run.name = model.scene.name;
      run.horizon = model.scene.horizon;
      run.sample = model.scene.sample;
      run.solver = solver.empty() ? pogear::solver_name(model.scene.solver) : solver;
      run.options.rtol = model.scene.tolerance;
      run.options.atol = model.scene.tolerance * 1e-2;
      run.options.h = model.scene.step;
      run.options.max_steps = model.scene.max_steps;
      run.out_dir = simulate_dir;
      run.repeat = repeat;
      std::filesystem::create_directories(simulate_dir);
      std::cout << pogear::operation_summary(model);
      // The simulator writes <name>.csv.tmp and renames it when done; an interrupt must not leave it.
      for (const char* suffix : {".csv.tmp", ".rigid.csv.tmp"})
        pogear::remember_temporary(simulate_dir + "/" + run.name + suffix);
      int status = 0;
      if (interpreted) {
        status = pogear::run_interpreted(model, run);
      } else {
        const std::string exe = pogear::build_simulator(pogear::generate_sources(model));
        status = pogear::run_compiled(exe, run);
        // std::system ignores SIGINT in pogear while the simulator runs; if it died of one, clean up.
        if (status > 128) pogear::remove_remembered_temporaries();
      }
      if (status != 0) return status;
      for (const auto& svg : pogear::plot_scene(model, simulate_dir)) std::cout << "wrote " << svg << "\n";
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
