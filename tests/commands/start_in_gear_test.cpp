// `pogear simulate` of scenes that start in a gear ([initial] gear = "1"): the shipped 6HP26 upshift
// starts stuck in 1st with no event and no transient, and a steady start in 1st stays where it is.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

Csv simulate(const fs::path& scene, const fs::path& dir, const std::string& suffix) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + scene.string() + " --interpreted -o " +
                                dir.string());
  EXPECT_EQ(c.status, 0) << c.err;
  return read_csv((dir / (scene.stem().string() + suffix + ".csv")).string());
}

double largest(const Csv& c, const std::vector<std::string>& columns) {
  double m = 0;
  for (const std::string& name : columns)
    for (const auto& row : c.rows) m = std::max(m, std::abs(row[c.column(name)]));
  return m;
}

TEST(StartInGear, ZF6HP26StartsStuckInFirstOnItsRigidModel) {
  const fs::path dir = temp_dir("start_in_gear");
  const fs::path scene = source_path("models/scenes/zf6hp26_1_2_upshift.toml");
  const Csv elastic = simulate(scene, dir, "");
  const Csv rigid = simulate(scene, dir, ".rigid");
  ASSERT_EQ(elastic.rows.size(), 801u);
  ASSERT_EQ(rigid.rows.size(), 801u);

  // No event before the first command changes, at 0.3 s: A and D start stuck and stay so.
  std::ifstream events(dir / "zf6hp26_1_2_upshift.events.csv");
  std::string line;
  std::getline(events, line);
  ASSERT_TRUE(std::getline(events, line));
  EXPECT_GE(std::stod(line), 0.3) << line;

  const std::vector<std::string> speeds{"omega_in", "omega_out", "omega_c1", "omega_s3", "omega_c2"};
  for (const Csv* c : {&elastic, &rigid}) {
    const auto& first = c->rows.front();
    // Bits of the stuck elements in model order A, C, D: A and D.
    EXPECT_EQ(first[c->column("mode")], 5);
    // The speeds are exact rationals rounded once (in rpm, ~2500): the slips are a few 1e-13 rpm.
    EXPECT_LE(std::abs(first[c->column("slip_A")]), 1e-9);
    EXPECT_LE(std::abs(first[c->column("slip_D")]), 1e-9);
    // 1st gear, i = omega_in / omega_out = 2 Z_r2 (Z_p1 + Z_s1) / (Z_s2 (2 Z_p1 + Z_s1)) = 9180/2201.
    EXPECT_NEAR(first[c->column("omega_in")] / first[c->column("omega_out")], 9180.0 / 2201, 1e-12);
  }
  // The stuck torques at t = 0, from the elastic state (its mesh forces eq. (8)'s) and from the rigid
  // model, each by the engine's own multipliers: one value, to the rounding of a few solves.
  for (const std::string element : {"T_A", "T_D"}) {
    const double a = elastic.rows.front()[elastic.column(element)];
    const double b = rigid.rows.front()[rigid.column(element)];
    EXPECT_NEAR(a, b, 1e-12 * std::abs(b)) << element;
    EXPECT_GT(std::abs(b), 100) << element;  // it carries the load: 295 and -511 N m
  }
  // No start-up transient: until the shift the elastic speeds follow the rigid ones to the
  // compliance's quasi-static deflection (~1e-8 of the speeds). From the same speeds with unloaded
  // meshes the input rings at 1 % of its speed.
  const double scale = largest(rigid, speeds);
  for (const std::string& name : speeds) {
    double gap = 0;
    for (std::size_t i = 0; i < 300; ++i)
      gap = std::max(gap, std::abs(elastic.rows[i][elastic.column(name)] - rigid.rows[i][rigid.column(name)]));
    EXPECT_LE(gap, 1e-6 * scale) << name;
  }
  // The same run from the same speeds, given: the meshes start unloaded, and the input rings.
  std::string text = read_text(scene);
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"gear = \"1\"", ""},
                                 {"name = \"zf6hp26_1_2_upshift\"", "name = \"given\""},
                                 {"\"../zf6hp26.toml\"", "\"" + source_path("models/zf6hp26.toml") + "\""},
                                 {"\"zf6hp26_D", "\"" + source_path("models/scenes/zf6hp26_D")},
                                 {"\"zf6hp26_C", "\"" + source_path("models/scenes/zf6hp26_C")},
                                 {"omega_in = \"2500*rpm\"", "omega_in = \"2500*rpm\"\nomega_out = \"" +
                                      std::to_string(rigid.rows.front()[rigid.column("omega_out")]) + "*rpm\""}})
    text.replace(text.find(from), from.size(), to);
  write_text(dir / "given.toml", text);
  const Csv given = simulate(dir / "given.toml", dir / "given", "");
  double gap = 0;
  for (std::size_t i = 0; i < 300; ++i)
    gap = std::max(gap, std::abs(given.rows[i][given.column("omega_in")] - rigid.rows[i][rigid.column("omega_in")]));
  EXPECT_GT(gap, 1e-3 * scale);
}

// The launch scene's engine and converter, started in 1st at 2000 rpm with the turbine at 1200 rpm
// (SR = 0.6, a table point): the converter's and the engine's torques at t = 0 enter the gear's
// rigid start, so A and D start stuck, and stay so with the throttle held.
TEST(StartInGear, EngineAndConverterStartInFirst) {
  const fs::path dir = temp_dir("driveline_in_gear");
  std::string text = read_text(source_path("models/scenes/zf6hp26_launch.toml"));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"{ step = 0.5, at = \"0.2*s\", before = 0.18 }", "0.5"},
                                 {"\"../zf6hp26.toml\"", "\"" + source_path("models/zf6hp26.toml") + "\""},
                                 {"\"zf6hp26_launch_", "\"" + source_path("models/scenes/zf6hp26_launch_")},
                                 {"\"zf6hp26_launch_", "\"" + source_path("models/scenes/zf6hp26_launch_")},
                                 {"\"zf6hp26_launch_", "\"" + source_path("models/scenes/zf6hp26_launch_")},
                                 {"omega_engine = \"750*rpm\"", "gear = \"1\"\nomega_engine = \"2000*rpm\"\nomega_in = \"1200*rpm\""},
                                 {"horizon = \"4*s\"", "horizon = \"0.5*s\""}}) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  write_text(dir / "zf6hp26_launch.toml", text);
  const Csv c = simulate(dir / "zf6hp26_launch.toml", dir, "");
  ASSERT_EQ(c.rows.size(), 251u);
  std::ifstream events(dir / "zf6hp26_launch.events.csv");
  std::string line;
  ASSERT_TRUE(std::getline(events, line));
  EXPECT_FALSE(std::getline(events, line)) << "an event: " << line;  // none within the run

  const auto& first = c.rows.front();
  EXPECT_EQ(first[c.column("mode")], 5);  // A and D stuck (bits of the commanded A, C, D, lockup)
  // The speeds are exact rationals rounded once (in rpm, ~2000): the slips are a few 1e-13 rpm.
  EXPECT_LE(std::abs(first[c.column("slip_A")]), 1e-9);
  EXPECT_LE(std::abs(first[c.column("slip_D")]), 1e-9);
  EXPECT_NEAR(first[c.column("omega_in")] / first[c.column("omega_out")], 9180.0 / 2201, 1e-12);
  // At t = 0, by hand from the tables: the map's 180 N m at (2000 rpm, 50 %); K(0.6) = 158 rpm/sqrt(N m),
  // so T_p = (2000/158)^2 N m, and TR(0.6) = 1.28. Table points: only the rounding of a few operations.
  const double pump = std::pow(2000.0 / 158, 2);
  EXPECT_NEAR(first[c.column("Tengine")], 180, 1e-12 * 180);
  EXPECT_NEAR(first[c.column("Tpump")], -pump, 1e-12 * pump);
  EXPECT_NEAR(first[c.column("Tturbine")], 1.28 * pump, 1e-12 * pump);
  // The engine accelerates at (Tengine + Tpump) / J_engine: over the first 2 ms sample the difference
  // quotient differs from it by the change of the torques (their slopes in the speeds, ~1e-3 of it).
  const double rpm = 0.10471975511965977;
  const double rate = (c.rows[1][c.column("omega_engine")] - first[c.column("omega_engine")]) * rpm / 2e-3;
  EXPECT_NEAR(rate, (180 - pump) / 0.22, 0.01 * (180 - pump) / 0.22);
}

// At equilibrium in 1st: the load's linear part against the drive, bearing friction on every body.
TEST(StartInGear, SteadyStartInFirstStaysPut) {
  const fs::path dir = temp_dir("steady_in_gear");
  const fs::path scene = dir / "steady.toml";
  write_text(scene, "name = \"steady\"\nmodel = \"" + source_path("models/zf6hp26.toml") +
                        "\"\neffects = [\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\", \"mesh_forces\"]\n"
                        "compare_rigid = true\n[inputs]\ntau_in = \"20*Nm\"\n"
                        "[loads]\nout = { constant = \"10*Nm\", linear = \"5*Nm*s/rad\" }\n"
                        "[engagement]\nA = \"1\"\nD = \"1\"\n[initial]\ngear = \"1\"\nstart = \"steady\"\n"
                        "[simulation]\nhorizon = \"0.2*s\"\nsample = \"1*ms\"\n");
  for (const std::string suffix : {"", ".rigid"}) {
    SCOPED_TRACE(suffix);
    const Csv c = simulate(scene, dir, suffix);
    ASSERT_EQ(c.rows.size(), 201u);
    EXPECT_EQ(c.rows.front()[c.column("mode")], 3);  // A and D, the only engaged elements
    EXPECT_GT(std::abs(c.rows.front()[c.column("omega_out")]), 1);  // it turns
    double speeds = 0;  // the largest speed: what speeds and slips at rest are rounded against
    for (std::size_t col = 1; col < c.header.size(); ++col)
      if (c.header[col].find("[rad/s]") != std::string::npos)
        for (const auto& row : c.rows) speeds = std::max(speeds, std::abs(row[col]));
    for (std::size_t col = 1; col < c.header.size(); ++col) {
      if (c.header[col].rfind("E_", 0) == 0) continue;  // stuck: no energy dissipated, 0 throughout
      double scale = c.header[col].find("[rad/s]") != std::string::npos ? speeds : 0, drift = 0;
      for (const auto& row : c.rows) {
        scale = std::max(scale, std::abs(row[col]));
        drift = std::max(drift, std::abs(row[col] - c.rows.front()[col]));
      }
      // The equilibrium solved exactly and rounded once: exact stepping keeps it to the rounding of
      // its matrix exponential over 200 steps (~1e-12 of the largest speed or force).
      EXPECT_LE(drift, 1e-9 * scale) << c.header[col];
    }
  }
}

}  // namespace
}  // namespace pogear::test
