// Starts in a gear ([initial] gear or engaged) that cannot be: an unknown gear or element, a gear
// named twice, an element open at t = 0 or overloaded, speeds the gear does not determine, or a
// state the start computes named as well.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// The ZF 6HP26 driven at its input, started in 1st (A and D) at 2500 rpm.
const std::string start_scene = R"(name = "start"
model = "gear.toml"
effects = ["mesh_compliance", "mesh_damping", "bearing_friction", "mesh_forces"]

[inputs]
tau_in = "200*Nm"

[engagement]
A = "1"
D = "1"

[initial]
gear = "1"
omega_in = "2500*rpm"

[simulation]
horizon = "0.01*s"
sample = "1*ms"
)";

class StartInGear : public ErrorTest {
 protected:
  void expect_start_error(const Edits& edits, const std::string& expected) {
    expect_documented(scene_error(edited(start_scene, edits), read_text(source_path("models/zf6hp26.toml"))), expected);
  }
};

// Its stuck torques are checked against the capacities at the scene's values.
// Tunable capacities are allowed (StartInGear.ParamMovesTheCapacities); a tunable that reaches the
// state is not, named itself or through a parameter defined by it.
TEST_F(StartInGear, WithTunables) {
  expect_start_error({{"effects = [", "tunable = [\"Tcap_A\", \"J_out\"]\neffects = ["}},
      R"~(scene.toml:14:8: error: a start in a gear is computed at the scene's parameter values, which tunable parameters other than brakes' and clutches' capacities change at run time ('J_out' is not a capacity); set it in [parameters], or start from given speeds)~");
}

// The gear's state would need the controller's torque at t = 0, which its state gives.
TEST_F(StartInGear, WithSlipControl) {
  expect_start_error({{"[simulation]", "[slip_control]\nD = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n\n[simulation]"}},
      R"~(scene.toml:13:8: error: a start in a gear is not available with [slip_control]; give every initial speed in [initial] instead of the gear)~");
}

TEST_F(StartInGear, UnknownGear) {
  expect_start_error({{R"(gear = "1")", R"(gear = "7")"}},
      R"~(scene.toml:13:8: error: '7' is not a gear of the model; its gears are 1, 2, 3, 4, 5, 6, R)~");
}

TEST_F(StartInGear, GearNamedTwice) {
  expect_start_error({{R"(gear = "1")", "gear = \"1\"\nengaged = [\"A\"]"}},
      R"~(scene.toml:13:8: error: [initial] names the gear it starts in once: gear = "1" or engaged = ["A", "D"], not both)~");
}

TEST_F(StartInGear, EngagedNamesNoElement) {
  expect_start_error({{R"(gear = "1")", R"(engaged = ["A", "X"])"}},
      R"~(scene.toml:13:11: error: engaged names 'X', which is no brake or clutch of the model; they are A, B, C, D, E)~");
  expect_start_error({{R"(gear = "1")", R"(engaged = ["A", "A"])"}},
      R"~(scene.toml:13:11: error: engaged names 'A' twice)~");
  expect_start_error({{R"(gear = "1")", R"(engaged = [])"}},
      R"~(scene.toml:13:11: error: engaged = [] names no brake or clutch; name those stuck at t = 0, or leave it out)~");
}

TEST_F(StartInGear, ElementOpenAtTheStart) {
  expect_start_error({{R"(D = "1")", R"(D = { step = "1", at = "0.005*s", before = "0" })"}},
      R"~(scene.toml:13:8: error: gear '1' engages D, but [engagement] leaves it open at t = 0; command it engaged from the start, e.g. D = "1")~");
}

// A command that rises at t = 0 reaches the element only after its actuator's delay or lag.
TEST_F(StartInGear, ElementTheActuatorHasNotEngagedAtTheStart) {
  expect_start_error({{R"(D = "1")", "D = { step = \"1\", at = \"0*s\", before = \"0\" }\n\n[actuators]\nD = { fill_delay = \"30*ms\" }"}},
      R"~(scene.toml:16:8: error: gear '1' engages D, but its actuator has not engaged it at t = 0 (its command rises at t = 0, behind its fill delay or lag); command it engaged before the run, e.g. D = "1")~");
}

TEST_F(StartInGear, ElementOutsideTheGearEngagedAtTheStart) {
  expect_start_error({{R"(D = "1")", "D = \"1\"\nB = \"0.5\""}},
      R"~(scene.toml:14:8: error: starting in gear '1', B is commanded 0.5 at t = 0, but the gear does not engage it; open it at t = 0 (its command 0), or start in a gear that engages it)~");
}

TEST_F(StartInGear, StuckTorqueBeyondCapacity) {
  expect_start_error({{R"(tau_in = "200*Nm")", R"(tau_in = "5000*Nm")"}},
      R"~(scene.toml:13:8: error: starting in gear '1', A carries 1177.19 N m at t = 0, beyond its static capacity of 900 N m (900 N m x static ratio 1 x command 1); raise its capacity or its command, or start with smaller torques)~");
}

TEST_F(StartInGear, SpeedsTheGearDoesNotDetermine) {
  expect_start_error({{R"(omega_in = "2500*rpm")", "omega_in = \"2500*rpm\"\nomega_out = \"600*rpm\""}},
      R"~(scene.toml:12:1: error: gear '1' leaves 1 degree of freedom, so the start needs the speed of 1 body in [initial] (2 named), e.g. omega_in)~");
  expect_start_error({{R"(gear = "1")", R"(engaged = ["A"])"}, {R"(D = "1")", R"(D = "0")"}},
      R"~(scene.toml:12:1: error: engaged = [A] leaves 2 degrees of freedom, so the start needs the speed of 2 bodies in [initial] (1 named), e.g. omega_in, omega_s3)~");
  expect_start_error({{R"(gear = "1")", R"(engaged = ["A", "D", "E"])"}},
      R"~(scene.toml:13:11: error: engaging A, D, E locks the gear: no body can turn, so there is no rigid model; engage fewer elements (pogear ratios lists the sets))~");
}

TEST_F(StartInGear, StartThatIsNoGearsStart) {
  expect_start_error({{R"(gear = "1")", "gear = \"1\"\nstart = \"given\""}},
      R"~(scene.toml:14:9: error: a start in a gear is "rigid" (the default: at the named speeds, with eq. (8)'s forces and torques) or "steady"; remove start, or write "steady")~");
  expect_start_error({{R"(gear = "1")", "gear = \"1\"\nstart = \"steady\""}},
      R"~(scene.toml:12:1: error: starting in gear '1' at equilibrium computes every speed and force; remove omega_in from [initial])~");
  expect_start_error({{R"(omega_in = "2500*rpm")", R"(F_p1s1 = "1*N")"}},
      R"~(scene.toml:12:1: error: starting in gear '1' takes the mesh forces from the gear's rigid model; remove F_p1s1 from [initial])~");
}

TEST_F(StartInGear, RigidStartWithElementsNeedsAGear) {
  expect_start_error({{R"(gear = "1")", R"(start = "rigid")"}},
      R"~(scene.toml:13:9: error: start = "rigid" is not available with brakes or clutches engaged (whether each one sticks at t = 0 is a choice of its own); start in a gear ([initial] gear = "1"), or from given speeds)~");
}

}  // namespace
}  // namespace pogear::test
