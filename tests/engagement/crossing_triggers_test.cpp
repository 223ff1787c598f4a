// Signals that start when a speed or a slip crosses a value (`when = "omega_<body> > v"`,
// `"|slip_<element>| < v"`): on a clutch between two bodies against the closed forms of their
// speeds, and on the rigid Simpson upshift against the slip a plain run reaches at the start.
#include <algorithm>
#include <cmath>
#include <cstdlib>
#include <filesystem>
#include <sstream>
#include <string>
#include <vector>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "pogear/hybrid.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

// x = [omega_1, omega_2]: J1 omega_1' = tau_1 - T, J2 omega_2' = -b omega_2 + tau_2 + T, the clutch
// fully applied from the start and slipping (omega_1 = 100 rad/s, omega_2 = 0), T = c while it slips.
// Then omega_1 = 100 - (c / J1) t and omega_2 = (c / b) (1 - e^(-b t / J2)) until it locks.
constexpr double kJ1 = 0.5, kJ2 = 1.0, kB = 0.5, kC = 20.0, kOmega10 = 100.0;

rt::HybridSystem slipping_pair() {
  rt::HybridSystem sys;
  sys.M = Eigen::Matrix2d{{0, 0}, {0, -kB / kJ2}};
  sys.N = Eigen::Matrix<double, 2, 3>{{1 / kJ1, 0, -1 / kJ1}, {0, 1 / kJ2, 1 / kJ2}};  // tau_1, tau_2, T
  sys.S = Eigen::RowVector2d{1, -1};
  sys.inputs = {rt::Constant{0.0}, rt::Constant{0.0}};
  sys.elements = {{"clutch", kC, 1.2, rt::Constant{1.0}, false}};
  return sys;
}

// Input `input` waiting for `crossing`, 0 until then.
rt::TriggeredSignal on_crossing(int input, rt::CrossingTrigger crossing, std::string name) {
  rt::TriggeredSignal s;
  s.index = input;
  s.name = std::move(name);
  s.before = rt::Signal{rt::Constant{0.0}};
  s.crossing = std::move(crossing);
  return s;
}

rt::CrossingTrigger speed_crossing(Eigen::RowVector2d speed, double value, bool upward) {
  rt::CrossingTrigger c;
  c.speed = speed;
  c.value = value;
  c.upward = upward;
  return c;
}

struct PairRun {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, w, slip, energy;
  std::vector<std::uint32_t> mode;
  std::vector<rt::HybridEvent> events;
  rt::RunStatus status;
};

PairRun run_pair(const rt::HybridSystem& sys, rt::Solver solver) {
  rt::HybridMethod method{solver, {}};
  rt::set_tolerance(method.options, 1e-12);
  rt::HybridEngine engine(sys, 4.0, method);
  PairRun r;
  r.status = engine.run(
      Eigen::Vector2d{kOmega10, 0.0}, 1e-3,
      [&](double t, const rt::HybridSample& s) {
        r.t.push_back(t);
        r.x.push_back(s.x);
        r.w.push_back(s.w);
        r.slip.push_back(s.slip);
        r.energy.push_back(s.energy);
        r.mode.push_back(s.mode);
        return true;
      },
      [&](const rt::HybridEvent& e) { r.events.push_back(e); });
  return r;
}

double start_of(const PairRun& r, int signal) {
  for (const rt::HybridEvent& e : r.events)
    if (e.started == signal) return e.t;
  return -1;
}

// The slip omega_1 - omega_2 before lock-up, and where it falls to v: bisected in long double on
// the closed form (it decreases monotonically), independent of the engine.
long double pair_slip(long double t) {
  return kOmega10 - (kC / kJ1) * t - (kC / kB) * (1 - std::exp(-kB * t / kJ2));
}
double slip_falls_to(double v) {
  long double a = 0, b = 4;
  for (int i = 0; i < 200; ++i) {
    const long double c = 0.5L * (a + b);
    (pair_slip(c) > v ? a : b) = c;
  }
  return static_cast<double>(0.5L * (a + b));
}

// tau_2 steps to 10 N m when omega_2 rises above 20 rad/s, at t = -(J2 / b) ln(1 - 20 b / c) =
// 2 ln 2 s; from there omega_2 relaxes to (c + 10) / b, whose closed form the samples follow.
// tau_1 steps to -5 N m when |slip| falls below 10 rad/s (the bisected root above). Exact stepping
// locates both to a few ulps of its exact flow; dopri5 at rtol 1e-12 to its dense output's error
// (1e-12 rad/s on a rate of 10 rad/s^2: about 1e-13 s), so both within 1e-12 s.
TEST(CrossingTriggers, StartsAtTheClosedFormTimeOfTheCrossing) {
  for (const rt::Solver solver : {rt::Solver::exact, rt::Solver::dopri5}) {
    SCOPED_TRACE(rt::solver_name(solver));
    rt::HybridSystem sys = slipping_pair();
    sys.inputs = {rt::Step{0.0, -5.0, 0.0}, rt::Step{0.0, 10.0, 0.0}};
    rt::CrossingTrigger slip;
    slip.slip_of = 0;
    slip.value = 10;
    sys.triggered = {on_crossing(1, speed_crossing({0, 1}, 20, true), "tau_2"),
                     on_crossing(0, slip, "tau_1")};
    const PairRun r = run_pair(sys, solver);
    ASSERT_TRUE(r.status.ok) << r.status.message;
    const double t2 = start_of(r, 0), t1 = start_of(r, 1);
    EXPECT_NEAR(t2, 2 * std::log(2.0), 1e-12);
    ASSERT_LT(t2, t1);
    // The slip's closed form holds until tau_2 starts; past it the slip's root moves, so it is
    // bisected again on the closed form with tau_2 = 10 N m from t2 (omega_1 is unchanged by it).
    auto slip_after = [&](long double t) {
      const long double w2 = (kC + 10) / kB + (20 - (kC + 10) / kB) * std::exp(-kB * (t - t2) / kJ2);
      return kOmega10 - (kC / kJ1) * t - w2;
    };
    long double a = t2, b = 4;
    for (int i = 0; i < 200; ++i) {
      const long double c = 0.5L * (a + b);
      (slip_after(c) > 10 ? a : b) = c;
    }
    EXPECT_NEAR(t1, static_cast<double>(a), 1e-12);
    EXPECT_GT(slip_falls_to(10), t1);  // without tau_2 the slip would have fallen later: the root moved
    // The samples: tau_2 is 0 before its start and 10 N m after; omega_2 its closed form on each side
    // (1e-12 relative: rounding of the exact flow, and dopri5's tolerance).
    std::size_t after = 0;
    for (std::size_t i = 0; i < r.t.size() && r.mode[i] == 0; ++i) {
      const double t = r.t[i];
      const double w2 = t < t2 ? (kC / kB) * (1 - std::exp(-kB * t / kJ2))
                               : (kC + 10) / kB + (20 - (kC + 10) / kB) * std::exp(-kB * (t - t2) / kJ2);
      EXPECT_NEAR(r.x[i](1), w2, 1e-11 * 60) << t;
      EXPECT_EQ(r.w[i](1), t < t2 ? 0.0 : 10.0) << t;
      EXPECT_EQ(r.w[i](0), t < t1 ? 0.0 : -5.0) << t;
      after += t > t1;
    }
    EXPECT_GT(after, 100u);
    // The monitors are no part of what the run reports: the samples have the system's own inputs,
    // slips, heat and mode bits, the events only the clutch's changes and the two starts (with no
    // element: no element triggered them).
    EXPECT_EQ(r.w.back().size(), 3);
    EXPECT_EQ(r.slip.back().size(), 1);
    EXPECT_EQ(r.energy.back().size(), 1);
    EXPECT_TRUE(std::all_of(r.mode.begin(), r.mode.end(), [](std::uint32_t m) { return m <= 1u; }));
    for (const rt::HybridEvent& e : r.events) {
      if (e.started >= 0) EXPECT_EQ(e.element, -1);
      else EXPECT_EQ(e.element, 0);
    }
    EXPECT_EQ(std::count_if(r.events.begin(), r.events.end(), [](const rt::HybridEvent& e) { return e.started >= 0; }), 2);
  }
}

// A crossing fires the first time the quantity passes the value after the start: omega_1 starts
// above 50 rad/s and only falls, so "omega_1 > 50" never fires and "omega_1 < 50" fires where its
// line reaches 50, t = (100 - 50) J1 / c = 1.25 s; "|slip| > 10" never fires either (the slip
// starts above it and falls to lock-up).
TEST(CrossingTriggers, QuantityBeyondItsValueAtTheStartMustComeBackFirst) {
  rt::HybridSystem sys = slipping_pair();
  sys.inputs = {rt::Step{0.0, 1.0, 0.0}, rt::Step{0.0, 1.0, 0.0}};
  sys.elements[0].command = rt::Constant{1.0};
  rt::CrossingTrigger slip;
  slip.slip_of = 0;
  slip.value = 10;
  slip.upward = true;
  sys.triggered = {on_crossing(0, speed_crossing({1, 0}, 50, true), "tau_1"),
                   on_crossing(1, speed_crossing({1, 0}, 50, false), "tau_2")};
  PairRun r = run_pair(sys, rt::Solver::exact);
  ASSERT_TRUE(r.status.ok) << r.status.message;
  EXPECT_EQ(start_of(r, 0), -1);
  // omega_1 is linear in t; its rounding over the 1250 steps to there (up to an ulp of 100 rad/s
  // each: 2e-11 rad/s) moves the crossing by up to 4e-13 s at 40 rad/s^2.
  EXPECT_NEAR(start_of(r, 1), 1.25, 1e-12);
  sys.triggered = {on_crossing(0, slip, "tau_1")};
  r = run_pair(sys, rt::Solver::exact);
  ASSERT_TRUE(r.status.ok) << r.status.message;
  EXPECT_EQ(start_of(r, 0), -1);
  EXPECT_TRUE(std::all_of(r.w.begin(), r.w.end(), [](const Eigen::VectorXd& w) { return w(0) == 0.0; }));
}

// A crossing the system cannot have is refused before the run.
TEST(CrossingTriggers, CrossingOfNoSlipOrOfANonPositiveSlipIsRefused) {
  rt::HybridSystem sys = slipping_pair();
  rt::CrossingTrigger slip;
  slip.slip_of = 3;
  slip.value = 10;
  sys.triggered = {on_crossing(0, slip, "tau_1")};
  PairRun r = run_pair(sys, rt::Solver::exact);
  EXPECT_FALSE(r.status.ok);
  EXPECT_EQ(r.status.message, "a triggered signal waits for the slip of no brake or clutch of the system");
  slip.slip_of = 0;
  slip.value = 0;
  sys.triggered = {on_crossing(0, slip, "tau_1")};
  r = run_pair(sys, rt::Solver::exact);
  EXPECT_EQ(r.status.message, "a triggered signal waits for a slip's magnitude to cross a value not above zero");
  sys.triggered = {on_crossing(0, speed_crossing({1, 0}, 50, true), "tau_1")};
  sys.triggered[0].crossing->speed = Eigen::RowVector3d{1, 0, 0};
  r = run_pair(sys, rt::Solver::exact);
  EXPECT_EQ(r.status.message, "a triggered signal waits for a speed that is not a row over the system's states");
}

// The rigid Simpson 3-speed in 1st gear (C1, B2), B2 releasing from 1 s to 1.15 s; B1's apply ramp
// starts when B2's slip exceeds 20 rad/s (just after it opens at 1.15 s), read by name from the scene. The run without B1 to the
// start's time ends with B2's slip at 20 rad/s (to the rounding of the located time's slip rate).
std::string crossing_simpson_scene(const std::string& b1, const std::string& horizon) {
  return "name = \"crossing\"\nmodel = \"../simpson_3speed.toml\"\neffects = []\n"
         "[parameters]\nJ_o = \"1.5*kg*m^2\"\n"
         "[inputs]\ntau_i = \"150*Nm\"\ntau_o = \"-200*Nm\"\n"
         "[engagement]\nC1 = \"1\"\nB2 = { table = \"simpson_B2_release.csv\" }\nB1 = " + b1 + "\n"
         "[simulation]\nhorizon = \"" + horizon + "\"\nsample = \"1*ms\"\nsolver = \"exact\"\n";
}

struct SceneEnd {
  std::vector<rt::HybridEvent> events;
  Eigen::VectorXd last_slip;
  rt::RunStatus status;
};

SceneEnd run_scene(const std::string& text) {
  const SpecializedScene model = specialize(parse_scene_text(text, source_path("models/scenes/crossing.toml")));
  const NumericSystem ns = numeric_system(model, model.main);
  const rt::HybridSystem hs = hybrid_system(model, model.main, ns);
  rt::HybridEngine engine(hs, model.scene.horizon, {rt::Solver::exact, {}});
  SceneEnd r;
  r.status = engine.run(
      ns.x0, model.scene.horizon / 1000,
      [&](double, const rt::HybridSample& s) {
        r.last_slip = s.slip;
        return true;
      },
      [&](const rt::HybridEvent& e) { r.events.push_back(e); });
  return r;
}

TEST(CrossingTriggers, SceneSlipCrossingStartsWhereThePlainRunReachesTheValue) {
  const SceneEnd triggered =
      run_scene(crossing_simpson_scene("{ table = [[0, 0], [\"0.15*s\", 1]], when = \"|slip_B2| > 20*rad/s\" }", "2*s"));
  ASSERT_TRUE(triggered.status.ok) << triggered.status.message;
  const auto started = std::find_if(triggered.events.begin(), triggered.events.end(),
                                    [](const rt::HybridEvent& e) { return e.started == 0; });
  ASSERT_NE(started, triggered.events.end());
  ASSERT_GT(started->t, 1.0);
  // Elements C1 (0), B1 (1), B2 (2): the plain run (B1 open) up to the start's time.
  const SceneEnd plain = run_scene(crossing_simpson_scene("{ step = \"1\", at = \"3*s\" }", fmt::format("{}*s", started->t)));
  ASSERT_TRUE(plain.status.ok) << plain.status.message;
  // The located time is within 4 ulps (1e-15 s) of the crossing; B2's slip grows there at some
  // 1e3 rad/s^2, and the plain run's last step rounds it: 1e-9 relative covers both.
  EXPECT_NEAR(std::abs(plain.last_slip(2)), 20.0, 20 * 1e-9);
}

// A speed held at its threshold by a stuck brake sits there within rounding (c2 held by B2 at 0 in
// 1st gear, -7.7e-13 rad/s of noise before the breakaway): the trigger on "omega_c2 < 0" must not
// fire on that noise (such a trigger chattered: 500 events at t = 3e-13 s), but once c2 turns
// backwards, just after B2 breaks away.
TEST(CrossingTriggers, SpeedHeldAtItsThresholdStartsWhenItTurns) {
  // Through `pogear simulate`, which reads the speed off the system's outputs.
  const std::filesystem::path dir = temp_dir("crossing_held");
  std::string text = crossing_simpson_scene("{ table = [[0, 0], [\"0.15*s\", 1]], when = \"omega_c2 < 0*rad/s\" }", "2*s");
  text = with_edits(text, {{"\"../simpson_3speed.toml\"", "\"" + source_path("models/simpson_3speed.toml") + "\""},
                           {"\"simpson_B2_release.csv\"", "\"" + source_path("models/scenes/simpson_B2_release.csv") + "\""}});
  write_text(dir / "held.toml", text);
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "held.toml").string() +
                                " --interpreted -o " + dir.string());
  ASSERT_EQ(c.status, 0) << c.err;
  double breakaway = -1, started = -1;
  std::stringstream in(read_text(dir / "crossing.events.csv"));
  for (std::string line; std::getline(in, line);) {
    const double t = std::atof(line.c_str());
    if (line.find(",command_B1,waiting,started") != std::string::npos) started = t;
    if (breakaway < 0 && line.find(",B2,stuck,slipping") != std::string::npos) breakaway = t;
  }
  ASSERT_GT(breakaway, 1.0);
  // c2 leaves the rounding of the speeds (256 ulps of some 100 rad/s: 6e-12 rad/s) within
  // microseconds of the breakaway, accelerating at hundreds of rad/s^2.
  EXPECT_GE(started, breakaway);
  EXPECT_LT(started - breakaway, 1e-6);
}

// The monitors' regimes are no modes of the gear: the pair slips, then locks (two modes met).
TEST(CrossingTriggers, ModesMetLeaveTheMonitorsOut) {
  rt::HybridSystem sys = slipping_pair();
  sys.inputs = {rt::Step{0.0, 1.0, 0.0}, rt::Step{0.0, 1.0, 0.0}};
  sys.triggered = {on_crossing(0, speed_crossing({1, 0}, 50, false), "tau_1"),
                   on_crossing(1, speed_crossing({0, 1}, 20, true), "tau_2")};
  rt::HybridEngine engine(sys, 4.0, {rt::Solver::exact, {}});
  const rt::RunStatus st = engine.run(Eigen::Vector2d{kOmega10, 0.0}, 1e-3, [](double, const rt::HybridSample&) { return true; },
                                      [](const rt::HybridEvent&) {});
  ASSERT_TRUE(st.ok) << st.message;
  EXPECT_EQ(engine.modes_met(), 2);
}

}  // namespace
}  // namespace pogear::test
