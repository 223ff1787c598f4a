// Exact stepping outside its accurate range, through `pogear simulate`: compiled and interpreted,
// the run fails with the message of docs/errors.md and a CSV marked incomplete. The library's
// refusal and the steps inside the range: tests/stability/exact_range_test.cpp.
#include <fstream>
#include <string>

#include "../stability/stability_support.hpp"

namespace pogear::test {
namespace {

// The user-visible result, compiled and interpreted, of the J_p = 1e-30 scene: exit status 3, the
// message on stderr (as docs/errors.md shows it), no velocity after t = 0, the CSV marked incomplete.
TEST(ExactRange, BothPathsFailTheRunWithTheMessage) {
  const auto dir = temp_dir("exact_range");
  std::string text = range_scene(kUndamped, "J_p = \"1e-30*kg*meters^2\"", "0.1*s", "1*ms");
  text = with_line(text, "model = \"../paper_one_stage.toml\"",
                   "model = \"" + source_path("models/paper_one_stage.toml") + "\"");
  { std::ofstream(dir / "scene.toml") << text; }
  const std::string expected =
      "paper_one_stage: error: exact stepping lost accuracy: with steps of 0.001 s the scene's fastest modes turn too "
      "far per step for double precision (estimated error per step 0.0087, limit 1e-10); shorten the sample, or check "
      "stiffnesses and inertias (without mesh_compliance the rigid model is the limit of stiff meshes); the CSV keeps "
      "what was computed and is marked incomplete\n";
  const std::string docs = read_text(source_path("docs/errors.md"));
  EXPECT_NE(docs.find(expected.substr(0, expected.size() - 1)), std::string::npos) << "docs/errors.md does not show it";
  EXPECT_NE(docs.find("`ExactRange.BothPathsFailTheRunWithTheMessage`"), std::string::npos);
  for (const std::string mode : {"", " --interpreted"}) {
    const auto out = dir / (mode.empty() ? "compiled" : "interpreted");
    const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() + mode +
                                  " -o " + out.string());
    EXPECT_EQ(c.status, 3) << mode << c.err;
    // The error is the last line; the diagnostics come before it. The estimate's two digits are
    // those of this build: a compiler that fuses products could round the second one otherwise.
    EXPECT_NE(c.err.find(expected), std::string::npos) << mode << c.err;
    const Csv csv = read_csv((out / "paper_one_stage.csv").string());
    EXPECT_TRUE(csv.incomplete) << mode;
    for (const auto& row : csv.rows) EXPECT_EQ(row[0], 0.0) << mode << ": a row after t = 0 was printed";
  }
}

}  // namespace
}  // namespace pogear::test
