// Fixed bodies (`fixed = true`) that cannot be: on an axis the housing does not hold, with what
// only a turning body has, held twice, locking the gear, or named where a body must turn.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// gear.toml with its ring r fixed: c, p, s and g turn, one degree of freedom (kept: c).
const Edits ring_fixed{{R"(name = "r")", "name = \"r\"\nfixed = true"}, {R"(keep = ["c", "r"])", R"(keep = ["c"])"}};

class Fixed : public ErrorTest {
 protected:
  // scene.toml on gear.toml with its ring fixed, keeping c.
  void expect_fixed_scene_error(const Edits& edits, const std::string& expected) {
    const std::string scene = edited(base_scene(), with({{R"(keep = ["c", "r"])", R"(keep = ["c"])"}}, edits));
    expect_documented(scene_error(scene, edited(base_model(), ring_fixed)), expected);
  }
};

TEST_F(Fixed, PlanetCannotBeFixed) {
  expect_model_error({{R"(name = "p")", "name = \"p\"\nfixed = true"}},
      R"~(gear.toml:10:9: error: body 'p' is a planet, whose axis moves with its carrier; fixed = true holds a body on the central axis (a ring, sun or carrier): fix its carrier instead)~");
}

TEST_F(Fixed, CountershaftCannotBeFixed) {
  expect_model_error({{R"(name = "g")", "name = \"g\"\nfixed = true"}},
      R"~(gear.toml:22:9: error: body 'g' turns about a fixed parallel axis; fixed = true holds a body on the central axis (a ring, sun or carrier): hold 'g' with a [[brake]])~");
}

TEST_F(Fixed, FixedBodyHasNoInertia) {
  expect_model_error({{R"(name = "r")", "name = \"r\"\nfixed = true\ninertia = \"J_r\""}},
      R"~(gear.toml:19:11: error: body 'r' is fixed: it does not turn, so its inertia plays no part; leave it out)~");
}

TEST_F(Fixed, FixedIsNotABoolean) {
  expect_model_error({{R"(name = "r")", "name = \"r\"\nfixed = \"yes\""}},
      R"~(gear.toml:18:9: error: fixed must be true or false: true when the housing holds the body)~");
}

TEST_F(Fixed, BrakeOnAFixedBody) {
  expect_model_error(with(ring_fixed, {{"[parameters]", "[[brake]]\nname = \"B1\"\nbody = \"r\"\n\n[parameters]"}}),
      R"~(gear.toml:39:8: error: brake 'B1' holds 'r', which is fixed already (fixed = true); remove the brake, or fixed = true if the brake releases it)~");
}

TEST_F(Fixed, ClutchToAFixedBody) {
  expect_model_error(with(ring_fixed, {{"[parameters]", "[[clutch]]\nname = \"C1\"\nbodies = [\"s\", \"r\"]\n\n[parameters]"}}),
      R"~(gear.toml:39:16: error: clutch 'C1' joins 'r', which is fixed (fixed = true); a clutch to the housing is a [[brake]], and a fixed body needs none)~");
}

TEST_F(Fixed, MeshBetweenTwoFixedBodies) {
  expect_model_error(with(ring_fixed, {{R"(name = "s")", "name = \"s\"\nfixed = true"},
                                       {"[parameters]", "[[mesh]]\nfirst = \"s1\"\nsecond = \"r1\"\n\n[parameters]"}}),
      R"~(gear.toml:40:10: error: 's' and 'r' are both fixed, so their mesh never turns; leave it out, or let one of them turn)~");
}

TEST_F(Fixed, ElementNamedLikeAFixedBody) {
  expect_model_error(with(ring_fixed, {{"[parameters]", "[[brake]]\nname = \"r\"\nbody = \"s\"\n\n[parameters]"}}),
      R"~(gear.toml:38:8: error: 'r' is the name of a fixed body (line 17), whose holding torque is T_r; give the brake another name)~");
}

TEST_F(Fixed, FixedBodiesLockTheGear) {
  expect_model_error(with(ring_fixed, {{R"(name = "s")", "name = \"s\"\nfixed = true"}}),
      R"~(gear.toml:3:8: error: the gear cannot turn: with s, r fixed, its meshes leave its 3 other bodies no degree of freedom (rank of R 3); fix fewer bodies)~");
}

TEST_F(Fixed, KeepNamesAFixedBody) {
  expect_model_error({{R"(name = "r")", "name = \"r\"\nfixed = true"}},
      R"~(gear.toml:3:14: error: keep names 'r', which is fixed; keep velocities of bodies that turn)~");
  expect_documented(model_error(edited(base_model(), ring_fixed), std::vector<std::string>{"r"}),
      R"~(gear.toml: error: keep 'r' is fixed (the housing holds it), so it has no speed and takes no torque; name a body that turns: c, p, s, g)~");
}

TEST_F(Fixed, SceneNamesAFixedBody) {
  expect_fixed_scene_error({{R"(tau_c = { constant = "100*Nm" })", "tau_c = { constant = \"100*Nm\" }\ntau_r = { constant = \"1*Nm\" }"}},
      R"~(scene.toml:10:1: error: 'tau_r' is of body 'r', which is fixed (the housing holds it), so it has no speed and takes no torque; name a body that turns: c, p, s, g)~");
  expect_fixed_scene_error({{R"(omega_c = "0*rpm")", R"(omega_r = "0*rpm")"}},
      R"~(scene.toml:12:1: error: 'omega_r' is of body 'r', which is fixed (the housing holds it), so it has no speed and takes no torque; name a body that turns: c, p, s, g)~");
  expect_fixed_scene_error({{"[initial]", "[loads]\nr = { constant = \"1*Nm\" }\n\n[initial]"}},
      R"~(scene.toml:12:5: error: the load's body 'r' is fixed (the housing holds it), so it has no speed and takes no torque; name a body that turns: c, p, s, g)~");
}

TEST_F(Fixed, TriggerOnTheSpeedOfAFixedBody) {
  expect_fixed_scene_error({{R"(tau_c = { constant = "100*Nm" })", R"(tau_c = { table = [[0, "100*Nm"]], when = "omega_r > 5*rad/s" })"}}, 
      R"~(scene.toml:9:43: error: 'r' is fixed to the housing: its speed is zero and crosses nothing; give a body that turns)~");
}

}  // namespace
}  // namespace pogear::test
