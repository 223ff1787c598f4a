// Brakes' and clutches' temperatures ([thermal], temp_<element> in the CSV): against the closed
// form of a constant heat flow, against the heat itself without cooling, and at two sample periods
// against the error the runtime states for a heat flow that varies within a period.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

Csv simulate_interpreted(const fs::path& dir, const std::string& scene, const std::string& name) {
  fs::create_directories(dir);
  write_text(dir / "scene.toml", scene);
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() +
                                " --interpreted -o " + (dir / "out").string());
  EXPECT_EQ(c.status, 0) << c.err;
  return read_csv((dir / "out" / (name + ".csv")).string());
}

// The ring of the paper's one-stage gear (rigid, no bearing friction) turning at 100 rad/s against
// a brake of 50 N m capacity fully applied, driven by 50 N m: the brake's torque balances the input,
// so the speeds hold and the brake takes a constant 5 kW. With C = 1000 J/K and G = 10 W/K
// (tau = 100 s) from 20 degC (given as 293.15 K) to an ambient of 80 degC the temperature is
// T = 80 + (20 - 80) e^(-t/tau) + (P/G) (1 - e^(-t/tau)).
TEST(Thermal, ConstantHeatFlowFollowsTheClosedForm) {
  const fs::path dir = temp_dir("thermal_constant");
  write_text(dir / "gear.toml", with_edits(read_text(source_path("tests/errors/gear.toml")),
                                           {{"[parameters]", "[[brake]]\nname = \"B1\"\nbody = \"r\"\n\n[parameters]"},
                                            {"b_c = \"0.08*Nm/rpm\"", "b_c = \"0.08*Nm/rpm\"\nTcap_B1 = \"50*N*m\""}}));
  const Csv csv = simulate_interpreted(
      dir,
      "name = \"hot\"\nmodel = \"gear.toml\"\neffects = []\nkeep = [\"c\", \"r\"]\n"
      "[inputs]\ntau_r = \"50*Nm\"\n[initial]\nomega_c = \"0*rad/s\"\nomega_r = \"100*rad/s\"\n"
      "[engagement]\nB1 = \"1\"\n"
      "[thermal]\nB1 = { heat_capacity = \"1000*J/K\", conductance = \"10*W/K\", ambient = \"80*degC\", initial = \"293.15*K\" }\n"
      "[simulation]\nhorizon = \"2*s\"\nsample = \"1*ms\"\nsolver = \"exact\"\n",
      "hot");
  const std::size_t t = csv.column("t"), T = csv.column("T_B1"), slip = csv.column("slip_B1"), temp = csv.column("temp_B1");
  ASSERT_LT(temp, csv.header.size());
  EXPECT_EQ(csv.header[temp], "temp_B1 [degC]");
  ASSERT_EQ(csv.rows.size(), 2001u);
  // The premise: the brake slips at 100 rad/s with 50 N m throughout (rounding of the balance).
  for (const auto& row : csv.rows) {
    ASSERT_NEAR(std::abs(row[T]), 50.0, 1e-9);
    ASSERT_NEAR(std::abs(row[slip]), 100.0, 1e-9);
  }
  const double P = 5000, G = 10, tau = 100;
  for (const auto& row : csv.rows) {
    const double decay = std::exp(-row[t] / tau);
    const double closed = 80 + (20 - 80) * decay + P / G * (1 - decay);
    // Exact for a constant power over each period; what is left is the rounding of 2000 updates
    // (and of 293.15 K - 273.15), some 1e-12 K.
    EXPECT_NEAR(row[temp], closed, 1e-9) << row[t];
  }
}

// The shipped Simpson upshift with temperatures on B1 and B2: without cooling a temperature is its
// start plus the element's heat over its heat capacity, to rounding, however the power varies. With
// cooling (tau = 10 s), the runs at 1 ms and at 0.1 ms agree within the error the runtime states for
// a power varying within a period: h / (2 tau) of the heat's own rise E / C, for each run.
TEST(Thermal, HeatWithoutCoolingAndTheStatedErrorWithCooling) {
  const fs::path dir = temp_dir("thermal_shift");
  auto scene = [&](const std::string& sample) {
    return with_edits(read_text(source_path("models/scenes/simpson_1_2_upshift.toml")),
                      {{"\"../simpson_3speed.toml\"", "\"" + source_path("models/simpson_3speed.toml") + "\""},
                       {"\"simpson_B2_release.csv\"", "\"" + source_path("models/scenes/simpson_B2_release.csv") + "\""},
                       {"\"simpson_B1_apply.csv\"", "\"" + source_path("models/scenes/simpson_B1_apply.csv") + "\""},
                       {"compare_rigid = true", "compare_rigid = false"},
                       {"sample = \"1*ms\"", "sample = \"" + sample + "\""}}) +
           "\n[thermal]\nB1 = { heat_capacity = \"500*J/K\", conductance = \"50*W/K\", ambient = \"90*degC\" }\n"
           "B2 = { heat_capacity = \"300*J/K\", ambient = \"90*degC\", initial = \"70*degC\" }\n";
  };
  const Csv coarse = simulate_interpreted(dir / "coarse", scene("1*ms"), "simpson_1_2_upshift");
  const Csv fine = simulate_interpreted(dir / "fine", scene("0.1*ms"), "simpson_1_2_upshift");
  const std::size_t t = coarse.column("t"), E1 = coarse.column("E_B1"), E2 = coarse.column("E_B2"),
                    T1 = coarse.column("temp_B1"), T2 = coarse.column("temp_B2");
  ASSERT_LT(T2, coarse.header.size());
  ASSERT_GT(coarse.rows.back()[E1], 100.0);  // the premise: B1 takes its inertia phase's heat
  for (const auto& row : coarse.rows) EXPECT_NEAR(row[T2], 70 + row[E2] / 300, 1e-9) << row[t];  // rounding
  ASSERT_EQ(fine.rows.size(), 10 * (coarse.rows.size() - 1) + 1);
  double largest = 0;
  for (std::size_t i = 0; i < coarse.rows.size(); ++i) {
    const auto& a = coarse.rows[i];
    const auto& b = fine.rows[10 * i];
    ASSERT_NEAR(a[t], b[t], 1e-12);
    const double rise = a[E1] / 500, bound = (1e-3 + 1e-4) / (2 * 10) * rise;
    EXPECT_LE(std::abs(a[T1] - b[T1]), bound + 1e-9) << a[t];
    largest = std::max(largest, std::abs(a[T1] - b[T1]));
  }
  EXPECT_GT(largest, 0.0);  // the two runs do differ: the bound is what they are held to
}

}  // namespace
}  // namespace pogear::test
