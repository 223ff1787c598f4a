// Signals that start on an event (`when`, `delay`, `before`): a command and an input torque started
// by the rigid Simpson upshift's breakaway and lock-up, against the closed form of the breakaway
// time; the compiled simulator against the interpreted run (tests/commands/shift_test.cpp).
#include <algorithm>
#include <cmath>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "pogear/hybrid.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

// The rigid Simpson 3-speed without bearing friction in 1st gear (C1, B2), B2 releasing from 1 s to
// 1.15 s as the shipped upshift's; `engagement` and `tau_i` are the lines under test.
std::string triggered_simpson_scene(const std::string& tau_i, const std::string& b1) {
  return "name = \"triggered\"\nmodel = \"../simpson_3speed.toml\"\neffects = []\n"
         "[parameters]\nJ_o = \"1.5*kg*m^2\"\n"
         "[inputs]\ntau_i = " + tau_i + "\ntau_o = \"-200*Nm\"\n"
         "[engagement]\nC1 = \"1\"\nB2 = { table = \"simpson_B2_release.csv\" }\nB1 = " + b1 + "\n"
         "[simulation]\nhorizon = \"2*s\"\nsample = \"1*ms\"\nsolver = \"exact\"\n";
}

struct TriggeredRun {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, w;
  std::vector<rt::HybridEvent> events;
  rt::RunStatus status;
};

TriggeredRun run_triggered(const std::string& text, rt::Solver solver = rt::Solver::exact) {
  const SpecializedScene model = specialize(parse_scene_text(text, source_path("models/scenes/triggered.toml")));
  const NumericSystem ns = numeric_system(model, model.main);
  const rt::HybridSystem hs = hybrid_system(model, model.main, ns);
  TriggeredRun r;
  rt::HybridMethod method{solver, {}};
  rt::set_tolerance(method.options, 1e-10);
  rt::HybridEngine engine(hs, model.scene.horizon, method);
  r.status = engine.run(
      ns.x0, model.scene.sample,
      [&](double t, const rt::HybridSample& s) {
        r.t.push_back(t);
        r.x.push_back(s.x);
        r.w.push_back(s.w);
        return true;
      },
      [&](const rt::HybridEvent& e) { r.events.push_back(e); });
  return r;
}

// Elements in the model's order: C1 (0), B1 (1), B2 (2); w = [tau_i, tau_o, T_C1, T_B1, T_B2].
constexpr int kB1 = 1, kB2 = 2;
constexpr Eigen::Index kTauI = 0, kTB1 = 3, kTB2 = 4;

double first_event_to(const TriggeredRun& r, int element, rt::ElementState to) {
  for (const rt::HybridEvent& e : r.events)
    if (e.started < 0 && e.element == element && e.to == to) return e.t;
  return -1;
}

// B1's apply ramp (0 to 1 in 150 ms) starts 20 ms after B2 breaks away. Without damping B2's stuck
// torque T0 is constant in 1st gear, and B2 breaks away where its static capacity 1.2 * 800 N m
// times its command 1 - (t - 1) / 0.15 falls to |T0|: t = 1 + 0.15 (1 - |T0| / 960). The located
// event lies within the root finder's 4 ulps of that (1e-15 s at t = 1 s), the start exactly
// there plus the delay, and B1's slipping torque is its capacity times the ramp from the start.
TEST(TriggeredSignals, CommandStartsAtTheLocatedBreakawayPlusItsDelay) {
  for (const rt::Solver solver : {rt::Solver::exact, rt::Solver::dopri5}) {
    SCOPED_TRACE(rt::solver_name(solver));
    const TriggeredRun r = run_triggered(triggered_simpson_scene("\"150*Nm\"", "{ table = [[0, 0], [\"0.15*s\", 1]], when = \"B2 slipping\", "
                                                             "delay = \"20*ms\" }"),
                                 solver);
    ASSERT_TRUE(r.status.ok) << r.status.message;
    const double T0 = r.w[500](kTB2);
    EXPECT_NEAR(r.w[900](kTB2), T0, 1e-12 * std::abs(T0));  // constant in 1st gear: the closed form's premise
    const double closed = 1 + 0.15 * (1 - std::abs(T0) / 960);
    const double breakaway = first_event_to(r, kB2, rt::ElementState::slipping);
    // The event functions of exact stepping are exact to rounding (4 ulps located); dopri5's to its
    // dense output, whose error at 1e-10 tolerance on this linear-in-time stuck torque is rounding too.
    EXPECT_NEAR(breakaway, closed, 1e-12);
    const auto started = std::find_if(r.events.begin(), r.events.end(), [](const rt::HybridEvent& e) { return e.started == 0; });
    ASSERT_NE(started, r.events.end());
    EXPECT_EQ(started->t, breakaway + 0.02);  // the start is the located time plus the delay, as computed
    EXPECT_EQ(started->element, kB2);
    // B1 is open (no torque) until the start, then slips with its kinetic capacity 400 N m times
    // the ramp, |T_B1| = 400 (t - start) / 0.15, until it locks.
    const double locked = first_event_to(r, kB1, rt::ElementState::stuck);
    ASSERT_GT(locked, started->t);
    std::size_t checked = 0;
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      if (r.t[i] < started->t) {
        EXPECT_EQ(r.w[i](kTB1), 0.0) << r.t[i];
      } else if (r.t[i] < locked) {
        const double expected = 400 * std::min(1.0, (r.t[i] - started->t) / 0.15);
        EXPECT_NEAR(std::abs(r.w[i](kTB1)), expected, 1e-9 * 400) << r.t[i];  // rounding of the table's interpolation
        ++checked;
      }
    }
    EXPECT_GT(checked, 20u);
  }
}

// A torque cut that ends at lock-up: tau_i falls from 150 to 100 N m over 20 ms from 1 s (its
// `before`) and, from the instant B1 locks, rises back over 20 ms, without a delay. The start is
// reported at the lock-up's own time, and the input follows the ramp from there.
TEST(TriggeredSignals, TorqueCutEndsAtTheInstantOfLockUp) {
  const TriggeredRun r = run_triggered(triggered_simpson_scene(
      "{ table = [[0, \"100*Nm\"], [\"20*ms\", \"150*Nm\"]], when = \"B1 stuck\", "
      "before = { table = [[0, \"150*Nm\"], [\"1*s\", \"150*Nm\"], [\"1.02*s\", \"100*Nm\"]] } }",
      "{ table = \"simpson_B1_apply.csv\" }"));
  ASSERT_TRUE(r.status.ok) << r.status.message;
  const double locked = first_event_to(r, kB1, rt::ElementState::stuck);
  ASSERT_GT(locked, 1.02);
  const auto started = std::find_if(r.events.begin(), r.events.end(), [](const rt::HybridEvent& e) { return e.started == 0; });
  ASSERT_NE(started, r.events.end());
  EXPECT_EQ(started->t, locked);
  EXPECT_EQ(std::count_if(r.events.begin(), r.events.end(), [](const rt::HybridEvent& e) { return e.started >= 0; }), 1);
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double t = r.t[i];
    const double expected = t < 1 ? 150 : t < locked ? std::max(100.0, 150 - 50 * (t - 1) / 0.02)
                                                     : std::min(150.0, 100 + 50 * (t - locked) / 0.02);
    EXPECT_NEAR(r.w[i](kTauI), expected, 1e-9) << t;  // the tables' interpolation in doubles
  }
  // B1 holds after the cut ends: the torque back at 150 N m does not break it away again.
  for (const rt::HybridEvent& e : r.events) EXPECT_FALSE(e.element == kB1 && e.t > locked) << e.t;
}

// A trigger that never comes leaves the signal at its `before`, and the run is that of the scene
// with `before` itself written, to the bit.
TEST(TriggeredSignals, SignalWaitingForAnEventThatNeverComesIsItsBefore) {
  const std::string before = "{ table = [[0, \"150*Nm\"], [\"1*s\", \"150*Nm\"], [\"1.02*s\", \"100*Nm\"]] }";
  const TriggeredRun waiting = run_triggered(triggered_simpson_scene("{ table = [[0, \"0*Nm\"]], when = \"C1 slipping\", before = " + before + " }",
                                                   "{ table = \"simpson_B1_apply.csv\" }"));
  const TriggeredRun plain = run_triggered(triggered_simpson_scene(before, "{ table = \"simpson_B1_apply.csv\" }"));
  ASSERT_TRUE(waiting.status.ok) << waiting.status.message;
  ASSERT_TRUE(plain.status.ok) << plain.status.message;
  ASSERT_EQ(waiting.t.size(), plain.t.size());
  for (std::size_t i = 0; i < plain.t.size(); ++i) ASSERT_EQ(waiting.w[i], plain.w[i]) << plain.t[i];
  ASSERT_EQ(waiting.events.size(), plain.events.size());
  for (std::size_t i = 0; i < plain.events.size(); ++i) EXPECT_EQ(waiting.events[i].t, plain.events[i].t);
}

// A delay below an ulp of the event's time starts the signal at the event's instant, as no delay
// does: the same run to the bit, events and all (it used to wait for the next event to resolve).
TEST(TriggeredSignals, DelayBelowAnUlpIsNoDelay) {
  const std::string b1 = "{ step = \"1\", at = \"0*s\", when = \"B2 slipping\"";
  const TriggeredRun tiny = run_triggered(triggered_simpson_scene("\"150*Nm\"", b1 + ", delay = \"1e-300*s\" }"));
  const TriggeredRun none = run_triggered(triggered_simpson_scene("\"150*Nm\"", b1 + " }"));
  ASSERT_TRUE(tiny.status.ok) << tiny.status.message;
  ASSERT_TRUE(none.status.ok) << none.status.message;
  ASSERT_EQ(tiny.events.size(), none.events.size());
  for (std::size_t i = 0; i < none.events.size(); ++i) {
    EXPECT_EQ(tiny.events[i].t, none.events[i].t) << i;
    EXPECT_EQ(tiny.events[i].to, none.events[i].to) << i;
  }
  ASSERT_EQ(tiny.t.size(), none.t.size());
  for (std::size_t i = 0; i < none.t.size(); ++i) ASSERT_EQ(tiny.x[i], none.x[i]) << none.t[i];
}

// A step at the horizon itself is a breakpoint too: the last step ends on the value before it, so
// the state at the horizon is that of the run without the step, to rounding (the exact method
// smeared it over the last sample period: 643 J of heat in B1 from a command that steps at 2 s).
// The last sample shows the inputs after the step, as at every breakpoint.
TEST(TriggeredSignals, StepAtTheHorizonLeavesTheStateAlone) {
  for (const rt::Solver solver : {rt::Solver::exact, rt::Solver::dopri5}) {
    SCOPED_TRACE(rt::solver_name(solver));
    const TriggeredRun stepped = run_triggered(
        triggered_simpson_scene("{ step = \"300*Nm\", at = \"2*s\", before = \"150*Nm\" }", "{ table = \"simpson_B1_apply.csv\" }"),
        solver);
    const TriggeredRun plain = run_triggered(triggered_simpson_scene("\"150*Nm\"", "{ table = \"simpson_B1_apply.csv\" }"), solver);
    ASSERT_TRUE(stepped.status.ok) << stepped.status.message;
    ASSERT_TRUE(plain.status.ok) << plain.status.message;
    ASSERT_EQ(stepped.t.size(), plain.t.size());
    // The resolution at the breakpoint projects the state onto the stuck elements' constraints:
    // a rounding of the speeds (1e-13 rad/s on 120 rad/s), where smearing the step moved them by
    // its 150 N m over the last millisecond.
    const double scale = plain.x.back().cwiseAbs().maxCoeff();
    for (Eigen::Index j = 0; j < plain.x.back().size(); ++j)
      EXPECT_NEAR(stepped.x.back()(j), plain.x.back()(j), 1e-14 * scale) << j;
    EXPECT_EQ(stepped.w.back()(kTauI), 300.0);
  }
}

}  // namespace
}  // namespace pogear::test
