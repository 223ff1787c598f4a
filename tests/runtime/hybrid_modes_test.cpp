// The matrices of a mode of stuck brakes and clutches (hybrid_modes.hpp): whether the stuck
// elements constrain the gear more than once is decided alike at every scale of the inertias.
#include <gtest/gtest.h>

#include <vector>

#include "pogear/hybrid_modes.hpp"

namespace pogear::rt {
namespace {

// Bodies a and b on separate trains (no mesh between them), inertias Ja and Jb, torques tau_a and
// tau_b, a brake on each and a clutch between them: w = [tau_a, tau_b, T_A, T_B, T_C], a brake's
// torque acting as -T on its body, the clutch's as -T on a and +T on b.
HybridSystem two_trains(double Ja, double Jb) {
  HybridSystem sys;
  sys.M = Eigen::MatrixXd::Zero(2, 2);
  sys.N = Eigen::MatrixXd::Zero(2, 5);
  sys.N(0, 0) = 1 / Ja;
  sys.N(1, 1) = 1 / Jb;
  sys.N(0, 2) = -1 / Ja;
  sys.N(1, 3) = -1 / Jb;
  sys.N(0, 4) = -1 / Ja;
  sys.N(1, 4) = 1 / Jb;
  sys.S = Eigen::MatrixXd(3, 2);
  sys.S << 1, 0, 0, 1, 1, -1;
  for (const char* name : {"A", "B", "C"}) sys.elements.push_back({name, 100, 1.2, Constant{1}});
  sys.inputs = {Constant{3}, Constant{-2}};
  return sys;
}

// Two brakes on two trains are independent whatever the trains' inertias, over the range a model
// file accepts for inertias that meet in one gear (1e-9 to 1e9 kg m^2 here, 18 decades apart);
// each holds the torque applied to its body, T = tau.
TEST(HybridModes, IndependentBrakesAreIndependentAtEveryScale) {
  for (double Ja : {1e-9, 1e-3, 1.0, 1e3, 1e9})
    for (double Jb : {1e-9, 1e-3, 1.0, 1e3, 1e9}) {
      SCOPED_TRACE(testing::Message() << "Ja " << Ja << ", Jb " << Jb);
      const hybrid_detail::ModeMatrices m = hybrid_detail::mode_matrices(two_trains(Ja, Jb), 0b011);
      ASSERT_FALSE(m.singular);
      ASSERT_EQ(m.Kv.rows(), 2);
      // T_S = Kv w with the stuck torques' own columns zero: T_A = tau_a, T_B = tau_b, to rounding.
      EXPECT_NEAR(m.Kv(0, 0), 1, 1e-14);
      EXPECT_NEAR(m.Kv(0, 1), 0, 1e-14);
      EXPECT_NEAR(m.Kv(1, 1), 1, 1e-14);
      EXPECT_NEAR(m.Kv(1, 0), 0, 1e-14);
      // Both bodies held: the mode has no motion.
      EXPECT_LE(m.A.cwiseAbs().maxCoeff(), 1e-14 * std::max(1 / Ja, 1 / Jb));
    }
}

// The clutch with both brakes constrains the two speeds three times: refused at every scale, as
// dependent rows, not as a matter of conditioning.
TEST(HybridModes, ABrakeClutchBrakeLoopIsOverConstrainedAtEveryScale) {
  for (double Ja : {1e-9, 1.0, 1e9})
    for (double Jb : {1e-9, 1.0, 1e9}) {
      SCOPED_TRACE(testing::Message() << "Ja " << Ja << ", Jb " << Jb);
      const hybrid_detail::ModeMatrices m = hybrid_detail::mode_matrices(two_trains(Ja, Jb), 0b111);
      EXPECT_TRUE(m.singular);
      EXPECT_FALSE(m.ill_conditioned);
    }
}

// Brake A and the clutch hold a, and b through a: T_A = tau_a + tau_b, T_C = -tau_b. The clutch
// couples the two inertias, so the torques are computed from accelerations of both scales; within
// six decades of each other they come out to 1e-9, beyond it (where double precision would give
// no correct digit: NaN at 1e-9 against 1e9 kg m^2) the mode is refused as ill-conditioned.
TEST(HybridModes, CoupledElementsAreComputedOrRefusedNeverWrong) {
  for (double Ja : {1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9})
    for (double Jb : {1e-9, 1e-6, 1e-3, 1.0, 1e3, 1e6, 1e9}) {
      SCOPED_TRACE(testing::Message() << "Ja " << Ja << ", Jb " << Jb);
      const hybrid_detail::ModeMatrices m = hybrid_detail::mode_matrices(two_trains(Ja, Jb), 0b101);
      const double spread = std::max(Ja, Jb) / std::min(Ja, Jb);
      if (spread <= 1e6) {
        ASSERT_FALSE(m.singular);
      }
      if (m.singular) {
        EXPECT_TRUE(m.ill_conditioned);
        continue;
      }
      // Error about eps times the spread (the rounding of the larger acceleration): at most 2e-10.
      EXPECT_NEAR(m.Kv(0, 0), 1, 1e-9);
      EXPECT_NEAR(m.Kv(0, 1), 1, 1e-9);
      EXPECT_NEAR(m.Kv(1, 0), 0, 1e-9);
      EXPECT_NEAR(m.Kv(1, 1), -1, 1e-9);
    }
  EXPECT_TRUE(hybrid_detail::mode_matrices(two_trains(1e-9, 1e9), 0b101).ill_conditioned);
}

}  // namespace
}  // namespace pogear::rt
