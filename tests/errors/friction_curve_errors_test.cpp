// Friction curves (friction_curve of a brake or clutch) refused where they cannot mean a friction
// coefficient, and the scenes that cannot run one: checked to the character against docs/errors.md.
#include <string>

#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// gear.toml with brake B1 on the ring (line 36), its friction_curve = `curve` on line 40, and its
// capacity after b_sg.
class FrictionCurves : public ErrorTest {
 protected:
  static std::string model(const std::string& curve, const std::string& static_ratio = "") {
    return edited(base_model(), {{"[parameters]", "[[brake]]\nname = \"B1\"\nbody = \"r\"\n" + static_ratio +
                                                      "friction_curve = " + curve + "\n\n[parameters]"},
                                 {R"(b_sg = "b_ps")", "b_sg = \"b_ps\"\nTcap_B1 = \"50*N*m\""}});
  }
  void expect_error(const std::string& curve, const std::string& expected, const std::string& static_ratio = "") {
    expect_documented(model_error(model(curve, static_ratio)), expected);
  }
};

const std::string falling = R"([["0*rad/s", 1.2], ["30*rad/s", 1]])";

TEST_F(FrictionCurves, NotAList) {
  expect_error("1.1", R"~(gear.toml:39:18: error: friction_curve of 'B1' is a list of rows [slip speed, ratio to the capacity], from zero slip, e.g. [["0*rad/s", 1.1], ["50*rad/s", 1]]; it needs two rows at least)~");
}
TEST_F(FrictionCurves, RowNotAPair) {
  expect_error(R"([["0*rad/s", 1.1], ["50*rad/s"]])", R"~(gear.toml:39:37: error: friction_curve of 'B1' is a list of rows [slip speed, ratio to the capacity], from zero slip, e.g. [["0*rad/s", 1.1], ["50*rad/s", 1]])~");
}
TEST_F(FrictionCurves, SlipWithoutUnit) {
  expect_error("[[0, 1.1], [50, 1]]", R"~(gear.toml:39:20: error: a slip speed of friction_curve is a speed with its unit, e.g. "10*rad/s" or "100*rpm")~");
}
TEST_F(FrictionCurves, SlipInHz) {
  expect_error(R"([["0*rad/s", 1.1], ["5*Hz", 1]])", R"~(gear.toml:39:38: error: a slip speed of friction_curve is in Hz, which could mean rev/s or rad/s; give it in rpm or rad/s)~");
}
TEST_F(FrictionCurves, SlipInPlainPerSecond) {
  expect_error(R"([["0*rad/s", 1.1], ["5/s", 1]])", R"~(gear.toml:39:38: error: a slip speed of friction_curve is in 1/s, which could mean rev/s or rad/s; give it in rpm or rad/s)~");
}
TEST_F(FrictionCurves, SlipNamesAParameter) {
  expect_error(R"([["0*rad/s", 1.1], ["v_max", 1]])", R"~(gear.toml:39:38: error: a slip speed of friction_curve names 'v_max'; the curve is data of the element, not of its parameters: give a number with its unit, e.g. "10*rad/s")~");
}
TEST_F(FrictionCurves, NotFromZeroSlip) {
  expect_error(R"([["5*rad/s", 1.1], ["50*rad/s", 1]])", R"~(gear.toml:39:20: error: friction_curve of 'B1' starts at zero slip, "0*rad/s" (the kinetic ratio as the element locks); its first row is at 5 rad/s)~");
}
TEST_F(FrictionCurves, SlipsNotIncreasing) {
  expect_error(R"([["0*rad/s", 1.1], ["50*rad/s", 1], ["300*rpm", 0.9]])", R"~(gear.toml:39:55: error: the slip speeds of friction_curve must increase strictly (31.41592653589793 rad/s follows 50 rad/s))~");
}
TEST_F(FrictionCurves, RatioNotPositive) {
  expect_error(R"([["0*rad/s", 1], ["50*rad/s", 0]])", R"~(gear.toml:39:48: error: a ratio of friction_curve is 0; it is positive, at most 10 (the kinetic torque over the capacity at that slip))~");
}
TEST_F(FrictionCurves, RatioNotANumber) {
  expect_error(R"([["0*rad/s", "1.1"], ["50*rad/s", 1]])", R"~(gear.toml:39:31: error: a ratio of friction_curve is a plain number, the kinetic torque over the capacity at that slip)~");
}
TEST_F(FrictionCurves, AboveTheStaticRatioAtZeroSlip) {
  expect_error(falling, R"~(gear.toml:39:18: error: friction_curve of 'B1' is 1.2 at zero slip, above its static_ratio 1; static friction is at least the kinetic one as it locks: raise static_ratio or lower the curve's first ratio)~");
}

// The scene of docs/errors.md engaging B1, whose curve falls from 1.2 at zero slip (static 1.3).
std::string engaging(const std::string& more = "") {
  return edited(base_scene(), {{"[simulation]", "[engagement]\nB1 = \"1\"\n" + more + "\n[simulation]"}});
}

TEST_F(FrictionCurves, ExactStepping) {
  expect_documented(scene_error(engaging(), model(falling, "static_ratio = 1.3\n")),
                    R"~(scene.toml:20:10: error: a friction curve makes a slipping element's torque vary with its slip, which exact stepping does not integrate; use solver = "dopri5" or "implicit")~");
}
TEST_F(FrictionCurves, SlipControl) {
  expect_documented(scene_error(edited(engaging("\n[slip_control]\nB1 = { target = \"10*rad/s\", kp = \"0.01*s/rad\" }\n"),
                                       {{R"(solver = "exact")", R"(solver = "dopri5")"}}),
                                model(falling, "static_ratio = 1.3\n")),
                    R"~(scene.toml:18:6: error: B1's friction varies with slip (friction_curve in the model), which a slip controller does not take; control an element of constant friction, or give B1 a constant ratio)~");
}

}  // namespace
}  // namespace pogear::test
