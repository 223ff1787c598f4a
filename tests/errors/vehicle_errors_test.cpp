// A scene's [vehicle] that cannot be: a key missing, a body it cannot drive from, drag half given,
// a second road load, a jerk the run cannot give.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// scene.toml with a car on the ring r of gear.toml (its half-shafts compliant like the meshes).
const std::string vehicle_table =
    "[vehicle]\nbody = \"r\"\nmass = \"1500*kg\"\nwheel_radius = \"0.3*m\"\nfinal_drive = 3.2\n"
    "half_shaft_stiffness = \"12000*N*m/rad\"\n";
const Edits with_vehicle{{R"("mesh_compliance", "mesh_damping", )", R"("mesh_compliance", "shaft_compliance", "mesh_damping", )"},
                         {"[simulation]", vehicle_table + "\n[simulation]"}};

class VehicleErrors : public ErrorTest {};

TEST_F(VehicleErrors, WithoutHalfShafts) {
  expect_scene_error(with(with_vehicle, {{"half_shaft_stiffness = \"12000*N*m/rad\"\n", ""}}),
      R"~(scene.toml:14:1: error: [vehicle] needs half_shaft_stiffness, e.g. half_shaft_stiffness = "12000*N*m/rad")~");
}

TEST_F(VehicleErrors, OnAPlanet) {
  expect_scene_error(with(with_vehicle, {{"body = \"r\"", "body = \"p\""}}),
      R"~(scene.toml:15:8: error: [vehicle] body 'p' is not on the central axis; the half-shafts turn with a body on it)~");
}

TEST_F(VehicleErrors, DragWithoutFrontalArea) {
  expect_scene_error(with(with_vehicle, {{"final_drive = 3.2\n", "final_drive = 3.2\ndrag_coefficient = 0.3\n"}}),
      R"~(scene.toml:19:20: error: aerodynamic drag needs both drag_coefficient and frontal_area; give both, or neither)~");
}

TEST_F(VehicleErrors, LoadedTwice) {
  expect_scene_error(with(with_vehicle, {{"[simulation]", "[loads]\nvehicle = { constant = \"10*N*m\" }\n\n[simulation]"}}),
      R"~(scene.toml:22:11: error: [loads] names the vehicle, whose road load [vehicle] gives; leave it out of [loads])~");
}

TEST_F(VehicleErrors, JerkBesideTheRigidModel) {
  expect_scene_error(with(with_vehicle, {{"keep = [\"c\", \"r\"]", "keep = [\"c\", \"r\"]\noutputs = [\"vehicle_jerk\"]"}}),
      R"~(scene.toml:6:11: error: vehicle_jerk is an output of the elastic model only (the rigid model's acceleration jumps at every event and input step); drop compare_rigid, or vehicle_jerk)~");
}

TEST_F(VehicleErrors, JerkOfARigidModel) {
  expect_scene_error(with(with_vehicle, {{"keep = [\"c\", \"r\"]", "keep = [\"c\", \"r\"]\noutputs = [\"vehicle_jerk\"]"},
                                         {R"("mesh_compliance", "shaft_compliance", "mesh_damping", )", ""},
                                         {"compare_rigid = true\n", ""}}),
      R"~(scene.toml:6:11: error: vehicle_jerk is an output of the elastic model, where the half-shafts' twist smooths the car's acceleration; add shaft_compliance (and mesh_compliance) to effects, or drop vehicle_jerk)~");
}

TEST_F(VehicleErrors, JerkOfAnInputOnTheCar) {
  expect_scene_error(with(with_vehicle, {{"keep = [\"c\", \"r\"]", "keep = [\"c\", \"r\"]\noutputs = [\"vehicle_jerk\"]"},
                                         {"compare_rigid = true\n", ""},
                                         {"tau_c = { constant = \"100*Nm\" }", "tau_c = { constant = \"100*Nm\" }\ntau_vehicle = { ramp = \"10*N*m/s\" }"}}),
      R"~(scene.toml:6:11: error: vehicle_jerk would read the rate of tau_vehicle, which acts on the car's speed and is not constant; drop vehicle_jerk, or make the input constant)~");
}

TEST_F(VehicleErrors, GradeThatIsNeitherAnAngleNorATable) {
  expect_scene_error(with(with_vehicle, {{"final_drive = 3.2\n", "final_drive = 3.2\ngrade = { ramp = \"1*deg/s\" }\n"}}),
      R"~(scene.toml:19:9: error: grade is an angle, e.g. "3*deg", or { table = "file.csv" } with two columns: time [s], grade [deg])~");
}

TEST_F(VehicleErrors, GradeTableWrittenInTheScene) {
  expect_scene_error(with(with_vehicle, {{"final_drive = 3.2\n", "final_drive = 3.2\ngrade = { table = [[0, \"2*deg\"]] }\n"}}),
      R"~(scene.toml:19:19: error: a grade's table is a CSV file, { table = "grade.csv" } with two columns: time [s], grade [deg])~");
}

TEST_F(VehicleErrors, OutsideTheRange) {
  expect_scene_error(with(with_vehicle, {{"wheel_radius = \"0.3*m\"", "wheel_radius = \"1e120*m\""}}),
      R"~(scene.toml:14:1: error: [vehicle] makes J_vehicle = 1.46484e+242 (SI), outside the range pogear computes with, 1e-30 to 1e+30; check the vehicle's values and their units)~");
}

}  // namespace
}  // namespace pogear::test
