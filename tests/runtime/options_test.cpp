// The generated simulators' command line (parse_command_line) read strictly, against the ranges of
// run_limits.hpp, and the drivers' step counting: no option value is read by its prefix, no count
// wraps around, no step longer than the one asked for is taken.
#include <gtest/gtest.h>
#include <unistd.h>

#include <filesystem>
#include <string>
#include <vector>

#include "pogear/command_line.hpp"
#include "pogear/drivers.hpp"
#include "pogear/parameters.hpp"
#include "pogear/run_support.hpp"

namespace rt = pogear::rt;
namespace fs = std::filesystem;

namespace {

// parse_command_line on `args` (argv[0] is "sim"); the SceneRun it filled in.
struct Parsed {
  bool ok = false;
  rt::SceneRun run;
};

Parsed parse(std::vector<std::string> args) {
  args.insert(args.begin(), "sim");
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  Parsed p;
  p.run.csv = false;  // no directory is created unless a test asks for one
  p.ok = rt::parse_command_line(static_cast<int>(argv.size()), argv.data(), p.run);
  return p;
}

TEST(Options, NumbersMustBeTheWholeArgument) {
  // atof/atoi read a prefix: 1e6 steps were 1, 0.05ms was 0.05 s, 1e-6x passed as 1e-6.
  EXPECT_FALSE(parse({"--step", "0.05ms"}).ok);
  EXPECT_FALSE(parse({"--tolerance", "1e-6x"}).ok);
  EXPECT_FALSE(parse({"--tolerance", ""}).ok);
  EXPECT_FALSE(parse({"--repeat", "3x"}).ok);
  EXPECT_FALSE(parse({"--max-steps", "12 "}).ok);
  const Parsed p = parse({"--max-steps", "1e6", "--step", "5e-05", "--tolerance", "1e-6", "--repeat", "7"});
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.run.options.max_steps, 1000000);
  EXPECT_EQ(p.run.options.h, 5e-05);
  EXPECT_EQ(p.run.options.rtol, 1e-6);
  EXPECT_EQ(p.run.options.atol, 1e-8);
  EXPECT_EQ(p.run.repeat, 7);
}

TEST(Options, NumbersMustBeFiniteAndInRange) {
  EXPECT_FALSE(parse({"--tolerance", "inf"}).ok);
  EXPECT_FALSE(parse({"--tolerance", "nan"}).ok);
  EXPECT_FALSE(parse({"--tolerance", "0.2"}).ok);  // dopri5 diverged there
  EXPECT_FALSE(parse({"--tolerance", "1e-15"}).ok);
  EXPECT_TRUE(parse({"--tolerance", std::to_string(rt::limits::max_tolerance)}).ok);
  EXPECT_FALSE(parse({"--step", "0"}).ok);
  EXPECT_FALSE(parse({"--step", "-1e-3"}).ok);
  EXPECT_FALSE(parse({"--repeat", "0"}).ok);
  EXPECT_FALSE(parse({"--repeat", "99999999999"}).ok);  // overflowed an int and ran for ever
  EXPECT_FALSE(parse({"--repeat", "2.5"}).ok);
  EXPECT_TRUE(parse({"--repeat", std::to_string(rt::limits::max_repeat)}).ok);
  EXPECT_FALSE(parse({"--repeat", std::to_string(rt::limits::max_repeat + 1)}).ok);
  EXPECT_FALSE(parse({"--max-steps", "0"}).ok);
  EXPECT_FALSE(parse({"--max-steps", "1e300"}).ok);
  EXPECT_TRUE(parse({"--max-steps", std::to_string(rt::limits::max_max_steps)}).ok);
}

TEST(Options, OutMustNameADirectoryAndIsCreated) {
  EXPECT_FALSE(parse({"--out", ""}).ok);  // wrote into "/" + name.csv
  const fs::path dir = fs::temp_directory_path() / ("pogear_options_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  std::vector<std::string> args{"sim", "--out", (dir / "a" / "b").string()};
  std::vector<char*> argv;
  for (auto& a : args) argv.push_back(a.data());
  rt::SceneRun run;
  EXPECT_TRUE(rt::parse_command_line(static_cast<int>(argv.size()), argv.data(), run));
  EXPECT_TRUE(fs::is_directory(dir / "a" / "b"));
  fs::remove_all(dir);
}

TEST(Options, ParamsAreCollectedAsGiven) {
  const Parsed p = parse({"--param", "J_c=0.5", "--param", "K_ps=2e6*Newton/m", "--param", "r_s="});
  ASSERT_TRUE(p.ok);
  const std::vector<std::pair<std::string, std::string>> expected{
      {"J_c", "0.5"}, {"K_ps", "2e6*Newton/m"}, {"r_s", ""}};
  EXPECT_EQ(p.run.params, expected);
  EXPECT_FALSE(parse({"--param", "J_c"}).ok);
  EXPECT_FALSE(parse({"--param", "=1"}).ok);
  EXPECT_FALSE(parse({"--param"}).ok);
}

// --param takes the magnitudes model files take (1e-30 to 1e30 SI, or zero): a value the model
// reader would refuse cannot come in at run time either.
TEST(Options, ParamsOutsideTheModelsRangeAreRefused) {
  double J = 1, g = 0;
  const std::vector<rt::ParameterField> fields{{"J_p", &J, {{"g*cm^2", 1e-7}}, "positive"}, {"grade", &g, {}, ""}};
  auto set = [&](const std::string& name, const std::string& text, std::string* err = nullptr) {
    testing::internal::CaptureStderr();
    const bool ok = rt::set_parameters({{name, text}}, fields, "sim");
    const std::string e = testing::internal::GetCapturedStderr();
    if (err) *err = e;
    return ok;
  };
  std::string err;
  EXPECT_FALSE(set("J_p", "1e-300", &err));
  EXPECT_NE(err.find("sim: error: --param J_p=1e-300 is outside the range pogear computes with"), std::string::npos)
      << err;
  EXPECT_EQ(J, 1);
  EXPECT_FALSE(set("J_p", "1e-24*g*cm^2"));  // 1e-31 kg m^2 once converted
  EXPECT_FALSE(set("grade", "-2e30"));
  EXPECT_TRUE(set("J_p", "1e-30"));
  EXPECT_EQ(J, 1e-30);
  EXPECT_TRUE(set("J_p", "3*g*cm^2"));
  EXPECT_DOUBLE_EQ(J, 3e-7);
  EXPECT_TRUE(set("grade", "0"));
  EXPECT_TRUE(set("grade", "-1e30"));
}

// A diverged run's advice names what can help the solver that ran it: never a tolerance or
// another step for exact stepping, which has neither.
TEST(Options, DivergenceAdviceFitsTheSolver) {
  EXPECT_NE(rt::divergence_advice(rt::Solver::rk4).find("--step"), std::string::npos);
  EXPECT_NE(rt::divergence_advice(rt::Solver::dopri5).find("--tolerance"), std::string::npos);
  EXPECT_NE(rt::divergence_advice(rt::Solver::implicit).find("--tolerance"), std::string::npos);
  const std::string exact = rt::divergence_advice(rt::Solver::exact);
  EXPECT_EQ(exact.find("--tolerance"), std::string::npos) << exact;
  EXPECT_EQ(exact.find("--solver exact"), std::string::npos) << exact;
  EXPECT_NE(exact.find("parameters"), std::string::npos) << exact;
  for (rt::Solver s : rt::all_solvers) EXPECT_EQ(rt::divergence_advice(s).find(std::string(rt::solver_name(s)) + " or"),
                                                 std::string::npos);
  // A nonlinear system: exact stepping is no remedy.
  for (rt::Solver s : {rt::Solver::rk4, rt::Solver::dopri5, rt::Solver::implicit})
    EXPECT_EQ(rt::divergence_advice(s, false).find("exact"), std::string::npos) << rt::solver_name(s);
}

// pogear runs a compiled simulator with command_line(run): every setting comes back as it was,
// numbers to the last bit.
TEST(Options, CommandLineReadsBackAsTheRun) {
  rt::SceneRun run;
  run.solver = rt::Solver::dopri5;
  rt::set_tolerance(run.options, 3e-7);
  run.options.h = 1.0 / 3;
  run.options.max_steps = 123456789012;
  run.out_dir = "some dir/with spaces";
  run.repeat = 7;
  run.csv = false;
  run.quiet = true;
  run.params = {{"J_c", "0.5"}, {"K_ps", "2e6*Newton/m"}};
  const Parsed p = parse(rt::command_line(run));
  ASSERT_TRUE(p.ok);
  EXPECT_EQ(p.run.solver, run.solver);
  EXPECT_EQ(p.run.options.rtol, run.options.rtol);
  EXPECT_EQ(p.run.options.atol, run.options.atol);
  EXPECT_EQ(p.run.options.h, run.options.h);
  EXPECT_EQ(p.run.options.max_steps, run.options.max_steps);
  EXPECT_EQ(p.run.out_dir, run.out_dir);
  EXPECT_EQ(p.run.repeat, run.repeat);
  EXPECT_EQ(p.run.csv, run.csv);
  EXPECT_EQ(p.run.quiet, run.quiet);
  EXPECT_EQ(p.run.params, run.params);
  for (const rt::Solver s : rt::all_solvers) {
    run.solver = s;
    EXPECT_EQ(parse(rt::command_line(run)).run.solver, s) << rt::solver_name(s);
  }
}

// The tolerance rule is the runtime's, whichever way the tolerance arrives.
TEST(Options, AbsoluteToleranceFollowsTheRelativeOne) {
  rt::SolverOptions options;
  rt::set_tolerance(options, 1e-6);
  EXPECT_EQ(options.atol, 1e-6 * rt::absolute_per_relative_tolerance);
  EXPECT_EQ(parse({"--tolerance", "1e-6"}).run.options.atol, options.atol);
}

// Which solvers may run a system, decided by solver_refusal alone: each reason, and the solvers
// left (what `generate --solvers all` compiles).
TEST(SolverRefusal, ALinearSystemWithoutEventsRunsWithEverySolver) {
  for (const rt::Solver s : rt::all_solvers) EXPECT_FALSE(rt::solver_refusal(s, {})) << rt::solver_name(s);
  EXPECT_EQ(rt::admissible_solvers({}), std::vector<rt::Solver>(rt::all_solvers.begin(), rt::all_solvers.end()));
}

TEST(SolverRefusal, ANonlinearSystemIsNotRunByExactSteppingNorRk4) {
  const rt::SystemTraits nonlinear{.nonlinear = true};
  EXPECT_EQ(rt::describe(*rt::solver_refusal(rt::Solver::exact, nonlinear)),
            "a quadratic load makes the scene nonlinear, which exact stepping does not integrate");
  EXPECT_EQ(rt::describe(*rt::solver_refusal(rt::Solver::rk4, nonlinear)),
            "a quadratic load makes the scene nonlinear, which rk4's fixed step cannot be checked against its "
            "stability limit");
  EXPECT_EQ(rt::admissible_solvers(nonlinear), (std::vector<rt::Solver>{rt::Solver::dopri5, rt::Solver::implicit}));
}

TEST(SolverRefusal, EventsAreNotLocatedByRk4) {
  const rt::SystemTraits friction{.engages_friction = true}, limits{.limits_torque = true};
  EXPECT_EQ(rt::describe(*rt::solver_refusal(rt::Solver::rk4, friction)),
            "the scene engages brakes or clutches, which rk4 does not simulate (its fixed steps cannot locate their "
            "events)");
  EXPECT_EQ(rt::describe(*rt::solver_refusal(rt::Solver::rk4, limits)),
            "a controller with torque limits switches at events, which rk4 does not locate (its fixed steps)");
  const std::vector<rt::Solver> others{rt::Solver::exact, rt::Solver::dopri5, rt::Solver::implicit};
  EXPECT_EQ(rt::admissible_solvers(friction), others);
  EXPECT_EQ(rt::admissible_solvers(limits), others);
}

// The hybrid engine steps nonlinear modes with dopri5 and TR-BDF2; exact stepping needs linear modes,
// and rk4 cannot locate the events.
TEST(SolverRefusal, ANonlinearSystemWithEventsRunsWithTheAdaptiveSolvers) {
  for (const rt::SystemTraits t : {rt::SystemTraits{.nonlinear = true, .engages_friction = true},
                                   rt::SystemTraits{.nonlinear = true, .limits_torque = true}}) {
    EXPECT_EQ(rt::describe(*rt::solver_refusal(rt::Solver::exact, t)),
              "a quadratic load makes the scene nonlinear, which exact stepping does not integrate");
    EXPECT_TRUE(rt::solver_refusal(rt::Solver::rk4, t));
    EXPECT_EQ(rt::admissible_solvers(t), (std::vector<rt::Solver>{rt::Solver::dopri5, rt::Solver::implicit}));
  }
}

// The messages and the usage line list the options of one table.
TEST(Options, UnknownOptionListsTheTable) {
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(parse({"--bogus"}).ok);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "sim: error: unknown option '--bogus'; options are --solver, --tolerance, --step, --out, --repeat, "
            "--max-steps, --param, --no-csv, --quiet, --help\n");
  ::testing::internal::CaptureStderr();
  EXPECT_FALSE(parse({"--solver", "euler"}).ok);
  EXPECT_EQ(::testing::internal::GetCapturedStderr(),
            "sim: error: unknown solver 'euler'; the solvers are exact, rk4, dopri5, implicit\n");
  EXPECT_EQ(rt::usage_lines("PROGRAM", 100),
            (std::vector<std::string>{
                "Usage: PROGRAM [--solver exact|rk4|dopri5|implicit] [--tolerance R] [--step S] [--out DIR]",
                "               [--repeat N] [--max-steps N] [--param NAME=VALUE] [--no-csv] [--quiet] [--help]"}));
}

using V1 = Eigen::Matrix<double, 1, 1>;

TEST(FixedSteps, AStepCountBeyondMaxStepsFailsBeforeStepping) {
  // 10 ms samples with h = 1e-30 s: ceil(len / h) = 1e28 overflowed the long to one 10 ms step.
  auto f = [](double, const V1& x, V1& dx) { dx = -x; };
  rt::SolverOptions opt;
  opt.h = 1e-30;
  long samples = 0;
  const rt::RunStatus st = rt::simulate_rk4(f, V1(1.0), 0.0, 1.0, 0.01, opt, [&](double, const V1&) { ++samples; });
  EXPECT_FALSE(st.ok);
  EXPECT_EQ(st.steps, 0);
  EXPECT_EQ(samples, 1);  // t = 0 only
  EXPECT_EQ(st.message, "rk4 cannot reach t = 0.01: steps of at most 1e-30 s need 1e+28 steps over 0.01 s, more "
                        "than max_steps = 100000000; raise the step or max_steps");
}

TEST(FixedSteps, ASampleCountBeyondALongIsRefused) {
  // (t_end - t0) / dt = 1e300 samples: llround is undefined there; the run is refused up front.
  auto f = [](double, const V1& x, V1& dx) { dx = -x; };
  long samples = 0;
  const rt::RunStatus st =
      rt::simulate_rk4(f, V1(1.0), 0.0, 1e100, 1e-200, rt::SolverOptions{}, [&](double, const V1&) { ++samples; });
  EXPECT_FALSE(st.ok);
  EXPECT_EQ(samples, 0);
  EXPECT_EQ(st.message, "too many samples: (t_end - t0) / dt = 1e+300");
}

TEST(FixedSteps, NoStepIsLongerThanAskedFor) {
  // Every step of rk4 and of exact stepping is at most h (up to the rounding of len / n).
  for (double h : {0.3, 1e-3, 7e-4}) {
    double longest = 0;
    auto advance = [&](double, double hs, bool, V1&) { longest = std::max(longest, hs); };
    V1 x(1.0);
    rt::SolverOptions opt;
    opt.h = h;
    auto obs = [](double, const V1&) {};
    const rt::RunStatus st = rt::detail::run_fixed("rk4", advance, x, 0.0, 1.0, 0.01, opt, obs, {0.005, 0.5});
    ASSERT_TRUE(st.ok) << st.message;
    EXPECT_LE(longest, h * (1 + 1e-8)) << h;
  }
}

TEST(AdaptiveSteps, MinimumStepFollowsTheTimeReachedNotTheHorizon) {
  // A fast transient at t = 0 (time constant 1e-7 s) on a horizon of 1e9 s: the minimum step was
  // 1e-14 of the horizon (1e-5 s), above the 1e-8 s steps the transient needs, so both adaptive
  // methods stalled at once.
  auto f = [](double, const V1& x, V1& dx) { dx(0) = -1e7 * (x(0) - 1); };
  auto jac = [](double, const V1&, Eigen::Matrix<double, 1, 1>& J) { J(0, 0) = -1e7; };
  rt::SolverOptions opt;
  opt.rtol = 1e-6;
  opt.atol = 1e-8;
  opt.h = 1e-9;
  V1 last(0.0);
  auto obs = [&](double, const V1& x) { last = x; };
  const rt::RunStatus imp = rt::simulate_implicit(f, jac, true, V1(0.0), 0.0, 1e9, 1e8, opt, obs);
  ASSERT_TRUE(imp.ok) << imp.message;
  // x -> 1 within the tolerance; the implicit method damps the stiff mode (L-stable).
  EXPECT_NEAR(last(0), 1.0, 1e-6);
  opt.max_steps = 1000;  // dopri5 cannot finish a stiff 1e9 s run; it must stop, not stall at t = 0
  const rt::RunStatus dp = rt::simulate_dopri5(f, V1(0.0), 0.0, 1e9, 1e8, opt, obs);
  EXPECT_FALSE(dp.ok);
  EXPECT_EQ(dp.message.find("below the minimum"), std::string::npos) << dp.message;
  EXPECT_GT(dp.t_reached, 1e-6);  // past the transient
}

}  // namespace
