// The errors of tunable parameters: a tunable radius that a given radius is tied to, and the
// generated simulators' `--param NAME=VALUE`.
#include <pogear/parameters.hpp>

#include "error_support.hpp"

namespace pogear::test {
namespace {

class TunableErrors : public ErrorTest {
 protected:
  // The fields codegen writes into the generated main (names, units, signs), over `values`.
  static std::vector<rt::ParameterField> parameter_fields(const SpecializedScene& model, std::vector<double>& values) {
    std::vector<rt::ParameterField> fields;
    for (std::size_t i = 0; i < values.size(); ++i) {
      const TunableParameter& p = model.main.params[i];
      rt::ParameterField f{p.name, &values[i], {}, p.sign};
      for (const UnitSpelling& u : p.units) f.units.push_back({u.unit, u.si});
      fields.push_back(f);
    }
    return fields;
  }
  // What the generated main of scene.toml with `tunable = [list]` says to `--param given`: the same
  // fields (names, units, signs) codegen writes into it, from the same specialized system.
  static std::string param_error(const std::string& list, const std::string& given) {
    write_text("scene.toml", edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [" + list + "]"}}));
    const SpecializedScene model = specialize(parse_scene("scene.toml"));
    std::vector<double> values(model.main.params.size());
    const std::vector<rt::ParameterField> fields = parameter_fields(model, values);
    const auto eq = given.find('=');
    ::testing::internal::CaptureStderr();
    const bool ok = rt::set_parameters({{given.substr(0, eq), given.substr(eq + 1)}}, fields, "./demo");
    const std::string err = ::testing::internal::GetCapturedStderr();
    EXPECT_FALSE(ok);
    return err;
  }
};

TEST_F(TunableErrors, GivenRadiusInAGeometryRelation) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\ntunable = [\"r_p\"]"}},
      R"~(scene.toml:7:11: error: tunable 'r_p' enters the geometry relation r_c = r_p+r_s1 of mesh ps (p with s1 of body s), but 'r_c' is given in the model and would keep its value; leave 'r_c' out of the model so that it is derived, or define it through the tunable, or do not tune a radius of this relation)~");
}

TEST_F(TunableErrors, DependentNotSymbolic) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\ntunable = [\"b_c\"]"},
                      {"[simulation]", "[parameters]\nb_p = \"2^-1*b_c\"\n\n[simulation]"}},
      R"~(scene.toml:16:8: error: parameter 'b_p' is defined through a tunable parameter, and pogear cannot keep this expression symbolic; put a signed exponent in parentheses, e.g. 2^(-1), or make 'b_p' tunable itself)~");
  // With the parentheses it follows b_c.
  write_text("scene.toml", edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"b_c\"]"},
                                                 {"[simulation]", "[parameters]\nb_p = \"2^(-1)*b_c\"\n\n[simulation]"}}));
  EXPECT_NE(generate_sources(specialize(parse_scene("scene.toml"))).header.find("*b_c*omega_p;"), std::string::npos);
}

TEST_F(TunableErrors, ParamWithoutTunables) {
  fs::create_symlink(POGEAR_SIM_ONE_STAGE, "paper_one_stage");
  const Command c = run("./paper_one_stage --param J_c=0.3");
  EXPECT_EQ(c.status, 1);
  expect_documented(c.err, R"~(./paper_one_stage: error: --param J_c: this simulator has no tunable parameters; list the parameters to set at run time in the scene's tunable = [...] and generate it again)~"
                           "\n");
}

TEST_F(TunableErrors, ParamUnknownName) {
  expect_documented(param_error("\"J_c\", \"K_ps\"", "J_x=0.3"),
      R"~(./demo: error: --param J_x: no tunable parameter has this name; the tunable parameters are J_c, K_ps)~" "\n");
}

TEST_F(TunableErrors, ParamNotAValue) {
  expect_documented(param_error("\"J_c\", \"K_ps\"", "K_ps=2000*lbf/in"),
      R"~(./demo: error: --param K_ps=2000*lbf/in is not a value; give a number in SI units, or NUMBER*Newton/mm, or NUMBER*kg/s^2, or NUMBER*N/m, or NUMBER*N/mm, or NUMBER*kN/mm)~" "\n");
}

// The engineering spellings of a parameter's dimension are accepted besides the model's own
// (issue 31, item 14: `--param K_ps=2000*N/mm` was refused where the model wrote Newton/mm).
TEST_F(TunableErrors, EngineeringSpellingsOfTheDimensionAreAccepted) {
  write_text("scene.toml", edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"J_c\", \"K_ps\"]"}}));
  const SpecializedScene model = specialize(parse_scene("scene.toml"));
  std::vector<double> values(model.main.params.size());
  const std::vector<rt::ParameterField> fields = parameter_fields(model, values);
  ASSERT_TRUE(rt::set_parameters({{"K_ps", "2000*N/mm"}, {"J_c", "30000*kg*mm^2"}}, fields, "./demo"));
  for (std::size_t i = 0; i < values.size(); ++i) {
    // Decimal unit factors: one rounding each.
    if (model.main.params[i].name == "K_ps") {
      EXPECT_NEAR(values[i], 2e6, 1e-9);
    } else if (model.main.params[i].name == "J_c") {
      EXPECT_NEAR(values[i], 0.03, 1e-17);
    }
  }
}

TEST_F(TunableErrors, ParamOutOfRange) {
  expect_documented(param_error("\"J_c\", \"K_ps\"", "J_c=-1"),
      R"~(./demo: error: --param J_c=-1: J_c must be positive; give a number in SI units, or NUMBER*kg*meters^2, or NUMBER*kg*m^2, or NUMBER*kg*mm^2)~" "\n");
}

TEST_F(TunableErrors, ParamOutsideTheModelsRange) {
  expect_documented(param_error("\"J_c\", \"K_ps\"", "J_c=1e-300"),
      R"~(./demo: error: --param J_c=1e-300 is outside the range pogear computes with, 1e-30 to 1e+30 in magnitude (SI); check the value and its unit)~" "\n");
}

// Values that are accepted, and what they mean.
TEST(TunableParam, AcceptsSINumbersAndTheUnitsListed) {
  double k = 0;
  const std::vector<rt::ParameterField> fields{{"K_ps", &k, {{"Newton/mm", 1000.0}, {"kg/s^2", 1.0}}, "positive"}};
  EXPECT_TRUE(rt::set_parameters({{"K_ps", "2e6"}}, fields, "demo"));
  EXPECT_EQ(k, 2e6);
  EXPECT_TRUE(rt::set_parameters({{"K_ps", "3000*Newton/mm"}}, fields, "demo"));
  EXPECT_EQ(k, 3e6);
  EXPECT_TRUE(rt::set_parameters({{"K_ps", "5*kg/s^2"}}, fields, "demo"));
  EXPECT_EQ(k, 5.0);
  ::testing::internal::CaptureStderr();
  for (const char* bad : {"", "1e6x", "inf", "nan", "1e6 ", "*Newton/mm", "1*Newton/mmm", "1e308*Newton/mm"})
    EXPECT_FALSE(rt::set_parameters({{"K_ps", bad}}, fields, "demo")) << bad;
  ::testing::internal::GetCapturedStderr();
  EXPECT_EQ(k, 5.0);
}

}  // namespace
}  // namespace pogear::test
