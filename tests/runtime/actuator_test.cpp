// Brake and clutch actuators (runtime/pogear/actuator.hpp): the engagement a command gives through a
// fill delay and a first-order lag, alone and in the hybrid engine, against closed forms solved here.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pogear/actuator.hpp"
#include "pogear/hybrid.hpp"

namespace pogear::rt {
namespace {

ActuatorKnots knots_of(const Signal& command, double delay, double tau) {
  ActuatorKnots k;
  add_knots(k, command, -std::numeric_limits<double>::infinity(), delay, tau);
  return k;
}

// A step from 0 to 1 at 0.1 s through 30 ms of delay and a 40 ms lag: 1 - e^(-(t - 0.13) / 0.04)
// from 0.13 s, and its rate e^(...) / 0.04.
TEST(Actuator, StepThroughDelayAndLag) {
  const ActuatorKnots k = knots_of(Step{0, 1, 0.1}, 0.03, 0.04);
  for (const double t : {-1.0, 0.0, 0.1, 0.129999}) EXPECT_EQ(engagement(k, 0.04, t), 0.0) << t;
  for (const double t : {0.13, 0.131, 0.2, 0.5, 3.0}) {
    // The closed form's own rounding: a few ulps of 1.
    EXPECT_NEAR(engagement(k, 0.04, t), 1 - std::exp(-(t - 0.13) / 0.04), 4e-16) << t;
    EXPECT_NEAR(engagement_slope(k, 0.04, t), std::exp(-(t - 0.13) / 0.04) / 0.04, 1e-13) << t;
  }
  EXPECT_TRUE(std::isnan(engagement(k, 0.04, std::nan(""))));  // read from a knot in range, not past the end
}

// Without a lag the engagement is the command delayed, jumps included (right-continuous).
TEST(Actuator, DelayAloneShiftsTheCommand) {
  const Table command{{0.1, 0.1, 0.3, 0.5}, {0, 0.4, 1, 0.2}};
  const ActuatorKnots k = knots_of(command, 0.05, 0);
  for (const double t : {0.0, 0.149, 0.15, 0.2, 0.35, 0.36, 0.5, 0.55, 0.7})
    EXPECT_EQ(engagement(k, 0, t), command.value(t - 0.05)) << t;
}

// A ramp from 0 at 0.1 s to 1 at 0.2 s (slope s = 10/s), 20 ms of delay, a 50 ms lag: over the
// ramp, from u = t - 0.12, e = s (u - tau (1 - e^(-u/tau))); after it (u > T = 0.1 s),
// e = 1 - (1 - e_T) e^(-(u - T)/tau).
TEST(Actuator, RampThroughDelayAndLag) {
  const double tau = 0.05, s = 10, T = 0.1;
  const ActuatorKnots k = knots_of(Table{{0.1, 0.2}, {0, 1}}, 0.02, tau);
  auto closed = [&](double t) {
    const double u = t - 0.12;
    if (u <= 0) return 0.0;
    if (u <= T) return s * (u - tau * (1 - std::exp(-u / tau)));
    const double eT = s * (T - tau * (1 - std::exp(-T / tau)));
    return 1 - (1 - eT) * std::exp(-(u - T) / tau);
  };
  for (double t = 0; t <= 0.6; t += 0.0125) EXPECT_NEAR(engagement(k, tau, t), closed(t), 1e-15) << t;
}

// One body J = 0.5 kg m^2 at 150 rad/s, braked by B (c = 20 N m). B's command is 0.6 from 0.1 s,
// and from 0.2 s after B starts slipping it ramps to 1 over 0.1 s (a triggered command); the actuator
// adds 30 ms of delay and a 40 ms lag. So B engages at 0.13 s (its slipping event), the trigger
// starts the ramp at 0.33 s, which reaches the engagement at 0.36 s: the engagement is the lag of
// 0.6 from 0.13 s, of the ramp 0.6 + 4 (t - 0.36) from 0.36 s, and of 1 from 0.46 s, each piece
// from where the last left it. J w' = -c e, so w = 150 - (c/J) int e, until w = 0, where B locks.
struct Piece {
  double t0, p0, s;
};
struct LagClosedForm {
  std::vector<Piece> pieces{{0.13, 0.6, 0}, {0.36, 0.6, 4}, {0.46, 1, 0}};
  double tau = 0.04;
  // e and int e from 0.13 s to t.
  void at(double t, double& e, double& integral) const {
    e = 0;
    integral = 0;
    for (std::size_t i = 0; i < pieces.size() && t > pieces[i].t0; ++i) {
      const Piece& p = pieces[i];
      const double end = i + 1 < pieces.size() ? std::min(t, pieces[i + 1].t0) : t, u = end - p.t0;
      const double a = e - p.p0 + p.s * tau;  // e = p0 + s (u - tau) + a e^(-u/tau)
      integral += p.p0 * u + p.s * (u * u / 2 - tau * u) + a * tau * (1 - std::exp(-u / tau));
      e = p.p0 + p.s * (u - tau) + a * std::exp(-u / tau);
    }
  }
  double speed(double t) const {
    double e, integral;
    at(t, e, integral);
    return std::max(150 - 40 * integral, 0.0);
  }
};

HybridSystem braked_body() {
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(1, 1);
  sys.N = Eigen::MatrixXd::Constant(1, 1, -1 / 0.5);
  sys.S = Eigen::MatrixXd::Ones(1, 1);
  FrictionElementData b{"B", 20, 1.2, Table{{0, 0.1}, {0.6, 1}}};
  b.fill_delay = 0.03;
  b.time_constant = 0.04;
  sys.elements.push_back(b);
  sys.triggered = {{true, 0, 0, ElementState::slipping, 0.2, "command_B", Signal{Step{0, 0.6, 0.1}}, std::nullopt}};
  return sys;
}

TEST(Actuator, TriggeredCommandLagsOnFromWhereTheEngagementWas) {
  const LagClosedForm closed;
  // The lock: w = 0 by bisection on the closed form (monotone), to rounding.
  double lo = 0.5, hi = 5;
  for (int i = 0; i < 200; ++i) (closed.speed(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double t_lock = hi;
  for (const Solver solver : {Solver::dopri5, Solver::implicit}) {
    SCOPED_TRACE(std::string(solver_name(solver)));
    SolverOptions options;
    set_tolerance(options, 1e-10);
    const HybridSystem sys = braked_body();
    HybridEngine engine(sys, 5.0, HybridMethod{solver, options});
    std::vector<HybridEvent> events;
    double worst = 0, heat = 0;
    const RunStatus status = engine.run(
        Eigen::VectorXd::Constant(1, 150), 0.01,
        [&](double t, const HybridSample& s) {
          worst = std::max(worst, std::abs(s.x(0) - closed.speed(t)));
          heat = s.energy(0);
          return true;
        },
        [&](const HybridEvent& e) { events.push_back(e); });
    ASSERT_TRUE(status.ok) << status.message;
    ASSERT_EQ(events.size(), 3u);
    EXPECT_EQ(events[0].to, ElementState::slipping);
    EXPECT_NEAR(events[0].t, 0.13, 1e-15);  // a breakpoint: the knot's time itself
    EXPECT_EQ(events[1].started, 0);
    EXPECT_NEAR(events[1].t, 0.33, 1e-15);
    EXPECT_EQ(events[2].to, ElementState::stuck);
    // At a relative tolerance of 1e-10, measured: dopri5 7.6e-8 rad/s off the closed form at worst
    // (5e-10 of the speed, its global error: largest just after the engagement's corners), TR-BDF2,
    // of order 2, 4.5e-6. The lock time is off by the speed's error over the final deceleration of
    // 40 rad/s^2 (2e-10 s, 1.1e-7 s); all the kinetic energy J w0^2 / 2 = 5625 J becomes heat, off by
    // J w dw (6.6e-7 J, 3.3e-4 J). Each bound is 3 to 5 times the measured.
    const bool dopri5 = solver == Solver::dopri5;
    EXPECT_LT(worst, dopri5 ? 3e-7 : 2e-5);
    EXPECT_NEAR(events[2].t, t_lock, dopri5 ? 1e-9 : 5e-7);
    EXPECT_NEAR(heat, 5625, dopri5 ? 3e-6 : 1e-3);
  }
}

// Exact stepping holds a command linear between breakpoints: a lag is refused, a delay alone is not
// (the same scene as above, its lag removed: w falls linearly at 40 e rad/s^2, e = 0.6 from 0.13 s,
// the ramp from 0.36 s and 1 from 0.46 s, so w = 0 at 0.46 + (150 - 40 (0.6 (0.36 - 0.13) + 0.08)) / 40 s,
// 0.08 the ramp's integral (0.6 + 1) / 2 * 0.1).
TEST(Actuator, ExactSteppingTakesADelayAndRefusesALag) {
  HybridSystem sys = braked_body();
  {
    HybridEngine engine(sys, 5.0, HybridMethod{Solver::exact, {}});
    const RunStatus status = engine.run(Eigen::VectorXd::Constant(1, 150), 0.01, [](double, const HybridSample&) { return true; },
                                        [](const HybridEvent&) {});
    EXPECT_FALSE(status.ok);
    EXPECT_NE(status.message.find("an actuator's lag"), std::string::npos) << status.message;
  }
  sys.elements[0].time_constant = 0;
  HybridEngine engine(sys, 5.0, HybridMethod{Solver::exact, {}});
  std::vector<HybridEvent> events;
  const RunStatus status = engine.run(Eigen::VectorXd::Constant(1, 150), 0.01, [](double, const HybridSample&) { return true; },
                                      [&](const HybridEvent& e) { events.push_back(e); });
  ASSERT_TRUE(status.ok) << status.message;
  ASSERT_EQ(events.size(), 3u);
  const double t_lock = 0.46 + (150 - 40 * (0.6 * (0.36 - 0.13) + 0.08)) / 40;
  EXPECT_NEAR(events[2].t, t_lock, 1e-12 * t_lock);  // the exact flow: rounding of the located time
}

// Refused before the run: a negative delay.
TEST(Actuator, RefusesWhatItCannotRun) {
  HybridSystem sys = braked_body();
  sys.elements[0].fill_delay = -0.01;
  HybridEngine engine(sys, 1.0, HybridMethod{Solver::dopri5, {}});
  const RunStatus status = engine.run(Eigen::VectorXd::Constant(1, 150), 0.01, [](double, const HybridSample&) { return true; },
                                        [](const HybridEvent&) {});
  EXPECT_FALSE(status.ok);
  EXPECT_NE(status.message.find("fill delay"), std::string::npos) << status.message;
}

}  // namespace
}  // namespace pogear::rt
