// A fixed body (`fixed = true`) against the same body held by a stuck brake: the two must be one gear,
// with the brake's torque as the fixed body's, in every sense the body's arrow can take.
#include <cmath>
#include <map>
#include <random>
#include <string>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "derive/derivation.hpp"
#include "derive/force_recovery.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear::test {
namespace {

// Modelica's SimpleGearShift gear (models/gearshift_planetary.toml): the ring held by the housing,
// or by its brake, with the ring drawn to the right or to the left.
std::string braked_gear(const std::string& ring_arrow) {
  std::string text = read_text(source_path("models/gearshift_planetary.toml"));
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  replace("name = \"r\"                        # ring", "name = \"r\"\narrow = \"" + ring_arrow + "\"");
  replace("keep = [\"s\", \"c\"]", "keep = [\"s\"]");
  return text;
}

std::string fixed_gear(const std::string& ring_arrow) {
  std::string text = braked_gear(ring_arrow);
  text.replace(text.find("arrow = \"" + ring_arrow + "\""), 0, "fixed = true\n");
  // No brake or clutch: a fixed ring needs none, and a clutch cannot join it.
  text.erase(text.find("[[brake]]"), text.find("[parameters]") - text.find("[[brake]]"));
  return text;
}

// e at the derivation's parameter values and the variables' values by name.
double value_at(const Derivation& d, const GiNaC::ex& e, const std::map<std::string, double>& variables) {
  const GiNaC::ex with_parameters = e.subs(d.values);
  GiNaC::exmap m;
  for (GiNaC::const_preorder_iterator it = with_parameters.preorder_begin(); it != with_parameters.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) {
      const auto v = variables.find(GiNaC::ex_to<GiNaC::symbol>(*it).get_name());
      if (v == variables.end()) ADD_FAILURE() << "no value for " << *it;
      else m[*it] = GiNaC::numeric(v->second);
    }
  return GiNaC::ex_to<GiNaC::numeric>(with_parameters.subs(m).evalf()).to_double();
}

std::size_t index_of(const std::vector<std::string>& names, const std::string& name) {
  const auto it = std::find(names.begin(), names.end(), name);
  EXPECT_NE(it, names.end()) << name;
  return static_cast<std::size_t>(it - names.begin());
}

const std::vector<std::string> kept_sun{"s"};

class FixedBodies : public ::testing::TestWithParam<std::string> {};

TEST_P(FixedBodies, FixedRingIsTheRingItsStuckBrakeHolds) {
  const SourceLocation here{"test", 0, 0};
  const Derivation fixed = derive_topology(parse_topology_text(fixed_gear(GetParam()), "fixed.toml"), kept_sun, here);
  const Topology braked_topology = parse_topology_text(braked_gear(GetParam()), "braked.toml");
  const Derivation braked = derive_topology(braked_topology, kept_sun, here, true,
                                            {find_friction_element(braked_topology, "brake")});
  ASSERT_EQ(fixed.topology.bodies.size(), 3u);  // s, c, p turn; r does not
  ASSERT_EQ(fixed.topology.grounded.size(), 1u);
  EXPECT_EQ(fixed.topology.grounded[0].name, "r");

  // R loses the ring's column and nothing else (the names are those of one file).
  const int ring = find_body(braked.topology, "r");
  for (unsigned i = 0; i < 2; ++i)
    for (unsigned k = 0; k < 3; ++k) {
      const int b = find_body(braked.topology, fixed.topology.bodies[k].name);
      EXPECT_EQ(value_at(fixed, fixed.elastic.R(i, k), {}), value_at(braked, braked.elastic.R(i, b), {}));
    }

  // The rigid model: omega = Q1 omega_s, L1 and A1, exact rationals compared exactly.
  ASSERT_EQ(fixed.rigid_values.Q1.cols(), 1u);
  ASSERT_EQ(braked.rigid_values.Q1.cols(), 1u);
  for (unsigned k = 0; k < 3; ++k) {
    const int b = find_body(braked.topology, fixed.topology.bodies[k].name);
    EXPECT_TRUE((fixed.rigid_values.Q1(k, 0) - braked.rigid_values.Q1(b, 0)).is_zero());
  }
  EXPECT_TRUE(braked.rigid_values.Q1(ring, 0).is_zero());
  EXPECT_TRUE((fixed.rigid_values.L1(0, 0) - braked.rigid_values.L1(0, 0)).is_zero());
  EXPECT_TRUE((fixed.rigid_values.A1(0, 0) - braked.rigid_values.A1(0, 0)).is_zero());
  // With the Willis ratio of Modelica's example: the carrier at 1 / (1 + 75/50) of the sun. The radii
  // in mm are doubles (0.05 m is not one), so the ratio is 2/5 to a few 1e-17.
  EXPECT_NEAR(value_at(fixed, fixed.rigid_values.Q1(find_body(fixed.topology, "c"), 0), {}), 0.4, 1e-15);

  // Mesh forces and the torque on the housing, eq. (8), at arbitrary speeds, accelerations and
  // torques (none on the braked ring, which a fixed ring cannot take): the fixed ring's T_r is the
  // brake's T_brake. Each side is a sum of a few products of doubles: equal to ~1e-15 relative.
  std::mt19937 random(7);
  std::uniform_real_distribution<double> any(-100, 100);
  for (int trial = 0; trial < 5; ++trial) {
    const std::map<std::string, double> v{{"omega_s", any(random)}, {"domega_s", any(random)}, {"tau_s", any(random)},
                                          {"tau_c", any(random)},   {"tau_p", any(random)},    {"tau_r", 0.0}};
    for (const std::string force : {"F_ps", "F_pr"}) {
      const double a = value_at(fixed, fixed.rigid.force_recovery[index_of(fixed.rigid.reactions, force)], v);
      const double b = value_at(braked, braked.rigid.force_recovery[index_of(braked.rigid.reactions, force)], v);
      EXPECT_NEAR(a, b, 1e-12 * (1 + std::abs(b))) << force;
    }
    const auto holding = fixed_body_torques(fixed.topology, fixed.radius.fixed_columns, fixed.rigid.force_recovery);
    ASSERT_EQ(holding.size(), 1u);
    const double brake = value_at(braked, braked.rigid.force_recovery[index_of(braked.rigid.reactions, "T_brake")], v);
    EXPECT_NEAR(value_at(fixed, holding[0], v), brake, 1e-12 * (1 + std::abs(brake)));
  }
}

// The elastic model without the ring's velocity is the braked gear's with the ring stuck: the same
// natural frequencies. Both come from eigenvalues of 3x3 problems in doubles: ~1e-13 relative.
TEST_P(FixedBodies, FixedRingVibratesAsTheStuckBrakesRing) {
  const SourceLocation here{"test", 0, 0};
  const Derivation fixed = derive_topology(parse_topology_text(fixed_gear(GetParam()), "fixed.toml"), kept_sun, here);
  const Derivation braked = derive_topology(parse_topology_text(braked_gear(GetParam()), "braked.toml"),
                                            std::vector<std::string>{"s", "c"}, here);
  const VibrationModes a = vibration_modes(fixed, fixed.values, "none");
  const VibrationModes b = vibration_modes(braked, braked.values, "none", {find_friction_element(braked.topology, "brake")});
  std::vector<double> fa, fb;
  for (const VibrationMode& m : a.modes)
    if (m.kind == ModeKind::elastic) fa.push_back(m.frequency_hz);
  for (const VibrationMode& m : b.modes)
    if (m.kind == ModeKind::elastic) fb.push_back(m.frequency_hz);
  ASSERT_EQ(fa.size(), 2u);
  ASSERT_EQ(fa.size(), fb.size());
  for (std::size_t i = 0; i < fa.size(); ++i) EXPECT_NEAR(fa[i], fb[i], 1e-10 * fb[i]);
}

INSTANTIATE_TEST_SUITE_P(RingArrow, FixedBodies, ::testing::Values("right", "left"));

}  // namespace
}  // namespace pogear::test
