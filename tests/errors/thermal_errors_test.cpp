// Brakes' and clutches' temperatures ([thermal]) refused where the scene cannot mean them: checked
// to the character against docs/errors.md.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// B1 (brake on the ring) applied throughout; [thermal] after it.
const std::string applied = "B1 = \"1\"\n\n[thermal]\n";

TEST_F(EngagementCommands, ThermalOfNoElement) {
  expect_error(applied + "B9 = { heat_capacity = \"800*J/K\", ambient = \"90*degC\" }\n", 
               R"~(scene.toml:25:6: error: 'B9' is no brake or clutch of the model (it has B1, C1); [thermal] gives an element's heat capacity and cooling)~");
}
TEST_F(EngagementCommands, ThermalWithoutAmbient) {
  expect_error(applied + "B1 = { heat_capacity = \"800*J/K\" }\n", 
               R"~(scene.toml:25:6: error: [thermal] B1 needs heat_capacity (e.g. "800*J/K") and ambient (e.g. "90*degC"); conductance (W/K, default 0: no cooling) and initial (default: ambient) are optional)~");
}
TEST_F(EngagementCommands, ThermalUnknownKey) {
  expect_error(applied + "B1 = { heat_capacity = \"800*J/K\", ambient = \"90*degC\", mass = \"2*kg\" }\n", 
               R"~(scene.toml:25:56: error: unknown key 'mass' in [thermal] B1; the keys are heat_capacity, conductance, ambient, initial)~");
}
TEST_F(EngagementCommands, ThermalCapacityInJoules) {
  expect_error(applied + "B1 = { heat_capacity = \"800*J\", ambient = \"90*degC\" }\n", 
               R"~(scene.toml:25:24: error: heat_capacity has unit kg*m^2/s^2; it needs kg*m^2/(s^2*K))~");
}
TEST_F(EngagementCommands, ThermalCapacityNotPositive) {
  expect_error(applied + "B1 = { heat_capacity = \"0*J/K\", ambient = \"90*degC\" }\n", 
               R"~(scene.toml:25:24: error: heat_capacity is above zero: the element's heat raises its temperature)~");
}
TEST_F(EngagementCommands, ThermalConductanceNegative) {
  expect_error(applied + "B1 = { heat_capacity = \"800*J/K\", conductance = \"-1*W/K\", ambient = \"90*degC\" }\n", 
               R"~(scene.toml:25:49: error: conductance is not negative: the element loses heat to the ambient)~");
}
TEST_F(EngagementCommands, ThermalTemperatureWithoutUnit) {
  expect_error(applied + "B1 = { heat_capacity = \"800*J/K\", ambient = \"90\" }\n", 
               R"~(scene.toml:25:45: error: ambient needs a unit of temperature, degC or K (not both), e.g. "90*degC")~");
}
TEST_F(EngagementCommands, ThermalBelowAbsoluteZero) {
  expect_error(applied + "B1 = { heat_capacity = \"800*J/K\", ambient = \"90*degC\", initial = \"-300*degC\" }\n", 
               R"~(scene.toml:25:66: error: initial is at or below absolute zero)~");
}
TEST_F(EngagementCommands, ThermalOfAnOpenElement) {
  expect_error("C1 = \"1\"\n\n[thermal]\nB1 = { heat_capacity = \"800*J/K\", ambient = \"90*degC\" }\n", 
               R"~(scene.toml:25:6: error: the scene does not engage B1, so it never heats; give B1 a command in [engagement], or drop it from [thermal])~");
}

}  // namespace
}  // namespace pogear::test
