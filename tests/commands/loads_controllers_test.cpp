// Scene loads and speed controllers through `pogear simulate`: the compiled simulator against the
// interpreted run, for the power-split drive and for a brake with a torque-limited controller.
// The closed forms and power balances: tests/simulate/loads_controllers_test.cpp.
#include <filesystem>
#include <string>

#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

TEST(SpeedController, CompiledPowerSplitDriveMatchesTheInterpretedRun) {
  const auto dir = temp_dir("power_split_drive");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " +
                                source_path("models/scenes/power_split_drive.toml") + " -o " + dir.string());
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("nonlinear (quadratic loads): integrated by implicit"), std::string::npos) << c.out;
  EXPECT_TRUE(std::filesystem::exists(dir / "power_split_drive.controllers.svg"));
  const SpecializedScene m = scene_model(scene_text("power_split_drive"));
  // Both integrate the same equations with TR-BDF2 at 1e-6; the compiled rhs sums its terms in
  // another order, and rounding differences move the adaptive steps: measured 3e-9 of the scale.
  expect_csv_matches_interpreted(dir / "power_split_drive.csv", m, m.main, 1e-6);
  expect_csv_matches_interpreted(dir / "power_split_drive.rigid.csv", m, *m.rigid, 1e-6);
}

TEST(TorqueLimits, CompiledSimulatorWithABrakeAndALimitedControllerMatchesTheInterpretedRun) {
  // The power-split launch with MG1 holding the engine speed within +-40 N m while the one-way brake
  // holds and releases the engine: friction elements and torque limits in one hybrid run.
  const std::string text = with_lines(scene_text("power_split_ev_launch"),
                                      {{"tau_s = \"-20*Nm\"", ""}, {"[engagement]",
                                        "[controllers]\nmg1 = { body = \"s\", speed_of = \"c\", set_point = { step = "
                                        "\"1500*rpm\", before = \"0*rpm\", at = \"3*s\" }, kp = \"1.5*N*m*s\", ki = \"4*N*m\", "
                                        "torque_min = \"-40*N*m\", torque_max = \"40*N*m\" }\n\n[engagement]"}});
  const auto dir = temp_dir("limits_compiled");
  write_text(dir / "power_split_ev_launch.toml", with_line(text, "model = \"../power_split.toml\"",
                                                           "model = \"" + source_path("models/power_split.toml") + "\""));
  std::filesystem::copy_file(source_path("models/scenes/power_split_mg2.csv"), dir / "power_split_mg2.csv",
                             std::filesystem::copy_options::overwrite_existing);
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " +
                                (dir / "power_split_ev_launch.toml").string() + " -o " + (dir / "compiled").string());
  ASSERT_EQ(c.status, 0) << c.err;
  const Command i = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " +
                                (dir / "power_split_ev_launch.toml").string() + " --interpreted -o " +
                                (dir / "interpreted").string());
  ASSERT_EQ(i.status, 0) << i.err;
  for (const std::string suffix : {"", ".rigid"}) {
    const HybridRun compiled = read_hybrid_run(dir / "compiled", "power_split_ev_launch" + suffix);
    const HybridRun interpreted = read_hybrid_run(dir / "interpreted", "power_split_ev_launch" + suffix);
    // The brake's and the controller's events, the same in both: the matrices differ by rounding
    // (folded expressions against L^-1 A), which moves an event by a few ulps of its time.
    ASSERT_EQ(compiled.events.size(), interpreted.events.size()) << suffix;
    EXPECT_GE(compiled.events.size(), 5u) << suffix;  // the brake's three, the controller at and off its limit
    for (std::size_t k = 0; k < compiled.events.size(); ++k) {
      const auto& [t, element, from, to] = compiled.events[k];
      const auto& [t_i, element_i, from_i, to_i] = interpreted.events[k];
      EXPECT_EQ(element + from + to, element_i + from_i + to_i) << suffix << " event " << k;
      EXPECT_NEAR(t, t_i, 1e-9 * (1 + t)) << suffix << " event " << k;
    }
    ASSERT_EQ(compiled.csv.rows.size(), interpreted.csv.rows.size());
    for (std::size_t col = 1; col < compiled.csv.header.size(); ++col)
      EXPECT_LT(column_error(compiled.csv.rows, interpreted.csv.rows, col), 1e-9) << suffix << " " << compiled.csv.header[col];
  }
}

}  // namespace
}  // namespace pogear::test
