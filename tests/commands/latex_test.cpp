// The LaTeX reports of `pogear derive`, `modes` and `ratios` compile with pdflatex and fit their
// page (every shipped model, a gear with matrices too wide for it, names and a title full of
// LaTeX's special characters), and the Markdown report carries the same mathematics. The layout
// code's own tests: tests/derive/latex_test.cpp.
#include <algorithm>
#include <filesystem>
#include <map>
#include <regex>
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

// Wider than this, an overfull line is a fault of the layout: a few points do not show on paper,
// and TeX reports overfull boxes of a fraction of a point from the rounding of glue.
constexpr double overfull_tolerance_pt = 5;

// The widths, in pt, of the overfull lines a pdflatex log reports.
std::vector<double> overfull_widths(const std::string& log) {
  static const std::regex overfull(R"(Overfull \\hbox \(([0-9.]+)pt too wide\))");
  std::vector<double> widths;
  for (std::sregex_iterator it(log.begin(), log.end(), overfull), end; it != end; ++it) widths.push_back(std::stod((*it)[1]));
  return widths;
}

// pdflatex on DIR/NAME.tex, in batch mode, once: the status and the end of its output when it
// failed, and no line wider than the page by more than the tolerance.
void expect_compiles(const fs::path& dir, const std::string& name) {
  const Command c = run_command("pdflatex -interaction=nonstopmode -halt-on-error " + name + ".tex < /dev/null", dir);
  std::string out = c.out;
  if (out.size() > 3000) out = out.substr(out.size() - 3000);
  EXPECT_EQ(c.status, 0) << name << ".tex:\n" << out;
  EXPECT_TRUE(fs::exists(dir / (name + ".pdf"))) << name;
  const std::vector<double> overfull = overfull_widths(read_text(dir / (name + ".log")));
  const double worst = overfull.empty() ? 0 : *std::max_element(overfull.begin(), overfull.end());
  EXPECT_LE(worst, overfull_tolerance_pt) << name << ".tex has a line " << worst << " pt wider than the page ("
                                          << overfull.size() << " overfull in " << (dir / (name + ".log")).string() << ")";
}

void expect_pdflatex() {
  // scripts/install-deps.sh installs it (texlive-latex-base, texlive-latex-recommended).
  ASSERT_EQ(run_command("command -v pdflatex").status, 0) << "pdflatex is missing: run scripts/install-deps.sh";
}

// `pogear COMMAND MODEL ARGS --format latex` written to DIR/NAME.tex, then compiled.
void expect_report_fits(const fs::path& dir, const std::string& command, const fs::path& model, const std::string& args,
                        const std::string& name) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " " + command + " " + model.string() + args +
                                " --format latex -o " + (dir / (name + ".tex")).string());
  ASSERT_EQ(c.status, 0) << command << " " << model << ": " << c.err;
  expect_compiles(dir, name);
}

// The input and output body of each shipped model with brakes or clutches, for `pogear ratios`.
const std::map<std::string, std::string> ratio_bodies{
    {"gearshift_planetary", " --input s --output c"},
    {"power_split", " --input c --output r"},
    {"simpson_3speed", " --input i --output o"},
    {"zf6hp26", " --input in --output out"},
};

bool has_friction_elements(const fs::path& model) {
  const std::string text = read_text(model);
  return text.find("[[brake]]") != std::string::npos || text.find("[[clutch]]") != std::string::npos;
}

// Issue 31: the derive report of a large gear ran 1283 pt off the page (L1, A1, the forces), the
// closed forms of modes ran off it, and the ratio table was a tabular that could run off it too.
TEST(LatexReports, EveryShippedModelsReportsCompileAndFitThePage) {
  expect_pdflatex();
  const fs::path dir = test_dir("latex");
  const std::vector<fs::path> models = shipped_models();
  ASSERT_GE(models.size(), 8u);
  for (const fs::path& model : models) {
    const std::string name = model.stem().string();
    for (const std::string command : {"derive", "modes"}) expect_report_fits(dir, command, model, "", name + "." + command);
    if (!has_friction_elements(model)) continue;
    ASSERT_TRUE(ratio_bodies.count(name)) << name << " has brakes or clutches: give its input and output in ratio_bodies";
    expect_report_fits(dir, "ratios", model, ratio_bodies.at(name), name + ".ratios");
  }
}

// A gear of 10 bodies (scripts/make_chain.sh 3, four degrees of freedom): its L1 and A1 are too
// wide for the page and are written entry by entry, the symmetric ones on and above the diagonal.
TEST(LatexReports, MatricesTooWideForThePageAreWrittenEntryByEntry) {
  expect_pdflatex();
  const fs::path dir = test_dir("latex_chain");
  const Command chain = run_command("bash " + source_path("scripts/make_chain.sh") + " 3 > chain.toml", dir);
  ASSERT_EQ(chain.status, 0) << chain.err;
  expect_report_fits(dir, "derive", dir / "chain.toml", "", "chain");
  const std::string tex = read_text(dir / "chain.tex");
  EXPECT_NE(tex.find("$\\mathbf{L}_1$ entry by entry"), std::string::npos);
  EXPECT_NE(tex.find("(\\mathbf{A}_1)_{1,2} = "), std::string::npos);
  EXPECT_EQ(tex.find("(\\mathbf{A}_1)_{2,1} = "), std::string::npos);
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

// The displayed mathematics of one report, in order: in LaTeX \[ ... \] and, for a formula wider
// than the line, the longformula environment; $$ ... $$ in Markdown.
std::vector<std::string> displays(const std::string& text, const std::vector<std::pair<std::string, std::string>>& delimiters) {
  std::vector<std::string> out;
  for (std::size_t at = 0;;) {
    std::size_t first = std::string::npos;
    const std::pair<std::string, std::string>* pair = nullptr;
    for (const auto& d : delimiters)
      if (const auto found = text.find(d.first, at); found < first) first = found, pair = &d;
    if (!pair) break;
    const auto end = text.find(pair->second, first + pair->first.size());
    if (end == std::string::npos) break;
    out.push_back(text.substr(first + pair->first.size(), end - first - pair->first.size()));
    at = end + pair->second.size();
  }
  return out;
}

TEST(LatexReports, MarkdownHasTheSameMathematics) {
  for (const fs::path& model : shipped_models()) {
    const std::string command = std::string(POGEAR_EXECUTABLE) + " derive " + model.string() + " --format ";
    const Command latex = run_command(command + "latex"), markdown = run_command(command + "markdown");
    ASSERT_EQ(latex.status, 0) << latex.err;
    ASSERT_EQ(markdown.status, 0) << markdown.err;
    const std::vector<std::string> a =
        displays(latex.out, {{"\\[\n", "\n\\]"}, {"\\begin{longformula}\n", "\n\\end{longformula}"}});
    const std::vector<std::string> b = displays(markdown.out, {{"$$\n", "\n$$"}});
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
