// Shafts ([[shaft]]) against closed forms: two inertias on a torsional spring, the arrows' signs, and
// a rigid shaft that adds its load's inertia to the gear body it turns with.
#include <cmath>
#include <numbers>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "test_support.hpp"
#include "derive/derivation.hpp"
#include "names/model_variables.hpp"
#include "read/topology.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear::test {
namespace {

const SourceLocation here{"shaft_test", 0, 0};

// Two inertias on one shaft; b drawn to the left when `b_left`.
std::string two_inertias(bool b_left) {
  return std::string(R"(name = "two_inertias"
[[body]]
name = "a"
[[body]]
name = "b"
)") + (b_left ? "arrow = \"left\"\n" : "") +
         R"([[shaft]]
name = "s"
bodies = ["a", "b"]
[parameters]
J_a = "0.2*kg*m^2"
J_b = "0.05*kg*m^2"
b_a = "0.01*N*m*s/rad"
b_b = "0.02*N*m*s/rad"
K_s = "2000*N*m/rad"
b_s = "1.5*N*m*s/rad"
)";
}

double number(const Derivation& d, const std::string& parameter) {
  return GiNaC::ex_to<GiNaC::numeric>(sym(d, parameter).subs(d.values).evalf()).to_double();
}

TEST(Shafts, TwoInertiasVibrateAtTheClosedFormFrequencyAndDamping) {
  const Derivation d = derive_topology(parse_topology_text(two_inertias(false), "two.toml"), std::nullopt, here);
  const double Ja = number(d, "J_a"), Jb = number(d, "J_b"), k = number(d, "K_s"), c = number(d, "b_s");
  const double mu = Ja * Jb / (Ja + Jb);
  // Bearing friction left out: the shaft's damper alone, c / (2 sqrt(k mu)).
  GiNaC::exmap values = d.values;
  values[sym(d, "b_a")] = 0;
  values[sym(d, "b_b")] = 0;
  const VibrationModes modes = vibration_modes(d, values, "shaft damping");
  ASSERT_EQ(modes.modes.size(), 2u);
  EXPECT_EQ(modes.modes[0].kind, ModeKind::rigid);
  const VibrationMode& m = modes.modes[1];
  // A 2x2 symmetric eigenproblem: a few ulps (measured 0 and 2e-16).
  EXPECT_NEAR(m.frequency_hz, std::sqrt(k / mu) / (2 * std::numbers::pi), 1e-13 * m.frequency_hz);
  ASSERT_TRUE(m.damping_ratio.has_value());
  EXPECT_NEAR(*m.damping_ratio, c / (2 * std::sqrt(k * mu)), 1e-12);
  // The shape: the bodies swing against each other about the common centre, J_a phi_a = -J_b phi_b.
  EXPECT_NEAR(m.shape(0) / m.shape(1), -Jb / Ja, 1e-13);
}

// A shaft's row is a_i u_i - a_j u_j: with b drawn to the left the rigid join is omega_b = -omega_a,
// and its torque T_s acts as -a_a T_s on a, +a_b T_s on b.
TEST(Shafts, RigidShaftJoinsItsBodiesInTheirArrowsSense) {
  for (const bool b_left : {false, true}) {
    const Derivation d = derive_topology(parse_topology_text(two_inertias(b_left), "two.toml"), std::nullopt, here);
    const double sign = b_left ? -1 : 1;
    EXPECT_TRUE((d.elastic.R(0, 0) - 1).is_zero());
    EXPECT_TRUE((d.elastic.R(0, 1) + sign).is_zero());
    ASSERT_EQ(d.rigid.Q1.cols(), 1u);
    EXPECT_TRUE((d.rigid.Q1(1, 0) - sign * d.rigid.Q1(0, 0)).is_zero()) << d.rigid.Q1;
    // L1 = J_a + J_b exactly (Q1 = (1, +-1)), A1 = -(b_a + b_b).
    EXPECT_TRUE((d.rigid.L1(0, 0) - sym(d, "J_a") - sym(d, "J_b")).expand().is_zero()) << d.rigid.L1;
    EXPECT_TRUE((d.rigid.A1(0, 0) + sym(d, "b_a") + sym(d, "b_b")).expand().is_zero()) << d.rigid.A1;
    // Eq. (8): b turns only by the shaft, J_b omega_b' = -b_b omega_b + a_b T_s, so
    // T_s = a_b (J_b omega_b' + b_b omega_b) = tau_a - J_a omega_a' - b_a omega_a on the rigid motion.
    ASSERT_EQ(d.rigid.reactions, std::vector<std::string>{"T_s"});
    const GiNaC::ex T = d.rigid.force_recovery[0];
    const GiNaC::ex expected = sym(d, "tau_a") - sym(d, "J_a") * sym(d, "domega_a") - sym(d, "b_a") * sym(d, "omega_a");
    const GiNaC::ex tau_b = sym(d, "tau_b");
    // Without tau_b (the scene gives none here) the two are one expression.
    EXPECT_TRUE((T.subs(tau_b == 0) - expected).expand().is_zero()) << T;
    EXPECT_EQ(d.elastic.forces, std::vector<std::string>{"T_s"});
    EXPECT_EQ(unit_of(d.topology, {VariableKind::force, 0}), "N m");
  }
}

// The paper's one-stage gear with a load inertia on a rigid shaft from the carrier: the same rigid
// model as the gear alone with J_c + J_load, b_c + b_load on the carrier, and the shaft's torque
// J_load omega_c' + b_load omega_c, what turning the load takes.
TEST(Shafts, RigidShaftAddsItsLoadToTheBodyItTurnsWith) {
  const std::string gear = read_text(source_path("models/paper_one_stage.toml"));
  std::string loaded = gear;
  const std::string body = "[[body]]\nname = \"load\"\n\n[[shaft]]\nname = \"output\"\nbodies = [\"c\", \"load\"]\n\n";
  loaded.insert(loaded.find("[[body]]"), body);
  loaded.insert(loaded.find("[parameters]") + std::string("[parameters]").size(),
                "\nJ_load = \"0.7*kg*m^2\"\nb_load = \"0.3*N*m*s/rad\"\nK_output = \"1e5*N*m/rad\"\nb_output = \"0\"\n");
  const std::vector<std::string> keep{"c", "r"};
  const Derivation plain = derive_topology(parse_topology_text(gear, "gear.toml"), keep, here);
  Derivation d = derive_topology(parse_topology_text(loaded, "loaded.toml"), keep, here);
  ASSERT_EQ(d.rigid.Q1.cols(), 2u);
  // The gear alone, its carrier given the load's inertia and friction, in the loaded model's symbols.
  GiNaC::exmap to_loaded;
  for (const auto& [name, value] : plain.symbols.parameters) to_loaded[value] = sym(d, name);
  to_loaded[sym(plain, "J_c")] = sym(d, "J_c") + sym(d, "J_load");
  to_loaded[sym(plain, "b_c")] = sym(d, "b_c") + sym(d, "b_load");
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned j = 0; j < 2; ++j) {
      EXPECT_TRUE(equal_under_geometry(d, d.rigid.L1(i, j), plain.rigid.L1(i, j).subs(to_loaded))) << i << j;
      EXPECT_TRUE(equal_under_geometry(d, d.rigid.A1(i, j), plain.rigid.A1(i, j).subs(to_loaded))) << i << j;
    }
  // The shaft's torque on rigid motions at random states and torques: accelerations from L1, A1.
  const auto shaft = std::find(d.rigid.reactions.begin(), d.rigid.reactions.end(), "T_output");
  ASSERT_NE(shaft, d.rigid.reactions.end());
  const GiNaC::ex T = d.rigid.force_recovery[static_cast<std::size_t>(shaft - d.rigid.reactions.begin())];
  const Eigen::MatrixXd L1 = evaluate_matrix(d.rigid.L1, d.values), A1 = evaluate_matrix(d.rigid.A1, d.values),
                        Q1 = evaluate_matrix(d.rigid.Q1, d.values);
  std::mt19937 rng(7);
  std::uniform_real_distribution<double> u(-50, 50);
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd x1(2), tau = Eigen::VectorXd::Zero(static_cast<Eigen::Index>(d.topology.bodies.size()));
    x1 << u(rng), u(rng);
    tau(find_body(d.topology, "c")) = u(rng);
    tau(find_body(d.topology, "r")) = u(rng);
    const Eigen::VectorXd dx1 = L1.ldlt().solve(A1 * x1 + Q1.transpose() * tau);
    GiNaC::exmap at = d.values;
    for (std::size_t b = 0; b < d.topology.bodies.size(); ++b)
      at[sym(d, "tau_" + d.topology.bodies[b].name)] = tau(static_cast<Eigen::Index>(b));
    for (std::size_t j = 0; j < 2; ++j) {
      at[sym(d, "omega_" + keep[j])] = x1(static_cast<Eigen::Index>(j));
      at[sym(d, "domega_" + keep[j])] = dx1(static_cast<Eigen::Index>(j));
    }
    const double got = GiNaC::ex_to<GiNaC::numeric>(T.subs(at).evalf()).to_double();
    const double expected = number(d, "J_load") * dx1(0) + number(d, "b_load") * x1(0);
    // Eq. (8) sums terms of the gear's size (J_c omega_c' ~ 1e2 N m) to the load's share: rounding
    // of a few eps of them (measured 3e-14).
    EXPECT_NEAR(got, expected, 1e-11 * (1 + std::abs(expected))) << trial;
  }
}

}  // namespace
}  // namespace pogear::test
