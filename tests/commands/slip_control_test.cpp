// Slip controllers ([slip_control]): on a brake holding one rigid degree of freedom against the closed
// forms of its P and PI loops, its back-calculation against a wound-up integral at lock-up, and the
// hand-over to the element at lock-up.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

// tests/vibration/pair.toml, rigid with only a kept: J = J_a + J_b (r_a / r_b)^2, its brake Ba on a
// (slip omega_a, capacity C), driven by tau_a.
constexpr double kJ = 0.02 + 0.3 * (0.1 / 0.25) * (0.1 / 0.25), kC = 100, kTau = 30, kOmega0 = 100;

struct SlipRun {
  Csv csv;
  std::string events;
};

SlipRun simulate_slip(const std::string& tag, const std::string& control, const std::string& horizon = "3*s") {
  const fs::path dir = temp_dir(tag);
  write_text(dir / "pair.toml", read_text(source_path("tests/vibration/pair.toml")));
  write_text(dir / "scene.toml",
             "name = \"slip\"\nmodel = \"pair.toml\"\neffects = []\nkeep = [\"a\"]\n"
             "[inputs]\ntau_a = \"30*Nm\"\n[initial]\nomega_a = \"100*rad/s\"\n[engagement]\nBa = \"0\"\n"
             "[slip_control]\nBa = " + control + "\n"
             "[simulation]\nhorizon = \"" + horizon + "\"\nsample = \"1*ms\"\ntolerance = 1e-11\n");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() +
                                " --interpreted -o " + (dir / "out").string());
  EXPECT_EQ(c.status, 0) << c.err;
  return {read_csv((dir / "out" / "slip.csv").string()), read_text(dir / "out" / "slip.events.csv")};
}

// P only: J omega' = tau - C kp (omega - r), so omega settles at r + tau / (C kp), the steady-state
// error of a P loop, with the time constant J / (C kp).
TEST(SlipControl, PControllerSettlesAtItsSteadyStateError) {
  const double kp = 0.02, r = 80;
  const SlipRun run = simulate_slip("slip_p", "{ target = \"80*rad/s\", kp = \"0.02*s/rad\" }");
  const Csv& csv = run.csv;
  const std::size_t t = csv.column("t"), w = csv.column("omega_a"), T = csv.column("T_Ba"), Tc = csv.column("Tc_slip_Ba");
  ASSERT_LT(Tc, csv.header.size());
  ASSERT_EQ(csv.rows.size(), 3001u);
  const double settled = r + kTau / (kC * kp), tau = kJ / (kC * kp);
  for (const auto& row : csv.rows) {
    const double closed = settled + (kOmega0 - settled) * std::exp(-row[t] / tau);
    // dopri5 at 1e-11: some 1e-9 rad/s.
    EXPECT_NEAR(row[w], closed, 1e-7) << row[t];
    EXPECT_NEAR(row[T], kC * kp * (row[w] - r), 1e-9) << row[t];  // the element carries the controller's torque
    EXPECT_NEAR(row[Tc], row[T], 1e-9) << row[t];
  }
  EXPECT_NEAR(csv.rows.back()[w], settled, 1e-6);  // 95 rad/s: the P loop's error tau / (C kp) = 15 rad/s
}

// PI: with e = omega - r and the integral Theta' = e from 0, J e'' + C kp e' + C ki e = 0 with
// e(0) = omega0 - r and J e'(0) = tau (the integral starts where the torque continues the command
// before, 0): two real poles, e -> 0 (no steady-state error),
// and the torque settles at tau.
TEST(SlipControl, PIControllerHoldsTheTargetAsTheClosedForm) {
  const double kp = 0.02, ki = 0.05, r = 80;
  const SlipRun run = simulate_slip("slip_pi", "{ target = \"80*rad/s\", kp = \"0.02*s/rad\", ki = \"0.05/rad\" }", "6*s");
  const Csv& csv = run.csv;
  const std::size_t t = csv.column("t"), w = csv.column("omega_a"), T = csv.column("T_Ba");
  const double a = kJ, b = kC * kp, c = kC * ki, root = std::sqrt(b * b - 4 * a * c);
  const double l1 = (-b + root) / (2 * a), l2 = (-b - root) / (2 * a);
  const double e0 = kOmega0 - r, de0 = kTau / kJ;  // bumpless: the command starts at Ba's, 0
  const double A = (de0 - l2 * e0) / (l1 - l2), B = e0 - A;
  double highest = 0;
  for (const auto& row : csv.rows) {
    const double e = A * std::exp(l1 * row[t]) + B * std::exp(l2 * row[t]);
    EXPECT_NEAR(row[w], r + e, 1e-7) << row[t];  // dopri5 at 1e-11
    highest = std::max(highest, row[T]);
  }
  ASSERT_LT(highest, kC);  // the premise: the loop stays linear, within [0, C]
  // No steady-state error: at 6 s the slow pole leaves A e^(6 l1), some 3e-6 rad/s, and the torque
  // is the input's.
  EXPECT_NEAR(csv.rows.back()[w], r, 1e-5);
  EXPECT_NEAR(csv.rows.back()[T], kTau, 1e-4);
}

// The target falls from 100 to 10 rad/s within 10 ms, holds, then ramps to 0 from 0.4 s to 0.7 s:
// the brake saturates at its capacity while the slip catches up, then follows the target down to
// lock-up. With back-calculation (tracking 5 ms) the integral leaves saturation consistent with the
// capacity: the slip stays above the plateau and the brake locks as the target reaches 0. An
// integral that winds up (tracking 1000 s) overshoots the plateau and locks the brake at once. The
// controller is on from t = 0 (the initial mode, no event) and off from the lock-up on, where the
// brake holds the input at full command.
TEST(SlipControl, BackCalculationLocksAtTheTargetsEndWithoutOvershoot) {
  const std::string target = "target = { table = [[0, \"100*rad/s\"], [\"10*ms\", \"10*rad/s\"], [\"0.4*s\", \"10*rad/s\"], "
                             "[\"0.7*s\", \"0*rad/s\"]] }, kp = \"0.05*s/rad\", ki = \"0.5/rad\"";
  const SlipRun tracked = simulate_slip("slip_tracked", "{ " + target + ", tracking_time = \"5*ms\" }", "1*s");
  const SlipRun wound = simulate_slip("slip_wound", "{ " + target + ", tracking_time = \"1000*s\" }", "1*s");
  auto lock_up = [](const std::string& events) {  // the time of ",Ba,slipping,stuck"
    const auto at = events.find(",Ba,slipping,stuck\n");
    if (at == std::string::npos) return -1.0;
    return std::stod(events.substr(events.rfind('\n', at) + 1));
  };
  const Csv& csv = tracked.csv;
  const std::size_t t = csv.column("t"), w = csv.column("omega_a"), T = csv.column("T_Ba");
  double saturated = 0, lowest = 1e9;
  for (const auto& row : csv.rows) {
    saturated = std::max(saturated, row[T]);
    if (row[t] > 0.05 && row[t] < 0.4) lowest = std::min(lowest, row[w]);
  }
  ASSERT_NEAR(saturated, kC, 1e-9);  // the premise: it reaches the capacity
  EXPECT_GT(lowest, 10.0) << tracked.events;  // approached from above: no undershoot of the plateau
  // At the target's end, to the lag of the loop on the final ramp (33 rad/s^2: 1.2 ms measured).
  EXPECT_NEAR(lock_up(tracked.events), 0.7, 5e-3) << tracked.events;
  EXPECT_LT(lock_up(wound.events), 0.4) << wound.events;  // the test can fail: a wound-up integral locks it early
  EXPECT_NE(tracked.events.find(",slip_Ba,linear,at_limit\n"), std::string::npos) << tracked.events;
  EXPECT_NE(tracked.events.find(",slip_Ba,at_limit,linear\n"), std::string::npos) << tracked.events;
  EXPECT_NE(tracked.events.find(",slip_Ba,linear,off\n"), std::string::npos) << tracked.events;
  EXPECT_NEAR(csv.rows.back()[w], 0.0, 1e-9);
  EXPECT_NEAR(csv.rows.back()[T], kTau, 1e-9);
}

// The shipped closed-loop upshift (models/scenes/simpson_1_2_closed_loop.toml), compiled and
// interpreted: the same events, B1's slip on its target ramp from 50 ms after the controller starts
// until lock-up, which comes at the ramp's end, and the cut's end started by it.
TEST(SlipControl, ClosedLoopUpshiftRunsCompiledAsInterpreted) {
  const fs::path dir = temp_dir("slip_upshift");
  write_text(dir / "upshift.toml", with_edits(read_text(source_path("models/scenes/simpson_1_2_closed_loop.toml")),
                                             {{"\"../simpson_3speed.toml\"", "\"" + source_path("models/simpson_3speed.toml") + "\""}}));
  for (const std::string how : {"", " --interpreted"}) {
    const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "upshift.toml").string() + how +
                                  " -o " + (dir / (how.empty() ? "compiled" : "interpreted")).string());
    ASSERT_EQ(c.status, 0) << c.err;
  }
  auto events = [&](const std::string& which) {
    std::vector<std::vector<std::string>> out;
    std::stringstream in(read_text(dir / which / "simpson_1_2_closed_loop.events.csv"));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line)) {
      std::vector<std::string> fields;
      std::stringstream ss(line);
      for (std::string f; std::getline(ss, f, ',');) fields.push_back(f);
      out.push_back(fields);
    }
    return out;
  };
  const auto a = events("compiled"), b = events("interpreted");
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(std::vector<std::string>(a[i].begin() + 1, a[i].end()), std::vector<std::string>(b[i].begin() + 1, b[i].end()));
    // Each path locates its events on its own dopri5 trajectory, and the two right-hand sides
    // differ by rounding, which the steps' control keeps at rounding (2e-15 s measured).
    EXPECT_NEAR(std::stod(a[i][0]), std::stod(b[i][0]), 1e-9) << i;
  }
  auto time_of = [&](const std::string& element, const std::string& to) {
    const auto e = std::find_if(a.begin(), a.end(), [&](const auto& r) { return r[1] == element && r[3] == to; });
    return e == a.end() ? -1.0 : std::stod((*e)[0]);
  };
  const double start = time_of("slip_B1", "linear"), lockup = time_of("B1", "stuck");
  ASSERT_GT(start, 1.0);
  EXPECT_NEAR(start, time_of("B2", "slipping"), 0.0);  // the controller starts as B2 breaks away
  EXPECT_NEAR(time_of("slip_B1", "off"), lockup, 0.0);  // and hands B1 over as it locks
  EXPECT_NEAR(time_of("tau_i", "started"), lockup, 0.0);
  EXPECT_NEAR(lockup, start + 0.25, 0.01);  // at the ramp's end, to the loop's lag
  const Csv csv = read_csv((dir / "compiled" / "simpson_1_2_closed_loop.csv").string());
  const std::size_t t = csv.column("t"), slip = csv.column("slip_B1");
  double worst = 0;
  for (const auto& row : csv.rows)
    if (row[t] > start + 0.05 && row[t] < lockup) worst = std::max(worst, std::abs(row[slip] - (-198 * (1 - (row[t] - start) / 0.25))));
  EXPECT_LT(worst, 12.0);  // the PI loop's lag on a ramp of 792 rad/s^2 with these gains: some 10 rad/s
}

// Runs the pair with omega_a = `speed`, Ba's command `command` and its slip controller `control`,
// which must stop the run with `message` (as docs/errors.md shows it).
void expect_run_stops(const std::string& tag, const std::string& speed, const std::string& command,
                      const std::string& control, const std::string& message) {
  const fs::path dir = temp_dir(tag);
  write_text(dir / "pair.toml", read_text(source_path("tests/vibration/pair.toml")));
  write_text(dir / "scene.toml",
             "name = \"slip\"\nmodel = \"pair.toml\"\neffects = []\nkeep = [\"a\"]\n"
             "[inputs]\ntau_a = \"30*Nm\"\n[initial]\nomega_a = \"" + speed + "\"\n[engagement]\nBa = \"" + command + "\"\n"
             "[slip_control]\nBa = " + control + "\n[simulation]\nhorizon = \"1*s\"\nsample = \"1*ms\"\n");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate scene.toml --interpreted -o out", dir);
  EXPECT_EQ(c.status, 3);
  const std::string expected = "slip: error: " + message + "; the CSV keeps what was computed and is marked incomplete\n";
  EXPECT_EQ(c.err, expected);
  EXPECT_NE(read_text(source_path("docs/errors.md")).find(expected), std::string::npos);
}

// A target of the other sign than the slip it is to hold stops the run as the controller starts:
// its torque would push the slip on instead of holding it.
TEST(SlipControl, TargetAgainstTheSlipStopsTheRun) {
  expect_run_stops("slip_against", "100*rad/s", "0", "{ target = \"-80*rad/s\", kp = \"0.05*s/rad\", ki = \"0.5/rad\" }",
                   "slip_Ba starts at t = 0 s while Ba slips at 100 rad/s, against its target's sign; give the target "
                   "the sign of the slip");
}

// The same for a controller that starts while its element does not slip (at rest, held by the
// brake's own command): it would lock it at once at full command, overriding that command.
TEST(SlipControl, StartOnAnElementAtRestStopsTheRun) {
  expect_run_stops("slip_at_rest", "0*rad/s", "1",
                   "{ target = \"20*rad/s\", kp = \"0.05*s/rad\", ki = \"0.5/rad\", start = \"0.3*s\" }",
                   "slip_Ba starts at t = 0.3 s while Ba does not slip; a slip controller takes over an element that "
                   "slips (an on-coming one once it engages): start it then");
}

// A slip controller started by the off-going element's break-away, on the shipped closed-loop
// upshift's rigid model: the mode is resolved again as the controller starts (bumpless, so the gear's
// state and B2's torque demand are those that released it), and B2 stays released. Before, the
// resolution from another order of rounding found B2 within its capacity, stuck it, and released it
// again 4e-16 s later with TR-BDF2: two events too many, and shift metrics that counted them.
TEST(SlipControl, StartOnABreakAwayKeepsTheElementReleased) {
  const fs::path dir = temp_dir("slip_break_away");
  write_text(dir / "upshift.toml",
             with_edits(read_text(source_path("models/scenes/simpson_1_2_closed_loop.toml")),
                        {{"\"../simpson_3speed.toml\"", "\"" + source_path("models/simpson_3speed.toml") + "\"\ncompare_rigid = true"}}));
  for (const std::string solver : {"dopri5", "implicit"}) {
    SCOPED_TRACE(solver);
    const fs::path out = dir / solver;
    const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "upshift.toml").string() +
                                  " --interpreted --solver " + solver + " -o " + out.string());
    ASSERT_EQ(c.status, 0) << c.err;
    // B2's changes of state in the rigid run: its break-away, then open as its command ends at 1.1 s.
    std::vector<std::string> changes;
    std::stringstream in(read_text(out / "simpson_1_2_closed_loop.rigid.events.csv"));
    std::string line;
    std::getline(in, line);
    while (std::getline(in, line))
      if (line.find(",B2,") != std::string::npos) changes.push_back(line.substr(line.find(",B2,") + 4));
    EXPECT_EQ(changes, (std::vector<std::string>{"stuck,slipping", "slipping,open"})) << read_text(out / "simpson_1_2_closed_loop.rigid.events.csv");
  }
}

}  // namespace
}  // namespace pogear::test
