// User text in generated C++: comments, string literals and identifiers are escaped or checked, and
// a number that is not finite is refused (issue 10, item 1). Hostile file names and a title run
// through `pogear simulate`: tests/commands/injection_test.cpp.
#include "codegen/codegen.hpp"
#include "common/cpp_text.hpp"
#include "sim_support.hpp"

namespace pogear::test {
namespace {

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

}  // namespace
}  // namespace pogear::test
