// The pogear command as users run it: exit statuses, messages, determinism across processes,
// and that a failed run leaves an existing output file untouched.
#include <filesystem>
#include <set>
#include <utility>

#include "../support/commands.hpp"
#include "../derive/test_support.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

Command run(const std::string& args) { return run_command(std::string(POGEAR_EXECUTABLE) + " " + args); }

std::string model(const std::string& name) { return source_path("models/" + name + ".toml"); }

TEST(Cli, DeriveSucceedsInEveryFormat) {
  for (const char* format : {"text", "latex", "markdown", "json"}) {
    const Command r = run("derive " + model("paper_one_stage") + " --keep c,r --format " + format);
    EXPECT_EQ(r.status, 0) << format << ": " << r.err;
    EXPECT_TRUE(r.err.empty()) << r.err;
    const bool math = std::string(format) == "latex" || std::string(format) == "markdown";
    EXPECT_EQ(r.out.find(math ? "r_{s1}" : "r_s1") != std::string::npos, true) << format;
  }
}

TEST(Cli, OutputIsTheSameBytesInSeparateProcesses) {
  // GiNaC's own printing order changes between processes; pogear's must not.
  for (const char* m : {"paper_one_stage", "paper_two_stage"})
    for (const char* format : {"json", "latex"}) {
      const Command a = run("derive " + model(m) + " --format " + format);
      const Command b = run("derive " + model(m) + " --format " + format);
      ASSERT_EQ(a.status, 0);
      EXPECT_EQ(a.out, b.out) << m << " " << format;
    }
}

// Cases whose arrangement after normal() depends on GiNaC's hash order, which the addresses of
// its type names seed: a dynamically linked pogear printed 7 texts in 12 runs of the first one.
// Eight processes, so that a run-to-run difference of that kind shows with certainty in practice.
TEST(Cli, HashOrderSensitiveOutputsAreTheSameBytesInSeparateProcesses) {
  const std::string derive = "derive " + model("paper_two_stage") + " --keep b,s --format text";
  const Command first = run(derive);
  ASSERT_EQ(first.status, 0) << first.err;
  for (int i = 0; i < 7; ++i) EXPECT_EQ(run(derive).out, first.out) << "run " << i + 2;

  const fs::path dir = fs::temp_directory_path() / ("pogear_cli_gen_" + std::to_string(::getpid()));
  std::string generated;
  for (int i = 0; i < 3; ++i) {
    fs::remove_all(dir);
    const Command g = run("generate " + source_path("models/scenes/three_planets.toml") + " -o " + dir.string());
    ASSERT_EQ(g.status, 0) << g.err;
    const std::string text = read_text((dir / "three_planets.hpp").string());
    if (i == 0) generated = text;
    else EXPECT_EQ(text, generated) << "generate three_planets, run " << i + 1;
  }
  fs::remove_all(dir);
}

// `generate --list-outputs` names the files `generate` writes (the CMake function builds on it):
// after the scene's `name`, not its file name; it writes nothing itself.
TEST(Cli, ListOutputsNamesTheFilesGenerateWrites) {
  const fs::path dir = fs::temp_directory_path() / ("pogear_cli_list_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  fs::create_directories(dir);
  std::string scene = read_text(source_path("models/scenes/paper_one_stage.toml"));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"name = \"paper_one_stage\"", "name = \"renamed\""},
                                 {"\"../paper_one_stage.toml\"", "\"" + model("paper_one_stage") + "\""}})
    scene.replace(scene.find(from), from.size(), to);
  write_text((dir / "scene.toml").string(), scene);
  const std::string out = (dir / "out").string();
  const Command listed = run("generate " + (dir / "scene.toml").string() + " -o " + out + " --list-outputs");
  ASSERT_EQ(listed.status, 0) << listed.err;
  EXPECT_EQ(listed.out, out + "/renamed.hpp\n" + out + "/renamed_main.cpp\n");
  EXPECT_FALSE(fs::exists(out));
  const Command generated = run("generate " + (dir / "scene.toml").string() + " -o " + out);
  ASSERT_EQ(generated.status, 0) << generated.err;
  std::set<std::string> written;
  for (const auto& e : fs::directory_iterator(out)) written.insert(e.path().string());
  EXPECT_EQ(written, (std::set<std::string>{out + "/renamed.hpp", out + "/renamed_main.cpp"}));
  const Command bad = run("generate " + (dir / "missing.toml").string() + " --list-outputs");
  EXPECT_EQ(bad.status, 2);
  EXPECT_TRUE(bad.out.empty()) << bad.out;
  fs::remove_all(dir);
}

TEST(Cli, JsonHasTheSchemaKeysInOrder) {
  const Command r = run("derive " + model("paper_one_stage") + " --keep c,r --format json");
  ASSERT_EQ(r.status, 0);
  std::size_t at = 0;
  for (const char* key : {"\"model\"", "\"velocities\"", "\"forces\"", "\"keep\"", "\"geometry\"", "\"R\"", "\"Q1\"",
                          "\"L1\"", "\"A1\"", "\"B1\"", "\"closed_form\"", "\"force_recovery\"", "\"numeric\"",
                          "\"J\"", "\"b\"", "\"K\"", "\"b_K\""}) {
    const auto pos = r.out.find(key, at);
    ASSERT_NE(pos, std::string::npos) << key;
    at = pos;
  }
  EXPECT_NE(r.out.find("\"geometry\": [\"r_c==r_p+r_s1\", \"r_r1==2*r_p+r_s1\"]"), std::string::npos);
  EXPECT_NE(r.out.find("\"J1\": \"J_c+J_p*r_c^2/r_p^2+4*J_s*r_c^2/r_s1^2+4*J_g*r_c^2*r_s2^2/(r_g^2*r_s1^2)\""),
            std::string::npos);
  // b_c = 0.08 Nm/rpm = 0.08 * 60 / (2 pi) = 0.76394372684109765 N m s/rad (docs/paper-errata.md, units); the
  // division order may move the last printed digit by one ulp, so compare 15 digits.
  EXPECT_NE(r.out.find("\"b\": [0.763943726841097"), std::string::npos);
}

TEST(Cli, BadInputExitsTwoWithLocation) {
  const fs::path bad = fs::temp_directory_path() / "pogear_cli_bad.toml";
  std::string text = read_text(model("paper_two_stage"));
  text.replace(text.find("r_r = \"13.0*cm\""), 15, "r_r = \"5.4*cm\"");
  { std::ofstream(bad) << text; }
  const Command r = run("derive " + bad.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(r.err.rfind(bad.string() + ":", 0), 0u) << r.err;
  EXPECT_NE(r.err.find(": error: 'r_r' = 5.4*cm"), std::string::npos) << r.err;
  EXPECT_TRUE(r.out.empty());
}

TEST(Cli, MissingFileExitsTwo) {
  const Command r = run("derive /nonexistent/model.toml");
  EXPECT_EQ(r.status, 2);
  EXPECT_NE(r.err.find("/nonexistent/model.toml: error: cannot read the file"), std::string::npos) << r.err;
}

TEST(Cli, BadUsageExitsOne) {
  EXPECT_EQ(run("derive " + model("paper_one_stage") + " --format pdf").status, 1);
  EXPECT_EQ(run("frobnicate").status, 1);
  EXPECT_EQ(run("").status, 1);
}

TEST(Cli, FailedRunLeavesTheExistingOutputFileUntouched) {
  const fs::path dir = fs::temp_directory_path() / ("pogear_cli_keep_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  const fs::path report = dir / "report.json";
  ASSERT_EQ(run("derive " + model("paper_one_stage") + " --format json -o " + report.string()).status, 0);
  const std::string good = read_text(report.string());
  ASSERT_FALSE(good.empty());
  const Command r = run("derive " + model("paper_one_stage") + " --keep s,g --format json -o " + report.string());
  EXPECT_EQ(r.status, 2);
  EXPECT_EQ(read_text(report.string()), good);
  std::size_t files = 0;
  for (const auto& e : fs::directory_iterator(dir)) files += e.is_regular_file();
  EXPECT_EQ(files, 1u) << "no temporary file left behind";
  fs::remove_all(dir);
}

}  // namespace
}  // namespace pogear::test
