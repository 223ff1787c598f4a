// Exact stepping outside its accurate range: steps that turn the fastest modes too far for double
// precision are refused with a message, never printed as results; huge steps of a damped scene
// land on its steady state; stiff scenes inside the range keep the slow motion to the estimate.
// The refusal as `pogear simulate` reports it: tests/commands/exact_range_test.cpp.
#include <fmt/format.h>

#include "stability_support.hpp"

namespace pogear::test {
namespace {

const char* const kLost = "exact stepping lost accuracy: with steps of 0.001 s the scene's fastest modes turn too far";

// The references below are the elastic model's exact solution x(t) = int_0^t e^(M s) ds N u, the
// top right column of exp([[M t, N u t], [0, 0]]), computed with mpmath's expm at 80 significant
// digits (120 for K = 1e30: the same digits) from the double-precision M and N that pogear derives
// for the scene. Their phase of the fastest modes (up to 5e27 rad) is exact there, and the
// velocities hardly depend on it: those modes move the velocities by ~F / sqrt(K J), below 1e-12.

// K = 1e30 N/m and J_p = 1e-30 kg m^2, no damping: modes of 5e28 rad/s, 5e25 rad per 1 ms step.
// Exact stepping printed 0 for every velocity; the reference omega_c(0.1 s) = 5.70718059817, which
// the rigid model (the limit of stiff meshes, as the message suggests) gives to 1e-12.
TEST(ExactRange, StiffMeshesWithATinyPlanetAreRefusedAndTheRigidModelIsRight) {
  const SpecializedScene m =
      scene_model(range_scene(kUndamped, "K_ps = \"1e30*Newton/m\"\nJ_p = \"1e-30*kg*meters^2\"", "0.1*s", "1*ms"));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
  EXPECT_FALSE(tr.status.ok);
  EXPECT_NE(tr.status.message.find(kLost), std::string::npos) << tr.status.message;
  EXPECT_NE(tr.status.message.find("(the matrix exponential overflows)"), std::string::npos) << tr.status.message;
  EXPECT_LE(tr.t.size(), 1u) << "no velocity may be printed past t = 0";

  const SpecializedScene rigid = scene_model(range_scene("", "K_ps = \"1e30*Newton/m\"\nJ_p = \"1e-30*kg*meters^2\"",
                                                 "0.1*s", "1*ms"));
  const Trajectory r = interpret_trajectory(rigid, rigid.main, run_settings(rigid));
  ASSERT_TRUE(r.status.ok) << r.status.message;
  // Frictionless rigid gear under a constant torque: omega grows linearly, the exact map has no
  // rounding but that of one product per step (1e-16 relative, 100 steps). The elastic
  // reference differs from it by the fast modes' share, below 1e-12.
  EXPECT_NEAR(r.x.back()(0), 5.70718059817, 1e-10);
}

// J_p = 1e-30 kg m^2 alone: 5e16 rad/s, 5e13 rad per step. Exact stepping printed
// omega_c(0.1 s) = 5.4168 (19 % off; reference 6.67140742453) and omega_p = 4.27 (reference
// 5.05791980484). With the squaring of e^(Mh) - I the carrier comes out right, but the planet's
// velocity, which the fast mode moves by a visible amount, cannot be (its phase is lost): refused.
TEST(ExactRange, ATinyPlanetInertiaIsRefused) {
  const SpecializedScene m = scene_model(range_scene(kUndamped, "J_p = \"1e-30*kg*meters^2\"", "0.1*s", "1*ms"));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
  EXPECT_FALSE(tr.status.ok);
  EXPECT_NE(tr.status.message.find(kLost), std::string::npos) << tr.status.message;
  EXPECT_LE(tr.t.size(), 1u);
}

// Every effect, steps of 1e14 s and 1e18 s. After a step of 1e14 s, 3e14 times the slowest time
// constant (0.32 s), e^(M h) is 0 to every digit, so each sample is the steady state -M^-1 N u,
// which one LU solve gives to cond(M) eps (the 80-digit reference agrees: omega_c = 17.1148855838,
// omega_m = -26.4338683070). Exact stepping printed 0.313 (e^-4 of it: one ulp of the neutral input
// hold squared 2^55 times) and 0 from 1e18 s on.
TEST(ExactRange, HugeStepsOfADampedSceneLandOnItsSteadyState) {
  for (const auto& [horizon, sample] : {std::pair{"1e15*s", "1e14*s"}, std::pair{"1e19*s", "1e18*s"}}) {
    const SpecializedScene m = scene_model(
        range_scene("\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\"", "", horizon, sample));
    const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
    ASSERT_TRUE(tr.status.ok) << tr.status.message;
    ASSERT_EQ(tr.t.size(), 11u);
    const NumericSystem ns = numeric_system(m, m.main);
    const Eigen::VectorXd steady = -ns.M.partialPivLu().solve(ns.N * Eigen::VectorXd::Constant(1, 100.0));
    EXPECT_NEAR(steady(0), 17.1148855838, 1e-9);
    const double cond = ns.M.norm() * ns.M.inverse().norm();
    for (std::size_t k = 1; k < tr.x.size(); ++k)
      // The step maps any state to the steady state up to the rounding of Gamma0 (the estimate
      // is 1e-20 here) and of the solve: cond(M) eps each, cond(M) = 2e5.
      EXPECT_LT((tr.x[k] - steady).norm() / steady.norm(), 100 * cond * std::numeric_limits<double>::epsilon())
          << sample << " sample " << k;
  }
}

// Stiffer and stiffer meshes, no damping, 100 steps of 1 ms: the measured range. Accepted while
// the estimate of one step's error stays below 1e-10. One step's rounding, repeated, adds up over
// the 100 steps; measured, the error after them is 75 to 1100 times the estimate, i.e. each step
// errs by 1 to 11 times it. The bound allows 100 times per step.
struct StiffCase {
  double K, omega_c, omega_p;  // N/m; the 80-digit references at 0.1 s
  bool accepted;
};

TEST(ExactRange, StiffMeshesKeepTheSlowMotionWithinTheEstimateOrAreRefused) {
  const StiffCase cases[] = {
      {1e12, 5.67926633301, 5.13879513086, true},  // estimate 1.9e-14, measured 4e-12
      {1e15, 5.67992004570, 5.13927725569, true},  // estimate 1.9e-13, measured 2.5e-11
      {1e18, 5.67990980749, 5.13935806678, true},  // estimate 3.5e-12, measured 4e-9
      {1e24, 5.67990988162, 5.13935659395, false},  // estimate 2.3e-9: refused
      {1e30, 5.67990988151, 5.13935659546, false},  // estimate 8e-6: refused
  };
  for (const StiffCase& c : cases) {
    const SpecializedScene m = scene_model(range_scene(kUndamped, fmt::format("K_ps = \"{}*Newton/m\"", c.K), "0.1*s", "1*ms"));
    const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
    EXPECT_EQ(tr.status.ok, c.accepted) << "K = " << c.K << ": " << tr.status.message;
    if (!c.accepted) {
      EXPECT_NE(tr.status.message.find(kLost), std::string::npos) << tr.status.message;
      continue;
    }
    const NumericSystem ns = numeric_system(m, m.main);
    const rt::ExactDiscretization<Eigen::Dynamic, Eigen::Dynamic> disc(ns.M, ns.N, 1e-3);
    ASSERT_EQ(tr.t.size(), 101u);
    // 100 steps, each within a few times the estimate (at least rounding, 1e-15).
    const double bound = 100 * 100 * std::max(disc.rounding, 1e-15);
    EXPECT_NEAR(tr.x.back()(0), c.omega_c, bound * c.omega_c) << "K = " << c.K << ", estimate " << disc.rounding;
    EXPECT_NEAR(tr.x.back()(1), c.omega_p, bound * c.omega_p) << "K = " << c.K << ", estimate " << disc.rounding;
  }
}

// A step other than the nominal one (next to a breakpoint, the last partial sample) is checked
// when it is built: an untrustworthy one stops the run on the spot.
TEST(ExactRange, AnUntrustworthyOddStepStopsTheRun) {
  const SpecializedScene m = scene_model(range_scene(kUndamped, "J_p = \"1e-30*kg*meters^2\"", "0.1*s", "1*ms"));
  const NumericSystem ns = numeric_system(m, m.main);
  using D = rt::ExactDiscretization<Eigen::Dynamic, Eigen::Dynamic>;
  D odd;
  Eigen::VectorXd x = Eigen::VectorXd::Zero(ns.M.rows());
  auto discretize = [&](double h) { return D(ns.M, ns.N, h); };
  rt::detail::refresh_odd(odd, discretize, 1e-12, x);  // 5e4 rad per step: fine
  EXPECT_TRUE(odd.accurate()) << odd.rounding;
  EXPECT_TRUE(x.allFinite());
  rt::detail::refresh_odd(odd, discretize, 1e-3, x);
  EXPECT_FALSE(odd.accurate()) << odd.rounding;
  EXPECT_FALSE(x.allFinite()) << "the state must stop the run";
  EXPECT_NE(rt::detail::inaccurate_exact_step(odd.h, odd.rounding).find(kLost), std::string::npos);
}

}  // namespace
}  // namespace pogear::test
