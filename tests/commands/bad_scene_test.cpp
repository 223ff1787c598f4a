// A bad scene file run by `pogear simulate`: exit status 2, the message with the file's name, no
// output. The messages themselves: tests/simulate/bad_scene_test.cpp.
#include <filesystem>
#include <fstream>

#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

TEST(BadScene, CommandLineExitStatusIsTwo) {
  const auto dir = temp_dir("bad_scene_cli");
  { std::ofstream(dir / "bad.toml") << with_line(base, "model = \"../paper_one_stage.toml\"",
                                                 "model = \"" + source_path("models/paper_one_stage.toml") + "\"\nfrobnicate = 1"); }
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "bad.toml").string() + " -o " +
                                (dir / "out").string());
  EXPECT_EQ(c.status, 2);
  EXPECT_NE(c.err.find("bad.toml:"), std::string::npos) << c.err;
  EXPECT_NE(c.err.find("unknown key 'frobnicate'"), std::string::npos) << c.err;
  EXPECT_FALSE(std::filesystem::exists(dir / "out" / "paper_one_stage.csv"));
}

}  // namespace
}  // namespace pogear::test
