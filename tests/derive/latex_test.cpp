// The LaTeX reports compile with pdflatex (every shipped model, and names and a title full of
// LaTeX's special characters), and the Markdown report carries the same mathematics.
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

std::vector<fs::path> shipped_models() {
  std::vector<fs::path> models;
  for (const auto& e : fs::directory_iterator(source_path("models")))
    if (e.path().extension() == ".toml") models.push_back(e.path());
  std::sort(models.begin(), models.end());
  return models;
}

// pdflatex on DIR/NAME.tex, in batch mode: the status and the end of its log when it failed.
void expect_compiles(const fs::path& dir, const std::string& name) {
  const Command c = run_command("pdflatex -interaction=nonstopmode -halt-on-error " + name + ".tex < /dev/null", dir);
  std::string log = c.out;
  if (log.size() > 3000) log = log.substr(log.size() - 3000);
  EXPECT_EQ(c.status, 0) << name << ".tex:\n" << log;
  EXPECT_TRUE(fs::exists(dir / (name + ".pdf"))) << name;
}

void expect_pdflatex() {
  // scripts/install-deps.sh installs it (texlive-latex-base, texlive-latex-recommended).
  ASSERT_EQ(run_command("command -v pdflatex").status, 0) << "pdflatex is missing: run scripts/install-deps.sh";
}

TEST(LatexReports, EveryShippedModelsDeriveAndModesReportsCompile) {
  expect_pdflatex();
  const fs::path dir = test_dir("latex");
  const std::vector<fs::path> models = shipped_models();
  ASSERT_GE(models.size(), 8u);
  for (const fs::path& model : models) {
    const std::string name = model.stem().string();
    for (const std::string command : {"derive", "modes"}) {
      const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " " + command + " " + model.string() +
                                    " --format latex -o " + (dir / (name + "." + command + ".tex")).string());
      ASSERT_EQ(c.status, 0) << command << " " << name << ": " << c.err;
      expect_compiles(dir, name + "." + command);
    }
  }
}

// A title and names with every character LaTeX treats specially in text (tests/errors/gear.toml with
// its planet named mg_2 and such a title).
TEST(LatexReports, SpecialCharactersInTitleAndNamesCompile) {
  expect_pdflatex();
  const fs::path dir = test_dir("latex_special");
  std::string model = read_text(source_path("tests/errors/gear.toml"));
  auto replace_all = [&](const std::string& from, const std::string& to) {
    for (auto at = model.find(from); at != std::string::npos; at = model.find(from, at + to.size()))
      model.replace(at, from.size(), to);
  };
  // The generator gear g becomes mg_2, its parameters and mesh keeping their names.
  replace_all("name = \"g\"\naxis = { fixed = \"below\" }",
              "name = \"mg_2\"\naxis = { fixed = \"below\" }\ninertia = \"J_g\"\nfriction = \"b_g\"\n"
              "wheels = [ { name = \"mg_2\", radius = \"r_g\" } ]");
  replace_all("second = \"g\"", "second = \"mg_2\"\nname = \"sg\"");
  replace_all("name = \"gear\"", "name = \"gear\"\ntitle = \"inertias in kg*m^2 & 100 % {sure} #1 $x$ ~_\\\\ <p> `b` \\\"q\\\"\"");
  write_text(dir / "special.toml", model);
  const Command derive = run_command(std::string(POGEAR_EXECUTABLE) + " derive special.toml --format latex -o special.tex", dir);
  ASSERT_EQ(derive.status, 0) << derive.err << "\n" << model;
  EXPECT_NE(read_text(dir / "special.tex").find("inertias in kg*m\\textasciicircum{}2 \\& 100 \\%"), std::string::npos);
  expect_compiles(dir, "special");
}

// The displayed mathematics of one report, in order: \[ ... \] in LaTeX, $$ ... $$ in Markdown.
std::vector<std::string> displays(const std::string& text, const std::string& open, const std::string& close) {
  std::vector<std::string> out;
  for (auto at = text.find(open); at != std::string::npos; at = text.find(open, at)) {
    const auto end = text.find(close, at + open.size());
    if (end == std::string::npos) break;
    out.push_back(text.substr(at + open.size(), end - at - open.size()));
    at = end + close.size();
  }
  return out;
}

TEST(LatexReports, MarkdownHasTheSameMathematics) {
  for (const fs::path& model : shipped_models()) {
    const std::string command = std::string(POGEAR_EXECUTABLE) + " derive " + model.string() + " --format ";
    const Command latex = run_command(command + "latex"), markdown = run_command(command + "markdown");
    ASSERT_EQ(latex.status, 0) << latex.err;
    ASSERT_EQ(markdown.status, 0) << markdown.err;
    const std::vector<std::string> a = displays(latex.out, "\\[\n", "\n\\]"), b = displays(markdown.out, "$$\n", "\n$$");
    EXPECT_GE(a.size(), 4u) << model;
    EXPECT_EQ(a, b) << model;
    // Both carry the parameter table and the diagnostics.
    for (const std::string& report : {latex.out, markdown.out}) {
      EXPECT_NE(report.find("Parameters"), std::string::npos) << model;
      EXPECT_NE(report.find("Diagnostics"), std::string::npos) << model;
      EXPECT_NE(report.find("lowest natural frequency"), std::string::npos) << model;
    }
  }
}

}  // namespace
}  // namespace pogear::test
