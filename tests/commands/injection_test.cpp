// User text in generated C++: a scene file name, a model path and a title that try to end a
// comment or a string and inject code reach the generated sources only escaped, and `pogear
// simulate` compiles and runs them (issue 10, item 1). The escaping functions themselves:
// tests/simulate/injection_test.cpp.
#include <regex>
#include <sstream>

#include "codegen/codegen.hpp"
#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

// Every line of `code` that holds `marker` is a comment line: the marker did not become code.
void expect_only_in_comments(const std::string& code, const std::string& marker) {
  std::istringstream lines(code);
  std::string line;
  while (std::getline(lines, line)) {
    if (line.find(marker) == std::string::npos) continue;
    EXPECT_TRUE(std::regex_search(line, std::regex("^\\s*//"))) << "'" << marker << "' reached code: " << line;
  }
}

// The reproduction: a scene file named `a<newline>#include <cstdlib><newline>static int pw =
// std::system("touch PWNED");...` made `pogear simulate` run `touch`. Here also the model's file
// name and title try to close a comment or continue it with a trailing backslash.
TEST(GeneratedCode, HostileFileNamesAndTitleCannotInjectCode) {
  namespace fs = std::filesystem;
  const fs::path dir = temp_dir("injection");
  // "*/" ends a block comment; in a path it needs a directory.
  fs::create_directories(dir / "sub*");
  const std::string model_name = "sub*/m\"o\\el.toml";
  std::string model = read_text(source_path("models/paper_one_stage.toml"));
  model = with_line(model, "title = \"One-stage planetary gear (Zanasi & Tebaldi, Sec. III, Fig. 3)\"",
                    "title = \"x */ #error injected \\u00e9 ends in a backslash \\\\\"");
  write_text(dir / model_name, model);
  const std::string scene_name = "a\n#include <cstdlib>\nstatic int pw = std::system(\"touch PWNED\");\n\".toml";
  write_text(dir / scene_name,
             "name = \"injection\"\nmodel = 'sub*/m\"o\\el.toml'\n[inputs]\ntau_c = \"100*Nm\"\n"
             "[simulation]\nhorizon = \"0.01*s\"\nsample = \"1*ms\"\n");

  const GeneratedSources g = generate_sources(specialize(parse_scene((dir / scene_name).string())));
  for (const std::string* code : {&g.header, &g.main}) {
    expect_only_in_comments(*code, "PWNED");
    expect_only_in_comments(*code, "#error");
    EXPECT_EQ(code->find("\n#include <cstdlib>"), std::string::npos);
    EXPECT_EQ(code->find("\\\n"), std::string::npos) << "a line ends in a backslash";
  }
  EXPECT_NE(g.header.find(" from the scene a<U+000A>#include <cstdlib><U+000A>static int pw"),
            std::string::npos)
      << g.header.substr(0, 400);

  // The simulator compiles with -Werror and runs; nothing ran `touch`.
  ::setenv("POGEAR_CACHE_DIR", (std::string(POGEAR_BINARY_DIR) + "/simulator-cache").c_str(), 1);
  const Command sim = run_argv(dir, {POGEAR_EXECUTABLE, "simulate", scene_name, "-o", "out", "--solver", "exact"});
  EXPECT_EQ(sim.status, 0) << sim.out << sim.err;
  EXPECT_TRUE(fs::exists(dir / "out" / "injection.csv"));
  EXPECT_FALSE(fs::exists(dir / "PWNED"));
  EXPECT_FALSE(fs::exists(dir / "out" / "PWNED"));
}

}  // namespace
}  // namespace pogear::test
