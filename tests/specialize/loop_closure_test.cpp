// Loads and a PI speed controller closed into the equations of tests/vibration/pair.toml, against
// the closed loop written out by hand: the specialized system's (M, N) and the reference model's,
// which computes them from the derivation's L, A, B by another route.
#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "../support/ports.hpp"
#include "common/exact_algebra.hpp"
#include "read/scene.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

// Wheel a (r_a = 10 cm, J_a = 0.02 kg m^2) meshing b (r_b = 25 cm, J_b = 0.3 kg m^2), no bearing
// friction, kept velocity omega_a: rigid, J omega_a' = torques on a, J = J_a + J_b (r_a / r_b)^2.
constexpr double inertia_seen_from_a = 0.02 + 0.3 * (0.10 / 0.25) * (0.10 / 0.25);

SpecializedScene pair_with(const std::string& tables) {
  const std::string text = "name = \"loops\"\nmodel = \"../../tests/vibration/pair.toml\"\nkeep = [\"a\"]\n"
                           "effects = [\"bearing_friction\"]\n" + tables +
                           "\n[initial]\nomega_a = \"0*rpm\"\n\n[simulation]\nhorizon = \"1*s\"\nsample = \"1*ms\"\n";
  return specialize(parse_scene_text(text, source_path("models/scenes/variant.toml")));
}

// Both routes to (M, N) against the expected ones; the specialized entries are exact rationals
// and the reference model rounds once, so only the last bits of the doubles may differ.
void expect_system(const SpecializedScene& m, const Eigen::MatrixXd& M, const Eigen::MatrixXd& N) {
  const Eigen::MatrixXd specialized_M = evaluate_matrix(m.main.M, {}), specialized_N = evaluate_matrix(m.main.N, {});
  const NumericSystem reference = numeric_system(m, m.main);
  ASSERT_EQ(specialized_M.rows(), M.rows());
  ASSERT_EQ(specialized_N.cols(), N.cols());
  const double scale = M.cwiseAbs().maxCoeff() + N.cwiseAbs().maxCoeff();
  EXPECT_LE((specialized_M - M).cwiseAbs().maxCoeff(), 1e-14 * scale) << specialized_M;
  EXPECT_LE((specialized_N - N).cwiseAbs().maxCoeff(), 1e-14 * scale) << specialized_N;
  EXPECT_LE((reference.M - M).cwiseAbs().maxCoeff(), 1e-14 * scale) << reference.M;
  EXPECT_LE((reference.N - N).cwiseAbs().maxCoeff(), 1e-14 * scale) << reference.N;
}

TEST(LoopClosure, PISpeedControllerByHand) {
  // Tc = kp (ref - omega_a) + ki theta, theta' = ref - omega_a; states (omega_a, theta), input ref.
  const double kp = 0.5, ki = 0.25, J = inertia_seen_from_a;
  const SpecializedScene m = pair_with(
      "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\", ki = \"0.25*N*m/rad\" }\n");
  ASSERT_EQ(state_names(m, m.main), (std::vector<std::string>{"omega_a", "theta_speed"}));
  ASSERT_EQ(input_names(m, m.main), (std::vector<std::string>{"ref_speed"}));
  Eigen::MatrixXd M(2, 2), N(2, 1);
  M << -kp / J, ki / J, -1, 0;
  N << kp / J, 1;
  expect_system(m, M, N);
}

TEST(LoopClosure, LinearLoadDampsAndItsConstantPartIsAnInput) {
  // The load -(c0 + c1 omega_a) on a: J omega_a' = TL_a - c1 omega_a, its constant part the input
  // TL_a (a constant signal of value -c0).
  const double c1 = 0.04, J = inertia_seen_from_a;
  const SpecializedScene m = pair_with("[loads]\na = { constant = \"0.2*N*m\", linear = \"0.04*N*m*s/rad\" }\n");
  ASSERT_EQ(state_names(m, m.main), (std::vector<std::string>{"omega_a"}));
  ASSERT_EQ(input_names(m, m.main), (std::vector<std::string>{"TL_a"}));
  Eigen::MatrixXd M(1, 1), N(1, 1);
  M << -c1 / J;
  N << 1 / J;
  expect_system(m, M, N);
}

}  // namespace
}  // namespace pogear::test
