// The hybrid engine (runtime/pogear/hybrid.hpp) on systems whose stick–slip motion is known in
// closed form: two inertias and a clutch, a brake that breaks away and sticks again, coupled clutches.
// Each with every method that runs brakes and clutches: the motions are piecewise polynomials of
// degree 2 at most, which dopri5 (order 5) and TR-BDF2 (order 2) and their dense outputs reproduce
// exactly, so all three are held to the same closed forms, up to rounding.
#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

#include "pogear/hybrid.hpp"

namespace pogear::rt {
namespace {

// Two inertias J1, J2 with torques tau1, tau2, joined by a clutch (slip s = omega1 - omega2): w =
// [tau1, tau2, T], the clutch torque acting as -T on body 1 and +T on body 2.
HybridSystem two_inertias(double J1, double J2, double tau1, double tau2, double capacity, double static_ratio,
                          Signal command) {
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(2, 2);
  sys.N = Eigen::MatrixXd::Zero(2, 3);
  sys.N(0, 0) = 1 / J1;
  sys.N(1, 1) = 1 / J2;
  sys.N(0, 2) = -1 / J1;
  sys.N(1, 2) = 1 / J2;
  sys.S = Eigen::MatrixXd(1, 2);
  sys.S << 1, -1;
  sys.elements.push_back({"C", capacity, static_ratio, std::move(command)});
  sys.inputs = {Constant{tau1}, Constant{tau2}};
  return sys;
}

struct Recorded {
  std::vector<HybridEvent> events;
  std::vector<double> t, w1, w2, T, slip, energy;
  std::vector<std::uint32_t> mode;
  RunStatus status;
};

class HybridMethods : public ::testing::TestWithParam<Solver> {
 protected:
  HybridMethod method() const { return HybridMethod{GetParam(), SolverOptions{}}; }
};

INSTANTIATE_TEST_SUITE_P(Hybrid, HybridMethods, ::testing::Values(Solver::exact, Solver::dopri5, Solver::implicit),
                         [](const auto& info) { return std::string(solver_name(info.param)); });

Recorded run(const HybridSystem& sys, const Eigen::VectorXd& x0, double horizon, double sample, HybridMethod method) {
  Recorded r;
  HybridEngine engine(sys, horizon, method);
  r.status = engine.run(
      x0, sample,
      [&](double t, const HybridSample& s) {
        r.t.push_back(t);
        r.w1.push_back(s.x(0));
        r.w2.push_back(s.x(1));
        r.T.push_back(s.w(s.w.size() - 1));
        r.slip.push_back(s.slip(0));
        r.energy.push_back(s.energy(0));
        r.mode.push_back(s.mode);
        return true;
      },
      [&](const HybridEvent& e) { r.events.push_back(e); });
  return r;
}

// Slipping with s > 0, the clutch torque c opposes it: s' = tau1/J1 - tau2/J2 - c (1/J1 + 1/J2), a
// constant, so the slip reaches zero at t* = s0 / (c (1/J1 + 1/J2) - (tau1/J1 - tau2/J2)). Locked,
// both turn at (tau1 + tau2)/(J1 + J2) with the clutch carrying T = (J2 tau1 - J1 tau2)/(J1 + J2).
TEST_P(HybridMethods, ClutchLockTimeInClosedForm) {
  const double J1 = 0.3, J2 = 1.7, tau1 = 20, tau2 = -5, c = 60;
  const HybridSystem sys = two_inertias(J1, J2, tau1, tau2, c, 1.2, Constant{1});
  Eigen::VectorXd x0(2);
  x0 << 100, 10;
  const double a = tau1 / J1 - tau2 / J2, b = c * (1 / J1 + 1 / J2), s0 = 90;
  const double t_lock = s0 / (b - a);
  const Recorded r = run(sys, x0, 2.0, 1e-3, method());
  ASSERT_TRUE(r.status.ok) << r.status.message;
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].from, ElementState::slipping);
  EXPECT_EQ(r.events[0].to, ElementState::stuck);
  // The bound: 1e-12 s (1 + t). The located time is the first double at which the slip has
  // crossed, found from the exact exponential, so its error is a few ulps of t.
  EXPECT_NEAR(r.events[0].t, t_lock, 1e-12 * (1 + t_lock));
  const double w_lock = 100 + (tau1 - c) / J1 * t_lock;
  const double T_stuck = (J2 * tau1 - J1 * tau2) / (J1 + J2);
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double t = r.t[i];
    if (t < t_lock) {
      // Rounding of sums of a few terms of size 100: 1e-12 absolute.
      EXPECT_NEAR(r.w1[i], 100 + (tau1 - c) / J1 * t, 1e-11) << t;
      EXPECT_NEAR(r.w2[i], 10 + (tau2 + c) / J2 * t, 1e-11) << t;
      EXPECT_EQ(r.T[i], c);
      EXPECT_EQ(r.mode[i], 0u);
      // Dissipated: c times the slip's integral, s falling linearly from s0.
      EXPECT_NEAR(r.energy[i], c * (s0 * t - 0.5 * (b - a) * t * t), 1e-9 * (1 + r.energy[i])) << t;
    } else {
      const double w = w_lock + (tau1 + tau2) / (J1 + J2) * (t - t_lock);
      EXPECT_NEAR(r.w1[i], w, 1e-11) << t;
      EXPECT_NEAR(r.w2[i], w, 1e-11) << t;
      EXPECT_NEAR(r.T[i], T_stuck, 1e-11) << t;
      EXPECT_EQ(r.mode[i], 1u);
      EXPECT_NEAR(r.energy[i], c * s0 * t_lock / 2, 1e-9 * r.energy[i]) << t;
    }
  }
}

// A clutch that cannot hold: the torque sticking would need exceeds the static capacity, so the slip
// passes through zero and reverses (no stuck phase), with the friction torque changing sign.
TEST_P(HybridMethods, SlipReversesWhenTheClutchCannotHold) {
  const double J1 = 1, J2 = 1, tau1 = 50, tau2 = -50, c = 10;  // sticking needs T = 50 > 1.5 c
  const HybridSystem sys = two_inertias(J1, J2, tau1, tau2, c, 1.5, Constant{1});
  Eigen::VectorXd x0(2);
  // s0 = -30: the torques drive s up at 100, friction opposing the negative slip adds 2c: s' = 120;
  // past zero friction turns against the positive slip: s' = 100 - 2c = 80.
  x0 << 0, 31;  // s0 = -31: the zero at 31/120 s falls between samples
  const Recorded r = run(sys, x0, 1.0, 1e-3, method());
  ASSERT_TRUE(r.status.ok) << r.status.message;
  const double t_zero = 31.0 / 120.0;
  ASSERT_EQ(r.events.size(), 0u);  // slipping throughout: the direction changes, the state does not
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double t = r.t[i];
    const double s = t < t_zero ? -31 + 120 * t : 80 * (t - t_zero);
    EXPECT_NEAR(r.slip[i], s, 1e-11) << t;
    EXPECT_EQ(r.T[i], t < t_zero ? -c : c) << t;
    EXPECT_EQ(r.mode[i], 0u);
  }
}

// Stuck, then break away when a growing torque exceeds the static capacity, then stick again when
// the torque falls: stuck -> slipping -> stuck, with the break-away time in closed form.
TEST_P(HybridMethods, BrakeBreaksAwayAndSticksAgain) {
  // One inertia J held by a brake (slip = omega), torque tau(t) = 40 t up to t = 1, then 40 - 200 (t - 1).
  HybridSystem sys;
  const double J = 2, c = 20, mu = 1.5;
  sys.M = Eigen::MatrixXd::Zero(1, 1);
  sys.N = Eigen::MatrixXd(1, 2);
  sys.N << 1 / J, -1 / J;
  sys.S = Eigen::MatrixXd::Ones(1, 1);
  sys.elements.push_back({"B", c, mu, Constant{1}});
  sys.inputs = {Table{{0, 1, 2}, {0, 40, -160}}};
  Recorded r;
  HybridEngine engine(sys, 2.0, method());
  r.status = engine.run(
      Eigen::VectorXd::Zero(1), 0.007,  // no event falls on a sample
      [&](double t, const HybridSample& s) {
        r.t.push_back(t);
        r.w1.push_back(s.x(0));
        r.T.push_back(s.w(1));
        r.mode.push_back(s.mode);
        return true;
      },
      [&](const HybridEvent& e) { r.events.push_back(e); });
  ASSERT_TRUE(r.status.ok) << r.status.message;
  // Breaks away when 40 t = mu c = 30: t = 0.75. Slipping forward, J omega' = tau - c, so omega =
  // (20 (t^2 - 0.75^2) - 20 (t - 0.75)) / J up to t = 1, then tau = 40 - 200 (t - 1); omega returns
  // to zero where its integral of (tau - c) vanishes, and the brake holds again (|tau| <= 30 there).
  ASSERT_GE(r.events.size(), 2u);
  EXPECT_EQ(r.events[0].from, ElementState::stuck);
  EXPECT_EQ(r.events[0].to, ElementState::slipping);
  EXPECT_NEAR(r.events[0].t, 0.75, 1e-12 * 1.75);
  EXPECT_EQ(r.events[1].to, ElementState::stuck);
  // omega(1) = (20 (1 - 0.5625) - 20 * 0.25) / 2 = 1.875; after t = 1: J omega' = 20 - 200 (t - 1),
  // omega = 1.875 + (20 u - 100 u^2) / 2 with u = t - 1: zero at u = (20 + sqrt(400 + 4*100*2*1.875)) / 200.
  const double u = (20 + std::sqrt(400 + 800 * 1.875)) / 200;
  EXPECT_NEAR(r.events[1].t, 1 + u, 1e-12 * (2 + u));
  // There the torque is 40 - 200 u = -23.6, within the static capacity 30: the brake holds until
  // the torque reaches -30 at t = 1.35, and the body breaks away backwards.
  ASSERT_EQ(r.events.size(), 3u);
  EXPECT_EQ(r.events[2].from, ElementState::stuck);
  EXPECT_NEAR(r.events[2].t, 1.35, 1e-12 * 2.35);
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double t = r.t[i];
    const bool stuck = t < 0.75 || (t >= 1 + u && t < 1.35);
    EXPECT_EQ(r.mode[i], stuck ? 1u : 0u) << t;
    if (stuck) {
      EXPECT_NEAR(r.w1[i], 0, 1e-12) << t;
      EXPECT_NEAR(r.T[i], t < 1 ? 40 * t : 40 - 200 * (t - 1), 1e-11) << t;
    }
  }
}

// Four inertias in a chain joined by three clutches (Modelica's CoupledClutches, with constant
// torque): friction torques are internal, so the total angular momentum grows by the input's
// impulse exactly, whatever the events; the clutches lock one after another until the chain turns
// as one, and the energy dissipated closes the power balance.
TEST_P(HybridMethods, ThreeCoupledClutches) {
  const std::vector<double> J{1, 2, 3, 4};
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(4, 4);
  sys.N = Eigen::MatrixXd::Zero(4, 4);  // w = [tau_1, T_C1, T_C2, T_C3]
  sys.N(0, 0) = 1 / J[0];
  sys.S = Eigen::MatrixXd::Zero(3, 4);
  for (int k = 0; k < 3; ++k) {
    sys.N(k, 1 + k) = -1 / J[k];
    sys.N(k + 1, 1 + k) = 1 / J[k + 1];
    sys.S(k, k) = 1;
    sys.S(k, k + 1) = -1;
  }
  sys.elements = {{"C1", 30, 1.2, Constant{1}}, {"C2", 20, 1.2, Constant{1}}, {"C3", 10, 1.2, Constant{1}}};
  sys.inputs = {Constant{10}};
  Eigen::VectorXd x0(4);
  x0 << 100, 50, 20, 0;
  const double h = 1e-3, horizon = 20;  // the clutches lock at 2, 7 and 17.3 s
  std::vector<double> t, momentum, kinetic, omega1;
  std::vector<HybridEvent> events;
  std::uint32_t last_mode = 0;
  Eigen::VectorXd last_x, dissipated;
  HybridEngine engine(sys, horizon, method());
  const RunStatus st = engine.run(
      x0, h,
      [&](double time, const HybridSample& s) {
        t.push_back(time);
        double p = 0, e = 0;
        for (int i = 0; i < 4; ++i) {
          p += J[i] * s.x(i);
          e += 0.5 * J[i] * s.x(i) * s.x(i);
        }
        momentum.push_back(p);
        kinetic.push_back(e);
        omega1.push_back(s.x(0));
        last_mode = s.mode;
        last_x = s.x;
        dissipated = s.energy;
        return true;
      },
      [&](const HybridEvent& e) { events.push_back(e); });
  ASSERT_TRUE(st.ok) << st.message;
  const double p0 = 100 * 1 + 50 * 2 + 20 * 3;
  // Sums of four products of size 1e3: rounding of 1e-12 relative per step, accumulated over the
  // 2e4 steps as a random walk at most.
  for (std::size_t i = 0; i < t.size(); ++i) EXPECT_NEAR(momentum[i], p0 + 10 * t[i], 1e-9 * p0) << t[i];
  EXPECT_EQ(last_mode, 0b111u);
  for (int i = 1; i < 4; ++i) EXPECT_NEAR(last_x(i), last_x(0), 1e-9 * std::abs(last_x(0)));
  int locks = 0;
  for (const HybridEvent& e : events) locks += e.to == ElementState::stuck;
  EXPECT_GE(locks, 3);
  // Input work 10 * int omega_1 dt by Simpson's rule: omega_1 is piecewise linear between events,
  // so the rule is exact on each piece and errs by O(h^2 * jump of its slope) at the kinks (1e-7).
  double work = 0;
  ASSERT_EQ((t.size() - 1) % 2, 0u);
  for (std::size_t i = 0; i + 2 < t.size(); i += 2) work += 10 * h / 3 * (omega1[i] + 4 * omega1[i + 1] + omega1[i + 2]);
  EXPECT_NEAR(kinetic.back() - kinetic.front(), work - dissipated.sum(), 1e-6 * work);
  EXPECT_GT(dissipated.minCoeff(), 0);
}

// A one-way brake on an inertia (J = 2): holding while the torque pushes it backwards, free while
// it pushes forwards; back at rest, it holds again. tau = -10 until 1 s, +10 until 2 s, then -10:
// free from 1 s with omega = 5 (t - 1), decelerating from 2 s to rest at exactly 3 s.
TEST_P(HybridMethods, OneWayBrakeFreewheelsForwardAndHoldsBackward) {
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(1, 1);
  sys.N = Eigen::MatrixXd(1, 2);
  sys.N << 0.5, -0.5;
  sys.S = Eigen::MatrixXd::Ones(1, 1);
  sys.elements.push_back({"OWB", 100, 1, Constant{1}, true});
  sys.inputs = {Table{{0, 1, 1, 2, 2}, {-10, -10, 10, 10, -10}}};
  std::vector<double> t, w, T, energy;
  std::vector<HybridEvent> events;
  HybridEngine engine(sys, 4.0, method());
  const RunStatus st = engine.run(
      Eigen::VectorXd::Zero(1), 0.007,
      [&](double time, const HybridSample& s) {
        t.push_back(time);
        w.push_back(s.x(0));
        T.push_back(s.w(1));
        energy.push_back(s.energy(0));
        return true;
      },
      [&](const HybridEvent& e) { events.push_back(e); });
  ASSERT_TRUE(st.ok) << st.message;
  ASSERT_EQ(events.size(), 2u);
  EXPECT_EQ(events[0].t, 1.0);  // on the input's breakpoint
  EXPECT_EQ(events[0].to, ElementState::slipping);
  EXPECT_NEAR(events[1].t, 3.0, 1e-12 * 4);
  EXPECT_EQ(events[1].to, ElementState::stuck);
  for (std::size_t i = 0; i < t.size(); ++i) {
    const double ti = t[i];
    const double omega = ti < 1 ? 0 : ti < 2 ? 5 * (ti - 1) : ti < 3 ? 5 - 5 * (ti - 2) : 0;
    EXPECT_NEAR(w[i], omega, 1e-12) << ti;
    // Holding, the brake carries the whole backward torque (-T on the body balances tau = -10).
    EXPECT_NEAR(T[i], ti < 1 || ti > 3 ? -10 : 0, 1e-12) << ti;
    EXPECT_EQ(energy[i], 0) << ti;  // freewheeling dissipates nothing
  }
}

// A mode whose fastest motion turns too far per sample for double precision: the exact method's
// exponential estimates its own rounding (exact.hpp) and the run stops with the simulators' message
// instead of printing states it cannot trust. Two inertias joined by a spring of 1e12 N m/rad (about
// 1.4e6 rad/s), sampled every 100 s: 1.4e8 rad per step, an estimated error of about 1e-8, above the
// 1e-10 limit. The clutch to the housing stays open, so that whole sample periods are stepped.
TEST(Hybrid, UntrustedExponentialStopsTheRun) {
  HybridSystem sys;
  const double J1 = 1, J2 = 1, k = 1e12;
  sys.M = Eigen::MatrixXd::Zero(3, 3);  // x = [omega1, omega2, twist]
  sys.M(0, 2) = -k / J1;
  sys.M(1, 2) = k / J2;
  sys.M(2, 0) = 1;
  sys.M(2, 1) = -1;
  sys.N = Eigen::MatrixXd::Zero(3, 2);  // w = [tau, T_C], the clutch between body 2 and the housing
  sys.N(0, 0) = 1 / J1;
  sys.N(1, 1) = -1 / J2;
  sys.S = Eigen::MatrixXd(1, 3);
  sys.S << 0, 1, 0;
  sys.elements.push_back({"C", 1.0, 1.0, Constant{0.0}});
  sys.inputs = {Constant{10.0}};
  Eigen::VectorXd x0(3);
  x0 << 0, 100, 0;
  HybridEngine engine(sys, 1000.0);
  long samples = 0;
  const RunStatus st = engine.run(
      x0, 100.0, [&](double, const HybridSample&) { return ++samples, true; }, [](const HybridEvent&) {});
  EXPECT_FALSE(st.ok);
  EXPECT_NE(st.message.find("exact stepping lost accuracy: with steps of 100 s"), std::string::npos) << st.message;
  EXPECT_EQ(samples, 1);  // t = 0 only: no state of an untrusted step was observed
}

// A speed crossing whose located state lies an ulp beyond its monitor's band: mode resolution judges
// the monitor's limit by the event function's own margin, so it changes regime there (before, a
// rounding of the widened limit kept it within, its event function stayed negative, and the run
// stopped as chattering). One body at 150 rad/s decelerating at 20 rad/s^2 (-10 N m on 0.5 kg m^2);
// the brake's command starts as the speed falls below the value, at (150 - value) / 20 s.
TEST_P(HybridMethods, SpeedCrossingOnItsBandStartsOnce) {
  for (const double value : {139.9, 139.3, 120.7}) {
    SCOPED_TRACE(value);
    HybridSystem sys;
    sys.M = Eigen::MatrixXd::Zero(1, 1);
    sys.N = Eigen::MatrixXd(1, 2);
    sys.N << 1 / 0.5, -1 / 0.5;
    sys.S = Eigen::MatrixXd::Ones(1, 1);
    sys.inputs = {Constant{-10}};
    sys.elements.push_back({"B", 20, 1.2, Table{{0, 0.1}, {1, 1}}});
    CrossingTrigger c;
    c.speed = Eigen::RowVectorXd::Ones(1);
    c.value = value;
    c.output = "omega_a";
    sys.triggered = {{true, 0, -1, ElementState::slipping, 0, "command_B", Signal{Constant{0}}, c}};
    Recorded r;
    HybridEngine engine(sys, 2.0, method());
    r.status = engine.run(Eigen::VectorXd::Constant(1, 150), 1e-3, [](double, const HybridSample&) { return true; },
                          [&](const HybridEvent& e) { r.events.push_back(e); });
    ASSERT_TRUE(r.status.ok) << r.status.message;
    ASSERT_EQ(r.events.size(), 2u);  // the start, and B engaging at it
    // The crossing lies beyond the band (256 ulps of 150 rad/s, 8.5e-12 rad/s, 4e-13 s at 20 rad/s^2)
    // and the exact flow's rounding over the run's steps: within 1e-12 s of the closed form.
    const double t = (150 - value) / 20;
    EXPECT_EQ(r.events[0].started, 0);
    EXPECT_NEAR(r.events[0].t, t, 1e-12);
    EXPECT_EQ(r.events[1].to, ElementState::slipping);
    EXPECT_EQ(r.events[1].t, r.events[0].t);
  }
}

}  // namespace
}  // namespace pogear::rt
