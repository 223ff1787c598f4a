// The Campbell diagram against the Willis equations written here: the operating line's speeds,
// each mesh's tooth-passing frequency, and every crossing with a natural frequency. `pogear modes
// --campbell`: tests/commands/campbell_test.cpp.
#include <cmath>
#include <stdexcept>
#include <string>

#include <gtest/gtest.h>

#include "vibration_support.hpp"
#include "vibrate/campbell.hpp"
#include "derive/engagement.hpp"

namespace pogear::test {
namespace {

// Ravigneaux set of models/ravigneaux.toml: small sun 30, large sun 36, ring 76 teeth.
constexpr double Z_ss = 30, Z_sl = 36, Z_r = 76;

// Large sun held, small sun driving. Willis for the train ss-ps-pl-r (two external meshes and an
// internal one): (w_r - w_c) = +Z_ss/Z_r (w_ss - w_c); for sl-pl-r: (w_r - w_c) = -Z_sl/Z_r (w_sl - w_c).
// With w_sl = 0 and w_ss = 1: w_c = Z_ss / (Z_ss + Z_sl). Every mesh of the set passes its teeth
// through the pinions of one carrier, so all mesh at Z_ss |w_ss - w_c| / 2 pi: Z_ss Z_sl / (Z_ss + Z_sl)
// per rev/s of the small sun.
// A low mode crossing near standstill (a 3 Hz mode at 2.6 rpm of an 8000 rpm axis) is counted,
// not listed, in the text, Markdown and LaTeX reports; the JSON keeps every crossing (issue 31,
// item 17).
TEST(Campbell, CrossingsNearStandstillAreCountedNotListed) {
  CampbellDiagram c;
  c.input = "s";
  c.max_rpm = 8000;
  c.natural_hz = {3, 1856};
  c.meshes.push_back(MeshLine{"ps", "s", 30, "housing", 30 * 1.0 / 60});
  c.crossings = {Crossing{{"ps"}, 1, 3, 2.6}, Crossing{{"ps"}, 1, 1856, 3712}};
  ASSERT_EQ(listed_crossings(c).size(), 1u);
  const std::string note = "1 crossing below 80 rpm (1 % of the axis) is not listed";
  const std::string tex_note = "1 crossing below 80 rpm (1 \\% of the axis) is not listed";
  for (const auto& [report, expected] : {std::pair{campbell_text(c), note}, std::pair{campbell_markdown(c), note},
                                         std::pair{campbell_latex(c), tex_note}}) {
    EXPECT_EQ(report.find("2.6"), std::string::npos) << report;
    EXPECT_NE(report.find("3712"), std::string::npos) << report;
    EXPECT_NE(report.find(expected), std::string::npos) << report;
  }
  const std::string json = campbell_json_member(c);
  EXPECT_NE(json.find("\"input_rpm\": 2.6"), std::string::npos) << json;
}

TEST(Campbell, RavigneauxLineAndMeshFrequenciesFollowTheWillisEquations) {
  const Derivation d = ravigneaux();
  const VibrationModes modes = vibration_modes(d, d.values, "none");
  const CampbellDiagram c = campbell_diagram(d, d.values, modes, {}, body(d, "ss"), {body(d, "sl")}, 0, 3);
  const double w_c = Z_ss / (Z_ss + Z_sl);
  // The line is solved exactly and rounded once: the speeds are the correctly rounded ratios.
  EXPECT_DOUBLE_EQ(c.speeds(body(d, "ss")), 1);
  EXPECT_EQ(c.speeds(body(d, "sl")), 0);
  EXPECT_DOUBLE_EQ(c.speeds(body(d, "c")), w_c);
  EXPECT_DOUBLE_EQ(c.speeds(body(d, "r")), Z_ss * (Z_r + Z_sl) / (Z_r * (Z_ss + Z_sl)));
  ASSERT_EQ(c.meshes.size(), d.topology.meshes.size());
  EXPECT_TRUE(c.without_teeth.empty());
  const double expected = Z_ss * Z_sl / (Z_ss + Z_sl) / 60;  // Hz per rpm
  for (const MeshLine& m : c.meshes) {
    EXPECT_EQ(m.frame, "c") << m.mesh;
    // Z |w - w_c| / 60 from one ratio and a subtraction: within a few ulps of the exact value.
    EXPECT_NEAR(m.hz_per_rpm / expected, 1, 1e-14) << m.mesh;
  }
  // The default axis reaches the slowest first harmonic to 1.2 times the highest natural frequency.
  ASSERT_FALSE(c.natural_hz.empty());
  EXPECT_NEAR(c.max_rpm, 1.2 * c.natural_hz.back() / expected, 1e-9 * c.max_rpm);
  // Every crossing: a harmonic of a mesh line at a natural frequency, each one found once.
  // All four meshes pass teeth alike: one line, whose crossings name them all.
  std::size_t count = 0;
  for (int h = 1; h <= 3; ++h)
    for (double f : c.natural_hz) count += f / (h * expected) <= c.max_rpm;
  EXPECT_EQ(c.crossings.size(), count);
  for (std::size_t i = 0; i < c.crossings.size(); ++i) {
    const Crossing& x = c.crossings[i];
    EXPECT_NEAR(x.harmonic * expected * x.input_rpm / x.natural_hz, 1, 1e-12);
    EXPECT_EQ(x.meshes, (std::vector<std::string>{"ssps", "pspl", "plsl", "plr"}));
    if (i > 0) {
      EXPECT_LE(c.crossings[i - 1].input_rpm, x.input_rpm);
    }
  }
}

// Carrier held: an ordinary gear train, the small sun's mesh at Z_ss per revolution of it.
TEST(Campbell, CarrierHeldMeshesAtTheSunsToothCount) {
  const Derivation d = ravigneaux();
  const VibrationModes modes = vibration_modes(d, d.values, "none");
  const CampbellDiagram c = campbell_diagram(d, d.values, modes, {}, body(d, "ss"), {body(d, "c")}, 6000, 2);
  EXPECT_DOUBLE_EQ(c.speeds(body(d, "r")), Z_ss / Z_r);
  EXPECT_DOUBLE_EQ(c.speeds(body(d, "sl")), -Z_ss / Z_sl);
  for (const MeshLine& m : c.meshes) EXPECT_NEAR(m.hz_per_rpm / (Z_ss / 60), 1, 1e-14) << m.mesh;
  EXPECT_EQ(c.max_rpm, 6000);
}

TEST(Campbell, OperatingLineMustBeOneDegreeOfFreedom) {
  const Derivation d = ravigneaux();
  const VibrationModes modes = vibration_modes(d, d.values, "none");
  try {
    campbell_diagram(d, d.values, modes, {}, body(d, "ss"), {}, 0, 3);
    FAIL() << "two degrees of freedom accepted";
  } catch (const std::domain_error& e) {
    EXPECT_NE(std::string(e.what()).find("2 degrees of freedom"), std::string::npos) << e.what();
  }
}

}  // namespace
}  // namespace pogear::test
