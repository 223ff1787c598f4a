// The hybrid engine (runtime/pogear/hybrid.hpp) on systems whose stick–slip motion is known in
// closed form: two inertias and a clutch, a brake that breaks away and sticks again, coupled clutches.
#include <gtest/gtest.h>

#include <cmath>
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

Recorded run(const HybridSystem& sys, const Eigen::VectorXd& x0, double horizon, double sample) {
  Recorded r;
  HybridEngine engine(sys, horizon);
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
TEST(Hybrid, ClutchLockTimeInClosedForm) {
  const double J1 = 0.3, J2 = 1.7, tau1 = 20, tau2 = -5, c = 60;
  const HybridSystem sys = two_inertias(J1, J2, tau1, tau2, c, 1.2, Constant{1});
  Eigen::VectorXd x0(2);
  x0 << 100, 10;
  const double a = tau1 / J1 - tau2 / J2, b = c * (1 / J1 + 1 / J2), s0 = 90;
  const double t_lock = s0 / (b - a);
  const Recorded r = run(sys, x0, 2.0, 1e-3);
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
TEST(Hybrid, SlipReversesWhenTheClutchCannotHold) {
  const double J1 = 1, J2 = 1, tau1 = 50, tau2 = -50, c = 10;  // sticking needs T = 50 > 1.5 c
  const HybridSystem sys = two_inertias(J1, J2, tau1, tau2, c, 1.5, Constant{1});
  Eigen::VectorXd x0(2);
  // s0 = -30: the torques drive s up at 100, friction opposing the negative slip adds 2c: s' = 120;
  // past zero friction turns against the positive slip: s' = 100 - 2c = 80.
  x0 << 0, 31;  // s0 = -31: the zero at 31/120 s falls between samples
  const Recorded r = run(sys, x0, 1.0, 1e-3);
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
TEST(Hybrid, BrakeBreaksAwayAndSticksAgain) {
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
  HybridEngine engine(sys, 2.0);
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

}  // namespace
}  // namespace pogear::rt
