// `pogear modes --campbell`: the SVG and the JSON member against the library's diagram, and a held
// body held in the natural frequencies the harmonics meet. The diagram against the Willis
// equations: tests/vibration/campbell_test.cpp.
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "../support/json.hpp"
#include "../vibration/vibration_support.hpp"
#include "vibrate/campbell.hpp"
#include "derive/engagement.hpp"

namespace pogear::test {
namespace {

// The command: the SVG (a whole document, every mesh in its legend) and the JSON member.
TEST(Campbell, CommandDrawsTheDiagramAndReportsTheCrossings) {
  const auto dir = test_dir("campbell");
  const std::string svg = (dir / "campbell.svg").string();
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " modes " + source_path("models/ravigneaux.toml") +
                                " --campbell " + svg + " --input ss --hold sl --format json");
  ASSERT_EQ(c.status, 0) << c.err;
  const std::string figure = read_text(svg);
  EXPECT_NE(figure.find("<svg"), std::string::npos);
  EXPECT_NE(figure.find("</svg>"), std::string::npos);
  EXPECT_NE(figure.find("meshes ssps, pspl, plsl, plr, 1x"), std::string::npos);
  const Json j = parse_json(c.out);
  const Json& campbell = j["campbell"];
  EXPECT_EQ(campbell["input"].str, "ss");
  EXPECT_EQ(campbell["meshes"].size(), 4u);
  const Derivation d = ravigneaux();
  // The held gear's modes: the large sun stands still on the line (AHeldBodyIsHeldInTheNaturalFrequencies).
  const VibrationModes modes = vibration_modes(d, d.values, "none", {}, {body(d, "sl")});
  const CampbellDiagram direct = campbell_diagram(d, d.values, modes, {}, body(d, "ss"), {body(d, "sl")}, 0, 3);
  ASSERT_EQ(campbell["crossings"].size(), direct.crossings.size());
  for (std::size_t i = 0; i < direct.crossings.size(); ++i) {
    EXPECT_EQ(campbell["crossings"][i]["input_rpm"].num, direct.crossings[i].input_rpm);
    EXPECT_EQ(campbell["crossings"][i]["meshes"].size(), 4u);
  }
}

// A held body stands still, so the natural frequencies a harmonic meets on the line are those of
// the gear with that body held: the same as with a brake on it engaged (modes --engaged), not the
// free gear's. With sl held they are 1856.0 and 1987.2 Hz, which scipy's eigenproblem of the
// constrained gear gave too.
TEST(Campbell, AHeldBodyIsHeldInTheNaturalFrequencies) {
  const auto dir = test_dir("campbell_held");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " modes " + source_path("models/ravigneaux.toml") +
                                " --campbell " + (dir / "c.svg").string() + " --input ss --hold sl --to 8000*rpm");
  ASSERT_EQ(c.status, 0) << c.err;
  EXPECT_NE(c.out.find("natural frequencies of the gear with sl held [Hz]: 1855.99, 1987.17,"), std::string::npos)
      << c.out;

  std::string text = read_text(source_path("models/ravigneaux.toml"));
  const std::size_t at = text.find("[parameters]");
  ASSERT_NE(at, std::string::npos);
  text.insert(at, "[[brake]]\nname = \"hold\"\nbody = \"sl\"\ncapacity = \"T_hold\"\n\n");
  text += "\nT_hold = \"100*N*m\"\n";
  const Derivation braked =
      derive_topology(parse_topology_text(text, "braked.toml"), std::nullopt, SourceLocation{"braked.toml", 0, 0});
  const VibrationModes engaged = vibration_modes(braked, braked.values, "none", {0});
  std::vector<double> expected;
  for (const VibrationMode& m : engaged.modes)
    if (m.kind != ModeKind::rigid && (expected.empty() || m.frequency_hz > expected.back() * (1 + degenerate_tolerance)))
      expected.push_back(m.frequency_hz);
  ASSERT_GE(expected.size(), 2u);
  EXPECT_NEAR(expected[0], 1856.0, 0.05);
  EXPECT_NEAR(expected[1], 1987.2, 0.05);

  const Derivation d = ravigneaux();
  const VibrationModes held = vibration_modes(d, d.values, "none", {}, {body(d, "sl")});
  EXPECT_EQ(held.held, std::vector<std::string>{"sl"});
  const CampbellDiagram line = campbell_diagram(d, d.values, held, {}, body(d, "ss"), {body(d, "sl")}, 8000, 1);
  ASSERT_EQ(line.natural_hz.size(), expected.size());
  // The same eigenproblem reached two ways (a brake's group, a held body's): equal to rounding.
  for (std::size_t i = 0; i < expected.size(); ++i) EXPECT_NEAR(line.natural_hz[i], expected[i], 1e-9 * expected[i]);
  const double hz_per_rpm = line.meshes.front().hz_per_rpm;
  ASSERT_GE(line.crossings.size(), 2u);
  EXPECT_NEAR(line.crossings[0].input_rpm, expected[0] / hz_per_rpm, 1e-9 * line.crossings[0].input_rpm);
  EXPECT_NEAR(line.crossings[0].input_rpm, 6805.3, 0.05);
  EXPECT_NEAR(line.crossings[1].input_rpm, 7286.3, 0.05);
}

}  // namespace
}  // namespace pogear::test
