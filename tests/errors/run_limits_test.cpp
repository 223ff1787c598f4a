// The limits of a run (runtime/pogear/run_limits.hpp), as the generated simulator's command line and
// the scene's [simulation] table enforce them, and the runs that stop instead of reporting wrong
// numbers. Each message is an entry of docs/errors.md, checked to the character.
#include "error_support.hpp"
#include "run/interpreted_run.hpp"

namespace pogear::test {
namespace {

class SimulatorOptions : public SimulatorTest {};

// atof read "1e-6x" as 1e-6, "0.05ms" as 0.05 s and "1e6" steps as 1.
TEST_F(SimulatorOptions, NotANumber) { expect_simulator_error("--tolerance 1e-6x", 1,
    R"~(./paper_one_stage: error: --tolerance '1e-6x' is not a finite number; give a relative tolerance from 1e-14 to 0.01, e.g. 1e-8)~"); }
TEST_F(SimulatorOptions, StepWithAUnit) { expect_simulator_error("--step 0.05ms", 1,
    R"~(./paper_one_stage: error: --step '0.05ms' is not a finite number; give a step in seconds as a plain number (no unit), from 1e-30 to 1e+30, e.g. 5e-05)~"); }
TEST_F(SimulatorOptions, InfiniteTolerance) { expect_simulator_error("--tolerance inf", 1,
    R"~(./paper_one_stage: error: --tolerance 'inf' is not a finite number; give a relative tolerance from 1e-14 to 0.01, e.g. 1e-8)~"); }
// --repeat 99999999999 overflowed an int and ran for ever.
TEST_F(SimulatorOptions, OutOfRange) { expect_simulator_error("--repeat 99999999999", 1,
    R"~(./paper_one_stage: error: --repeat 99999999999 is out of range; give a whole number from 1 to 1000000, e.g. 10)~"); }
TEST_F(SimulatorOptions, ToleranceTooLoose) { expect_simulator_error("--tolerance 0.2", 1,
    R"~(./paper_one_stage: error: --tolerance 0.2 is out of range; give a relative tolerance from 1e-14 to 0.01, e.g. 1e-8)~"); }

TEST_F(SimulatorOptions, MaxStepsInExponentNotation) {
  // 1e6 is a million steps, not 1: rk4 needs 40000 steps of 0.05 ms for the 2 s scene.
  const Command c = run("./paper_one_stage --solver rk4 --max-steps 1e6 --quiet");
  EXPECT_EQ(c.status, 0) << c.err;
  const std::string csv = read_text("paper_one_stage.csv");
  EXPECT_EQ(csv.find("# incomplete"), std::string::npos);
}

// --out '' wrote into "/".
TEST_F(SimulatorOptions, EmptyOut) { expect_simulator_error("--out ''", 1,
    R"~(./paper_one_stage: error: --out needs a directory name, not an empty one; give e.g. --out results)~"); }
TEST_F(SimulatorOptions, OutCannotBeCreated) { expect_simulator_error("--out gear.toml/results", 1,
    R"~(./paper_one_stage: error: cannot create the output directory 'gear.toml/results' (Not a directory); give --out a directory you can create or write to)~"); }

TEST_F(SimulatorOptions, OutIsCreated) {
  const Command c = run("./paper_one_stage --out runs/today --quiet");
  EXPECT_EQ(c.status, 0) << c.err;
  EXPECT_TRUE(fs::is_regular_file("runs/today/paper_one_stage.csv"));
  EXPECT_TRUE(fs::is_regular_file("runs/today/paper_one_stage.rigid.csv"));
}

TEST_F(SimulatorOptions, ParamWithoutValue) { expect_simulator_error("--param J_c", 1,
    R"~(./paper_one_stage: error: --param 'J_c' is not NAME=VALUE; give a tunable parameter and its value, e.g. --param J_c=0.5)~"); }

// ceil(0.001 / 1e-30) overflowed a long: rk4 took one 1 ms step per sample and exited 0.
TEST_F(SimulatorOptions, StepCountAboveMaxSteps) { expect_simulator_error("--solver rk4 --step 1e-30", 3,
    R"~(paper_one_stage: error: rk4 cannot reach t = 0.001: steps of at most 1e-30 s need 1e+27 steps over 0.001 s, more than max_steps = 10000000; raise the step or max_steps; the CSV keeps what was computed and is marked incomplete)~"); }

// A run that diverges stops instead of writing wrong numbers. The tolerance 0.2 is beyond what the
// scene file and the simulator accept, so the run is set up through the library, as a program of
// the user's could (the review's case: dopri5 at 0.2 ended at 3.8e10 rad/s, exact 26.4, exit 0).
class RunChecks : public ErrorTest {};

TEST_F(RunChecks, DivergedSolution) {
  write_text("scene.toml", edited(base_scene(), {{"horizon = \"0.1*s\"", "horizon = \"2*s\""}}));
  const SpecializedScene m = specialize(parse_scene("scene.toml"));
  rt::SceneRun run;
  run.name = m.scene.name;
  run.horizon = m.scene.horizon;
  run.sample = m.scene.sample;
  run.solver = rt::Solver::dopri5;
  rt::set_tolerance(run.options, 0.2);
  run.out_dir = "out";
  run.quiet = true;
  fs::create_directory("out");
  ::testing::internal::CaptureStderr();
  EXPECT_EQ(run_interpreted(m, run), 3);
  expect_documented(::testing::internal::GetCapturedStderr(),
      R"~(demo: error: the solution diverged at t = 0.169: its energy is 4.08 times what the initial state and the inputs can supply; use a tighter --tolerance, or --solver exact or implicit; the CSV keeps what was computed and is marked incomplete)~" "\n");
  const std::string csv = read_text("out/demo.csv");
  EXPECT_NE(csv.find("\n# incomplete: the solution diverged at t = "), std::string::npos);
}

class SceneLimits : public ErrorTest {};

TEST_F(SceneLimits, StepOutOfRange) { expect_scene_error({{"step = \"0.05*ms\"", "step = \"1e-31*s\""}},
    R"~(scene.toml:19:8: error: step must be from 1e-30 s to 1e+30 s; give a step in that range)~"); }
TEST_F(SceneLimits, MaxStepsTooLarge) {
  expect_scene_error({{"solver = \"exact\"", "solver = \"exact\"\nmax_steps = 9223372036854775807"}},
                     R"~(scene.toml:18:13: error: max_steps is a whole number from 1 to 1000000000000)~");
}

}  // namespace
}  // namespace pogear::test
