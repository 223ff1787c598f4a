// The pogear command line: a thin layer that parses options and calls the library.
#include <cstdio>
#include <iostream>
#include <optional>
#include <sstream>

#include <CLI/CLI.hpp>

#include "derivation.hpp"
#include "output_file.hpp"
#include "report.hpp"

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

  try {
    app.parse(argc, argv);
  } catch (const CLI::ParseError& e) {
    const int code = app.exit(e);
    return code == 0 ? 0 : 1;
  }

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
