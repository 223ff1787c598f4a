// Explicit methods on stiff scenes through `pogear simulate --interpreted`: rk4 above its stability
// limit is refused with the limit, and a dopri5 run that cannot finish leaves its CSV marked
// incomplete (exit status 3). The methods themselves: tests/stability/solvers_test.cpp.
#include <filesystem>
#include <fstream>
#include <string>

#include "../stability/stability_support.hpp"

namespace pogear::test {
namespace {

TEST(ExplicitOnStiff, Rk4AboveItsStabilityLimitIsRefusedWithTheLimit) {
  const auto dir = temp_dir("rk4_refused");
  { std::ofstream(dir / "scene.toml") << with_line(stiff_scene("solver = \"rk4\""), "model = \"../paper_one_stage.toml\"",
                                                   "model = \"" + source_path("models/paper_one_stage.toml") + "\""); }
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() +
                                " --interpreted -o " + (dir / "out").string());
  EXPECT_EQ(c.status, 3);
  EXPECT_NE(c.err.find("rk4 step 5e-05 s is above its stability limit"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("or --solver exact or implicit"), std::string::npos) << c.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "paper_one_stage.csv"));
}

TEST(ExplicitOnStiff, TheSimulatorMarksTheCsvIncomplete) {
  const auto dir = temp_dir("incomplete");
  { std::ofstream(dir / "scene.toml") << with_line(stiff_scene("solver = \"dopri5\"\nmax_steps = 20000"),
                                                   "model = \"../paper_one_stage.toml\"",
                                                   "model = \"" + source_path("models/paper_one_stage.toml") + "\""); }
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() +
                                " --interpreted -o " + (dir / "out").string());
  EXPECT_EQ(c.status, 3);
  const Csv csv = read_csv((dir / "out" / "paper_one_stage.csv").string());
  EXPECT_TRUE(csv.incomplete);
  EXPECT_FALSE(csv.rows.empty());
}

}  // namespace
}  // namespace pogear::test
