// Brakes' and clutches' actuators ([actuators]) refused where the scene cannot mean them: checked
// to the character against docs/errors.md.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// B1 (brake on the ring) applied throughout; [actuators] after it.
const std::string actuated_b1 = "B1 = \"1\"\n\n[actuators]\n";

TEST_F(EngagementCommands, ActuatorOfNoElement) {
  expect_error(actuated_b1 + "B9 = { fill_delay = \"30*ms\" }\n",
               R"~(scene.toml:25:6: error: 'B9' is no brake or clutch of the model (it has B1, C1); [actuators] gives an element's fill delay and lag)~");
}
TEST_F(EngagementCommands, ActuatorWithoutTimes) {
  expect_error(actuated_b1 + "B1 = {}\n",
               R"~(scene.toml:25:6: error: [actuators] B1 needs fill_delay (e.g. "30*ms"), time_constant (e.g. "40*ms") or both)~");
}
TEST_F(EngagementCommands, ActuatorUnknownKey) {
  expect_error(actuated_b1 + "B1 = { fill_delay = \"30*ms\", lag = \"40*ms\" }\n",
               R"~(scene.toml:25:30: error: unknown key 'lag' in [actuators] B1; the keys are fill_delay, time_constant)~");
}
TEST_F(EngagementCommands, ActuatorDelayInMetres) {
  expect_error(actuated_b1 + "B1 = { fill_delay = \"30*m\" }\n", R"~(scene.toml:25:21: error: fill_delay has unit m; it needs s)~");
}
TEST_F(EngagementCommands, ActuatorDelayNegative) {
  expect_error(actuated_b1 + "B1 = { fill_delay = \"-30*ms\" }\n", R"~(scene.toml:25:21: error: fill_delay is negative; a delay or lag is 0 or more)~");
}
TEST_F(EngagementCommands, ActuatorLagBelowANanosecond) {
  expect_error(actuated_b1 + "B1 = { time_constant = \"1e-12*s\" }\n",
               R"~(scene.toml:25:24: error: time_constant is 0 or from 1e-9 s to 3600 s; give it in s or ms, e.g. "40*ms")~",
               {{R"(solver = "exact")", R"(solver = "dopri5")"}});
}
TEST_F(EngagementCommands, ActuatorOfAnOpenElement) {
  expect_error("C1 = \"1\"\n\n[actuators]\nB1 = { fill_delay = \"30*ms\" }\n",
               R"~(scene.toml:25:6: error: the scene does not engage B1, so its actuator has nothing to apply; give B1 a command in [engagement], or drop it from [actuators])~");
}
// A lag makes the engagement exponential between breakpoints; the scene says exact (a delay alone
// would run exact).
TEST_F(EngagementCommands, ActuatorLagWithExactStepping) {
  expect_error(actuated_b1 + "B1 = { time_constant = \"40*ms\" }\n",
               R"~(scene.toml:17:10: error: an actuator's lag makes its element's engagement exponential between the command's breakpoints, which exact stepping does not integrate; use solver = "dopri5" or "implicit")~");
}
TEST_F(EngagementCommands, ActuatorOfAOneWayElement) {
  expect_documented(scene_error(base_scene() + "\n[engagement]\n" + actuated_b1 + "B1 = { fill_delay = \"30*ms\" }\n",
                                edited(shift_model(), {{"body = \"r\"\n", "body = \"r\"\none_way = true\n"}})),
                    R"~(scene.toml:25:6: error: B1 is a one-way element, which holds by its shape, not by a command; drop it from [actuators])~");
}
TEST_F(EngagementCommands, ActuatorUnderSlipControl) {
  expect_error("B1 = \"0\"\n\n[slip_control]\nB1 = { target = \"-10*rad/s\", kp = \"0.004*s/rad\" }\n\n[actuators]\n"
               "B1 = { fill_delay = \"30*ms\" }\n",
               R"~(scene.toml:28:6: error: B1 is under slip control, whose command the actuator would lag through a state of its own, which pogear does not model yet; drop B1 from [actuators] or from [slip_control])~",
               {{R"(solver = "exact")", R"(solver = "dopri5")"}});
}

}  // namespace
}  // namespace pogear::test
