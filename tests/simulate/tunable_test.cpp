// Tunable parameters (issue 10, item 15): finite and compact generated code, parameters defined
// through a tunable follow it, geometry relations, and `--param` against the interpreted path.
#include <regex>
#include <sstream>

#include "run/simulator_cache.hpp"
#include "sim_support.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

std::string with_tunable(const std::string& scene, const std::string& list) {
  return with_line(scene, "compare_rigid = true", "compare_rigid = true\ntunable = [" + list + "]");
}

// scripts/make_chain.sh K: the model, and its own scene (every effect, compare_rigid) with `extra`.
fs::path chain_scene(int k, const std::string& extra) {
  const fs::path dir = temp_dir("chain_" + std::to_string(k));
  write_text(dir / "scene.toml", with_line(chain_scene_text(k, dir), "compare_rigid = true", "compare_rigid = true\n" + extra));
  return dir / "scene.toml";
}

bool has_inf_or_nan(const std::string& code) {
  return std::regex_search(code, std::regex("\\b(inf|nan|INF|NAN|infinity)\\b", std::regex::icase));
}

// The issue: `inf*J_c1*omega_r1/((inf*J_c1 + inf))`, from the exact coefficients of an expanded
// symbolic inverse of L1 that overflow doubles.
TEST(Tunables, ChainWithATunableInertiaPrintsFiniteNumbers) {
  const SpecializedScene m = specialize(parse_scene(chain_scene(5, "tunable = [\"J_c1\"]").string()));
  const GeneratedSources g = generate_sources(m);
  EXPECT_FALSE(has_inf_or_nan(g.header)) << g.header.substr(0, 3000);
  // The rigid system's M at the scene's values is the interpreted path's (another formula):
  // both are exact up to one rounding of each entry and a small solve, ~1e-15 relative.
  ASSERT_TRUE(m.rigid);
  EXPECT_LT(relative_gap(state_matrix(m, *m.rigid), numeric_system(m, *m.rigid).M), 1e-12);
}

// The one-stage gear's rigid system has 2 states; its rhs was 22 operations without tunables,
// 291 with 2 and 21,844 with 10 (a symbolic L1^-1 over one common denominator).
TEST(Tunables, OperationCountsStayBoundedWithManyTunables) {
  const std::string scene = scene_text("paper_one_stage");
  const SpecializedScene none = scene_model(scene);
  const SpecializedScene ten = scene_model(
      with_tunable(scene, "\"J_c\", \"J_p\", \"J_r\", \"J_s\", \"J_g\", \"J_m\", \"b_c\", \"b_p\", \"K_ps\", \"b_ps\""));
  ASSERT_TRUE(ten.rigid);
  // L1, A1 (2x2, sums of at most 6 monomials each), B1 (2x1) and a 2x2 Cholesky solve: 70
  // operations, and no more with more tunables; 200 leaves room and is below the 291 of 2 tunables
  // before (1,912 for these 10).
  EXPECT_LT(ten.rigid->rhs_ops.total(), 200) << ten.rigid->rhs_ops.total() << " vs " << none.rigid->rhs_ops.total();
  EXPECT_LT(generate_sources(ten).header.size(), 2 * generate_sources(none).header.size());
  EXPECT_LT(relative_gap(state_matrix(ten, *ten.rigid), numeric_system(ten, *ten.rigid).M), 1e-12);
}

TEST(Tunables, ParametersDefinedThroughATunableFollowIt) {
  // K_pr, K_sg and K_rm are "K_ps" in the model; b_p ... b_m are "b_c".
  const SpecializedScene m = scene_model(with_tunable(scene_text("paper_one_stage"), "\"K_ps\", \"b_c\""));
  const std::string header = generate_sources(m).header;
  // The systems' code, after the parameter table (which lists every parameter with its value).
  const std::string h = header.substr(header.find("\nstruct "));
  for (const char* name : {"K_pr", "K_sg", "K_rm"}) EXPECT_EQ(h.find(name), std::string::npos) << name;
  // K_ps = 1000 N/mm = 1e6 N/m and b_c = 0.08 N m/rpm appear as values of Params only.
  EXPECT_EQ(std::regex_search(h, std::regex("[^=] 1000000\\.0")), false);
  std::size_t k_ps = 0;
  for (auto pos = h.find("*K_ps"); pos != std::string::npos; pos = h.find("*K_ps", pos + 1)) ++k_ps;
  EXPECT_GE(k_ps, 4u) << "every mesh's stiffness follows K_ps";
}

TEST(Tunables, GivenRadiusInAGeometryRelationWithATunableIsAnError) {
  try {
    scene_model(with_tunable(scene_text("paper_one_stage"), "\"r_p\""));
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    EXPECT_NE(std::string(e.what()).find("tunable 'r_p' enters the geometry relation r_c = r_p+r_s1"),
              std::string::npos)
        << e.what();
  }
}

// Without r_c and r_r1 in the model they are derived, and follow the tunable r_p.
TEST(Tunables, DerivedRadiiFollowATunableRadius) {
  const fs::path dir = temp_dir("derived_radii");
  std::string model = read_text(source_path("models/paper_one_stage.toml"));
  model = with_line(model, "r_c = \"14.8*cm\"", "");
  model = with_line(model, "r_r1 = \"19.6*cm\"", "");
  write_text(dir / "model.toml", model);
  std::string scene = with_tunable(scene_text("paper_one_stage"), "\"r_p\"");
  scene = with_line(scene, "model = \"../paper_one_stage.toml\"", "model = \"model.toml\"");
  write_text(dir / "scene.toml", scene);
  const SpecializedScene m = specialize(parse_scene((dir / "scene.toml").string()));
  const std::string h = generate_sources(m).header;
  EXPECT_NE(h.find("double r_p = 0.048;"), std::string::npos);
  EXPECT_NE(h.find("inline constexpr double r_c = 0.14800000000000002;  // m, derived from the geometry\n"), std::string::npos);
  EXPECT_NE(h.find("r_p + 0.1"), std::string::npos) << h.substr(0, 4000);  // r_c = r_p + r_s1
  EXPECT_LT(relative_gap(state_matrix(m, m.main), numeric_system(m, m.main).M), 1e-12);
  EXPECT_LT(relative_gap(state_matrix(m, *m.rigid), numeric_system(m, *m.rigid).M), 1e-12);
}

// A tunable inertia makes the rigid model an implicit form; with the power-split drive's speed
// controller and quadratic road load it is closed over the loop (the controller's integral, the load's
// linear part in A, its quadratic torque's column in Q). Solved at the scene's values it is the
// reference model's closed loop, which that builds from L, A, B in doubles by another formula.
TEST(Tunables, RigidImplicitFormClosesLoadsAndControllers) {
  const SpecializedScene m = scene_model(with_tunable(scene_text("power_split_drive"), "\"J_c\""));
  ASSERT_TRUE(m.rigid && m.rigid->implicit);
  const ImplicitForm& f = *m.rigid->implicit;
  ASSERT_EQ(f.L.rows(), 3u);  // omega_c, omega_r and the controller's integral
  const NumericSystem reference = numeric_system(m, *m.rigid);
  const GiNaC::exmap& at = m.values.numbers;
  const Eigen::LLT<Eigen::MatrixXd> L(evaluate_matrix(f.L, at));
  // A 3 x 3 Cholesky solve against the reference's exact-then-rounded M: a few eps of each column.
  EXPECT_LT(relative_gap(L.solve(evaluate_matrix(f.A, at)), reference.M), 1e-12);
  EXPECT_LT(relative_gap(L.solve(evaluate_matrix(f.B, at)), reference.N), 1e-12);
  ASSERT_EQ(reference.quadratic.size(), 1u);
  EXPECT_LT(relative_gap(L.solve(evaluate_matrix(f.Q, at)), Eigen::MatrixXd(reference.quadratic[0].state_column)), 1e-12);
}

// The ZF 6HP26 launch (rigid: an engine, a converter, a vehicle's road load, brakes and clutches) with
// a tunable output inertia: its implicit form solved at the scene's values is the reference model's
// system, the engine's and converter's torque columns among its inputs.
TEST(Tunables, RigidImplicitFormWithAnEngineAndAConverter) {
  std::string scene = scene_text("zf6hp26_launch");
  scene = with_line(scene, "speed_unit = \"rpm\"", "speed_unit = \"rpm\"\ntunable = [\"J_out\", \"Tcap_C\"]");
  const SpecializedScene m = scene_model(scene);
  ASSERT_TRUE(m.main.implicit);
  ASSERT_FALSE(m.main.driveline.empty());
  const ImplicitForm& f = *m.main.implicit;
  const NumericSystem reference = numeric_system(m, m.main);
  const GiNaC::exmap& at = m.values.numbers;
  const Eigen::LLT<Eigen::MatrixXd> L(evaluate_matrix(f.L, at));
  // A Cholesky solve against the reference's exact-then-rounded M and N: a few eps of each column.
  EXPECT_LT(relative_gap(L.solve(evaluate_matrix(f.A, at)), reference.M), 1e-12);
  EXPECT_LT(relative_gap(L.solve(evaluate_matrix(f.B, at)), reference.N), 1e-12);
  ASSERT_EQ(reference.quadratic.size(), 1u);  // the car's drag
  EXPECT_LT(relative_gap(L.solve(evaluate_matrix(f.Q, at)), Eigen::MatrixXd(reference.quadratic[0].state_column)), 1e-12);
}

// The compiled tunable path, with values other than the scene's through --param, against the
// interpreted path of the same scene with those values as [parameters] overrides.
TEST(Tunables, ParamOptionMatchesTheInterpretedPathWithTheSameValues) {
  const std::string scene = with_tunable(scene_text("paper_one_stage"), "\"K_ps\", \"J_c\"");
  const SpecializedScene tunable = scene_model(scene);
  // J_c enters L1: the rigid system is the implicit one, L1 x1' = A1 x1 + B1 tau solved by the
  // generated code from Params (its outputs, the eq. 8 forces, call rhs and so that solve).
  ASSERT_TRUE(tunable.rigid && tunable.rigid->implicit);
  ASSERT_TRUE(tunable.rigid->output_derivatives);
  const GeneratedSources sources = generate_sources(tunable);
  ASSERT_NE(sources.header.find("implicit_form(p, L, A, B);"), std::string::npos);
  const CompiledSimulator sim = build_simulator(sources);
  const fs::path dir = temp_dir("tunable_param");
  const Command run = run_command(sim.executable() + " --out " + dir.string() +
                                  " --quiet --param K_ps=2000*Newton/mm --param J_c=0.3");
  ASSERT_EQ(run.status, 0) << run.err;

  const SpecializedScene reference = scene_model(with_parameters(scene, "K_ps = \"2000*Newton/mm\"\nJ_c = 0.3"));
  // Both step with exp(M h) of the same M, built once from Params by the generated code (a 2x2
  // Cholesky solve for the rigid system) and once from L^-1 A in doubles: entries differ by
  // rounding, which 2000 contracting steps keep below 1e-10 of each column's scale. With the
  // scene's values instead (K_ps 1000 N/mm, J_c 0.17648) the difference is of order 1.
  expect_csv_matches_interpreted(dir / "paper_one_stage.csv", reference, reference.main, 1e-10);
  expect_csv_matches_interpreted(dir / "paper_one_stage.rigid.csv", reference, *reference.rigid, 1e-10);
}

}  // namespace
}  // namespace pogear::test

namespace pogear::test {
namespace {

// A program over a generated header that prints output_matrices_error of its systems, with Params
// `values` (C++ statements setting `p`).
std::string output_matrices_checker(const std::string& header, const std::string& values) {
  return "#include \"" + header + "\"\n#include \"" + source_path("tests/support/output_matrices_check.hpp") + R"("
#include <cstdio>

namespace scene = pogear_generated::paper_one_stage;

template <class System>
double error() {
  typename System::Params p;
  )" + values + R"(
  return pogear::test::output_matrices_error<System>(p);
}

int main() { std::printf("%.3g %.3g\n", error<scene::Elastic>(), error<scene::Rigid>()); }
)";
}

// The rigid system with tunable inertias solves L dx/dt = A x + B u numerically: output_matrices
// takes the mesh forces' dependence on dx/dt through matrices() (C + E M, D + E N), at values
// other than the scene's.
TEST(Tunables, OutputMatricesMatchTheOutputsAtOtherValues) {
  GeneratedSources sources = generate_sources(scene_model(with_tunable(scene_text("paper_one_stage"), "\"K_ps\", \"J_c\"")));
  ASSERT_NE(sources.header.find("implicit_form"), std::string::npos);
  sources.main = output_matrices_checker(sources.header_name, "p.K_ps = 2e6;\n  p.J_c = 0.3;");
  const CompiledSimulator checker = build_simulator(sources);
  const Command run = run_command(checker.executable());
  ASSERT_EQ(run.status, 0) << run.err;
  std::istringstream printed(run.out);
  double elastic = 1, rigid = 1;
  ASSERT_TRUE(printed >> elastic >> rigid) << run.out;
  // The elastic outputs are states and the force each damped mesh transmits, F + b_K R omega, whose
  // terms output_matrices sums in another order: a few eps (measured 1.8e-16).
  EXPECT_LT(elastic, 1e-14);
  // (E M) x against E (M x), with M from a 2x2 Cholesky solve both ways: a few eps of the largest
  // term (measured 5e-16); 1e-14 leaves room, and C without E M is off by 1.4 (measured).
  EXPECT_LT(rigid, 1e-14);
}

}  // namespace
}  // namespace pogear::test
