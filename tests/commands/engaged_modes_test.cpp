// `pogear modes --engaged` names the engaged elements and gives the library's frequencies; a scene
// with brakes and clutches says which gear its modes and responses are of. The modes against
// references: tests/vibration/engaged_modes_test.cpp.
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "../support/json.hpp"
#include "../derive/test_support.hpp"
#include "derive/engagement.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear::test {
namespace {

TEST(EngagedModes, CommandLineNamesTheEngagedElementsAndGivesTheLibrarysFrequencies) {
  const std::string model = source_path("models/simpson_3speed.toml");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " modes " + model + " --engaged C1,B2 --format json");
  ASSERT_EQ(c.status, 0) << c.err;
  const Json j = parse_json(c.out);
  ASSERT_EQ(j["engaged"].size(), 2u);
  EXPECT_EQ(j["engaged"][0].str, "C1");
  EXPECT_EQ(j["engaged"][1].str, "B2");
  const Derivation d = derive_file("simpson_3speed");
  const VibrationModes m = vibration_modes(d, d.values, "as defined", parse_engaged(d.topology, "C1,B2", {}));
  ASSERT_EQ(j["modes"].size(), m.modes.size());
  for (std::size_t i = 0; i < m.modes.size(); ++i) {
    EXPECT_EQ(j["modes"][i]["frequency_hz"].num, m.modes[i].frequency_hz);  // shortest round trip
    EXPECT_EQ(j["modes"][i]["shape"].size(), d.topology.bodies.size());     // per body of the gear
  }
  const Command t = run_command(std::string(POGEAR_EXECUTABLE) + " modes " + model + " --engaged C1,B2");
  ASSERT_EQ(t.status, 0) << t.err;
  EXPECT_NE(t.out.find("engaged (stuck): C1, B2"), std::string::npos) << t.out;
}

// A scene's brakes and clutches switch, so its modes and responses are of one gear only when
// --engaged names it; without it they are of the free gear, and the command says so. The summary
// of derive --engaged gives that gear's lowest frequency.
TEST(EngagedModes, SceneWithBrakesAndClutchesSaysWhichGearItsModesAndResponsesAreOf) {
  const std::string scene = source_path("models/scenes/simpson_1_2_upshift.toml");
  const std::string exe(POGEAR_EXECUTABLE);
  const Command free_modes = run_command(exe + " modes " + scene);
  ASSERT_EQ(free_modes.status, 0) << free_modes.err;
  EXPECT_NE(free_modes.err.find("warning: the scene's brakes and clutches (C1, B1, B2) are open in these modes: they "
                                "are of the free gear, not of a gear the scene engages; give --engaged with the "
                                "elements that hold, e.g. --engaged C1"),
            std::string::npos)
      << free_modes.err;
  const Command first = run_command(exe + " modes " + scene + " --engaged C1,B2");
  ASSERT_EQ(first.status, 0) << first.err;
  EXPECT_EQ(first.err, "");
  const auto dir = temp_dir("engaged_response");
  const Command free_response = run_command(exe + " response " + scene + " --input tau_i --output omega_o -o " +
                                            (dir / "free").string());
  ASSERT_EQ(free_response.status, 0) << free_response.err;
  EXPECT_NE(free_response.err.find("are open in these responses"), std::string::npos) << free_response.err;
  const Command response = run_command(exe + " response " + scene + " --input tau_i --output omega_o --engaged C1,B2 -o " +
                                       (dir / "first").string());
  ASSERT_EQ(response.status, 0) << response.err;
  EXPECT_EQ(response.err, "");
  EXPECT_NE(response.out.find("resonance peak"), std::string::npos) << response.out;

  const Derivation d = derive_file("simpson_3speed");
  const double first_gear =
      vibration_modes(d, d.values, "as defined", parse_engaged(d.topology, "C1,B2", {})).modes[1].frequency_hz;
  const Command derive = run_command(exe + " derive " + source_path("models/simpson_3speed.toml") +
                                     " --engaged C1,B2 --keep i");
  ASSERT_EQ(derive.status, 0) << derive.err;
  EXPECT_NE(derive.out.find(fmt::format("lowest natural frequency {:.6g} Hz (undamped elastic model, C1, B2 engaged)",
                                        first_gear)),
            std::string::npos)
      << derive.out;
}

}  // namespace
}  // namespace pogear::test
