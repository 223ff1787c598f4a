// Bad scene files: each mistake gets a message with its position, never a crash. The exit status
// of `pogear simulate` on one: tests/commands/bad_scene_test.cpp.
#include <algorithm>
#include <fstream>

#include "report/model_errors.hpp"
#include "sim_support.hpp"

namespace pogear::test {
namespace {

InputError scene_error(const std::string& text) {
  try {
    scene_model(text);
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

int line_of(const std::string& text, const std::string& marker) {
  const auto pos = text.find(marker);
  EXPECT_NE(pos, std::string::npos) << marker;
  return 1 + static_cast<int>(std::count(text.begin(), text.begin() + pos, '\n'));
}

TEST(BadScene, UnknownBody) {
  const std::string text = with_line(base, "tau_c = {", "tau_x = {");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "tau_x"));
  EXPECT_NE(e.message().find("input 'tau_x' names no body"), std::string::npos) << e.what();
}

TEST(BadScene, UnknownEffect) {
  const std::string text = with_effects(base, "\"mesh_compliance\", \"gear_backlash\"");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "effects ="));
  EXPECT_NE(e.message().find("unknown effect 'gear_backlash'"), std::string::npos) << e.what();
}

TEST(BadScene, UnknownSolver) {
  const std::string text = with_line(base, "solver = \"exact\"", "solver = \"euler\"");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "solver = "));
  EXPECT_NE(e.message().find("unknown solver 'euler'; the solvers are exact, rk4, dopri5, implicit"),
            std::string::npos) << e.what();
}

TEST(BadScene, MissingModel) {
  const std::string text = with_line(base, "model = \"../paper_one_stage.toml\"", "model = \"../no_such_gear.toml\"");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "model = "));
  EXPECT_NE(e.message().find("does not exist"), std::string::npos) << e.what();
}

TEST(BadScene, BadSignalTable) {
  const auto dir = temp_dir("bad_table");
  { std::ofstream(dir / "torque.csv") << "t,tau\n0,0\n0.5,abc\n1,100\n"; }
  const std::string text = with_line(base, "tau_c = { constant = \"100*Nm\" }",
                                     "tau_c = { table = \"" + (dir / "torque.csv").string() + "\" }");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().file, (dir / "torque.csv").string());
  EXPECT_EQ(e.where().line, 3);
  EXPECT_NE(e.message().find("abc"), std::string::npos) << e.what();
}

TEST(BadScene, DampingWithoutCompliance) {
  const std::string text = with_effects(base, "\"mesh_damping\", \"bearing_friction\"");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "effects ="));
  EXPECT_NE(e.message().find("mesh_damping needs mesh_compliance"), std::string::npos) << e.what();
}

TEST(BadScene, ForceOutputWithoutMeshForces) {
  const std::string text = with_line(with_effects(base, "\"mesh_compliance\""), "compare_rigid = true",
                                     "compare_rigid = true\noutputs = [\"F_ps\"]");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "outputs ="));
  EXPECT_NE(e.message().find("add it to effects"), std::string::npos) << e.what();
}

TEST(BadScene, RigidComparisonOfARigidScene) {
  const std::string text = with_effects(base, "\"bearing_friction\"");
  const InputError e = scene_error(text);
  EXPECT_EQ(e.where().line, line_of(text, "compare_rigid ="));
  EXPECT_NE(e.message().find("already rigid"), std::string::npos) << e.what();
}

TEST(BadScene, WrongUnitOfAnInput) {
  const std::string text = with_line(base, "\"100*Nm\"", "\"100*N\"");
  const InputError e = scene_error(text);
  EXPECT_NE(e.message().find("has unit kg*m/s^2; it needs kg*m^2/s^2"), std::string::npos) << e.what();
}

TEST(BadScene, OverrideThatBreaksTheGeometry) {
  const std::string text = with_parameters(base, "r_p = \"5*cm\"");
  const InputError e = scene_error(text);
  EXPECT_NE(e.message().find("'r_c' = 14.8*cm"), std::string::npos) << e.what();
}

}  // namespace
}  // namespace pogear::test
