// Errors of the command lines: pogear's own (usage, output files, the compiler and gnuplot it
// calls) and those of a generated simulator. Each is an entry of docs/errors.md, checked to the
// character, with the exit status.
#include "../errors/error_support.hpp"

namespace pogear::test {
namespace {

class Cli : public ErrorTest {};

TEST_F(Cli, MissingArgument) { expect_pogear_error("derive", 1, R"~(MODEL is required
Run with --help for more information.)~"); }
TEST_F(Cli, UnknownFormat) { expect_pogear_error("derive gear.toml --format pdf", 1,
    R"~(--format: pdf not in {text,latex,markdown,json}
Run with --help for more information.)~"); }
TEST_F(Cli, NoSubcommand) { expect_pogear_error("", 1, R"~(A subcommand is required
Run with --help for more information.)~"); }

TEST_F(Cli, InputErrorExitsTwo) {
  write_text("gear.toml", edited(base_model(), {{R"(r_g = "16*cm")", R"(r_g = "0*cm")"}}));
  expect_pogear_error("derive gear.toml", 2,
      R"~(gear.toml:40:7: error: parameter 'r_g' is a radius and must be positive (it is 0))~");
}

TEST_F(Cli, ParamOfASceneWithoutTunables) {
  expect_pogear_error("simulate scene.toml --interpreted -o out --param J_c=0.5", 2,
      R"~(scene.toml: error: --param J_c: the scene has no tunable parameters; list J_c in the scene's tunable = [...] to set it at run time, or set it in [parameters])~");
  EXPECT_FALSE(fs::exists("out"));  // refused before anything runs
}

TEST_F(Cli, ParamNotTunable) {
  write_text("scene.toml", edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"J_c\"]"}}));
  expect_pogear_error("simulate scene.toml --interpreted -o out --param J_p=0.5", 2,
      R"~(scene.toml: error: --param J_p: not a tunable parameter of the scene; its tunables are J_c)~");
}

TEST_F(Cli, ParamValueRefused) {
  write_text("scene.toml", edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"J_c\"]"}}));
  expect_pogear_error("simulate scene.toml --interpreted -o out --param J_c=-0.5", 2,
      R"~(scene.toml: error: --param J_c=-0.5: parameter 'J_c' is an inertia and must be positive (it is -0.5))~");
  EXPECT_FALSE(fs::exists("out"));
}

TEST_F(Cli, ToleranceOutOfRange) {
  expect_pogear_error("simulate scene.toml --interpreted --tolerance 0.5", 1,
      R"~(--tolerance: '0.5' is not a tolerance from 1e-14 to 0.01; give a relative tolerance, e.g. --tolerance 1e-10
Run with --help for more information.)~");
}

TEST_F(Cli, OutputInAFile) { expect_pogear_error("derive gear.toml -o gear.toml/report.txt", 2,
    R"~(pogear: error: cannot create the directory gear.toml: a file of that name is in the way; give another directory)~"); }

TEST_F(Cli, OutputIsADirectory) {
  fs::create_directories("reports/old");
  expect_pogear_error("derive gear.toml -o reports", 2,
      R"~(pogear: error: reports is a directory; give the path of a file to write)~");
}

TEST_F(Cli, OutputWriteFails) {
  // A file size limit of one block makes the write fail with EFBIG (SIGXFSZ ignored, as a shell may).
  expect_pogear_error("derive gear.toml -o report.txt", 2,
      R"~(pogear: error: cannot write report.txt: File too large; check the free space and the output directory)~",
      "trap '' XFSZ; ulimit -f 1; ");
  for (const auto& e : fs::directory_iterator("."))  // no report, and no temporary file either
    EXPECT_EQ(e.path().filename().string().find("report.txt"), std::string::npos) << e.path();
}

TEST_F(Cli, OutputDirectoryInAFile) {
  expect_pogear_error("simulate scene.toml --interpreted -o gear.toml/out", 2,
      R"~(pogear: error: cannot create the directory gear.toml/out: Not a directory; give a directory you can write to)~");
}

TEST_F(Cli, GnuplotMissing) {
  expect_pogear_error("simulate scene.toml --interpreted -o out", 2,
      R"~(pogear: error: gnuplot is not installed, so no figures were drawn (the CSV files are written); install gnuplot-nox (scripts/install-deps.sh))~",
      "PATH=/nonexistent ");
  EXPECT_TRUE(fs::exists("out/demo.csv"));
}

TEST_F(Cli, RunFails) {
  // 1e308 rad/s overflows in the first step. (With compare_rigid the elastic model would start
  // from the rigid state, whose planet speed, r_c/r_p times the carrier's, is already infinite.)
  write_text("scene.toml", edited(base_scene(), {{R"(omega_c = "0*rpm")", R"(omega_c = "1e308*rad/s")"},
                                                 {"compare_rigid = true", "compare_rigid = false"}}));
  expect_pogear_error("simulate scene.toml --interpreted -o out", 3,
      R"~(demo: error: non-finite state at t = 0.001; last finite sample at t = 0; the CSV keeps what was computed and is marked incomplete)~");
  const std::string csv = read_text("out/demo.csv");
  EXPECT_NE(csv.find("\n# incomplete: non-finite state at t = 0.001"), std::string::npos);
  // The t = 0 row's rates overflow to inf; no output may become NaN through a structural zero.
  EXPECT_EQ(csv.find("nan"), std::string::npos) << csv;
}

TEST_F(Cli, CompileFailure) {
  // A broken <array> ahead of the system's makes the generated simulator fail to compile, after a
  // wall of warnings; the compiler's first error follows pogear's line, not the warnings.
  fs::create_directory("include");
  std::string header;
  for (int i = 0; i < 200; ++i) header += "#warning pogear test: noise\n";
  write_text("include/array", header + "#error pogear test: a broken header\n");
  const Command c = run("POGEAR_CACHE_DIR=cache CPLUS_INCLUDE_PATH=include " + pogear() + " simulate scene.toml -o out");
  EXPECT_EQ(c.status, 2);
  const std::string expected = "pogear: error: compiling the simulator failed (exit status 1); this is a fault of "
                               "pogear or of the compiler installation, not of the scene: report it with the scene "
                               "and model files. The compiler's first error:\n";
  expect_documented(c.err.substr(0, expected.size()), expected);
  const std::string rest = c.err.substr(std::min(expected.size(), c.err.size()));
  // The compiler's own line, as g++ ("error: #error ...") or clang ("error: ...") writes it.
  const auto line = rest.find("include/array:201:2: error: ");
  ASSERT_NE(line, std::string::npos) << c.err;
  EXPECT_LT(rest.find("pogear test: a broken header\n", line), rest.find('\n', line) + 1) << c.err;
  EXPECT_EQ(rest.find("noise"), std::string::npos) << rest;
}

// A simulator built by `pogear simulate` has the solver it runs (here the scene's, exact) and no
// other: asked for another, it says how to get one.
TEST_F(Cli, SolverNotCompiledIn) {
  ASSERT_EQ(run("POGEAR_CACHE_DIR=cache " + pogear() + " simulate scene.toml -o out >/dev/null").status, 0);
  std::string simulator;
  for (const auto& entry : fs::directory_iterator("cache"))
    if (fs::exists(entry.path() / "simulator")) simulator = fs::absolute(entry.path() / "simulator").string();
  ASSERT_FALSE(simulator.empty());
  fs::create_symlink(simulator, "demo");
  const Command c = run("./demo --solver dopri5 --out out");
  EXPECT_EQ(c.status, 1);
  expect_documented(c.err, R"~(./demo: error: this simulator was compiled with the solver exact only, not dopri5; `pogear simulate SCENE --solver dopri5` builds and runs one that has it, `pogear generate SCENE --solvers all` writes one with every solver)~" "\n");
  const Command help = run("./demo --help");
  EXPECT_EQ(help.status, 0) << help.err;
  EXPECT_NE(help.out.find("[--solver exact] [--tolerance R]"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("compiled with the solver exact (the scene's: exact)"), std::string::npos) << help.out;
}

// The generated simulators' command line (here the paper's one-stage scene, built by CMake).
class Simulator : public SimulatorTest {};

TEST_F(Simulator, NeedsAValue) { expect_simulator_error("--solver", 1,
    R"~(./paper_one_stage: error: --solver needs a value)~"); }
TEST_F(Simulator, UnknownOption) { expect_simulator_error("--horizon 2", 1,
    R"~(./paper_one_stage: error: unknown option '--horizon'; options are --solver, --tolerance, --step, --out, --repeat, --max-steps, --param, --no-csv, --quiet, --help)~"); }
TEST_F(Simulator, UnknownSolver) { expect_simulator_error("--solver euler", 1,
    R"~(./paper_one_stage: error: unknown solver 'euler'; the solvers are exact, rk4, dopri5, implicit)~"); }
TEST_F(Simulator, NotPositive) { expect_simulator_error("--step 0", 1,
    R"~(./paper_one_stage: error: --step 0 is out of range; give a step in seconds as a plain number (no unit), from 1e-30 to 1e+30, e.g. 5e-05)~"); }
TEST_F(Simulator, Rk4AboveItsStabilityLimit) { expect_simulator_error("--solver rk4 --step 0.01", 3,
    R"~(paper_one_stage: error: rk4 step 0.01 s is above its stability limit 0.00266428 s for this scene (fastest mode); use --step 0.00239785 or smaller, or --solver exact or implicit)~"); }
// --out creates a missing directory; /proc exists but takes no new files (not even as root).
TEST_F(Simulator, CsvCannotOpen) { expect_simulator_error("--out /proc", 3,
    R"~(paper_one_stage: error: cannot write /proc/paper_one_stage.csv: No such file or directory; check that the output directory exists and is writable)~"); }

TEST_F(Simulator, CsvWriteFails) {
  expect_simulator_error("--out .", 3,
      R"~(paper_one_stage: error: cannot write ./paper_one_stage.csv: File too large; check the free space and the output directory)~",
      "trap '' XFSZ; ulimit -f 10; ");
  EXPECT_FALSE(fs::exists("paper_one_stage.csv"));
}

TEST_F(Simulator, CsvCannotReplace) {
  fs::create_directories("out/paper_one_stage.csv/old");
  expect_simulator_error("--out out", 3,
      R"~(paper_one_stage: error: out/paper_one_stage.csv is a directory; give the path of a file to write)~");
  EXPECT_TRUE(fs::exists("out/paper_one_stage.csv/old"));
}

TEST_F(Simulator, RunStopped) {
  // 20 steps per 1 ms sample: the first sample is reached, the second is not.
  expect_simulator_error("--solver rk4 --max-steps 30", 3,
      R"~(paper_one_stage: error: rk4 stopped at t = 0.0015: max_steps = 30 reached; the CSV keeps what was computed and is marked incomplete)~");
  const std::string csv = read_text("paper_one_stage.csv");
  EXPECT_EQ(csv.substr(csv.rfind('#')), "# incomplete: rk4 stopped at t = 0.0015: max_steps = 30 reached\n");
}

TEST_F(Cli, ModesOfARigidScene) {
  write_text("scene.toml", edited(base_scene(), {{R"(effects = ["mesh_compliance", "mesh_damping", "bearing_friction", "mesh_forces"])",
                                                  R"(effects = ["bearing_friction"])"},
                                                 {"compare_rigid = true", "compare_rigid = false"}}));
  expect_pogear_error("modes scene.toml", 2,
      R"~(scene.toml: error: the scene simulates the rigid model (no mesh_compliance in its effects), which has no elastic modes; add mesh_compliance to its effects, or give the model file)~");
}

TEST_F(Cli, ModesWithEveryBodyHeld) {
  write_text("gear.toml", read_text(source_path("tests/vibration/pair.toml")));  // brakes Ba, Bb, one on each body

  expect_pogear_error("modes gear.toml --engaged Ba,Bb", 2,
      R"~(gear.toml: error: the engaged brakes hold every body, so nothing can vibrate; engage fewer elements)~");
  // One brake leaves the other wheel free: the command succeeds.
  const Command one = run(pogear() + " modes gear.toml --engaged Ba");
  EXPECT_EQ(one.status, 0) << one.err;
}

// A kept body that the engaged elements hold is at rest in every rigid motion: the message names it
// so (it read "r are tied together", though nothing else was kept).
TEST_F(Cli, KeptBodyHeldByAnEngagedBrake) {
  write_text("gear.toml", read_text(source_path("models/gearshift_planetary.toml")));
  expect_pogear_error("derive gear.toml --engaged brake --keep r", 2,
      R"~(gear.toml: error: the kept velocities r do not parametrize the rigid motions: omega_r is 0 in every rigid motion; valid choices are s; c; p)~");
}

TEST_F(Cli, ModesOfFrequenciesTooFarApart) {
  write_text("gear.toml", edited(base_model(), {{R"(K_sg = "K_ps")", R"(K_sg = "1e13*Newton/mm")"}}));
  expect_pogear_error("modes gear.toml", 2,
      R"~(gear.toml: error: the natural frequencies span a ratio of 1.57e+05 (lambda from 2.9e+05 to 7.16e+15 1/s^2), above 1e+04, the widest span whose lowest frequency double precision gives to 8 digits; make the stiffnesses and inertias less disparate)~");
}

TEST_F(Cli, CampbellWithoutToothCounts) {
  expect_pogear_error("modes gear.toml --campbell c.svg --input s --hold r", 2,
      R"~(gear.toml: error: no mesh has a tooth count, so no mesh frequency is known; give the wheels' teeth (docs/model-format.md, "Tooth counts and modules"))~");
  EXPECT_FALSE(std::filesystem::exists("c.svg"));
}

TEST_F(Cli, CampbellOnTwoDegreesOfFreedom) {
  write_text("gear.toml", read_text(source_path("models/ravigneaux.toml")));
  expect_pogear_error("modes gear.toml --campbell c.svg --input ss", 2,
      R"~(gear.toml: error: a Campbell diagram follows one operating line, but with no body held the gear has 2 degrees of freedom; hold more bodies (--hold) or engage brakes or clutches (--engaged))~");
}

TEST_F(Cli, CampbellSpeedInHz) {
  write_text("gear.toml", read_text(source_path("models/ravigneaux.toml")));
  expect_pogear_error("modes gear.toml --campbell c.svg --input ss --hold sl --to 100*Hz", 2,
      R"~(gear.toml: error: --to '100*Hz' is in Hz, which for a speed could mean rev/s or rad/s; give it in rpm or rad/s, e.g. --to 6000*rpm)~");
}

TEST_F(Cli, CampbellHoldTwice) {
  write_text("gear.toml", read_text(source_path("models/ravigneaux.toml")));
  expect_pogear_error("modes gear.toml --campbell c.svg --input ss --hold sl,sl", 2,
      R"~(gear.toml: error: --hold names 'sl' twice; name each body once)~");
}

TEST_F(Cli, OutputIsTheModel) {
  expect_pogear_error("derive gear.toml -o ./gear.toml", 2,
      R"~(./gear.toml: error: this output is also the model file; write it to another file)~");
  EXPECT_NE(read_text("gear.toml").find("[[body]]"), std::string::npos);  // untouched
}

TEST_F(Cli, CampbellOptionWithoutCampbell) {
  expect_pogear_error("modes gear.toml --input s", 2,
      R"~(gear.toml: error: --input belongs to the Campbell diagram; add --campbell FILE.svg)~");
}

TEST_F(Cli, ResponseUnknownInput) {
  expect_pogear_error("response scene.toml --input tau_x --output omega_r", 2,
      R"~(scene.toml: error: --input 'tau_x' is not tau_<body> of the model; give the torque of one of its bodies, e.g. tau_c)~");
}

TEST_F(Cli, ResponseUnknownOutput) {
  expect_pogear_error("response scene.toml --input tau_c --output omega_x", 2,
      R"~(scene.toml: error: --output 'omega_x' is neither omega_<body>, F_<mesh> nor Tc_<controller> of the scene; give the velocity of a body, the force of a mesh or a controller's torque, e.g. omega_c)~");
}

TEST_F(Cli, ResponseTooLarge) {
  expect_pogear_error("response scene.toml --input tau_c,tau_s,tau_r --output omega_c,omega_p,omega_s,omega_r "
                      "--points 1000000", 2,
      R"~(scene.toml: error: the CSV files of this response may take up to 1.2 GB (1000000 points for each of 12 input-output pairs); the limit is 1.07 GB: give fewer --points, inputs or outputs)~");
}

TEST_F(Cli, ResponseEmptyRange) {
  expect_pogear_error("response scene.toml --input tau_c --output omega_r --from '10*Hz' --to '1*Hz'", 2,
      R"~(scene.toml: error: the frequency range --from 10*Hz --to 1*Hz is empty; give --from below --to)~");
}

TEST_F(Cli, ResponseNegativeFrequency) {
  expect_pogear_error("response scene.toml --input tau_c --output omega_r --from '-1*Hz'", 2,
      R"~(scene.toml: error: --from '-1*Hz' is not a positive frequency; the response is drawn on a logarithmic axis from a frequency above 0)~");
}

TEST_F(Cli, ResponseFrequencyNotInHz) {
  expect_pogear_error("response scene.toml --input tau_c --output omega_r --to '100*rpm'", 2,
      R"~(scene.toml: error: --to '100*rpm' is not a frequency in Hz; give it in Hz or kHz, e.g. --to 10*Hz)~");
}

TEST_F(Cli, ResponseEngagedOverconstrained) {
  write_text("shift.toml", read_text(source_path("models/simpson_3speed.toml")));
  write_text("scene.toml", "name = \"shift\"\nmodel = \"shift.toml\"\neffects = [\"mesh_compliance\"]\n"
                           "compare_rigid = true\n");
  expect_pogear_error("response scene.toml --input tau_i --output omega_o --engaged C1,C2,B1,B2", 2,
      R"~(scene.toml: error: the engaged elements C1, C2, B1, B2 constrain the gear more than once (their torques are undetermined); engage fewer of them)~");
}

TEST_F(Cli, ResponseOfAModelFile) {
  expect_pogear_error("response gear.toml --input tau_c --output omega_r", 2,
      R"~(gear.toml: error: this is a model file; response needs a scene, which says the effects and parameters to analyse: write one that names this model (docs/scene-format.md))~");
}

TEST_F(Cli, ResponseWithoutInput) {
  expect_pogear_error("response scene.toml --input '' --output omega_r", 2,
      R"~(scene.toml: error: --input names no torque; give one or more, comma-separated, e.g. tau_c)~");
}

// gear.toml with a brake on the ring, a clutch joining sun and carrier, and brakes on the sun and
// on g, which meshes the sun: holding both adds nothing to holding one.
class Engaged : public ErrorTest {
 protected:
  void SetUp() override {
    ErrorTest::SetUp();
    write_text("shift.toml", edited(base_model(), {{"[parameters]", R"([[brake]]
name = "B1"
body = "r"

[[clutch]]
name = "C1"
bodies = ["s", "c"]

[[brake]]
name = "B2"
body = "s"

[[brake]]
name = "B3"
body = "g"

[parameters])"}, {R"(b_sg = "b_ps")", "b_sg = \"b_ps\"\nTcap_B1 = \"50*N*m\"\nTcap_C1 = \"50*N*m\"\nTcap_B2 = \"50*N*m\"\nTcap_B3 = \"50*N*m\""}}));
  }
};

TEST_F(Engaged, UnknownElement) {
  expect_pogear_error("derive shift.toml --engaged B9", 2,
      R"~(shift.toml: error: --engaged names 'B9', which is not a brake or clutch of the model; its elements are B1, C1, B2, B3)~");
}

TEST_F(Engaged, RepeatedElement) {
  expect_pogear_error("derive shift.toml --engaged B1,B1", 2,
      R"~(shift.toml: error: --engaged names 'B1' twice; name each element once)~");
}

TEST_F(Engaged, Empty) {
  expect_pogear_error("derive shift.toml --engaged ''", 2,
      R"~(shift.toml: error: --engaged is empty; name the engaged elements, e.g. --engaged B1)~");
}

TEST_F(Engaged, ModelWithoutElements) {
  expect_pogear_error("derive gear.toml --engaged B1", 2,
      R"~(gear.toml: error: --engaged names brakes or clutches, and the model has none; add [[brake]] or [[clutch]] tables to it, or leave --engaged out)~");
}

TEST_F(Engaged, LocksTheGear) {
  expect_pogear_error("derive shift.toml --engaged B1,C1", 2,
      R"~(shift.toml: error: engaging B1, C1 locks the gear: no body can turn, so there is no rigid model; engage fewer elements (pogear ratios lists the sets))~");
}

TEST_F(Engaged, AddsNoConstraint) {
  expect_pogear_error("derive shift.toml --engaged B2,B3", 2,
      R"~(shift.toml: error: engaging B3 adds no constraint that B2 and the meshes do not already impose, so its torque is not determined; engage fewer elements (pogear ratios lists the sets))~");
}

TEST_F(Engaged, RatiosOfAnUnknownBody) {
  expect_pogear_error("ratios shift.toml --input x --output c", 2,
      R"~(shift.toml: error: --input 'x' is not a body of the model; its bodies are c, p, s, r, g)~");
}

TEST_F(Engaged, RatiosOfOneBody) {
  expect_pogear_error("ratios shift.toml --input c --output c", 2,
      R"~(shift.toml: error: --input and --output are both 'c'; give two bodies)~");
}

// [gears] appended to shift.toml (its last line is 77): the table on line 79, the first gear on 80.
void append_gears(const std::string& gears) {
  write_text("shift.toml", read_text("shift.toml") + "\n[gears]\n" + gears);
}

TEST_F(Engaged, GearNamesAnUnknownElement) {
  append_gears("\"1\" = [\"B1\", \"B9\"]\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:14: error: gear '1' names 'B9', which is no brake or clutch of the model; they are B1, C1, B2, B3)~");
}

TEST_F(Engaged, GearNamesAnElementTwice) {
  append_gears("\"1\" = [\"B1\", \"B1\"]\n");
  expect_pogear_error("derive shift.toml", 2, R"~(shift.toml:80:14: error: gear '1' names 'B1' twice)~");
}

TEST_F(Engaged, TwoGearsEngageTheSameElements) {
  append_gears("\"1\" = [\"B1\"]\nlow = [\"B1\"]\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:81:1: error: gear 'low' engages the same elements as gear '1' (line 80); give each gear its own elements)~");
}

TEST_F(Engaged, GearNameIsNotPlain) {
  append_gears("\"1st gear\" = [\"B1\"]\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:1: error: a gear's name is letters, digits and '_', at most 64 characters, e.g. "1" or R; rename the gear)~");
}

TEST_F(Engaged, GearIsNotAList) {
  append_gears("\"1\" = \"B1\"\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:7: error: gear '1' must list the brakes and clutches it engages, e.g. "1" = ["B1"])~");
}

TEST_F(Engaged, GearLeavesDegreesOfFreedom) {
  append_gears("\"0\" = []\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:1: error: gear '0' (nothing) leaves 2 degrees of freedom; a gear leaves one: engage more elements)~");
}

TEST_F(Engaged, GearLocksTheGear) {
  append_gears("\"1\" = [\"B1\", \"C1\"]\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:1: error: gear '1' (B1, C1) locks the gear: nothing turns; engage fewer elements)~");
}

TEST_F(Engaged, GearWithAnElementThatAddsNothing) {
  append_gears("\"1\" = [\"B2\", \"B3\"]\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:1: error: gear '1' engages B2, B3, of which one element adds no constraint to the others (the set moves as it would without it); name the elements that make the gear)~");
}

TEST_F(Engaged, GearHoldsTheOutput) {
  append_gears("\"1\" = [\"B1\"]\n");
  expect_pogear_error("ratios shift.toml --input c --output r", 2,
      R"~(shift.toml:80:1: error: gear '1' (B1) holds the output 'r', so it has no ratio between c and r)~");
}

TEST_F(Engaged, RedundantMeshes) {
  // The three explicit planets of models/three_planets.toml, with a brake on the ring.
  std::string model = read_text(source_path("models/three_planets.toml"));
  model = edited(model, {{"[parameters]", "[[brake]]\nname = \"B\"\nbody = \"r\"\n\n[parameters]\nTcap_B = \"100*N*m\""}});
  write_text("planets.toml", model);
  expect_pogear_error("derive planets.toml --engaged B", 2,
      R"~(planets.toml: error: the gear's meshes are redundant (rank of R 4 for 6 meshes), and pogear does not split their load with brakes or clutches engaged; leave --engaged out)~");
}

}  // namespace
}  // namespace pogear::test
