// The rigid model of a mode with brakes and clutches stuck (pogear derive --engaged): its mesh
// forces and element torques satisfy every body's equation of motion, and at rest under balanced
// torques they are those of statics (a clutch carries the input torque, the brake the rest).
#include <algorithm>
#include <map>
#include <set>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "derive/derivation.hpp"
#include "derive/engagement.hpp"
#include "vibrate/diagnostics.hpp"
#include "vibrate/vibration_modes.hpp"
#include "common/exact_algebra.hpp"

namespace pogear::test {
namespace {

Derivation simpson_in(const std::string& engaged) {
  const std::string path = source_path("models/simpson_3speed.toml");
  Topology t = parse_topology(path);
  const SourceLocation where{path, 0, 0};
  const std::vector<int> stuck = parse_engaged(t, engaged, where);
  return derive_topology(std::move(t), std::nullopt, where, true, stuck);
}

// The recovered forces and torques with tau, omega and domega put in (exact numbers).
std::vector<GiNaC::numeric> reactions_at(const Derivation& d, const std::vector<GiNaC::numeric>& tau,
                                         const std::vector<GiNaC::numeric>& x1, const std::vector<GiNaC::numeric>& dx1) {
  GiNaC::exmap at = d.values;
  for (std::size_t b = 0; b < tau.size(); ++b) at[variable_symbol(d.symbols, {VariableKind::torque, static_cast<int>(b)})] = tau[b];
  for (std::size_t j = 0; j < x1.size(); ++j) {
    at[variable_symbol(d.symbols, {VariableKind::velocity, d.rigid.kept[j]})] = x1[j];
    at[variable_symbol(d.symbols, {VariableKind::acceleration, d.rigid.kept[j]})] = dx1[j];
  }
  std::vector<GiNaC::numeric> out;
  for (const GiNaC::ex& f : d.rigid.force_recovery) out.push_back(as_number(exact_value(f, at)));
  return out;
}

// A brake's or clutch's capacity and its torque have names of their own: the capacity's default
// parameter is Tcap_<element>, the torque the reports and CSV files print T_<element>. A model
// that names its capacity keeps that name (pair.toml: capacity = "T_B", an old default's form).
TEST(EngagedModel, CapacityAndTorqueHaveNamesOfTheirOwn) {
  const Derivation d = simpson_in("C1,B2");
  std::set<std::string> capacities;
  for (const FrictionElement& e : d.topology.friction_elements) {
    EXPECT_EQ(e.capacity_parameter, "Tcap_" + e.name);
    capacities.insert(e.capacity_parameter);
  }
  const std::vector<std::string> torques(d.rigid.reactions.end() - 2, d.rigid.reactions.end());
  EXPECT_EQ(torques, (std::vector<std::string>{"T_C1", "T_B2"}));
  for (const std::string& name : d.rigid.reactions) EXPECT_EQ(capacities.count(name), 0u) << name;
  const Topology pair = parse_topology(source_path("tests/vibration/pair.toml"));
  for (const FrictionElement& e : pair.friction_elements) EXPECT_EQ(e.capacity_parameter, "T_B") << e.name;
}

TEST(EngagedModel, ForcesAndTorquesSatisfyEveryBodysEquationOfMotion) {
  for (const std::string engaged : {"C1,B2", "C1,B1", "C1,C2", "C2,B2", "B2"}) {
    SCOPED_TRACE(engaged);
    const Derivation d = simpson_in(engaged);
    const int n = static_cast<int>(d.topology.bodies.size());
    const unsigned k = d.rigid.kept.size();
    ASSERT_EQ(d.rigid.reactions.size(), d.topology.meshes.size() + d.engaged.size());
    // Arbitrary torques and speeds (exact), and the accelerations the mode's rigid model gives.
    std::vector<GiNaC::numeric> tau, x1, dx1;
    for (int b = 0; b < n; ++b) tau.push_back(GiNaC::numeric(7 * b - 11, 3));
    for (unsigned j = 0; j < k; ++j) x1.push_back(GiNaC::numeric(5 + 3 * static_cast<int>(j), 2));
    const RigidValues& v = d.rigid_values;
    GiNaC::matrix rhs(k, 1);
    for (unsigned i = 0; i < k; ++i) {
      GiNaC::ex r = 0;
      for (unsigned j = 0; j < k; ++j) r += v.A1(i, j) * x1[j];
      for (int b = 0; b < n; ++b) r += v.Q1(b, i) * tau[b];
      rhs(i, 0) = r;
    }
    const GiNaC::matrix acc = exact_solve(v.L1, rhs);
    for (unsigned j = 0; j < k; ++j) dx1.push_back(as_number(acc(j, 0)));
    const std::vector<GiNaC::numeric> lambda = reactions_at(d, tau, x1, dx1);
    // J omega' = tau - B_J omega - C^T [F; T], body by body, exactly: the recovery of eq. (8) with
    // C = [R; E_S] is exact on the rigid motion, whatever the values.
    const GiNaC::matrix C = exact_matrix(d.constraints, d.values);
    for (int b = 0; b < n; ++b) {
      GiNaC::ex omega = 0, domega = 0;
      for (unsigned j = 0; j < k; ++j) {
        omega += v.Q1(b, j) * x1[j];
        domega += v.Q1(b, j) * dx1[j];
      }
      GiNaC::ex residual = exact_value(d.elastic.J(b, b), d.values) * domega - tau[b] +
                           exact_value(d.elastic.B_J(b, b), d.values) * omega;
      for (unsigned i = 0; i < C.rows(); ++i) residual += C(i, b) * lambda[i];
      EXPECT_TRUE(residual.expand().is_zero()) << d.topology.bodies[b].name << ": " << residual;
    }
  }
}

// First gear (C1, B2) at rest: 1 N m on the input and the output loaded by -1/ratio N m, which
// balances it (L1 x1' = tau_i + ratio tau_o = 0). Statics of the whole gear then says: the clutch
// C1 passes the whole input torque to the front ring, T_C1 = 1 (it acts -T on the input shaft),
// and the housing takes the rest through B2, -(tau_i + tau_o) on c2, so T_B2 = tau_i + tau_o.
TEST(EngagedModel, FirstGearAtRestHasTheTorquesOfStatics) {
  const Derivation d = simpson_in("C1,B2");
  const double k = 72.0 / 30.0, ratio = k / (2 * k + 1);
  const int n = static_cast<int>(d.topology.bodies.size());
  std::vector<GiNaC::numeric> tau(n, 0);
  tau[find_body(d.topology, "i")] = 1;
  tau[find_body(d.topology, "o")] = exact_number(-1 / ratio);
  const std::vector<GiNaC::numeric> zero(d.rigid.kept.size(), 0);
  const std::vector<GiNaC::numeric> lambda = reactions_at(d, tau, zero, zero);
  std::map<std::string, double> by_name;
  for (std::size_t i = 0; i < lambda.size(); ++i) by_name[d.rigid.reactions[i]] = lambda[i].to_double();
  // The model's radii meet the geometry to rounding of their decimal values (~1e-17 m), and
  // -1/ratio is a rounded double: both move the torques by ~1e-15.
  EXPECT_NEAR(by_name.at("T_C1"), 1.0, 1e-13);
  EXPECT_NEAR(by_name.at("T_B2"), 1.0 - 1 / ratio, 1e-13);
}

// Stuck elements change the rigid model, not the elastic gear the report and its time scales show;
// the lowest natural frequency, below which that rigid model holds, is the engaged gear's (the one
// pogear modes --engaged gives), and the summary says so.
TEST(EngagedModel, ElasticDiagnosticsAreTheGears) {
  const std::string path = source_path("models/simpson_3speed.toml");
  const Derivation gear = derive_topology(parse_topology(path), std::nullopt, SourceLocation{path, 0, 0});
  const Derivation first = simpson_in("C1,B2");
  const Diagnostics gear_diagnostics = derivation_diagnostics(gear), first_diagnostics = derivation_diagnostics(first);
  EXPECT_EQ(first_diagnostics.stiffness_ratio, gear_diagnostics.stiffness_ratio);
  EXPECT_EQ(first_diagnostics.fastest_time_constant, gear_diagnostics.fastest_time_constant);
  ASSERT_TRUE(gear_diagnostics.lowest_natural_frequency_hz);
  ASSERT_TRUE(first_diagnostics.lowest_natural_frequency_hz);
  const VibrationModes modes = vibration_modes(gear, gear.values, "as defined", first.engaged);
  const auto elastic = std::find_if(modes.modes.begin(), modes.modes.end(),
                                    [](const VibrationMode& m) { return m.kind != ModeKind::rigid; });
  ASSERT_NE(elastic, modes.modes.end());
  EXPECT_EQ(*first_diagnostics.lowest_natural_frequency_hz, elastic->frequency_hz);
  EXPECT_NE(*first_diagnostics.lowest_natural_frequency_hz, *gear_diagnostics.lowest_natural_frequency_hz);
  EXPECT_EQ(first_diagnostics.natural_frequency_of, "C1, B2 engaged");
  EXPECT_EQ(first.rigid.rank, gear.rigid.rank + 2);
}

}  // namespace
}  // namespace pogear::test
