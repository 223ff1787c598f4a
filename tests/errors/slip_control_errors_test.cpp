// Slip controllers ([slip_control]) refused where the scene cannot mean them: checked to the
// character against docs/errors.md.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// B1 (brake on the ring) open until its controller starts; dopri5, which slip control runs with.
const std::string controlled = "B1 = \"0\"\n\n[slip_control]\n";
const Edits adaptive = {{R"(solver = "exact")", R"(solver = "dopri5")"}};

TEST_F(EngagementCommands, SlipControlOfNoElement) {
  expect_error(controlled + "B9 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:25:1: error: 'B9' is no brake or clutch of the model (it has B1, C1); [slip_control] controls the slip of one of them)~", adaptive);
}
// A slip controller's gains and limits are its element's capacity at the scene's value times the
// scene's per-unit values; other tunables are its scene's (SimulateCommand.ParamWithSlipControl).
TEST_F(EngagementCommands, SlipControlOfATunableCapacity) {
  Edits edits = adaptive;
  edits.push_back({"compare_rigid = true", "compare_rigid = true\ntunable = [\"Tcap_B1\"]"});
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:7:11: error: the capacity of B1 (Tcap_B1) depends on tunable 'Tcap_B1', and B1's slip controller takes its gains and limits at the scene's capacity; drop 'Tcap_B1' from tunable, or set it in [parameters] and generate one simulator per value)~", edits);
}
// Speed and slip controllers share the scene's 16 (a run's modes are bits of a 32-bit word).
TEST_F(EngagementCommands, SlipControlBeyondSixteenControllers) {
  std::string controllers = "\n[controllers]\n";
  for (int i = 0; i < 16; ++i) controllers += "c" + std::to_string(i) + " = { body = \"s\", set_point = \"1*rpm\", kp = \"1*N*m*s\" }\n";
  expect_error("B1 = \"0\"\n" + controllers + "\n[slip_control]\nB1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:43:6: error: more than 16 controllers and slip controllers; a scene has at most 16)~", adaptive);
}
TEST_F(EngagementCommands, SlipControlNotATable) {
  expect_error(controlled + "B1 = \"10*rad/s\"\n",
               R"~(scene.toml:25:6: error: a slip controller is a table { target = <slip speed signal>, kp = "<s/rad>", ki = "<1/rad>" })~", adaptive);
}
TEST_F(EngagementCommands, SlipControlUnknownKey) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\", gain = 2 }\n",
               R"~(scene.toml:25:48: error: unknown key 'gain' in a slip controller; the keys are target, kp, ki, tracking_time, start)~", adaptive);
}
TEST_F(EngagementCommands, SlipControlWithoutTarget) {
  expect_error(controlled + "B1 = { kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:25:6: error: the slip controller has no target; add target = <slip speed signal>, e.g. { table = [[0, "30*rad/s"], ["0.3*s", "0*rad/s"]], when = "B2 slipping" })~", adaptive);
}
TEST_F(EngagementCommands, SlipControlSineTarget) {
  expect_error(controlled + "B1 = { target = { sine = \"10*rad/s\", frequency = \"2*Hz\" }, kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:25:17: error: a slip controller's target is a constant, step, ramp or table: a sine changes the slip's sign)~", adaptive);
}
TEST_F(EngagementCommands, SlipControlTargetZero) {
  expect_error(controlled + "B1 = { target = \"0*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:25:6: error: the target of B1's slip controller is zero throughout the run; a target has the sign of the slip it holds (slip_B1 in the CSV))~", adaptive);
}
TEST_F(EngagementCommands, SlipControlWithoutGains) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\" }\n",
               R"~(scene.toml:25:6: error: a slip controller's gains kp and ki are non-negative and not both zero; give kp = "<s/rad>" (command per slip speed) and ki = "<1/rad>" (command per slip angle))~", adaptive);
}
TEST_F(EngagementCommands, SlipControlNegativeGain) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"-0.01*s/rad\" }\n",
               R"~(scene.toml:25:34: error: a slip controller's gains kp and ki are non-negative and not both zero; give kp = "<s/rad>" (command per slip speed) and ki = "<1/rad>" (command per slip angle))~", adaptive);
}
TEST_F(EngagementCommands, SlipControlGainWithoutUnit) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"0.01\" }\n",
               R"~(scene.toml:25:34: error: kp has no unit (0.01); give it with its unit, e.g. "0.01*s/rad")~", adaptive);
}
TEST_F(EngagementCommands, SlipControlTrackingWithoutKi) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\", tracking_time = \"5*ms\" }\n",
               R"~(scene.toml:25:64: error: tracking_time is the time constant with which the integral follows a limit; it needs ki)~", adaptive);
}
TEST_F(EngagementCommands, SlipControlKiWithoutKp) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", ki = \"0.5/rad\" }\n",
               R"~(scene.toml:25:6: error: a slip controller with no kp needs tracking_time, the time constant with which its integral follows a limit (kp / ki, the default, is zero))~", adaptive);
}
TEST_F(EngagementCommands, SlipControlStartWithWhen) {
  expect_error(controlled + "B1 = { target = { table = [[0, \"10*rad/s\"]], when = \"C1 slipping\" }, kp = \"0.01*s/rad\", start = \"1*s\" }\n",
               R"~(scene.toml:25:97: error: the target's `when` starts the slip controller; drop start, or the target's when)~", adaptive);
}
TEST_F(EngagementCommands, SlipControlOfAnElementWithoutCommand) {
  expect_error("C1 = \"1\"\n\n[slip_control]\nB1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:25:6: error: B1 has a slip controller but no command in [engagement]; give it its command until the controller starts, e.g. B1 = "0" (open))~", adaptive);
}
TEST_F(EngagementCommands, SlipControlWithExactStepping) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:17:10: error: a slip controller makes its element's heat quadratic in the state, which exact stepping does not integrate; use solver = "dopri5" or "implicit")~");
}
TEST_F(EngagementCommands, SlipControlNamedAsASpeedController) {
  expect_error(controlled + "B1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n",
               R"~(scene.toml:28:6: error: [controllers] has a controller named 'slip_B1', the name of B1's slip controller; rename the controller)~",
               with(adaptive, {{"[simulation]", "[controllers]\nslip_B1 = { body = \"s\", set_point = \"10*rad/s\", kp = \"1*N*m*s/rad\" }\n\n[simulation]"}}));
}

}  // namespace
}  // namespace pogear::test
