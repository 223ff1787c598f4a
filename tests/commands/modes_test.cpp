// `pogear derive` and `pogear modes`: the lowest natural frequency in the derive report, one JSON
// entry per mode with every field, and the same bytes in every format from separate processes. The
// modes against independent references: tests/vibration/modes_test.cpp.
#include <string>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "../support/json.hpp"
#include "../vibration/vibration_support.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear::test {
namespace {

TEST(Modes, LowestNaturalFrequencyIsInTheDeriveReport) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " derive " + source_path("models/three_planets.toml") +
                                " --format json");
  ASSERT_EQ(c.status, 0) << c.err;
  const Json j = parse_json(c.out);
  const Derivation d = derive_file("three_planets");
  EXPECT_EQ(j["diagnostics"]["lowest_natural_frequency_hz"].num, lowest_natural_frequency(d, d.values));
  const Command t = run_command(std::string(POGEAR_EXECUTABLE) + " derive " + source_path("models/three_planets.toml"));
  EXPECT_NE(t.out.find("lowest natural frequency "), std::string::npos) << t.out;
}

TEST(Modes, JsonHasOneEntryPerModeWithEveryField) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " modes " + source_path("models/three_planets.toml") +
                                " --format json");
  ASSERT_EQ(c.status, 0) << c.err;
  const Json j = parse_json(c.out);
  EXPECT_EQ(j["model"].str, "three_planets");
  const Json& modes = j["modes"];
  ASSERT_EQ(modes.size(), 6u);
  double previous = -1;
  int planet = 0;
  for (std::size_t i = 0; i < modes.size(); ++i) {
    const Json& m = modes[i];
    EXPECT_GE(m["frequency_hz"].num, previous);
    previous = m["frequency_hz"].num;
    EXPECT_EQ(m["shape"].size(), 6u);
    EXPECT_EQ(m["kinetic_energy"].size(), 6u);
    const std::string kind = m["kind"].str;
    EXPECT_TRUE(kind == "rigid" || kind == "planet" || kind == "elastic") << kind;
    if (kind == "rigid") {
      EXPECT_EQ(m["frequency_hz"].num, 0);
      EXPECT_EQ(m["damping_ratio"].kind, Json::null);
      EXPECT_EQ(m["strain_energy"].size(), 0u);
    } else {
      EXPECT_EQ(m["strain_energy"].size(), 6u);
      EXPECT_EQ(m["damping_ratio"].kind, Json::number);  // the model defines mesh damping
    }
    if (kind == "planet") {
      ++planet;
      EXPECT_EQ(m["multiplicity"].num, 2);
    }
  }
  EXPECT_EQ(planet, 2);
}

// Every format, in separate processes: the closed forms go through pogear's stable printer, so the
// bytes do not depend on GiNaC's hash order.
TEST(Modes, EveryFormatIsTheSameBytesInSeparateProcesses) {
  const auto dir = test_dir("modes_formats");
  write_text(dir / "simple.toml", simple_model);
  for (const std::string& model : {(dir / "simple.toml").string(), source_path("tests/errors/gear.toml")})
    for (const std::string format : {"text", "markdown", "latex", "json"}) {
      const std::string command = std::string(POGEAR_EXECUTABLE) + " modes " + model + " --format " + format;
      const Command a = run_command(command), b = run_command(command);
      ASSERT_EQ(a.status, 0) << a.err;
      EXPECT_TRUE(a.err.empty()) << a.err;
      EXPECT_EQ(a.out, b.out) << model << " " << format;
      EXPECT_NE(a.out.find("lambda"), std::string::npos) << format;  // the closed form or polynomial
    }
}

}  // namespace
}  // namespace pogear::test
