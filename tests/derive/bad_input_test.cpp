// Bad model files: one test per class of mistake, each checking the message and the position
// it points at (FILE:LINE:COL).
#include "report/model_errors.hpp"
#include "test_support.hpp"

namespace pogear::test {
namespace {

std::string paper_text() { return read_text(source_path("models/paper_one_stage.toml")); }

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

int line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

int column_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  const auto start = text.rfind('\n', pos);
  return static_cast<int>(pos - (start == std::string::npos ? 0 : start + 1)) + 1;
}

// Derives `text` and returns the error; fails the test if there is none.
InputError error_of(const std::string& text, const std::vector<std::string>& keep = {}) {
  try {
    std::optional<std::vector<std::string>> k;
    if (!keep.empty()) k = keep;
    derive_topology(parse_topology_text(text, "bad.toml"), k, SourceLocation{"bad.toml", 0, 0});
  } catch (const InputError& e) {
    return e;
  } catch (const GeometryConflict& e) {  // the derivation's typed errors, as the command line prints them
    return input_error_of(e);
  } catch (const TiedVelocities& e) {
    return input_error_of(e);
  }
  ADD_FAILURE() << "no error";
  return InputError({}, "");
}

TEST(BadInput, TomlSyntaxError) {
  const std::string text = replaced(paper_text(), "r_s1 = \"10*cm\"", "r_s1 = \"10*cm");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "r_s1 = \"10*cm"));
  EXPECT_NE(e.message().find("TOML"), std::string::npos) << e.what();
}

TEST(BadInput, UnknownWheelInMesh) {
  const std::string text = replaced(paper_text(), "second = \"s1\"", "second = \"s9\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "second = \"s9\""));
  EXPECT_EQ(e.where().column, column_of(text, "\"s9\""));
  EXPECT_NE(e.message().find("no wheel or body named 's9'"), std::string::npos) << e.what();
}

TEST(BadInput, BodyWithSeveralWheelsNeedsAWheelName) {
  const std::string text = replaced(paper_text(), "second = \"s1\"", "second = \"s\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "second = \"s\""));
  EXPECT_NE(e.message().find("several wheels (s1, s2)"), std::string::npos) << e.what();
}

TEST(BadInput, DuplicateBodyName) {
  const std::string text = replaced(paper_text(), "name = \"m\"", "name = \"g\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "name = \"g\"                   # motor"));
  EXPECT_NE(e.message().find("duplicate name 'g'"), std::string::npos) << e.what();
}

TEST(BadInput, MissingParameter) {
  const std::string text = replaced(paper_text(), "J_g = \"0.48197*kg*meters^2\"", "");
  const InputError e = error_of(text);
  EXPECT_NE(e.message().find("missing parameter 'J_g'"), std::string::npos) << e.what();
  EXPECT_EQ(e.where().line, line_of(text, "name = \"g\""));
}

TEST(BadInput, UnknownParameterInExpression) {
  const std::string text = replaced(paper_text(), "b_p = \"b_c\"", "b_p = \"b_cc\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "b_p = \"b_cc\""));
  EXPECT_EQ(e.where().column, column_of(text, "b_cc\""));
  EXPECT_NE(e.message().find("unknown unit or parameter 'b_cc'"), std::string::npos) << e.what();
}

TEST(BadInput, UnitTypo) {
  const std::string text = replaced(paper_text(), "r_p = \"4.8*cm\"", "r_p = \"4.8*cn\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "4.8*cn"));
  EXPECT_EQ(e.where().column, column_of(text, "cn\""));
  EXPECT_NE(e.message().find("unknown unit or parameter 'cn'"), std::string::npos) << e.what();
}

TEST(BadInput, WrongUnitForTheRole) {
  const std::string text = replaced(paper_text(), "J_p = \"0.009756*kg*meters^2\"", "J_p = \"0.009756*kg*meters\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "J_p = "));
  EXPECT_NE(e.message().find("has unit kg*m; it needs kg*m^2"), std::string::npos) << e.what();
}

TEST(BadInput, ZeroRadius) {
  const std::string text = replaced(paper_text(), "r_g = \"16*cm\"", "r_g = \"0*cm\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "r_g = "));
  EXPECT_NE(e.message().find("'r_g' is a radius and must be positive"), std::string::npos) << e.what();
}

TEST(BadInput, NegativeInertia) {
  const std::string text = replaced(paper_text(), "J_m = \"0.15263*kg*meters^2\"", "J_m = \"-0.15263*kg*meters^2\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "J_m = "));
  EXPECT_NE(e.message().find("'J_m' is an inertia and must be positive"), std::string::npos) << e.what();
}

TEST(BadInput, InconsistentGeometryOfThePrintedTwoStageListing) {
  // The paper prints r_r = 5.4*cm in Sec. IV-A (docs/paper-errata.md E10): the ring cannot mesh planet p then.
  const std::string text =
      replaced(read_text(source_path("models/paper_two_stage.toml")), "r_r = \"13.0*cm\"", "r_r = \"5.4*cm\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "r_r = \"5.4*cm\""));
  EXPECT_EQ(e.where().column, column_of(text, "\"5.4*cm\""));
  EXPECT_NE(e.message().find("'r_r' = 5.4*cm (0.054 m) contradicts the geometry"), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("mesh pr"), std::string::npos) << e.what();
  EXPECT_NE(e.message().find("r_r = 2*r_p+r_s1 = 0.13 m"), std::string::npos) << e.what();
}

TEST(BadInput, WrongNumberOfKeptVelocities) {
  const InputError e = error_of(paper_text(), {"c", "r", "s"});
  EXPECT_NE(e.message().find("3 velocities kept, but this gear has 2 degrees of freedom"), std::string::npos)
      << e.what();
}

TEST(BadInput, DependentKeptSet) {
  const InputError e = error_of(paper_text(), {"s", "g"});
  EXPECT_NE(e.message().find("do not parametrize the rigid motions: s and g are tied: omega_g == "),
            std::string::npos)
      << e.what();
  EXPECT_NE(e.message().find("valid choices are c,p; c,s;"), std::string::npos) << e.what();
}

TEST(BadInput, DependentKeptSetFromTheModelFileIsLocated) {
  const std::string text = replaced(paper_text(), "keep = [\"c\", \"r\"]", "keep = [\"s\", \"g\"]");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().file, "bad.toml");
  EXPECT_EQ(e.where().line, line_of(text, "keep = "));
}

TEST(BadInput, UnknownKeyIsNamed) {
  const std::string text = replaced(paper_text(), "axis = { fixed = \"below\" }", "axsi = { fixed = \"below\" }");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().line, line_of(text, "axsi"));
  EXPECT_NE(e.message().find("unknown key 'axsi' in a [[body]]"), std::string::npos) << e.what();
}

TEST(BadInput, ParameterDefinedThroughItself) {
  const std::string text = replaced(paper_text(), "b_c = \"0.08*Nm/rpm\"", "b_c = \"b_p\"");
  const InputError e = error_of(text);
  EXPECT_NE(e.message().find("is defined through itself"), std::string::npos) << e.what();
}

TEST(BadInput, AddingDifferentUnits) {
  const std::string text = replaced(paper_text(), "r_s1 = \"10*cm\"", "r_s1 = \"10*cm + 1*kg\"");
  const InputError e = error_of(text);
  EXPECT_EQ(e.where().column, column_of(text, "+ 1*kg"));
  EXPECT_NE(e.message().find("adds kg to m"), std::string::npos) << e.what();
}

TEST(BadInput, DeeplyNestedExpressionIsRefused) {
  const std::string deep = std::string(200, '(') + "1" + std::string(200, ')');
  const std::string text = replaced(paper_text(), "r_s1 = \"10*cm\"", "r_s1 = \"" + deep + "\"");
  const InputError e = error_of(text);
  EXPECT_NE(e.message().find("nested deeper than"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace pogear::test
