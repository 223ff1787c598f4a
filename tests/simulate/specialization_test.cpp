// Simulate only what the scene calls for: each effect left out removes operations, gives the
// trajectory of that effect's parameters set to zero, and zero inputs or unrequested outputs
// leave nothing behind.
#include <numbers>

#include "codegen/codegen.hpp"
#include "common/exact_algebra.hpp"
#include "specialize/initial_state.hpp"
#include "sim_support.hpp"
#include "../support/ports.hpp"

namespace pogear::test {
namespace {

const std::string all = "\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\", \"mesh_forces\"";

int total_ops(const SpecializedScene& m) { return m.main.rhs_ops.total() + m.main.output_ops.total(); }

TEST(Specialization, EachEffectLeftOutRemovesOperations) {
  for (const char* scene : {"paper_one_stage", "paper_two_stage"}) {
    const std::string base = with_line(scene_text(scene), "compare_rigid = true", "compare_rigid = false");
    const int full = total_ops(scene_model(with_effects(base, all)));
    const int no_damping = total_ops(scene_model(with_effects(base, "\"mesh_compliance\", \"bearing_friction\", \"mesh_forces\"")));
    const int no_friction = total_ops(scene_model(with_effects(base, "\"mesh_compliance\", \"mesh_damping\", \"mesh_forces\"")));
    const SpecializedScene no_forces_model = scene_model(with_effects(base, "\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\""));
    const int rigid = total_ops(scene_model(with_effects(base, "\"bearing_friction\", \"mesh_forces\"")));
    const int rigid_no_forces = total_ops(scene_model(with_effects(base, "\"bearing_friction\"")));
    EXPECT_LT(no_damping, full) << scene;
    EXPECT_LT(no_friction, full) << scene;
    // The rigid model recovers forces from eq. (8) at each sample, which the elastic model has
    // as states; per step it costs far less, which is what its rhs counts.
    EXPECT_LT(scene_model(with_effects(base, "\"bearing_friction\", \"mesh_forces\"")).main.rhs_ops.total(),
              scene_model(with_effects(base, all)).main.rhs_ops.total()) << scene;
    EXPECT_LT(rigid_no_forces, rigid) << scene;
    // Elastic forces are states: leaving them out of the outputs shrinks the output vector.
    EXPECT_LT(no_forces_model.main.outputs.size(), scene_model(with_effects(base, all)).main.outputs.size());
  }
}

// M of the specialized expressions, numerically.
Eigen::MatrixXd specialized_M(const SpecializedScene& m) {
  Eigen::MatrixXd M(m.main.M.rows(), m.main.M.cols());
  for (unsigned i = 0; i < m.main.M.rows(); ++i)
    for (unsigned j = 0; j < m.main.M.cols(); ++j) M(i, j) = to_double(m.main.M(i, j));
  return M;
}

TEST(Specialization, AnEffectLeftOutEqualsItsParametersAtZero) {
  const std::string base = scene_text("paper_one_stage");
  const SpecializedScene no_friction = scene_model(with_effects(base, "\"mesh_compliance\", \"mesh_damping\", \"mesh_forces\""));
  const SpecializedScene zero_friction =
      scene_model(with_parameters(base, "b_c = 0\nb_p = 0\nb_s = 0\nb_r = 0\nb_g = 0\nb_m = 0"));
  // Same numbers through different expressions: equal to rounding of a few operations.
  EXPECT_LT((specialized_M(no_friction) - specialized_M(zero_friction)).norm(), 1e-12 * specialized_M(zero_friction).norm());
  const Trajectory a = interpret_trajectory(no_friction, no_friction.main, run_settings(no_friction));
  const Trajectory b = interpret_trajectory(zero_friction, zero_friction.main, run_settings(zero_friction));
  ASSERT_EQ(a.y.size(), b.y.size());
  EXPECT_LT((a.y.back() - b.y.back()).norm(), 1e-12 * b.y.back().norm());

  const SpecializedScene no_damping = scene_model(with_effects(base, "\"mesh_compliance\", \"bearing_friction\", \"mesh_forces\""));
  const SpecializedScene zero_damping = scene_model(with_parameters(base, "b_ps = 0"));  // b_pr, b_sg, b_rm follow b_ps
  EXPECT_LT((specialized_M(no_damping) - specialized_M(zero_damping)).norm(), 1e-12 * specialized_M(zero_damping).norm());
}

TEST(Specialization, ZeroInputsAreNotInputs) {
  const std::string text = with_line(scene_text("paper_one_stage"), "tau_c = { constant = \"100*Nm\" }",
                                     "tau_c = { constant = \"100*Nm\" }\ntau_p = \"0*Nm\"\ntau_g = { step = \"0*Nm\", at = \"1*s\" }");
  const SpecializedScene m = scene_model(text);
  EXPECT_EQ(input_names(m, m.main), std::vector<std::string>{"tau_c"});
  EXPECT_EQ(input_names(m, *m.rigid), std::vector<std::string>{"tau_c"});
}

TEST(Specialization, OnlyRequestedOutputsAreComputed) {
  const std::string text = with_line(scene_text("paper_one_stage"), "compare_rigid = true",
                                     "compare_rigid = true\noutputs = [\"omega_c\", \"F_sg\"]");
  const SpecializedScene m = scene_model(text);
  EXPECT_EQ(output_names(m, *m.rigid), (std::vector<std::string>{"omega_c", "F_sg"}));
  const SpecializedScene full = scene_model(scene_text("paper_one_stage"));
  EXPECT_LT(m.rigid->output_ops.total(), full.rigid->output_ops.total());
  const GeneratedSources g = generate_sources(m);
  EXPECT_NE(g.header.find("static constexpr int nx = 2, nu = 1, ny = 2;"), std::string::npos);
}

TEST(Specialization, NonTunableParametersAreLiteralsTunablesAreNot) {
  const SpecializedScene fixed = scene_model(scene_text("paper_one_stage"));
  EXPECT_NE(generate_sources(fixed).header.find("struct Params {};"), std::string::npos);
  const SpecializedScene tuned = scene_model(with_line(scene_text("paper_one_stage"), "compare_rigid = true",
                                               "compare_rigid = true\ntunable = [\"J_c\", \"K_ps\"]"));
  const std::string h = generate_sources(tuned).header;
  EXPECT_NE(h.find("double J_c = 0.17648;"), std::string::npos);
  EXPECT_NE(h.find("double K_ps = 1000000.0;"), std::string::npos);
  EXPECT_NE(h.find("const double J_c = p.J_c;"), std::string::npos);
  // A tunable radius and the radii the geometry ties to it: Tunables.DerivedRadiiFollowATunableRadius.
}

// A scene's quantities are evaluated against its model with the scene's own parameter values: the
// carrier radius below is the override's 24.8 cm, not the model's 14.8 cm.
TEST(Specialization, InitialStateAndInputsSeeTheSceneParameters) {
  std::string text = with_line(scene_text("paper_one_stage"), "omega_c = \"0*rpm\"", "omega_c = \"r_c*100/(m*s)\"");
  text = with_line(text, "tau_c = { constant = \"100*Nm\" }", "tau_c = { constant = \"r_c*1000*N\" }");
  const SpecializedScene m = scene_model(with_parameters(text, "r_s1 = \"20*cm\"\nr_c = \"24.8*cm\"\nr_r1 = \"29.6*cm\""));
  // 0.248 * 100 and * 1000 in doubles: the product's rounding, a few ulps.
  EXPECT_NEAR(initial_values(m.main).at(0), 24.8, 1e-12);
  ASSERT_EQ(m.scene.inputs.size(), 1u);
  EXPECT_NEAR(rt::value(m.scene.inputs[0].signal, 0.0), 248.0, 1e-11);
  ASSERT_TRUE(m.rigid.has_value());
  EXPECT_NEAR(initial_values(*m.rigid).at(0), 24.8, 1e-12);
}

// [initial] on a rigid scene: every named speed is honoured, whether the body is kept or not, and
// the freedom left is fixed by kept bodies at rest in the kept order (docs/scene-format.md).
TEST(InitialState, RigidSceneHonoursEveryNamedSpeed) {
  const std::string rigid = with_effects(with_line(scene_text("paper_one_stage"), "compare_rigid = true", "compare_rigid = false"),
                                         "\"bearing_friction\", \"mesh_forces\"");
  const double rpm = 2 * std::numbers::pi / 60;
  // The sun is not kept (keep = ["c", "r"]): one condition on two kept speeds; c, first kept and
  // not named, is at rest.
  const SpecializedScene m = scene_model(with_line(rigid, "omega_c = \"0*rpm\"", "omega_s = \"3600*rpm\""));
  const Derivation& d = m.derivation;
  const Eigen::MatrixXd Q1 = evaluate_matrix(d.rigid.Q1, d.values);
  const std::vector<double> start = initial_values(m.main);
  const Eigen::VectorXd x0 = Eigen::Map<const Eigen::VectorXd>(start.data(), static_cast<Eigen::Index>(start.size()));
  const Eigen::VectorXd omega = Q1 * x0;
  auto body = [&](const std::string& name) {
    for (std::size_t b = 0; b < d.topology.bodies.size(); ++b)
      if (d.topology.bodies[b].name == name) return static_cast<Eigen::Index>(b);
    ADD_FAILURE() << name;
    return Eigen::Index{0};
  };
  // A QR solve of a 2x2 system of ratios of radii: a few ulps of the speed.
  EXPECT_NEAR(omega(body("s")) / (3600 * rpm), 1, 1e-14);
  EXPECT_EQ(omega(body("c")), 0);
  // The carrier at rest: the ring turns at r_s1/r_r1 of the sun's speed, and no mesh deflects.
  const auto value = [&](const char* p) { return to_double(d.values.at(parameter_symbol(d.symbols, p))); };
  EXPECT_NEAR(std::abs(omega(body("r"))) / (value("r_s1") / value("r_r1") * 3600 * rpm), 1, 1e-14);
  EXPECT_LT((evaluate_matrix(d.elastic.R, d.values) * omega).cwiseAbs().maxCoeff(), 1e-13 * 3600 * rpm);
  // A kept body named keeps its value bit for bit.
  const SpecializedScene k = scene_model(with_line(rigid, "omega_c = \"0*rpm\"", "omega_r = \"1234.5*rpm\"\nomega_s = \"10*rpm\""));
  EXPECT_EQ(initial_values(k.main).at(1), 1234.5 * rpm);
  const Eigen::VectorXd w = Q1 * Eigen::Map<const Eigen::VectorXd>(initial_values(k.main).data(), 2);
  EXPECT_NEAR(w(body("s")) / (10 * rpm), 1, 1e-12);  // 10 rpm against ring terms of ~1000 rpm: 1e-14 of those
}

// compare_rigid: the elastic model starts from the rigid model's state, unnamed bodies included,
// so the two start together and the elastic one without mesh deflection rates.
TEST(InitialState, CompareRigidStartsBothModelsFromOneConsistentState) {
  const SpecializedScene m = scene_model(with_line(scene_text("paper_one_stage"), "omega_c = \"0*rpm\"", "omega_s = \"3600*rpm\""));
  ASSERT_TRUE(m.rigid.has_value());
  const Derivation& d = m.derivation;
  const Eigen::VectorXd x1 = Eigen::Map<const Eigen::VectorXd>(initial_values(*m.rigid).data(), 2);
  const Eigen::VectorXd omega = evaluate_matrix(d.rigid.Q1, d.values) * x1;
  const std::size_t n = d.topology.bodies.size();
  Eigen::VectorXd elastic(static_cast<Eigen::Index>(n));
  for (std::size_t b = 0; b < n; ++b) elastic(static_cast<Eigen::Index>(b)) = initial_values(m.main).at(b);  // velocities first
  EXPECT_LT((elastic - omega).cwiseAbs().maxCoeff(), 1e-12 * omega.cwiseAbs().maxCoeff());
  // No mesh is deflecting: R omega = 0 to rounding.
  EXPECT_LT((evaluate_matrix(d.elastic.R, d.values) * elastic).cwiseAbs().maxCoeff(), 1e-13 * omega.cwiseAbs().maxCoeff());
  EXPECT_GT(omega.cwiseAbs().maxCoeff(), 100);  // the state is not at rest
}

// An elastic scene may start off the rigid kinematics (that is physical), but the summary says
// which meshes start deflecting and how fast.
TEST(InitialState, ElasticSpeedsThatBreakTheKinematicsAreNamedInTheSummary) {
  const std::string elastic = with_line(scene_text("paper_one_stage"), "compare_rigid = true", "compare_rigid = false");
  const std::string sun = with_line(elastic, "omega_c = \"0*rpm\"", "omega_s = \"100*rpm\"");
  const std::string note = initial_deflection_note(scene_model(sun));
  // Only the sun turns: its two meshes (ps with wheel s1, sg with wheel s2) deflect, at r omega.
  const SpecializedScene m = scene_model(sun);
  const auto value = [&](const char* p) { return to_double(m.derivation.values.at(parameter_symbol(m.derivation.symbols, p))); };
  const double w = 100 * 2 * std::numbers::pi / 60;
  for (const auto& [mesh, radius] : {std::pair<std::string, const char*>{"ps", "r_s1"}, {"sg", "r_s2"}}) {
    const auto at = note.find("deflect mesh " + mesh + " at ");
    ASSERT_NE(at, std::string::npos) << note;
    const double rate = std::stod(note.substr(at + 17 + mesh.size()));
    EXPECT_NEAR(std::abs(rate) / (value(radius) * w), 1, 1e-3) << note;  // printed to 4 digits
  }
  EXPECT_EQ(note.find("mesh pr "), std::string::npos) << note;
  EXPECT_EQ(note.find("mesh rm "), std::string::npos) << note;
  // From rest, or from the rigid model's state with compare_rigid, no mesh deflects.
  EXPECT_EQ(initial_deflection_note(scene_model(elastic)), "");
  EXPECT_EQ(initial_deflection_note(scene_model(with_line(sun, "compare_rigid = false", "compare_rigid = true"))), "");
}

// start = "rigid": the elastic model starts on the rigid model's trajectory, its speeds the rigid
// state's and its forces eq. (8)'s at t = 0, so it has no start-up transient to ring down.
TEST(InitialState, RigidStartMeetsTheRigidModelAtTheStart) {
  const std::string sun = with_line(scene_text("paper_one_stage"), "omega_c = \"0*rpm\"", "omega_s = \"3600*rpm\"");
  const SpecializedScene given = scene_model(sun);
  const SpecializedScene rigid_start = scene_model(with_line(sun, "omega_s = \"3600*rpm\"", "omega_s = \"3600*rpm\"\nstart = \"rigid\""));
  ASSERT_TRUE(rigid_start.rigid.has_value());
  const Trajectory r = interpret_trajectory(rigid_start, *rigid_start.rigid, run_settings(rigid_start));
  const Trajectory e = interpret_trajectory(rigid_start, rigid_start.main, run_settings(rigid_start));
  const Trajectory e0 = interpret_trajectory(given, given.main, run_settings(given));
  ASSERT_TRUE(r.status.ok && e.status.ok && e0.status.ok);
  // Outputs of both systems: omega of every body, then F of every mesh, in the model's order. The
  // rigid run's first sample is the reference model's eq. (8) (its own solve, in doubles); the
  // start's is exact and rounded once: they agree to the reference's rounding.
  const Eigen::VectorXd& y0 = r.y.front();
  EXPECT_LT((e.y.front() - y0).cwiseAbs().maxCoeff(), 1e-12 * y0.cwiseAbs().maxCoeff());
  const auto n = static_cast<Eigen::Index>(rigid_start.derivation.topology.bodies.size());
  const auto m = static_cast<Eigen::Index>(rigid_start.derivation.topology.meshes.size());
  EXPECT_GT(y0.segment(n, m).cwiseAbs().maxCoeff(), 100);  // the forces at t = 0 are not zero
  // Over the first 50 ms the given start's forces ring around the rigid ones (the meshes start
  // unloaded); the rigid start's follow them. Measured: 71 N against 5783 N.
  auto force_gap = [&](const Trajectory& x) {
    double gap = 0;
    for (std::size_t i = 0; i < x.t.size() && x.t[i] <= 0.05; ++i)
      gap = std::max(gap, (x.y[i].segment(n, m) - r.y[i].segment(n, m)).cwiseAbs().maxCoeff());
    return gap;
  };
  EXPECT_LT(force_gap(e), force_gap(e0) / 10) << force_gap(e) << " " << force_gap(e0);
}

// start = "steady": the equilibrium of the inputs at t = 0, M x0 + N u0 = 0, where a constant input
// keeps the run (elastic and rigid) to rounding.
// Redundant meshes (three planets) too: their force loops are unloaded, as from an unloaded start.
TEST(InitialState, SteadyStartStaysAtTheEquilibrium) {
  for (const std::string name : {"paper_one_stage", "three_planets"}) {
    const std::string text = scene_text(name);
    const SpecializedScene m = scene_model(name == "three_planets" ? text + "\n[initial]\nstart = \"steady\"\n"
                                                                   : with_line(text, "omega_c = \"0*rpm\"", "start = \"steady\""));
    ASSERT_TRUE(m.rigid.has_value());
    for (const SpecializedSystem* sys : {&m.main, &*m.rigid}) {
      // The reference model's M and N (another formula, in doubles) at the start: zero to its rounding.
      const NumericSystem ref = numeric_system(m, *sys);
      const Eigen::VectorXd u = Eigen::VectorXd::Constant(1, rt::value(m.scene.inputs[0].signal, 0.0));
      const Eigen::VectorXd dx = ref.M * ref.x0 + ref.N * u;
      const double scale = (ref.M.cwiseAbs() * ref.x0.cwiseAbs()).maxCoeff();
      EXPECT_LT(dx.cwiseAbs().maxCoeff(), 1e-13 * scale) << sys->kind;
      EXPECT_GT(ref.x0.cwiseAbs().maxCoeff(), 1) << sys->kind;  // not the rest state
      // Exact stepping of a constant input from an equilibrium moves by rounding only.
      const Trajectory tr = interpret_trajectory(m, *sys, run_settings(m));
      ASSERT_TRUE(tr.status.ok);
      double drift = 0;
      for (const Eigen::VectorXd& x : tr.x) drift = std::max(drift, (x - ref.x0).cwiseAbs().maxCoeff());
      EXPECT_LT(drift, 1e-9 * ref.x0.cwiseAbs().maxCoeff()) << name << " " << sys->kind;
    }
  }
}

// start = "steady" where nothing drives at t = 0: rest is the equilibrium, also without bearing
// friction (issue 31, item 14: it was refused as "no equilibrium"). The torque arrives later.
TEST(InitialState, SteadyStartAtRestWithoutTorque) {
  std::string text = with_line(scene_text("paper_one_stage"), "omega_c = \"0*rpm\"", "start = \"steady\"");
  text = with_line(text, "tau_c = { constant = \"100*Nm\" }", "tau_c = { step = \"100*Nm\", at = \"0.5*s\" }");
  text = with_line(text, "effects = [\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\", \"mesh_forces\"]",
                   "effects = [\"mesh_compliance\", \"mesh_damping\", \"mesh_forces\"]");
  const SpecializedScene m = scene_model(text);
  for (const SpecializedSystem* sys : {&m.main, &*m.rigid}) {
    const NumericSystem ref = numeric_system(m, *sys);
    EXPECT_EQ(ref.x0.cwiseAbs().maxCoeff(), 0.0) << sys->kind;
  }
}

// Loads start with the gear. Steady: the constant and linear parts of a road load on the ring
// enter the rigid equilibrium, M x0 + N u0 = 0 with the specialized M (the loads' damping) and N
// (the constant part, the input TL_r), and the run stays there; also without bearing friction,
// where the loads alone give the equilibrium. Rigid: the loads' torques at the given speeds, a
// quadratic one included, enter eq. (8), and the elastic start meets the rigid run's forces at t = 0.
TEST(InitialState, LoadsStartSteadyAndRigid) {
  // Loads on both kept bodies: the gear has 2 degrees of freedom, which the loads alone then damp.
  const std::string loads =
      "\n[loads]\nr = { constant = \"20*N*m\", linear = \"0.5*N*m*s\" }\nc = { linear = \"0.2*N*m*s\" }\n";
  for (const std::string effects : {"\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\", \"mesh_forces\"",
                                    "\"mesh_compliance\", \"mesh_damping\", \"mesh_forces\""}) {
    const SpecializedScene m = scene_model(
        with_effects(with_line(scene_text("paper_one_stage"), "omega_c = \"0*rpm\"", "start = \"steady\""), effects) + loads);
    for (const SpecializedSystem* sys : {&m.main, &*m.rigid}) {
      SCOPED_TRACE(effects + " " + std::string(kind_name(sys->kind)));
      const NumericSystem ref = numeric_system(m, *sys);
      const std::vector<rt::Signal> signals = input_signals(*sys);
      Eigen::VectorXd u(static_cast<Eigen::Index>(signals.size()));
      rt::input_values(signals, 0.0, u);
      const Eigen::VectorXd dx = ref.M * ref.x0 + ref.N * u;
      const double scale = (ref.M.cwiseAbs() * ref.x0.cwiseAbs()).maxCoeff();
      EXPECT_LT(dx.cwiseAbs().maxCoeff(), 1e-13 * scale);
      EXPECT_GT(ref.x0.cwiseAbs().maxCoeff(), 1);  // not the rest state
      const Trajectory tr = interpret_trajectory(m, *sys, run_settings(m));
      ASSERT_TRUE(tr.status.ok) << tr.status.message;
      double drift = 0;
      for (const Eigen::VectorXd& x : tr.x) drift = std::max(drift, (x - ref.x0).cwiseAbs().maxCoeff());
      EXPECT_LT(drift, 1e-9 * ref.x0.cwiseAbs().maxCoeff());
    }
  }
  const std::string rigid_start =
      with_lines(scene_text("paper_one_stage"), {{"omega_c = \"0*rpm\"", "omega_s = \"3600*rpm\"\nstart = \"rigid\""},
                                                  {"solver = \"exact\"", "solver = \"dopri5\""},
                                                  {"tolerance = 1e-9", "tolerance = 1e-12"}}) +
      "\n[loads]\nr = { constant = \"20*N*m\", linear = \"0.5*N*m*s\", quadratic = \"0.01*N*m*s^2\" }\n";
  const SpecializedScene m = scene_model(rigid_start);
  const Trajectory r = interpret_trajectory(m, *m.rigid, run_settings(m, rt::Solver::dopri5));
  const Trajectory e = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::dopri5));
  ASSERT_TRUE(r.status.ok && e.status.ok) << r.status.message << e.status.message;
  // As in RigidStartMeetsTheRigidModelAtTheStart: the rigid run's first sample is the reference
  // model's eq. (8), loads included; the start's is exact and rounded once.
  const Eigen::VectorXd& y0 = r.y.front();
  EXPECT_LT((e.y.front() - y0).cwiseAbs().maxCoeff(), 1e-12 * y0.cwiseAbs().maxCoeff());
}

// speed_unit = "rpm": every speed output is the rad/s one times 60 / 2 pi, labelled rpm; forces and
// states are unchanged.
TEST(Specialization, SpeedsInRpm) {
  const std::string text = scene_text("paper_one_stage");
  const SpecializedScene si = scene_model(text);
  const SpecializedScene rpm = scene_model(with_line(text, "compare_rigid = true", "compare_rigid = true\nspeed_unit = \"rpm\""));
  for (const bool elastic : {true, false}) {
    const SpecializedSystem& a = elastic ? si.main : *si.rigid;
    const SpecializedSystem& b = elastic ? rpm.main : *rpm.rigid;
    const Trajectory ta = interpret_trajectory(si, a, run_settings(si));
    const Trajectory tb = interpret_trajectory(rpm, b, run_settings(rpm));
    ASSERT_TRUE(ta.status.ok && tb.status.ok);
    ASSERT_EQ(output_names(si, a), output_names(rpm, b));
    const std::vector<std::string> units_a = output_units(si.derivation.topology, a), units_b = output_units(rpm.derivation.topology, b);
    for (std::size_t j = 0; j < a.outputs.size(); ++j) {
      const bool speed = a.outputs[j].variable.kind == VariableKind::velocity;
      EXPECT_EQ(units_b[j], speed ? "rpm" : units_a[j]);
      const double factor = speed ? 60 / (2 * std::numbers::pi) : 1.0;
      for (std::size_t k = 0; k < ta.t.size(); ++k) {
        const auto i = static_cast<Eigen::Index>(j);
        // One more rounding (the factor's and the product's): a few ulps.
        EXPECT_NEAR(tb.y[k](i), factor * ta.y[k](i), 1e-14 * std::abs(factor * ta.y[k](i)) + 1e-300) << j;
      }
    }
  }
}

// The load split of redundant meshes has exact weights: each coefficient of the rigid force outputs
// is the correctly rounded value of an exact number, the one the reference model rounds, and not
// a sum of rounded weights whose last bits (1.7e-18 for an exact 0) follow GiNaC's term order.
TEST(Specialization, RedundantMeshForcesHaveCorrectlyRoundedCoefficients) {
  const SpecializedScene m = scene_model(scene_text("three_planets"));
  ASSERT_TRUE(m.derivation.rigid.redundant_meshes);
  ASSERT_TRUE(m.rigid.has_value());
  const SpecializedSystem& sys = *m.rigid;
  const NumericSystem ref = numeric_system(m, sys);
  int forces = 0;
  for (std::size_t i = 0; i < sys.outputs.size(); ++i) {
    if (sys.outputs[i].variable.kind != VariableKind::force) continue;
    ++forces;
    const GiNaC::ex y = sys.outputs[i].value.expand();
    for (std::size_t j = 0; j < sys.states.size(); ++j) {
      const GiNaC::realsymbol& x = variable_symbol(m.derivation.symbols, sys.states[j].variable);
      EXPECT_EQ(to_double(y.coeff(x, 1)), ref.C(static_cast<Eigen::Index>(i), static_cast<Eigen::Index>(j)))
          << variable_name(m.derivation.symbols, sys.outputs[i].variable) << " " << x;
    }
  }
  EXPECT_EQ(forces, 6);
}

TEST(Specialization, GenerationIsDeterministic) {
  const SpecializedScene a = scene_model(scene_text("paper_two_stage"));
  const SpecializedScene b = scene_model(scene_text("paper_two_stage"));
  EXPECT_EQ(generate_sources(a).header, generate_sources(b).header);
}

}  // namespace
}  // namespace pogear::test
