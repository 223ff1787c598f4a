// `pogear simulate --param NAME=VALUE` and `--tolerance R`: options of the one compiled simulator
// (not rebuilt for them), which then runs as the scene with those values written in does.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"
#include "../support/gaps.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

// The paper's one-stage scene over 0.2 s as `name`, with `extra` after its compare_rigid line.
fs::path one_stage_scene(const fs::path& dir, const std::string& name, const std::string& extra) {
  std::string text = read_text(source_path("models/scenes/paper_one_stage.toml"));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"name = \"paper_one_stage\"", "name = \"" + name + "\""},
                                 {"\"../paper_one_stage.toml\"", "\"" + source_path("models/paper_one_stage.toml") + "\""},
                                 {"compare_rigid = true", "compare_rigid = true\n" + extra},
                                 {"horizon = \"2*s\"", "horizon = \"0.2*s\""}})
    text.replace(text.find(from), from.size(), to);
  write_text(dir / (name + ".toml"), text);
  return dir / (name + ".toml");
}

Command simulate(const fs::path& scene, const std::string& options) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + scene.string() + " " + options);
  EXPECT_EQ(c.status, 0) << c.err;
  return c;
}

std::string simulator_path(const std::string& out) {
  const auto at = out.find("\nsimulator ");
  if (at == std::string::npos) return "";
  const auto from = at + 11;
  return out.substr(from, out.find('\n', from) - from);
}

// The largest gap between two runs' columns, each relative to the column's largest magnitude.
double relative_gap(const Csv& a, const Csv& b) {
  EXPECT_EQ(a.rows.size(), b.rows.size());
  EXPECT_EQ(a.header.size(), b.header.size());
  double worst = 0;
  for (std::size_t col = 1; col < std::min(a.header.size(), b.header.size()); ++col)
    worst = std::max(worst, column_error(a.rows, b.rows, col));
  return worst;
}

TEST(SimulateCommand, ParamAndToleranceAsTheSimulatorTakesThem) {
  const fs::path dir = temp_dir("param_option");
  const fs::path tunable = one_stage_scene(dir, "tunable", "tunable = [\"K_ps\", \"J_c\"]");
  const fs::path literal = one_stage_scene(dir, "literal", "[parameters]\nK_ps = \"2000*N/mm\"\nJ_c = 0.3");
  const std::string values = "--param K_ps=2000*N/mm --param J_c=0.3";
  const Command first = simulate(tunable, values + " -o " + (dir / "a").string());
  const Command other = simulate(tunable, "--param J_c=0.2 -o " + (dir / "b").string());
  // One simulator, in the cache, for both values.
  const std::string path = simulator_path(first.out);
  ASSERT_FALSE(path.empty()) << first.out;
  EXPECT_TRUE(fs::exists(path)) << path;
  EXPECT_EQ(simulator_path(other.out), path);
  simulate(literal, "--interpreted -o " + (dir / "c").string());
  simulate(tunable, "--interpreted " + values + " -o " + (dir / "d").string());
  const Csv reference = read_csv((dir / "c/literal.csv").string());
  // Compiled with Params against the values folded in as literals: exp(M h) of the same M, built from
  // Params by the generated code and from L^-1 A in doubles; the entries differ by rounding, which
  // 4000 contracting steps keep below 1e-10 of each column's scale.
  EXPECT_LT(relative_gap(read_csv((dir / "a/tunable.csv").string()), reference), 1e-10);
  // Interpreted at the options' values: the same exact numbers but for 0.3 read as a double (1e-17).
  EXPECT_LT(relative_gap(read_csv((dir / "d/tunable.csv").string()), reference), 1e-12);
  // The other value took effect: a lighter carrier moves the run by far more than rounding.
  EXPECT_GT(relative_gap(read_csv((dir / "b/tunable.csv").string()), reference), 1e-3);

  // --tolerance is the scene's tolerance for the run: dopri5 at 1e-5 given either way is one run.
  simulate(literal, "--interpreted --solver dopri5 --tolerance 1e-5 -o " + (dir / "e").string());
  const fs::path loose = one_stage_scene(dir, "loose", "[parameters]\nK_ps = \"2000*N/mm\"\nJ_c = 0.3");
  write_text(loose, [&] {
    std::string text = read_text(loose);
    text.replace(text.find("solver = \"exact\""), 16, "solver = \"dopri5\"");
    text.replace(text.find("tolerance = 1e-9"), 16, "tolerance = 1e-5");
    return text;
  }());
  simulate(loose, "--interpreted -o " + (dir / "f").string());
  const Csv at_option = read_csv((dir / "e/literal.csv").string());
  EXPECT_EQ(relative_gap(at_option, read_csv((dir / "f/loose.csv").string())), 0);
  // ... and not the scene's 1e-9: dopri5's error at 1e-5 is far above the exact run's rounding.
  EXPECT_GT(relative_gap(at_option, reference), 1e-8);
}

// A value may name another --param's parameter, in either order, as in [parameters]; the summary's
// figures (the frequencies, the step limits) are those of the values run.
TEST(SimulateCommand, ParamValuesNameEachOtherAndTheSummaryFollows) {
  const fs::path dir = temp_dir("param_each_other");
  const fs::path tunable = one_stage_scene(dir, "tunable", "tunable = [\"J_c\", \"J_p\", \"K_ps\"]");
  const fs::path literal = one_stage_scene(dir, "literal",
                                           "[parameters]\nJ_c = \"2*J_p\"\nJ_p = \"0.02*kg*m^2\"\nK_ps = \"3000*N/mm\"");
  const Command reference = simulate(literal, "--interpreted -o " + (dir / "ref").string());
  const Csv expected = read_csv((dir / "ref/literal.csv").string());
  auto frequency_line = [](const std::string& out) {
    const auto at = out.find("lowest natural frequency");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  ASSERT_FALSE(frequency_line(reference.out).empty()) << reference.out;
  for (const std::string order : {"--param J_c=2*J_p --param J_p=0.02*kg*m^2", "--param J_p=0.02*kg*m^2 --param J_c=2*J_p"}) {
    SCOPED_TRACE(order);
    const Command c = simulate(tunable, "--interpreted " + order + " --param K_ps=1*N/mm --param K_ps=3000*N/mm -o " +
                                            (dir / "run").string());
    // The same exact numbers but for the two doubles the options pass on (0.02 and 0.04 kg m^2).
    EXPECT_LT(relative_gap(read_csv((dir / "run/tunable.csv").string()), expected), 1e-12);
    EXPECT_EQ(frequency_line(c.out), frequency_line(reference.out));
  }
}

}  // namespace
}  // namespace pogear::test
