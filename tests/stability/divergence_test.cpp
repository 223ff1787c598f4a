// Wrong numbers never reported as success: a diverging run trips the energy bound of the power
// balance, an rk4 step too small to count fails instead of wrapping around, the diagnostics call
// undamped fast modes stiff, and the implicit method covers horizons of 1e8 s.
#include <fmt/format.h>

#include <filesystem>

#include "../simulate/sim_support.hpp"
#include "paper_one_stage.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

// The rk4 step a scene's systems are all stable with: its own step, or 0.9 of the tightest limit.
double stable_rk4_step(const SpecializedScene& m) {
  double h = m.scene.step;
  h = std::min(h, 0.9 * system_diagnostics(m, m.main).rk4_max_step);
  if (m.rigid) h = std::min(h, 0.9 * system_diagnostics(m, *m.rigid).rk4_max_step);
  return h;
}

TEST(Divergence, Dopri5AtTolerance02IsReportedAsDiverged) {
  // The review's case: dopri5 at tolerance 0.2 ended at omega_c = 3.8e10 rad/s (exact 26.4) with
  // exit 0. The scene reader and the simulator now refuse such a tolerance, so the run is set up
  // through the library, as a program of the user's could.
  const SpecializedScene m = scene_model(scene_text("paper_one_stage"));
  rt::SceneRun run = run_settings(m, rt::Solver::dopri5);
  rt::set_tolerance(run.options, 0.2);
  run.quiet = true;
  const fs::path dir = temp_dir("diverged");
  run.out_dir = dir.string();
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(run_interpreted(m, run), 3);
  const std::string err = ::testing::internal::GetCapturedStderr();
  const std::string expected =
      "paper_one_stage: error: the solution diverged at t = 0.165: its energy is 4.06 times what the initial state "
      "and the inputs can supply; use a tighter --tolerance, or --solver exact or implicit; the CSV keeps what was "
      "computed and is marked incomplete\n";
  EXPECT_EQ(err, expected);  // docs/errors.md shows it for the demo scene (RunChecks.DivergedSolution)
  const Csv csv = read_csv((dir / "paper_one_stage.csv").string());
  EXPECT_TRUE(csv.incomplete);
  const std::string text = read_text((dir / "paper_one_stage.csv").string());
  EXPECT_NE(text.find("# incomplete: the solution diverged at t = "), std::string::npos) << text.substr(text.rfind('#'));
  // What was written before the check tripped is bounded: omega_c (column 1) stays below twice
  // what the power balance allows, far below the 1e10 rad/s the run reached unchecked.
  for (const auto& row : csv.rows) EXPECT_LT(std::abs(row[1]), 1e4) << row[0];
  fs::remove_all(dir);
}

TEST(Divergence, UndampedGearWithDopri5AtTheLoosestToleranceIsCaught) {
  // A free oscillation (no damping, no friction, no input) keeps its energy exactly. dopri5 at the
  // loosest allowed tolerance (1e-2) let its amplitude grow 19-fold over the 2 s (measured): a
  // wrong result, which the check stops; at 1e-9 the energy stays put and the run passes.
  std::string text = with_effects(scene_text("paper_one_stage"), "\"mesh_compliance\"");
  text = with_line(text, "compare_rigid = true", "compare_rigid = false");
  text = with_line(text, "tau_c = { constant = \"100*Nm\" }", "");
  text = with_line(text, "omega_c = \"0*rpm\"", "omega_c = \"100*rpm\"");
  const SpecializedScene m = scene_model(text);
  for (const auto& [tolerance, status] : {std::pair{1e-2, 3}, std::pair{1e-9, 0}}) {
    rt::SceneRun run = run_settings(m, rt::Solver::dopri5);
    rt::set_tolerance(run.options, tolerance);
    run.csv = false;
    run.quiet = true;
    ::testing::internal::CaptureStderr();
    EXPECT_EQ(run_interpreted(m, run), status) << tolerance;
    const std::string err = ::testing::internal::GetCapturedStderr();
    if (status == 3) {
      EXPECT_NE(err.find("error: the solution diverged at t = "), std::string::npos) << err;
    }
  }
}

TEST(Divergence, HonestRunsOfEverySceneWithEverySolverNeverTripTheBound) {
  // Every scene of models/scenes/ with every solver, adaptive ones at the scene's tolerance and at
  // the loosest allowed (1e-2), rk4 at a stable step: all must finish (status 0), so the check
  // never flags a run that is merely inaccurate within its tolerance.
  for (const auto& entry : fs::directory_iterator(source_path("models/scenes"))) {
    if (entry.path().extension() != ".toml") continue;
    const SpecializedScene m = specialize(parse_scene(entry.path().string()));
    // Brakes and clutches refuse rk4, quadratic loads exact stepping and rk4 (rt::solver_refusal).
    for (const rt::Solver solver : rt::admissible_solvers(solver_traits(m))) {
      std::vector<double> tolerances{m.scene.tolerance};
      if (solver == rt::Solver::dopri5 || solver == rt::Solver::implicit)
        tolerances.push_back(rt::limits::max_tolerance);
      for (double tolerance : tolerances) {
        rt::SceneRun run = run_settings(m, solver);
        rt::set_tolerance(run.options, tolerance);
        if (solver == rt::Solver::rk4) run.options.h = stable_rk4_step(m);
        run.csv = false;
        run.quiet = true;
        EXPECT_EQ(run_interpreted(m, run), 0)
            << entry.path().filename() << " " << rt::solver_name(solver) << " " << tolerance;
      }
    }
  }
}

TEST(Divergence, CompiledSimulatorsCheckTheBoundToo) {
  // The generated energy_matrix is the numeric L of the derivation (diag(J, K^-1), and L1 for the
  // rigid model), so the compiled path checks the same bound as the interpreted one.
  const SpecializedScene m = specialize(parse_scene(source_path("models/scenes/paper_one_stage.toml")));
  namespace g = pogear_generated::paper_one_stage;
  g::Elastic::StateMatrix L;
  g::Elastic::energy_matrix({}, L);
  const Eigen::MatrixXd Ln = numeric_system(m, m.main).L;
  // Both are the same exact rationals rounded once to double.
  EXPECT_EQ((L - Ln).cwiseAbs().maxCoeff(), 0.0) << L << "\n\n" << Ln;
  g::Rigid::StateMatrix L1;
  g::Rigid::energy_matrix({}, L1);
  const Eigen::MatrixXd L1n = numeric_system(m, *m.rigid).L;
  // L1 = Q1^T J Q1 summed in another order than exact_rigid_values: equal to a few ulps.
  EXPECT_LT((L1 - L1n).cwiseAbs().maxCoeff(), 1e-14 * L1n.cwiseAbs().maxCoeff()) << L1 << "\n\n" << L1n;
  for (const std::string solver : {"exact", "rk4", "dopri5", "implicit"}) {
    const Command c = run_command(std::string(POGEAR_SIM_ONE_STAGE) + " --no-csv --quiet --solver " + solver +
                                  " --tolerance 1e-2");
    EXPECT_EQ(c.status, 0) << solver << ": " << c.err;
  }
}

TEST(TinyStep, Rk4WithA1e30SecondStepFailsInsteadOfTakingOneStepPerSample) {
  // The review's case: sample 10 ms, step 1e-30 s; ceil(0.01 / 1e-30) overflowed a long, and rk4
  // took one 10 ms step per sample (unstable: omega_c = 1.4e265 rad/s after "100 steps", exit 0).
  const SpecializedScene m = scene_model(with_lines(scene_text("paper_one_stage"), {{"solver = \"exact\"", "solver = \"rk4\""},
                                                                          {"sample = \"1*ms\"", "sample = \"10*ms\""},
                                                                          {"step = \"0.05*ms\"", "step = \"1e-30*s\""}}));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::rk4));
  EXPECT_FALSE(tr.status.ok);
  EXPECT_EQ(tr.status.steps, 0);
  EXPECT_EQ(tr.status.message.rfind("rk4 cannot reach t = 0.01: steps of at most 1e-30 s need 1e+28 steps", 0), 0u)
      << tr.status.message;
  for (const auto& x : tr.x) EXPECT_LT(x.norm(), 1e3);
}

// The shipped elastic Simpson upshift is stiff (its meshes ring 1e3 times faster than the sample
// period): without its brakes and clutches the advice among adaptive methods is implicit. With them
// it is dopri5: every step is then held to the event-check step, which resolves the fastest mode, and
// dopri5 was measured more accurate than implicit at each tolerance on every shipped shift
// (bench/shift_solvers.py, docs/accuracy-vs-time.md "Which solver for a shift").
TEST(Diagnostics, ShiftsAdviseDopri5AmongAdaptiveMethods) {
  const std::string text = scene_text("simpson_1_2_upshift");
  const SpecializedScene shift = scene_model(text);
  const Diagnostics with = system_diagnostics(shift, shift.main);
  EXPECT_EQ(with.suggested_solver, "exact");
  EXPECT_EQ(with.adaptive_solver, "dopri5") << with.reason;
  EXPECT_NE(with.reason.find("among adaptive methods use dopri5 (brakes and clutches"), std::string::npos) << with.reason;
  const std::string engagement = text.substr(text.find("[engagement]"), text.find("[simulation]") - text.find("[engagement]"));
  const SpecializedScene gear = scene_model(with_line(text, engagement, ""));
  const Diagnostics without = system_diagnostics(gear, gear.main);
  EXPECT_EQ(without.adaptive_solver, "implicit") << without.reason;
}

TEST(Diagnostics, UndampedFastModesAreStiff) {
  // No damping at all and mesh modes of ~1e-29 s: the stiffness ratio sees no decaying mode (1),
  // and the verdict was "dopri5 (not stiff)", which then stalls. An explicit method's step is
  // bounded by the fastest mode whether it decays or not.
  std::string text = with_effects(scene_text("paper_one_stage"), "\"mesh_compliance\"");
  text = with_line(text, "compare_rigid = true", "compare_rigid = false");
  text = with_parameters(text, "K_ps = \"1e30*Newton/m\"\nJ_p = \"1e-30*kg*meters^2\"");
  const SpecializedScene m = scene_model(text);
  const Diagnostics d = system_diagnostics(m, m.main);
  EXPECT_LT(d.fastest_time_constant, 1e-20);
  EXPECT_EQ(d.adaptive_solver, "implicit") << d.reason;
  EXPECT_NE(d.reason.find("among adaptive methods use implicit (the fastest time scale"), std::string::npos)
      << d.reason;
}

TEST(Diagnostics, AVeryStiffPassiveGearHasNoGrowingMode) {
  // The one-stage gear with bearing friction and undamped meshes as stiff as 1e18 and 1e20 N/m:
  // passive, so no mode grows. Its eigenvalues computed from M unbalanced (mesh-force rows 1e20
  // times the speed rows) had real parts of rounding's size, and up to 7 modes were called
  // growing, the scene "unstable".
  for (const char* K : {"1e18", "1e20"}) {
    std::string text = with_effects(scene_text("paper_one_stage"), "\"mesh_compliance\", \"bearing_friction\"");
    text = with_parameters(text, fmt::format("K_ps = \"{}*N/m\"\nK_pr = \"{}*N/m\"", K, K));
    const SpecializedScene m = scene_model(text);
    const Diagnostics d = system_diagnostics(m, m.main);
    EXPECT_EQ(d.growing_modes, 0) << K << ": the fastest grows by e in " << 1 / d.fastest_growth_rate << " s";
  }
}

TEST(Diagnostics, ThePaperScenesStayNotStiff) {
  // The fastest time scale of the paper's scenes (~1 ms) is that of their 1 ms sample period.
  for (const char* name : {"paper_one_stage", "paper_two_stage"}) {
    const SpecializedScene m = specialize(parse_scene(source_path(std::string("models/scenes/") + name + ".toml")));
    const Diagnostics d = system_diagnostics(m, m.main);
    EXPECT_EQ(d.adaptive_solver, "dopri5") << name << ": " << d.reason;
  }
}

TEST(LongHorizon, ImplicitFinishesA1e8SecondHorizon) {
  // The minimum step was 1e-14 of the horizon, 1e-6 s here, above the steps the start of the
  // transient needs: the implicit method stalled at t = 0. Over 1e8 s the gear must settle where
  // M x + N u = 0.
  const SpecializedScene m = scene_model(with_lines(scene_text("paper_one_stage"), {{"horizon = \"2*s\"", "horizon = \"1e8*s\""},
                                                                          {"sample = \"1*ms\"", "sample = \"1e5*s\""},
                                                                          {"solver = \"exact\"", "solver = \"implicit\""}}));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::implicit));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  EXPECT_EQ(tr.t.back(), 1e8);
  const NumericSystem ns = numeric_system(m, m.main);
  const Eigen::VectorXd steady = -ns.M.partialPivLu().solve(ns.N * Eigen::VectorXd::Constant(1, 100.0));
  // Long after the transient the local error test holds the state at the steady state to about
  // the tolerance (1e-9 relative, atol 1e-11).
  EXPECT_LT((tr.x.back() - steady).norm() / steady.norm(), 1e-6);
}

}  // namespace
}  // namespace pogear::test
