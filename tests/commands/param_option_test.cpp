// `pogear simulate --param NAME=VALUE` and `--tolerance R`: options of the one compiled simulator
// (not rebuilt for them), which then runs as the scene with those values written in does.
#include <algorithm>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"
#include "../support/gaps.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

// The paper's one-stage scene over 0.2 s as `name`, with `extra` after its compare_rigid line.
fs::path one_stage_scene(const fs::path& dir, const std::string& name, const std::string& extra) {
  std::string text = read_text(source_path("models/scenes/paper_one_stage.toml"));
  for (const auto& [from, to] : {std::pair<std::string, std::string>{"name = \"paper_one_stage\"", "name = \"" + name + "\""},
                                 {"\"../paper_one_stage.toml\"", "\"" + source_path("models/paper_one_stage.toml") + "\""},
                                 {"compare_rigid = true", "compare_rigid = true\n" + extra},
                                 {"horizon = \"2*s\"", "horizon = \"0.2*s\""}})
    text.replace(text.find(from), from.size(), to);
  write_text(dir / (name + ".toml"), text);
  return dir / (name + ".toml");
}

Command simulate(const fs::path& scene, const std::string& options) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + scene.string() + " " + options);
  EXPECT_EQ(c.status, 0) << c.err;
  return c;
}

std::string simulator_path(const std::string& out) {
  const auto at = out.find("\nsimulator ");
  if (at == std::string::npos) return "";
  const auto from = at + 11;
  return out.substr(from, out.find('\n', from) - from);
}

// An events file's rows past its header: time, and the rest of the row.
std::vector<std::pair<double, std::string>> event_rows(const fs::path& file) {
  std::vector<std::pair<double, std::string>> rows;
  std::ifstream in(file);
  std::string line;
  std::getline(in, line);
  while (std::getline(in, line)) rows.emplace_back(std::stod(line.substr(0, line.find(','))), line.substr(line.find(',')));
  return rows;
}

// The largest gap between two runs' columns, each relative to the column's largest magnitude.
double relative_gap(const Csv& a, const Csv& b) {
  EXPECT_EQ(a.rows.size(), b.rows.size());
  EXPECT_EQ(a.header.size(), b.header.size());
  double worst = 0;
  for (std::size_t col = 1; col < std::min(a.header.size(), b.header.size()); ++col)
    worst = std::max(worst, column_error(a.rows, b.rows, col));
  return worst;
}

TEST(SimulateCommand, ParamAndToleranceAsTheSimulatorTakesThem) {
  const fs::path dir = temp_dir("param_option");
  const fs::path tunable = one_stage_scene(dir, "tunable", "tunable = [\"K_ps\", \"J_c\"]");
  const fs::path literal = one_stage_scene(dir, "literal", "[parameters]\nK_ps = \"2000*N/mm\"\nJ_c = 0.3");
  const std::string values = "--param K_ps=2000*N/mm --param J_c=0.3";
  const Command first = simulate(tunable, values + " -o " + (dir / "a").string());
  const Command other = simulate(tunable, "--param J_c=0.2 -o " + (dir / "b").string());
  // One simulator, in the cache, for both values.
  const std::string path = simulator_path(first.out);
  ASSERT_FALSE(path.empty()) << first.out;
  EXPECT_TRUE(fs::exists(path)) << path;
  EXPECT_EQ(simulator_path(other.out), path);
  simulate(literal, "--interpreted -o " + (dir / "c").string());
  simulate(tunable, "--interpreted " + values + " -o " + (dir / "d").string());
  const Csv reference = read_csv((dir / "c/literal.csv").string());
  // Compiled with Params against the values folded in as literals: exp(M h) of the same M, built from
  // Params by the generated code and from L^-1 A in doubles; the entries differ by rounding, which
  // 4000 contracting steps keep below 1e-10 of each column's scale.
  EXPECT_LT(relative_gap(read_csv((dir / "a/tunable.csv").string()), reference), 1e-10);
  // Interpreted at the options' values: the same exact numbers but for 0.3 read as a double (1e-17).
  EXPECT_LT(relative_gap(read_csv((dir / "d/tunable.csv").string()), reference), 1e-12);
  // The other value took effect: a lighter carrier moves the run by far more than rounding.
  EXPECT_GT(relative_gap(read_csv((dir / "b/tunable.csv").string()), reference), 1e-3);

  // --tolerance is the scene's tolerance for the run: dopri5 at 1e-5 given either way is one run.
  simulate(literal, "--interpreted --solver dopri5 --tolerance 1e-5 -o " + (dir / "e").string());
  const fs::path loose = one_stage_scene(dir, "loose", "[parameters]\nK_ps = \"2000*N/mm\"\nJ_c = 0.3");
  write_text(loose, [&] {
    std::string text = read_text(loose);
    text.replace(text.find("solver = \"exact\""), 16, "solver = \"dopri5\"");
    text.replace(text.find("tolerance = 1e-9"), 16, "tolerance = 1e-5");
    return text;
  }());
  simulate(loose, "--interpreted -o " + (dir / "f").string());
  const Csv at_option = read_csv((dir / "e/literal.csv").string());
  EXPECT_EQ(relative_gap(at_option, read_csv((dir / "f/loose.csv").string())), 0);
  // ... and not the scene's 1e-9: dopri5's error at 1e-5 is far above the exact run's rounding.
  EXPECT_GT(relative_gap(at_option, reference), 1e-8);
}

// A value may name another --param's parameter, in either order, as in [parameters]; the summary's
// figures (the frequencies, the step limits) are those of the values run.
TEST(SimulateCommand, ParamValuesNameEachOtherAndTheSummaryFollows) {
  const fs::path dir = temp_dir("param_each_other");
  const fs::path tunable = one_stage_scene(dir, "tunable", "tunable = [\"J_c\", \"J_p\", \"K_ps\"]");
  const fs::path literal = one_stage_scene(dir, "literal",
                                           "[parameters]\nJ_c = \"2*J_p\"\nJ_p = \"0.02*kg*m^2\"\nK_ps = \"3000*N/mm\"");
  const Command reference = simulate(literal, "--interpreted -o " + (dir / "ref").string());
  const Csv expected = read_csv((dir / "ref/literal.csv").string());
  auto frequency_line = [](const std::string& out) {
    const auto at = out.find("lowest natural frequency");
    return at == std::string::npos ? std::string() : out.substr(at, out.find('\n', at) - at);
  };
  ASSERT_FALSE(frequency_line(reference.out).empty()) << reference.out;
  for (const std::string order : {"--param J_c=2*J_p --param J_p=0.02*kg*m^2", "--param J_p=0.02*kg*m^2 --param J_c=2*J_p"}) {
    SCOPED_TRACE(order);
    const Command c = simulate(tunable, "--interpreted " + order + " --param K_ps=1*N/mm --param K_ps=3000*N/mm -o " +
                                            (dir / "run").string());
    // The same exact numbers but for the two doubles the options pass on (0.02 and 0.04 kg m^2).
    EXPECT_LT(relative_gap(read_csv((dir / "run/tunable.csv").string()), expected), 1e-12);
    EXPECT_EQ(frequency_line(c.out), frequency_line(reference.out));
  }
}


// Shipped scene models/scenes/<shipped>.toml as `name` in `dir`: its model and tables (`files`, in
// models/ and models/scenes/) by absolute path, then `edits` in order, each of a text it has.
fs::path shipped_scene(const fs::path& dir, const std::string& shipped, const std::string& name,
                       const std::vector<std::string>& files, const std::vector<std::pair<std::string, std::string>>& edits) {
  std::string text = read_text(source_path("models/scenes/" + shipped + ".toml"));
  auto edit = [&](const std::string& from, const std::string& to) {
    const auto at = text.find(from);
    EXPECT_NE(at, std::string::npos) << from;
    if (at != std::string::npos) text.replace(at, from.size(), to);
  };
  edit("name = \"" + shipped + "\"", "name = \"" + name + "\"");
  for (const std::string& f : files)
    edit("\"" + f + "\"", "\"" + source_path(f.rfind("../", 0) == 0 ? "models/" + f.substr(3) : "models/scenes/" + f) + "\"");
  for (const auto& [from, to] : edits) edit(from, to);
  write_text(dir / (name + ".toml"), text);
  return dir / (name + ".toml");
}

// The Simpson 1-2 upshift as `name` in `dir`, with `extra` after its compare_rigid line and
// `parameters` after its [parameters] header.
fs::path simpson_scene(const fs::path& dir, const std::string& name, const std::string& extra, const std::string& parameters) {
  return shipped_scene(dir, "simpson_1_2_upshift", name, {"../simpson_3speed.toml", "simpson_B2_release.csv", "simpson_B1_apply.csv"},
                       {{"compare_rigid = true", "compare_rigid = true\n" + extra}, {"[parameters]\n", "[parameters]\n" + parameters + "\n"}});
}

// A brake's capacity that follows a tunable (B1's through B2's) takes --param's value, compiled and
// interpreted, as the values written in [parameters] do; one the values make negative is refused.
TEST(SimulateCommand, ParamMovesCapacitiesThatFollowATunable) {
  const fs::path dir = temp_dir("param_capacity");
  const fs::path tunable = simpson_scene(dir, "tunable", "tunable = [\"Tcap_B2\"]", "Tcap_B1 = \"Tcap_B2 - 450*N*m\"");
  const fs::path literal = simpson_scene(dir, "literal", "", "Tcap_B2 = \"750*N*m\"\nTcap_B1 = \"300*N*m\"");
  const Command first = simulate(tunable, "--param Tcap_B2=750*N*m -o " + (dir / "a").string());
  simulate(tunable, "--interpreted --param Tcap_B2=750*N*m -o " + (dir / "b").string());
  simulate(literal, "--interpreted -o " + (dir / "c").string());
  simulate(tunable, "--interpreted -o " + (dir / "d").string());  // at the scene's 800 and 350 N m
  for (const std::string suffix : {"", ".rigid"}) {
    SCOPED_TRACE(suffix);
    const Csv reference = read_csv((dir / "c" / ("literal" + suffix + ".csv")).string());
    // The compiled run's matrices are the generated code's and the interpreted run's are the
    // reference model's, equal up to rounding; over 2000 steps and the events that stays below 1e-9
    // of each column's scale (the compiled shift test's bound). Interpreted with the option, the same
    // numbers reach the same engine (300 N m exactly, 750 - 450).
    EXPECT_LT(relative_gap(read_csv((dir / "a" / ("tunable" + suffix + ".csv")).string()), reference), 1e-9);
    EXPECT_EQ(relative_gap(read_csv((dir / "b" / ("tunable" + suffix + ".csv")).string()), reference), 0);
    // The same events in the same order; the scene's capacities move the shift by far more than rounding.
    const std::string file = suffix + ".events.csv";
    const auto compiled = event_rows(dir / "a" / ("tunable" + file)), written = event_rows(dir / "c" / ("literal" + file));
    ASSERT_EQ(compiled.size(), written.size());
    ASSERT_GE(compiled.size(), 3u);
    for (std::size_t i = 0; i < compiled.size(); ++i) {
      EXPECT_EQ(compiled[i].second, written[i].second);
      EXPECT_NEAR(compiled[i].first, written[i].first, 1e-12);  // located to rounding of the same trajectory
    }
    EXPECT_GT(relative_gap(read_csv((dir / "d" / ("tunable" + suffix + ".csv")).string()), reference), 1e-3);
  }
  // At 400 N m B1's capacity would be -50 N m: pogear refuses the value as it refuses it in
  // [parameters], and the simulator run by itself refuses the capacity.
  const Command refused = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + tunable.string() +
                                      " --param Tcap_B2=400*N*m -o " + (dir / "e").string());
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("parameter 'Tcap_B1' is a brake's torque capacity and must be positive (it is -50)"),
            std::string::npos)
      << refused.err;
  const std::string simulator = simulator_path(first.out);
  ASSERT_FALSE(simulator.empty()) << first.out;
  const Command alone = run_command(simulator + " --quiet --param Tcap_B2=400*N*m --out " + (dir / "f").string());
  EXPECT_EQ(alone.status, 3);
  EXPECT_NE(alone.err.find("B1 has a torque capacity of -50 N m; a capacity is positive"), std::string::npos) << alone.err;
}


// The power-split drive (a speed controller and a quadratic road load) over 4 s as `name` in `dir`,
// with `scene_lines` after its compare_rigid line (which `keep_rigid` false drops) and `parameters`.
fs::path power_split_scene(const fs::path& dir, const std::string& name, bool keep_rigid, const std::string& scene_lines,
                           const std::string& parameters) {
  return shipped_scene(dir, "power_split_drive", name, {"../power_split.toml", "power_split_drive_mg2.csv"},
                       {{"compare_rigid = true", (keep_rigid ? "compare_rigid = true\n" : "") + scene_lines},
                        {"[inputs]\n", "[parameters]\n" + parameters + "\n\n[inputs]\n"},
                        {"horizon = \"8*s\"", "horizon = \"4*s\""}});
}

// Tunables with loads and controllers: an inertia and a stiffness in both models (compiled; the rigid
// one then an implicit form over the controller's integral and the quadratic road load), an inertia
// that the load's column divides by in the elastic model (interpreted), each as the values written.
TEST(SimulateCommand, ParamWithLoadsAndControllers) {
  const fs::path dir = temp_dir("param_loops");
  const fs::path tunable = power_split_scene(dir, "tunable", true, "tunable = [\"J_c\", \"K_ps\"]", "");
  const fs::path both_written = power_split_scene(dir, "written", true, "", "J_c = \"0.2*kg*m^2\"\nK_ps = \"2e8*N/m\"");
  simulate(tunable, "--param J_c=0.2*kg*m^2 --param K_ps=2e8*N/m -o " + (dir / "a").string());
  simulate(both_written, "--interpreted -o " + (dir / "b").string());
  simulate(tunable, "--interpreted -o " + (dir / "f").string());  // the scene's 0.15 kg m^2 and 1e8 N/m
  for (const std::string suffix : {"", ".rigid"}) {
    SCOPED_TRACE(suffix);
    const Csv reference = read_csv((dir / "b" / ("written" + suffix + ".csv")).string());
    // TR-BDF2 at the scene's 1e-6 steps generated and reference matrices equal up to rounding (the
    // rigid ones solved from L at run time); the step sizes its error control picks follow them
    // continuously, and the runs part by 9e-11 and 8e-15 of a column's scale (measured; 1e-8 leaves
    // room for another machine's rounding). The scene's own values part them by more than 1e-3.
    EXPECT_LT(relative_gap(read_csv((dir / "a" / ("tunable" + suffix + ".csv")).string()), reference), 1e-8);
    EXPECT_GT(relative_gap(read_csv((dir / "f" / ("tunable" + suffix + ".csv")).string()), reference), 1e-3);
  }
  const fs::path inertia = power_split_scene(dir, "inertia", false, "tunable = [\"J_r\"]", "");
  const fs::path inertia_written = power_split_scene(dir, "inertia_written", false, "", "J_r = \"9*kg*m^2\"");
  simulate(inertia, "--interpreted --param J_r=9*kg*m^2 -o " + (dir / "c").string());
  simulate(inertia_written, "--interpreted -o " + (dir / "d").string());
  simulate(inertia, "--interpreted -o " + (dir / "e").string());
  const Csv written = read_csv((dir / "d/inertia_written.csv").string());
  // The same exact numbers reach the same engine.
  EXPECT_EQ(relative_gap(read_csv((dir / "c/inertia.csv").string()), written), 0);
  EXPECT_GT(relative_gap(read_csv((dir / "e/inertia.csv").string()), written), 1e-3);  // the model's 7 kg m^2
}


// The ZF 6HP26 launch (rigid: engine, converter, vehicle, shift and lock-up) as `name` in `dir`, with
// `scene_lines` after its speed_unit line and `parameters` in a [parameters] table.
fs::path launch_scene(const fs::path& dir, const std::string& name, const std::string& scene_lines,
                      const std::string& parameters) {
  return shipped_scene(dir, "zf6hp26_launch", name,
                       {"../zf6hp26.toml", "zf6hp26_launch_D_release.csv", "zf6hp26_launch_C_apply.csv", "zf6hp26_launch_lockup.csv"},
                       {{"speed_unit = \"rpm\"", "speed_unit = \"rpm\"\n" + scene_lines},
                        {"[engine]\n", "[parameters]\n" + parameters + "\n\n[engine]\n"}});
}

// Tunables with an engine and a converter: a clutch's capacity and the output inertia (which makes
// the rigid model an implicit form over the engine's, converter's and drag's torques), compiled, as
// the values written.
TEST(SimulateCommand, ParamWithAnEngineAndAConverter) {
  const fs::path dir = temp_dir("param_launch");
  const fs::path tunable = launch_scene(dir, "tunable", "tunable = [\"J_out\", \"Tcap_C\"]", "");
  const fs::path values = launch_scene(dir, "written", "", "J_out = \"0.05*kg*m^2\"\nTcap_C = \"300*N*m\"");
  simulate(tunable, "--param J_out=0.05*kg*m^2 --param Tcap_C=300*N*m -o " + (dir / "a").string());
  simulate(values, "--interpreted -o " + (dir / "b").string());
  simulate(tunable, "--interpreted -o " + (dir / "c").string());  // the model's 0.035 kg m^2 and 900 N m
  const Csv reference = read_csv((dir / "b/written.csv").string());
  // dopri5 at the scene's 1e-9 on matrices solved from L at run time against the reference's exact
  // ones: the step sequences part, and the runs with them by the method's global error, 3.3e-7 of a
  // speed's scale (measured, for this run and for the shipped one alike against a run at 1e-12; 1e-5
  // leaves 30 times that).
  // The zero slip of a stuck element is rounding (2e-11 rpm), which the column's scale leaves out.
  const Csv compiled = read_csv((dir / "a/tunable.csv").string());
  for (std::size_t col = 1; col < reference.header.size(); ++col) {
    if (reference.header[col].rfind("slip_A", 0) == 0) continue;
    EXPECT_LT(column_error(compiled.rows, reference.rows, col), 1e-5) << reference.header[col];
  }
  EXPECT_GT(relative_gap(read_csv((dir / "c/tunable.csv").string()), reference), 1e-3);
}


// Tunable radii with a limited speed controller that measures a body the rigid model does not keep:
// the law reads the radii through that body's row of Q1 (generated torque_limit_laws read them from
// Params), compiled as the values written, both models stepped exactly.
TEST(SimulateCommand, ParamWithTunableRadiiAndALimitedController) {
  const fs::path dir = temp_dir("param_radii");
  auto scene = [&](const std::string& name, const std::string& tunable, const std::string& parameters) {
    return shipped_scene(
        dir, "lumped_planets", name, {"../lumped_planets.toml"},
        {{"compare_rigid = true", "compare_rigid = true\n" + tunable},
         {"[simulation]", "[loads]\nr = { constant = \"5*N*m\", linear = \"0.2*N*m*s\" }\n\n[controllers]\nhold = { body = "
                          "\"s\", speed_of = \"s\", set_point = { step = \"300*rpm\", before = \"0*rpm\", at = \"0.5*s\" }, "
                          "kp = \"2*N*m*s\", ki = \"10*N*m\", torque_max = \"40*N*m\" }\n\n[parameters]\n" +
                              parameters + "\n\n[simulation]"}});
  };
  const fs::path tunable = scene("tunable", "tunable = [\"r_s\", \"r_p\", \"J_r\"]", "");
  const fs::path written = scene("written", "", "r_s = \"9*cm\"\nr_p = \"5*cm\"\nJ_r = \"0.7*kg*m^2\"");
  simulate(tunable, "--param r_s=9*cm --param r_p=5*cm --param J_r=0.7*kg*m^2 -o " + (dir / "a").string());
  simulate(written, "--interpreted -o " + (dir / "b").string());
  for (const std::string suffix : {"", ".rigid"}) {
    SCOPED_TRACE(suffix);
    // Exact steps of matrices equal up to rounding (the rigid one solved from L at run time), and the
    // controller's limit events located on them: 6e-14 of a column's scale (measured).
    EXPECT_LT(relative_gap(read_csv((dir / "a" / ("tunable" + suffix + ".csv")).string()),
                           read_csv((dir / "b" / ("written" + suffix + ".csv")).string())),
              1e-10);
  }
}

// Tunables in a slip-controlled shift (the shipped closed-loop upshift): the off-going brake's
// capacity and the output inertia, whose values move the torque phase and the inertia phase the
// controller holds B1's slip through, compiled and interpreted, as the values written.
TEST(SimulateCommand, ParamWithSlipControl) {
  const fs::path dir = temp_dir("param_slip");
  auto scene = [&](const std::string& name, const std::string& tunable, const std::string& parameters) {
    return shipped_scene(dir, "simpson_1_2_closed_loop", name, {"../simpson_3speed.toml"},
                         {{"outputs = [", tunable + "\noutputs = ["}, {"J_o = \"1.5*kg*m^2\"", parameters}});
  };
  const fs::path tunable = scene("tunable", "tunable = [\"Tcap_B2\", \"J_o\"]", "J_o = \"1.5*kg*m^2\"");
  const fs::path written = scene("written", "", "J_o = \"1.2*kg*m^2\"\nTcap_B2 = \"700*N*m\"");
  const std::string values = "--param Tcap_B2=700*N*m --param J_o=1.2*kg*m^2 -o ";
  simulate(tunable, values + (dir / "a").string());
  simulate(tunable, "--interpreted " + values + (dir / "b").string());
  simulate(written, "--interpreted -o " + (dir / "c").string());
  simulate(tunable, "--interpreted -o " + (dir / "d").string());  // the scene's 800 N m and 1.5 kg m^2
  const Csv reference = read_csv((dir / "c/written.csv").string());
  // Interpreted with the option, the same numbers reach the same engine.
  EXPECT_EQ(relative_gap(read_csv((dir / "b/tunable.csv").string()), reference), 0);
  // Compiled, the generated matrices equal the reference model's up to rounding, and dopri5 locates
  // each event on its own trajectory: both gaps measure 0 here, bounds that leave room for another
  // machine's rounding (the compiled closed-loop shift's, SlipControl.ClosedLoopUpshiftRunsCompiledAsInterpreted).
  EXPECT_LT(relative_gap(read_csv((dir / "a/tunable.csv").string()), reference), 1e-9);
  const auto a = event_rows(dir / "a/tunable.events.csv"), c = event_rows(dir / "c/written.events.csv");
  ASSERT_EQ(a.size(), c.size());
  ASSERT_GE(a.size(), 8u);  // B2's release, the controller's start and hand-over, B1's lock-up, the cut's end
  for (std::size_t i = 0; i < a.size(); ++i) {
    EXPECT_EQ(a[i].second, c[i].second) << i;
    EXPECT_NEAR(a[i].first, c[i].first, 1e-9) << i;
  }
  // The scene's own values move the shift by far more than rounding.
  EXPECT_GT(relative_gap(read_csv((dir / "d/tunable.csv").string()), reference), 1e-3);
}

// A start in a gear with tunable capacities (the shipped 6HP26 upshift, started stuck in 1st): the
// off-going D's and on-coming C's capacities move the shift, compiled and interpreted, as the values
// written; a value below the torque 1st gear holds D with at t = 0 is refused by pogear and by the
// simulator run by itself.
TEST(StartInGear, ParamMovesTheCapacities) {
  const fs::path dir = temp_dir("param_in_gear");
  auto scene = [&](const std::string& name, const std::string& tunable, const std::string& parameters) {
    return shipped_scene(dir, "zf6hp26_1_2_upshift", name,
                         {"../zf6hp26.toml", "zf6hp26_D_release.csv", "zf6hp26_C_apply.csv"},
                         {{"compare_rigid = true", "compare_rigid = true\n" + tunable},
                          {"[parameters]\n", "[parameters]\n" + parameters + "\n"}});
  };
  const fs::path tunable = scene("tunable", "tunable = [\"Tcap_D\", \"Tcap_C\"]", "");
  const fs::path written = scene("written", "", "Tcap_D = \"1200*N*m\"\nTcap_C = \"700*N*m\"");
  const std::string values = "--param Tcap_D=1200*N*m --param Tcap_C=700*N*m -o ";
  const Command first = simulate(tunable, values + (dir / "a").string());
  simulate(tunable, "--interpreted " + values + (dir / "b").string());
  simulate(written, "--interpreted -o " + (dir / "c").string());
  simulate(tunable, "--interpreted -o " + (dir / "d").string());  // the model's 1500 N m and 900 N m
  for (const std::string suffix : {"", ".rigid"}) {
    SCOPED_TRACE(suffix);
    const Csv reference = read_csv((dir / "c" / ("written" + suffix + ".csv")).string());
    // The same exact numbers reach the same engine.
    EXPECT_EQ(relative_gap(read_csv((dir / "b" / ("tunable" + suffix + ".csv")).string()), reference), 0);
    // Exact steps of the generated matrices against the reference model's, equal up to rounding:
    // 0 and 1.4e-16 of a column's scale (measured), the events at the same times; 1e-9 is the compiled
    // shift's bound. A stays stuck throughout: its slip is rounding (the zero-slip rule), which a
    // column's scale leaves out.
    const Csv compiled = read_csv((dir / "a" / ("tunable" + suffix + ".csv")).string());
    for (std::size_t col = 1; col < reference.header.size(); ++col) {
      if (reference.header[col].rfind("slip_A", 0) == 0) continue;
      EXPECT_LT(column_error(compiled.rows, reference.rows, col), 1e-9) << reference.header[col];
    }
    EXPECT_GT(relative_gap(read_csv((dir / "d" / ("tunable" + suffix + ".csv")).string()), reference), 1e-3);
  }
  const Command refused = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + tunable.string() +
                                      " --param Tcap_D=400*N*m -o " + (dir / "e").string());
  EXPECT_EQ(refused.status, 2);
  EXPECT_NE(refused.err.find("tunable.toml: error: --param: starting in gear '1', D carries -511.193 N m at t = 0, "
                             "beyond its static capacity of 400 N m (400 N m x static ratio 1 x command 1); raise its "
                             "capacity or its command, or start with smaller torques"),
            std::string::npos)
      << refused.err;
  EXPECT_FALSE(fs::exists(dir / "e" / "tunable.csv"));
  // Just below the torque (511.19326144216495 N m elastic, 511.1932614421659 N m rigid, each exact and
  // rounded once): refused, the two numbers printed with the digits that tell them apart.
  const Command close = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + tunable.string() +
                                    " --param Tcap_D=511.1932614421655*N*m -o " + (dir / "g").string());
  EXPECT_EQ(close.status, 2);
  const auto number_after = [&](const std::string& text, const std::string& before) {
    const auto at = text.find(before);
    if (at == std::string::npos) return std::string("none");
    const auto from = at + before.size();
    return text.substr(from, text.find(' ', from) - from);
  };
  const std::string carried = number_after(close.err, "D carries -"), holds = number_after(close.err, "static capacity of ");
  EXPECT_NE(carried, "none") << close.err;
  EXPECT_NE(carried, holds) << close.err;
  EXPECT_GT(std::stod(carried), std::stod(holds)) << close.err;
  const std::string simulator = simulator_path(first.out);
  ASSERT_FALSE(simulator.empty()) << first.out;
  const Command alone = run_command(simulator + " --quiet --param Tcap_D=400*N*m --out " + (dir / "f").string());
  EXPECT_EQ(alone.status, 3);
  EXPECT_NE(alone.err.find("D slips at t = 0, where the start in a gear holds it: its torque exceeds its static "
                           "capacity there, 400 N m (400 N m x static ratio 1 x command 1); raise its capacity "
                           "(--param), or start with smaller torques"),
            std::string::npos)
      << alone.err;
}

}  // namespace
}  // namespace pogear::test
