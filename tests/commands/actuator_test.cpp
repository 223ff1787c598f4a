// Brake and clutch actuators of a scene ([actuators]): a ramped command through a fill delay and a
// first-order lag on one rigid body against its closed form, interpreted and compiled, and a delay
// alone, which exact stepping runs.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "../support/braked_wheels.hpp"
#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

// a spun at 150 rad/s; B's command ramps from 0 at 0.1 s to 1 at 0.2 s; its actuator as given.
fs::path simulate_actuated(const std::string& name, const std::string& actuator, const std::string& args) {
  const fs::path dir = temp_dir("actuator_" + name);
  fs::create_directories(dir);
  write_text(dir / "braked_wheels.toml", braked_wheels_model());
  write_text(dir / "scene.toml", "name = \"spin\"\nmodel = \"braked_wheels.toml\"\neffects = []\n[initial]\n"
                                 "omega_a = \"150*rad/s\"\n[engagement]\nB = { table = [[0, 0], [\"0.1*s\", 0], "
                                 "[\"0.2*s\", 1]] }\n[actuators]\nB = " + actuator +
                                 "\n[simulation]\nhorizon = \"4.5*s\"\nsample = \"1*ms\"\ntolerance = 1e-10\n");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() + " " +
                                args + " -o " + (dir / "out").string());
  EXPECT_EQ(c.status, 0) << c.err;
  return dir / "out";
}

// With 20 ms of delay and a 50 ms lag tau the engagement starts at 0.12 s; over the ramp (slope s =
// 10/s, u = t - 0.12 <= T = 0.1 s) e = s (u - tau (1 - e^(-u/tau))), whose integral is I(u) = s (u^2/2
// - tau u + tau^2 (1 - e^(-u/tau))); after it e = 1 - (1 - e_T) e^(-v/tau) (v = u - T), integral
// I(T) + v - (1 - e_T) tau (1 - e^(-v/tau)). J w' = -c e: w = 150 - 40 int e, until it reaches 0.
double lagged_speed(double t, double tau) {
  const double s = 10, T = 0.1, u = t - 0.12;
  if (u <= 0) return 150;
  auto ramp_integral = [&](double x) { return s * (x * x / 2 - tau * x + tau * tau * (1 - std::exp(-x / tau))); };
  double integral = 0;
  if (u <= T) {
    integral = ramp_integral(u);
  } else {
    const double eT = s * (T - tau * (1 - std::exp(-T / tau))), v = u - T;
    integral = ramp_integral(T) + v - (1 - eT) * tau * (1 - std::exp(-v / tau));
  }
  return std::max(150 - 40 * integral, 0.0);
}

// The run's largest speed error, its heat at the end and its lock time (B slipping -> stuck).
struct Measured {
  double worst = 0, heat = 0, lock = 0;
};
Measured measure(const fs::path& out, double tau) {
  Measured m;
  const Csv csv = read_csv((out / "spin.csv").string());
  const std::size_t t = csv.column("t"), w = csv.column("omega_a"), E = csv.column("E_B");
  EXPECT_LT(E, csv.header.size());
  EXPECT_EQ(csv.rows.size(), 4501u);
  if (E >= csv.header.size()) return m;
  for (const auto& row : csv.rows) m.worst = std::max(m.worst, std::abs(row[w] - lagged_speed(row[t], tau)));
  m.heat = csv.rows.back()[E];
  const std::string events = read_text(out / "spin.events.csv");
  const auto at = events.find(",B,slipping,stuck");
  EXPECT_NE(at, std::string::npos) << events;
  if (at != std::string::npos) m.lock = std::stod(events.substr(events.rfind('\n', at) + 1));
  return m;
}

// The lock time of the closed form, by bisection (the speed falls monotonically).
double lagged_lock(double tau) {
  double lo = 1, hi = 4.5;
  for (int i = 0; i < 200; ++i) (lagged_speed(0.5 * (lo + hi), tau) > 0 ? lo : hi) = 0.5 * (lo + hi);
  return hi;
}

void expect_lagged_closed_form(const std::string& solver, const std::string& path) {
  SCOPED_TRACE(solver + " " + path);
  const fs::path out = simulate_actuated(solver + (path.empty() ? "_compiled" : "_interpreted"),
                                         "{ fill_delay = \"20*ms\", time_constant = \"50*ms\" }", "--solver " + solver + " " + path);
  const Measured m = measure(out, 0.05);
  // At a relative tolerance of 1e-10, as the same motion in the runtime's tests
  // (Actuator.TriggeredCommandLagsOnFromWhereTheEngagementWas): dopri5's global error about 1e-7
  // rad/s, TR-BDF2's (order 2) some 5e-6; the lock time off by that over the final 40 rad/s^2, the
  // heat (J w0^2 / 2 = 5625 J) by J w dw.
  const bool dopri5 = solver == "dopri5";
  EXPECT_LT(m.worst, dopri5 ? 3e-7 : 2e-5);
  EXPECT_NEAR(m.lock, lagged_lock(0.05), dopri5 ? 1e-9 : 5e-7);
  EXPECT_NEAR(m.heat, 5625, dopri5 ? 3e-6 : 1e-3);
}

TEST(Actuators, RampThroughDelayAndLagFollowsTheClosedForm) {
  for (const std::string solver : {"dopri5", "implicit"}) expect_lagged_closed_form(solver, "--interpreted");
}

// Compiled: the generated friction_elements() carries the actuator to the same engine.
TEST(Actuators, CompiledRampThroughDelayAndLagFollowsTheClosedForm) { expect_lagged_closed_form("dopri5", ""); }

// A delay alone keeps the engagement piecewise linear: the scene stays with exact stepping, and w =
// 150 - 40 (int e) is piecewise quadratic, the ramp's integral 0.05 s from 0.12 s to 0.22 s, locking
// at 0.22 + (150 - 40 * 0.05) / 40 s, to the rounding of the exact flow.
TEST(Actuators, FillDelayAloneRunsExact) {
  const fs::path out = simulate_actuated("delay_exact", "{ fill_delay = \"20*ms\" }", "--interpreted");
  const std::string events = read_text(out / "spin.events.csv");
  const Measured m = measure(out, 0);
  const double lock = 0.22 + (150 - 40 * 0.05) / 40;
  EXPECT_NEAR(m.lock, lock, 1e-12 * lock);
  EXPECT_LT(m.worst, 1e-10);  // the exact flow's rounding over 4500 steps of 150 rad/s
  EXPECT_NEAR(m.heat, 5625, 1e-8);
  // B engages at 0.1 s + 20 ms, as the doubles add them (0.12000000000000001).
  const auto at = events.find(",B,open,slipping");
  ASSERT_NE(at, std::string::npos) << events;
  EXPECT_NEAR(std::stod(events.substr(events.rfind('\n', at) + 1)), 0.12, 2e-17);
}

}  // namespace
}  // namespace pogear::test
