// Shafts ([[shaft]]) that cannot be: ending where no shaft turns, joining a body to itself or two
// fixed bodies, named like another torque, with the wrong units; and scenes that ask a shaft for an
// effect or output it cannot have.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// gear.toml with a load inertia on a shaft from the carrier c.
const std::string shaft_table = "[[shaft]]\nname = \"output\"\nbodies = [\"c\", \"load\"]\n\n";
const Edits with_shaft{{"[parameters]", "[[body]]\nname = \"load\"\n\n" + shaft_table +
                                            "[parameters]\nJ_load = \"0.5*kg*m^2\"\nb_load = \"0\"\n"
                                            "K_output = \"2e4*N*m/rad\"\nb_output = \"10*N*m*s/rad\""}};

class ShaftErrors : public ErrorTest {
 protected:
  void expect_shaft_scene_error(const Edits& edits, const std::string& expected) {
    expect_documented(scene_error(edited(base_scene(), edits), edited(base_model(), with_shaft)), expected);
  }
};

TEST_F(ShaftErrors, UnknownBody) {
  expect_model_error(with(with_shaft, {{R"(bodies = ["c", "load"])", R"(bodies = ["c", "wheel"])"}}),
      R"~(gear.toml:41:16: error: shaft 'output' names 'wheel', which is not a body; the bodies are c, p, s, r, g, load)~");
}

TEST_F(ShaftErrors, EndsAtAPlanet) {
  expect_model_error(with(with_shaft, {{R"(bodies = ["c", "load"])", R"(bodies = ["p", "load"])"}}),
      R"~(gear.toml:41:11: error: shaft 'output' ends at 'p', which turns about a planet axis; a shaft joins two bodies on the central axis (give a driveline body of its own, axis = "central"))~");
}

TEST_F(ShaftErrors, JoinsABodyToItself) {
  expect_model_error(with(with_shaft, {{R"(bodies = ["c", "load"])", R"(bodies = ["c", "c"])"}}),
      R"~(gear.toml:41:16: error: shaft 'output' joins body 'c' to itself; name two bodies)~");
}

TEST_F(ShaftErrors, NamedLikeAClutch) {
  expect_model_error(with(with_shaft, {{"[parameters]", "[[clutch]]\nname = \"output\"\nbodies = [\"s\", \"r\"]\n\n[parameters]"}}),
      R"~(gear.toml:40:8: error: shaft 'output' has the name of the clutch at line 44: both torques would be T_output; give the shaft another name)~");
}

TEST_F(ShaftErrors, StiffnessInNewtonsPerMetre) {
  expect_model_error(with(with_shaft, {{R"(K_output = "2e4*N*m/rad")", R"(K_output = "2e4*N/m")"}}),
      R"~(gear.toml:46:12: error: parameter 'K_output' is a shaft's torsional stiffness but has unit kg/s^2; it needs kg*m^2/s^2)~");
}

TEST_F(ShaftErrors, WithoutBodies) {
  expect_model_error(with(with_shaft, {{R"(bodies = ["c", "load"])", ""}}),
      R"~(gear.toml:39:1: error: shaft 'output' needs the two bodies it joins, e.g. bodies = ["out", "wheels"])~");
}

TEST_F(ShaftErrors, CompliantMeshesRigidShafts) {
  expect_shaft_scene_error({},
      R"~(scene.toml:4:11: error: mesh_compliance without shaft_compliance: pogear derives a gear whose meshes and shafts are both compliant or both rigid, not one of each; add shaft_compliance or drop mesh_compliance)~");
}

TEST_F(ShaftErrors, ShaftDampingWithoutCompliance) {
  expect_shaft_scene_error({{R"("mesh_compliance", "mesh_damping", )", R"("shaft_damping", )"}, {"compare_rigid = true\n", ""}},
      R"~(scene.toml:4:11: error: shaft_damping needs shaft_compliance: a rigid shaft has no twist to damp; add shaft_compliance or drop shaft_damping)~");
}

TEST_F(ShaftErrors, ShaftEffectWithoutShafts) {
  expect_scene_error({{R"("mesh_compliance", )", R"("mesh_compliance", "shaft_compliance", )"}},
      R"~(scene.toml:4:11: error: model gear has no [[shaft]], so shaft_compliance has nothing to act on; drop it)~");
}

TEST_F(ShaftErrors, SpringTorqueOfARigidShaft) {
  expect_shaft_scene_error({{R"("mesh_compliance", "mesh_damping", )", ""},
                            {"compare_rigid = true\n", "outputs = [\"omega_c\", \"Tspring_output\"]\n"}},
      R"~(scene.toml:6:11: error: output 'Tspring_output' is the spring's torque alone, which only a compliant shaft has; add shaft_compliance to effects, or ask for T_output, what the rigid shaft transmits)~");
}

}  // namespace
}  // namespace pogear::test
