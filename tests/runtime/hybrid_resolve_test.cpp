// Mode resolution alone (runtime/pogear/hybrid_resolve.hpp) on the static cases of
// docs/friction-elements.md: an element at zero slip sticks when its torque is within its static
// capacity and slips in its torque's direction when not; two brakes on one body over-constrain it;
// a one-way element holds backward and freewheels forward; coupled clutches release the most
// overloaded first; an open element is no candidate; a stuck state is projected onto its constraint.
#include <gtest/gtest.h>

#include <string>
#include <vector>

#include "pogear/hybrid_data_check.hpp"
#include "pogear/hybrid_resolve.hpp"

namespace pogear::rt {
namespace {

// Inertias J_i in a chain with input torques tau_i, clutch k between bodies k and k+1 (slip
// omega_k - omega_{k+1}, its torque acting as -T on body k and +T on body k+1).
HybridSystem chain(const std::vector<double>& J, const std::vector<double>& tau, const std::vector<double>& capacity,
                   double static_ratio) {
  const auto n = static_cast<Eigen::Index>(J.size()), nc = static_cast<Eigen::Index>(capacity.size());
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(n, n);
  sys.N = Eigen::MatrixXd::Zero(n, n + nc);
  sys.S = Eigen::MatrixXd::Zero(nc, n);
  for (Eigen::Index i = 0; i < n; ++i) {
    sys.N(i, i) = 1 / J[static_cast<std::size_t>(i)];
    sys.inputs.emplace_back(Constant{tau[static_cast<std::size_t>(i)]});
  }
  for (Eigen::Index k = 0; k < nc; ++k) {
    sys.N(k, n + k) = -1 / J[static_cast<std::size_t>(k)];
    sys.N(k + 1, n + k) = 1 / J[static_cast<std::size_t>(k + 1)];
    sys.S(k, k) = 1;
    sys.S(k, k + 1) = -1;
    const char* names[] = {"C1", "C2", "C3"};
    sys.elements.push_back({names[k], capacity[static_cast<std::size_t>(k)], static_ratio, Constant{1}});
  }
  return sys;
}

struct Resolved {
  bool ok = false;
  std::string error;
  std::vector<HybridEvent> events;
};

Resolved resolve(const HybridSystem& sys, hybrid::HybridData& d, const Eigen::VectorXd& x, int trigger = -1) {
  Resolved r;
  d.x = x;
  r.ok = hybrid::resolve_mode(sys, d, 0.0, trigger, [&](const HybridEvent& e) { r.events.push_back(e); }, r.error);
  return r;
}

// Two inertias J1 = 1, J2 = 3 at one speed, tau1 = 8: held together, the clutch carries
// T = (J2 tau1 - J1 tau2) / (J1 + J2) = 6 N m.
TEST(ResolveMode, ClutchAtZeroSlipHoldsWithinItsStaticCapacity) {
  const HybridSystem sys = chain({1, 3}, {8, 0}, {5}, 1.5);  // static capacity 7.5
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved r = resolve(sys, d, Eigen::Vector2d(2, 2));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(d.mask, 1u);
  EXPECT_EQ(d.state[0], ElementState::stuck);
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_EQ(r.events[0].from, ElementState::open);
  EXPECT_EQ(r.events[0].to, ElementState::stuck);
  EXPECT_EQ(d.x, Eigen::Vector2d(2, 2));  // already on the constraint: the projection leaves it
  const auto& m = hybrid::mode_of(sys, d.cache, d.mask);
  hybrid::known_inputs(sys, d, 0.0, false, d.x, d.v);
  const double T = (m.Kx * d.x + m.Kv * d.v)(0);
  EXPECT_NEAR(T, 6, 1e-14);  // a few roundings of the 2x2 solve
}

TEST(ResolveMode, ClutchBeyondItsStaticCapacitySlipsInItsTorquesDirection) {
  const HybridSystem sys = chain({1, 3}, {8, 0}, {5}, 1.0);  // static capacity 5 < 6
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved r = resolve(sys, d, Eigen::Vector2d(2, 2));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(d.mask, 0u);
  EXPECT_EQ(d.state[0], ElementState::slipping);
  EXPECT_EQ(d.dir[0], 1);  // T > 0: body 1 runs ahead
  hybrid::known_inputs(sys, d, 0.0, false, d.x, d.v);
  EXPECT_EQ(d.v(2), 5);  // the kinetic torque c p, in the slip's direction
}

// The zero-slip rule (docs/friction-elements.md): a slip within 256 ulps of the speeds it is
// computed from is zero. A locked pair at 300 rad/s whose second speed carries a rounding error of
// 1e-15 relative has a slip of 3e-13 rad/s: the clutch holds (before, the noise's sign chose a
// slipping direction and the full kinetic torque). A slip of 1e-9 rad/s is real and slips.
TEST(ResolveMode, SlipWithinTheRoundingOfItsSpeedsIsZero) {
  const HybridSystem sys = chain({1, 3}, {8, 0}, {5}, 1.5);
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Eigen::Vector2d x(300, 300 * (1 - 1e-15));
  ASSERT_NE(x(0) - x(1), 0.0);
  const Resolved held = resolve(sys, d, x);
  ASSERT_TRUE(held.ok) << held.error;
  EXPECT_EQ(d.mask, 1u);
  EXPECT_EQ(d.state[0], ElementState::stuck);

  hybrid::HybridData e = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved slips = resolve(sys, e, Eigen::Vector2d(300, 300 - 1e-9));
  ASSERT_TRUE(slips.ok) << slips.error;
  EXPECT_EQ(e.mask, 0u);
  EXPECT_EQ(e.dir[0], 1);
}

// A brake on a body whose speed is -1.4e-17 rad/s by rounding while the gear's other body turns at
// 100 rad/s: the brake starts stuck, carrying the body's torque, not its full capacity backward.
TEST(ResolveMode, BrakeOnABodyAtRestByRoundingStartsStuck) {
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(2, 2);
  sys.N = Eigen::MatrixXd::Zero(2, 3);
  sys.N(0, 0) = 1;
  sys.N(1, 1) = 0.5;
  sys.N(1, 2) = -0.5;
  sys.S = Eigen::MatrixXd(1, 2);
  sys.S << 0, 1;
  sys.elements = {{"B", 50, 1.2, Constant{1}}};
  sys.inputs = {Constant{0}, Constant{4}};
  sys.speed_states = {0, 1};  // both states are speeds: the scale is the gear's, 100 rad/s
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved r = resolve(sys, d, Eigen::Vector2d(100, -1.4e-17));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(d.mask, 1u);
  EXPECT_EQ(d.x(1), 0.0);  // projected onto the constraint
  const auto& m = hybrid::mode_of(sys, d.cache, d.mask);
  hybrid::known_inputs(sys, d, 0.0, false, d.x, d.v);
  EXPECT_NEAR((m.Kx * d.x + m.Kv * d.v)(0), 4, 1e-14);  // the input torque, to rounding
}

TEST(ResolveMode, TwoBrakesOnOneBodyOverConstrainIt) {
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(1, 1);
  sys.N = Eigen::MatrixXd(1, 3);
  sys.N << 1, -1, -1;
  sys.S = Eigen::MatrixXd::Ones(2, 1);
  sys.elements = {{"B1", 10, 1, Constant{1}}, {"B2", 10, 1, Constant{1}}};
  sys.inputs = {Constant{1}};
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved r = resolve(sys, d, Eigen::VectorXd::Zero(1));
  EXPECT_FALSE(r.ok);
  EXPECT_NE(r.error.find("the stuck elements B1, B2 constrain the gear more than once"), std::string::npos) << r.error;
}

// One body held by a one-way brake (slip = omega): it holds a torque that pushes backward and lets
// the body run forward, carrying nothing then.
TEST(ResolveMode, OneWayBrakeHoldsBackwardAndFreewheelsForward) {
  for (const double tau : {-3.0, 3.0}) {
    HybridSystem sys;
    sys.M = Eigen::MatrixXd::Zero(1, 1);
    sys.N = Eigen::MatrixXd(1, 2);
    sys.N << 1, -1;
    sys.S = Eigen::MatrixXd::Ones(1, 1);
    sys.elements.push_back({"F", 100, 1, Constant{1}, true});
    sys.inputs = {Constant{tau}};
    hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
    const Resolved r = resolve(sys, d, Eigen::VectorXd::Zero(1));
    ASSERT_TRUE(r.ok) << r.error;
    hybrid::known_inputs(sys, d, 0.0, false, d.x, d.v);
    if (tau < 0) {
      EXPECT_EQ(d.state[0], ElementState::stuck);
    } else {
      EXPECT_EQ(d.state[0], ElementState::slipping);
      EXPECT_EQ(d.dir[0], 1);
      EXPECT_EQ(d.v(1), 0);  // freewheeling
    }
  }
}

// Three equal inertias at one speed, 9 N m on body 1: both clutches stuck would carry 6 and 3 N m.
// C1 (capacity 4) is the more overloaded and is released first; with C1 slipping at 4 N m, C2
// carries 2 and holds.
TEST(ResolveMode, CoupledClutchesReleaseTheMostOverloadedFirst) {
  const HybridSystem sys = chain({1, 1, 1}, {9, 0, 0}, {4, 2.5}, 1.0);
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved r = resolve(sys, d, Eigen::Vector3d(1, 1, 1));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(d.mask, 2u);
  EXPECT_EQ(d.state[0], ElementState::slipping);
  EXPECT_EQ(d.state[1], ElementState::stuck);
  EXPECT_EQ(r.events.size(), 2u);
}

TEST(ResolveMode, OpenElementIsNoCandidate) {
  HybridSystem sys = chain({1, 3}, {8, 0}, {5}, 1.5);
  sys.elements[0].command = Constant{0};
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Resolved r = resolve(sys, d, Eigen::Vector2d(2, 1));
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(d.mask, 0u);
  EXPECT_EQ(d.state[0], ElementState::open);
  EXPECT_TRUE(r.events.empty());  // open it was
  EXPECT_EQ(d.dir[0], 1);         // the slip's direction, for when it engages
}

// A slip that has just reached zero (the event's element, `trigger`) up to the location's rounding:
// the stuck state is projected onto S x = 0, conserving the angular momentum J1 w1 + J2 w2.
TEST(ResolveMode, StuckStateIsProjectedOntoTheConstraint) {
  const HybridSystem sys = chain({1, 3}, {8, 0}, {5}, 1.5);
  hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  const Eigen::Vector2d x(2 + 1e-9, 2);
  const Resolved r = resolve(sys, d, x, 0);
  ASSERT_TRUE(r.ok) << r.error;
  EXPECT_EQ(d.mask, 1u);
  EXPECT_NEAR(d.x(0) - d.x(1), 0, 1e-15);               // rounding of the projection of states near 2
  EXPECT_NEAR(d.x(0) + 3 * d.x(1), x(0) + 3 * x(1), 1e-14);  // ditto, momentum about 8
}

TEST(HybridData, MismatchedSystemIsReported) {
  const HybridSystem sys = chain({1, 3}, {8, 0}, {5}, 1.5), other = chain({1, 1, 1}, {9, 0, 0}, {4, 2.5}, 1.0);
  const hybrid::HybridData d = hybrid::make_hybrid_data(sys, 1.0);
  EXPECT_EQ(hybrid::data_mismatch(sys, d), nullptr);
  EXPECT_NE(hybrid::data_mismatch(other, d), nullptr);
}

}  // namespace
}  // namespace pogear::rt
