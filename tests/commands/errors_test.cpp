// Entries of docs/errors.md whose test runs `pogear`: a solver that cannot run a scene with brakes
// and clutches, loads or torque limits, refused by simulate, generate and response. The fixtures
// (EngagementCommands, LoadsAndControllers) are in tests/errors/error_support.hpp, beside the
// suites' other tests in tests/errors/errors_test.cpp.
#include <string>

#include "../errors/error_support.hpp"

namespace pogear::test {
namespace {

TEST_F(EngagementCommands, SolverOptionRk4) {
  write_text("gear.toml", shift_model());
  write_text("scene.toml", base_scene() + "\n[engagement]\nB1 = \"1\"\n");
  expect_pogear_error("simulate scene.toml --solver rk4 -o out", 2,
                      R"~(scene.toml: error: the scene engages brakes or clutches, which rk4 does not simulate (its fixed steps cannot locate their events); use --solver exact, dopri5 or implicit)~");
}

// generate refuses a solver that can never run the scene, with the reason simulate gives; --solvers
// all compiles the others (issue 31, item 9).
TEST_F(EngagementCommands, GenerateRk4) {
  write_text("gear.toml", shift_model());
  write_text("scene.toml", base_scene() + "\n[engagement]\nB1 = \"1\"\n");
  expect_pogear_error("generate scene.toml --solvers rk4 -o out", 2,
                      R"~(scene.toml: error: the scene engages brakes or clutches, which rk4 does not simulate (its fixed steps cannot locate their events); leave rk4 out of --solvers)~");
  const Command all = run(pogear() + " generate scene.toml --solvers all -o out");
  ASSERT_EQ(all.status, 0) << all.err;
  const std::string main = read_text("out/demo_main.cpp");
  EXPECT_NE(main.find("Solver::dopri5"), std::string::npos) << main;
  EXPECT_EQ(main.find("Solver::rk4"), std::string::npos) << main;
}

TEST_F(LoadsAndControllers, ResponseOfANonlinearScene) {
  write_nonlinear_scene();
  expect_pogear_error("response scene.toml --input tau_c --output omega_c", 2,
                      R"~(scene.toml: error: the scene is nonlinear (a quadratic load), and a frequency response is of a linear system; drop the load's quadratic part (or linearize it: a linear load of 2 c omega at the operating speed omega))~");
}

TEST_F(LoadsAndControllers, TorqueLimitsWithRk4) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\", torque_max = \"50*N*m\" }\n",
               R"~(scene.toml:17:10: error: a controller with torque limits switches at events, which rk4 does not locate (its fixed steps); use solver = "exact", "dopri5" or "implicit")~",
               {{R"(solver = "exact")", R"(solver = "rk4")"}});
  write_text("gear.toml", base_model());
  write_text("scene.toml", base_scene() + "\n[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\", torque_max = \"50*N*m\" }\n");
  expect_pogear_error("simulate scene.toml --solver rk4 --interpreted -o out", 2,
                      R"~(scene.toml: error: a controller with torque limits switches at events, which rk4 does not locate (its fixed steps); use --solver exact, dopri5 or implicit)~");
}

TEST_F(LoadsAndControllers, SimulateWithExactSolver) {
  write_nonlinear_scene();
  expect_pogear_error("simulate scene.toml --solver exact --interpreted -o out", 2,
                      R"~(scene.toml: error: a quadratic load makes the scene nonlinear, which exact stepping does not integrate; use --solver dopri5 or implicit)~");
  expect_pogear_error("generate scene.toml --solvers exact,dopri5 -o out", 2,
                      R"~(scene.toml: error: a quadratic load makes the scene nonlinear, which exact stepping does not integrate; leave exact out of --solvers)~");
}

}  // namespace
}  // namespace pogear::test
