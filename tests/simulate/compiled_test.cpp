// The compiled path against independent references: the interpreted path (numeric L, A, B of
// the derivation), and one matrix exponential over the whole horizon built from the numbers
// that `pogear derive --format json` reports. Also: generated/ is what the generator writes.
#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>

#include <unsupported/Eigen/MatrixFunctions>

#include "build_config/build_config.hpp"
#include "sim_support.hpp"
#include "run/simulator_cache.hpp"

namespace pogear::test {
namespace {

struct PaperScene {
  std::string name;
  std::string simulator;  // the CMake-built generated/ simulator
};

class PaperScenes : public ::testing::TestWithParam<PaperScene> {};

TEST_P(PaperScenes, CompiledAgreesWithInterpretedTo1em12) {
  const auto& p = GetParam();
  const auto dir = temp_dir("compiled_" + p.name);
  const Command c = run_command(p.simulator + " --out " + dir.string() + " --quiet");
  ASSERT_EQ(c.status, 0) << c.err;
  const SpecializedScene model = scene_model(scene_text(p.name));
  for (const SpecializedSystem* sys : {&model.main, &*model.rigid}) {
    const Csv csv = read_csv((dir / (p.name + (sys->kind == SystemKind::rigid ? ".rigid" : "") + ".csv")).string());
    const std::vector<std::vector<double>> interpreted = interpreted_rows(model, *sys);
    ASSERT_EQ(csv.rows.size(), interpreted.size());
    for (std::size_t col = 1; col < csv.header.size(); ++col) {
      // Both step with exp(M h) of the same M, computed once from folded symbolic expressions and
      // once from L^-1 A in doubles: entries differ by rounding (~1e-16), which 2000 contracting
      // steps keep far below 1e-12 of each column's scale.
      EXPECT_LT(column_error(csv.rows, interpreted, col), 1e-12) << sys->kind << " " << csv.header[col];
    }
  }
}

TEST_P(PaperScenes, GeneratedSourcesHaveNotDrifted) {
  const auto& p = GetParam();
  const auto dir = temp_dir("drift_" + p.name);
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " generate " +
                                source_path("models/scenes/" + p.name + ".toml") + " --solvers all -o " + dir.string());
  ASSERT_EQ(c.status, 0) << c.err;
  for (const std::string& file : {p.name + ".hpp", p.name + "_main.cpp"})
    EXPECT_EQ(read_text((dir / file).string()), read_text(source_path("generated/" + file)))
        << "generated/" << file << " is stale: run build/pogear generate models/scenes/" << p.name
        << ".toml --solvers all -o generated";
}

INSTANTIATE_TEST_SUITE_P(Paper, PaperScenes,
                         ::testing::Values(PaperScene{"paper_one_stage", POGEAR_SIM_ONE_STAGE},
                                           PaperScene{"paper_two_stage", POGEAR_SIM_TWO_STAGE}),
                         [](const auto& info) { return info.param.name; });

// A cached simulator must never outlive a change to anything compiled into it: an edit of one
// runtime header (here a copy of runtime/, so the real one stays untouched) gives a new key.
TEST(SimulatorCache, KeyFollowsSourcesAndRuntimeHeaders) {
  namespace fs = std::filesystem;
  const GeneratedSources sources = generate_sources(scene_model(scene_text("paper_one_stage")));
  const fs::path runtime = temp_dir("cache_key_runtime");
  fs::copy(source_path("runtime"), runtime, fs::copy_options::recursive | fs::copy_options::overwrite_existing);
  const std::uint64_t key = simulator_cache_key(sources, runtime.string());
  EXPECT_EQ(simulator_cache_key(sources, runtime.string()), key);

  GeneratedSources edited = sources;
  edited.header += "\n";
  EXPECT_NE(simulator_cache_key(edited, runtime.string()), key);

  { std::ofstream(runtime / "pogear" / "exact.hpp", std::ios::app) << "// edited\n"; }
  EXPECT_NE(simulator_cache_key(sources, runtime.string()), key);
}

// Eigen allocates differently with wider vector alignment (-mavx) or under AddressSanitizer, and
// libpogear_runtime hands matrices across; a program compiled otherwise than the library must fail
// to link, naming the mismatch, instead of freeing memory with the wrong allocator (api.hpp). The
// same program with the library's own flags links and runs: the control that the failure is the tag.
TEST(RuntimeLibrary, ProgramWithOtherEigenAlignmentFailsToLink) {
  const auto dir = temp_dir("runtime_abi");
  write_text(dir / "main.cpp",
             "#include <pogear/run_support.hpp>\n"
             "int main() { return pogear::rt::rk4_step_limit(-Eigen::MatrixXd::Identity(2, 2)) > 0 ? 0 : 1; }\n");
  auto compile = [&](const std::string& extra) {
    std::string cmd = std::string(build_config::cxx_compiler);
    for (const char* flag : build_config::simulator_flags) cmd += std::string(" ") + flag;
    cmd += extra + " -I" + std::string(build_config::eigen_include) + " -I" + build_config::runtime_include +
           " main.cpp " + build_config::runtime_library + " -o main";
    return run_command(cmd, dir);
  };
  const Command same = compile("");
  ASSERT_EQ(same.status, 0) << same.err;
  EXPECT_EQ(run_command("./main", dir).status, 0);
  const Command wider = compile(" -mavx");
  EXPECT_NE(wider.status, 0);
  EXPECT_NE(wider.err.find("pogear::rt::eigen_align32"), std::string::npos) << wider.err;
}

// Done-when of the simulate issue: `pogear simulate --solver exact` end to end, against
// x(T) = exp(M T) x0 + (integral of exp(M s) ds) N u from the derive report's numbers.
class SimulateCommand : public ::testing::TestWithParam<std::string> {};

TEST_P(SimulateCommand, FinalStateMatchesOneMatrixExponentialOfTheDerivedNumbers) {
  const std::string name = GetParam();
  const auto dir = temp_dir("simulate_" + name);
  ::setenv("POGEAR_CACHE_DIR", (std::string(POGEAR_BINARY_DIR) + "/simulator-cache").c_str(), 1);
  const Command sim = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " +
                                  source_path("models/scenes/" + name + ".toml") + " -o " + dir.string() +
                                  " --solver exact");
  ASSERT_EQ(sim.status, 0) << sim.out << sim.err;
  for (const std::string& f : {name + ".csv", name + ".rigid.csv", name + ".velocities.svg", name + ".forces.svg"})
    EXPECT_TRUE(std::filesystem::exists(dir / f)) << f;

  const Command derive = run_command(std::string(POGEAR_EXECUTABLE) + " derive " +
                                     source_path("models/" + name + ".toml") + " --format json");
  ASSERT_EQ(derive.status, 0) << derive.err;
  const Json j = parse_json(derive.out)["numeric"];
  const std::size_t n = j["J"].size(), m = j["K"].size();
  Eigen::MatrixXd L = Eigen::MatrixXd::Zero(n + m, n + m), A = Eigen::MatrixXd::Zero(n + m, n + m);
  Eigen::MatrixXd R(m, n), BK = Eigen::MatrixXd::Zero(m, m), BJ = Eigen::MatrixXd::Zero(n, n);
  for (std::size_t i = 0; i < m; ++i)
    for (std::size_t k = 0; k < n; ++k) R(i, k) = j["R"][i][k].num;
  for (std::size_t k = 0; k < n; ++k) L(k, k) = j["J"][k].num, BJ(k, k) = j["b"][k].num;
  for (std::size_t i = 0; i < m; ++i) L(n + i, n + i) = 1 / j["K"][i].num, BK(i, i) = j["b_K"][i].num;
  // Eq. (3).
  A.topLeftCorner(n, n) = -BJ - R.transpose() * BK * R;
  A.topRightCorner(n, m) = -R.transpose();
  A.bottomLeftCorner(m, n) = R;
  const Eigen::MatrixXd M = L.inverse() * A;
  // The paper scenes drive their first body (tau_c, resp. tau_s) with 100 N m from rest.
  Eigen::VectorXd Bu = Eigen::VectorXd::Zero(n + m);
  Bu(0) = 100.0 / L(0, 0);
  const double T = name == "paper_one_stage" ? 2.0 : 1.0;
  Eigen::MatrixXd aug = Eigen::MatrixXd::Zero(n + m + 1, n + m + 1);
  aug.topLeftCorner(n + m, n + m) = M * T;
  aug.topRightCorner(n + m, 1) = Bu * T;
  const Eigen::VectorXd xT = aug.exp().topRightCorner(n + m, 1);  // x0 = 0

  const Csv csv = read_csv((dir / (name + ".csv")).string());
  ASSERT_FALSE(csv.rows.empty());
  const auto& last = csv.rows.back();
  ASSERT_DOUBLE_EQ(last[0], T);
  // One exponential over T against 1000-2000 exponential steps: both exact, so the difference
  // is rounding accumulated over the steps, ~1e-13 relative; 1e-9 is the issue's bound.
  for (std::size_t k = 0; k < n + m; ++k)
    EXPECT_LT(std::abs(last[k + 1] - xT(k)), 1e-9 * xT.cwiseAbs().maxCoeff()) << csv.header[k + 1];
}

INSTANTIATE_TEST_SUITE_P(Paper, SimulateCommand, ::testing::Values("paper_one_stage", "paper_two_stage"));

// Files of an earlier run of the scene that this run does not write (events of brakes since taken
// out, a shift figure) are listed, and left alone: pogear cannot tell them from a user's file.
TEST(SimulateOutputs, FilesOfAnEarlierRunAreListedNotRemoved) {
  const auto dir = temp_dir("stale_outputs");
  const auto an_hour_ago = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  for (const std::string f : {"paper_one_stage.csv", "paper_one_stage.events.csv", "paper_one_stage.shift.svg",
                              "paper_one_stage.notes.txt"}) {
    write_text((dir / f).string(), "from an earlier run\n");
    std::filesystem::last_write_time(dir / f, an_hour_ago);
  }
  const Command sim = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " +
                                  source_path("models/scenes/paper_one_stage.toml") + " -o " + dir.string() +
                                  " --interpreted");
  ASSERT_EQ(sim.status, 0) << sim.out << sim.err;
  for (const std::string f : {"paper_one_stage.events.csv", "paper_one_stage.shift.svg"}) {
    EXPECT_NE(sim.out.find("note: " + (dir / f).string() + " is from an earlier run; this run did not write it\n"),
              std::string::npos) << sim.out;
    EXPECT_EQ(read_text((dir / f).string()), "from an earlier run\n");
  }
  // Written by this run, or no name of pogear's: not listed.
  EXPECT_EQ(sim.out.find("paper_one_stage.csv is from"), std::string::npos) << sim.out;
  EXPECT_EQ(sim.out.find("notes.txt"), std::string::npos) << sim.out;
  EXPECT_NE(read_text((dir / "paper_one_stage.csv").string()), "from an earlier run\n");
}

// A reviewer traces each number of the generated code to a parameter: the header lists every
// parameter in SI with its unit, its text and where it was written (the model, or the scene that
// overrides it), and says which pogear made it from which texts. It needs Eigen alone.
TEST(GeneratedHeader, ListsEveryParameterWithItsOriginAndTheProvenance) {
  const std::string scene = with_parameters(scene_text("paper_one_stage"), "J_c = \"0.2*kg*meters^2\"");
  const SpecializedScene m = scene_model(scene);
  const std::string h = generate_sources(m).header;
  const auto npos = std::string::npos;
  EXPECT_NE(h.find("namespace parameters {\ninline constexpr double r_s1 = 0.1;  // m, \"10*cm\" (paper_one_stage.toml:"),
            npos) << h.substr(0, 3000);
  EXPECT_NE(h.find("inline constexpr double r_c = 0.14800000000000002;  // m, \"14.8*cm\" (paper_one_stage.toml:"), npos);
  EXPECT_NE(h.find("inline constexpr double K_pr = 1000000.0;  // kg/s^2, \"K_ps\" (paper_one_stage.toml:"), npos);
  // The scene's override, where the scene writes it.
  const long line = std::count(scene.begin(), scene.begin() + static_cast<long>(scene.find("J_c = ")), '\n') + 1;
  EXPECT_NE(h.find(fmt::format("inline constexpr double J_c = 0.2;  // kg*m^2, \"0.2*kg*meters^2\" (variant.toml:{})", line)),
            npos);
  EXPECT_NE(h.find(fmt::format("generated by pogear {} from", build_config::version)), npos);
  EXPECT_NE(h.find(fmt::format("pogear_version = \"{}\";", build_config::version)), npos);
  ASSERT_EQ(m.derivation.topology.digest.size(), 16u);
  EXPECT_NE(h.find("model_digest = \"" + m.derivation.topology.digest + "\";"), npos);
  ASSERT_EQ(m.scene.digest.size(), 16u);
  EXPECT_NE(h.find("scene_digest = \"" + m.scene.digest + "\";"), npos);
  EXPECT_EQ(h.find("#include <pogear/"), npos) << "the header needs Eigen alone";
}

}  // namespace
}  // namespace pogear::test
