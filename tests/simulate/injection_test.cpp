// User text in generated C++: a scene file name, a model path and a title that try to end a
// comment or a string and inject code reach the generated sources only escaped (issue 10, item 1).
#include <fstream>
#include <regex>

#include "codegen/codegen.hpp"
#include "common/cpp_text.hpp"
#include "sim_support.hpp"

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

TEST(GeneratedCode, CommentTextIsOneLineOfPrintableAsciiWithoutCommentEnds) {
  const std::string hostile = "a\nb\r\x01 */ end\\\n\xc3\xa9\xff\x7f";
  const std::string c = comment_text(hostile).str();
  EXPECT_EQ(c, "a<U+000A>b<U+000D><U+0001> <U+002A>/ end<U+005C><U+000A><U+00E9><0xFF><U+007F>");
  for (char ch : c) EXPECT_TRUE(ch >= 0x20 && ch < 0x7f) << int(ch);
  EXPECT_EQ(c.find("*/"), std::string::npos);
  EXPECT_EQ(c.find('\\'), std::string::npos);  // a backslash at a line's end continues a // comment
}

TEST(GeneratedCode, StringLiteralsEscapeQuotesBackslashesAndControlCharacters) {
  EXPECT_EQ(string_literal("rad/s").str(), "\"rad/s\"");
  // Octal escapes are always three digits: "\0" followed by "12" would otherwise read as "\012".
  EXPECT_EQ(string_literal("a\"b\\c\n12\xc3\xa9").str(), "\"a\\042b\\134c\\01212\\303\\251\"");
}

TEST(GeneratedCode, IdentifiersAreCheckedNotEscaped) {
  EXPECT_EQ(identifier("omega_c").str(), "omega_c");
  for (const char* bad : {"", "1a", "a b", "a\n#include", "int", "a;b", "EIGEN_X", "\xc3\xa9"})
    EXPECT_THROW(identifier(bad), std::invalid_argument) << bad;
  EXPECT_THROW(number_code(std::numeric_limits<double>::infinity()), std::invalid_argument);
  EXPECT_THROW(number_code(std::nan("")), std::invalid_argument);
}

// The last line of defence: what the readers let through is checked again, and nothing is written.
TEST(GeneratedCode, NonFiniteNumberIsRefused) {
  SpecializedScene m = scene_model(scene_text("paper_one_stage"));
  m.main.states[0].initial = std::numeric_limits<double>::infinity();
  try {
    generate_sources(m);
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_EQ(e.message(), "cannot generate the simulator: a number of the generated code is not finite; report this "
                           "scene as a pogear bug");
  }
  // A name in the state list is only ever a string literal; a parameter is a C++ variable.
  SpecializedScene renamed = scene_model(scene_text("paper_one_stage"));
  renamed.main.params.push_back(TunableParameter{"J_c;\n#include <cstdlib>", 1.0, {}, ""});
  EXPECT_THROW(generate_sources(renamed), InputError);
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
