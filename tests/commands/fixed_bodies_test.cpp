// `pogear simulate` and `pogear ratios` of a gear with a fixed ring against the same gear whose ring
// a brake holds for the whole run: one gear, every speed and mesh force alike, with no brake to list.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const auto at = text.find(from);
  EXPECT_NE(at, std::string::npos) << from;
  if (at != std::string::npos) text.replace(at, from.size(), to);
  return text;
}

// models/gearshift_planetary.toml with its ring fixed: no brake or clutch, one degree of freedom.
std::string fixed_ring_model() {
  std::string text = read_text(source_path("models/gearshift_planetary.toml"));
  text = replaced(text, "name = \"r\"                        # ring", "name = \"r\"\nfixed = true");
  text = replaced(text, "keep = [\"s\", \"c\"]", "keep = [\"s\"]");
  text.erase(text.find("[[brake]]"), text.find("[parameters]") - text.find("[[brake]]"));
  return text;
}

// The engine drives the sun against a load on the carrier from rest, meshes elastic and damped.
std::string scene(const std::string& model, const std::string& engagement) {
  return "name = \"run\"\nmodel = \"" + model + "\"\n"
         "effects = [\"mesh_compliance\", \"mesh_damping\", \"mesh_forces\"]\ncompare_rigid = true\n"
         "[inputs]\ntau_s = \"20*Nm\"\ntau_c = \"-10*Nm\"\n" + engagement +
         "[simulation]\nhorizon = \"0.2*s\"\nsample = \"1*ms\"\nsolver = \"exact\"\n";
}

TEST(FixedRing, SimulatesAsTheRingItsBrakeHoldsThroughout) {
  const fs::path dir = temp_dir("fixed_ring");
  write_text(dir / "fixed.toml", fixed_ring_model());
  // The brake's capacity far above the ~30 N m the ring carries here, so that it never slips.
  write_text(dir / "braked.toml", replaced(read_text(source_path("models/gearshift_planetary.toml")),
                                           "Tcap_brake = \"100*N*m\"", "Tcap_brake = \"1e5*N*m\""));
  write_text(dir / "fixed_scene.toml", scene("fixed.toml", ""));
  write_text(dir / "braked_scene.toml", scene("braked.toml", "[engagement]\nbrake = \"1\"\nclutch = \"0\"\n"));
  for (const std::string which : {"fixed", "braked"}) {
    const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / (which + "_scene.toml")).string() +
                                  " --interpreted -o " + (dir / which).string());
    ASSERT_EQ(c.status, 0) << c.err;
  }
  for (const std::string suffix : {"", ".rigid"}) {
    SCOPED_TRACE(suffix);
    const Csv fixed = read_csv((dir / "fixed" / ("run" + suffix + ".csv")).string());
    const Csv braked = read_csv((dir / "braked" / ("run" + suffix + ".csv")).string());
    // The fixed ring has no speed column; the braked one's stays 0 (stuck from the start).
    EXPECT_EQ(std::find(fixed.header.begin(), fixed.header.end(), "omega_r [rad/s]"), fixed.header.end());
    ASSERT_EQ(fixed.rows.size(), braked.rows.size());
    ASSERT_EQ(fixed.rows.size(), 201u);
    for (std::size_t col = 0; col < fixed.header.size(); ++col) {
      const auto other = std::find(braked.header.begin(), braked.header.end(), fixed.header[col]);
      ASSERT_NE(other, braked.header.end()) << fixed.header[col];
      const std::size_t k = static_cast<std::size_t>(other - braked.header.begin());
      double scale = 0, gap = 0;
      for (std::size_t i = 0; i < fixed.rows.size(); ++i) {
        scale = std::max(scale, std::abs(braked.rows[i][k]));
        gap = std::max(gap, std::abs(fixed.rows[i][col] - braked.rows[i][k]));
      }
      // Two exact steppings of one linear system, assembled differently (the braked one's stuck
      // mode projects the ring out): matrix exponentials equal to ~1e-15, grown over 200 steps.
      EXPECT_LE(gap, 1e-11 * std::max(scale, 1e-300)) << fixed.header[col];
      EXPECT_GT(scale, 0) << fixed.header[col];
    }
  }
}

TEST(FixedRing, RatiosListNoBrakeForTheFixedRing) {
  const fs::path dir = temp_dir("fixed_ring_ratios");
  write_text(dir / "fixed.toml", fixed_ring_model());
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " ratios " + (dir / "fixed.toml").string() +
                                " --input s --output c --format json");
  ASSERT_EQ(c.status, 0) << c.err;
  // One set, nothing engaged, the reduction of Modelica's example: 1 / (1 + 75/50) = 0.4, from radii
  // in mm (doubles): to a few 1e-17.
  EXPECT_NE(c.out.find("\"engaged\": []"), std::string::npos) << c.out;
  const auto at = c.out.find("\"value\": ");
  ASSERT_NE(at, std::string::npos) << c.out;
  EXPECT_NEAR(std::stod(c.out.substr(at + 9)), 0.4, 1e-15);
}

}  // namespace
}  // namespace pogear::test
