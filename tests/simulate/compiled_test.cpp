// The compiled path against the interpreted path (numeric L, A, B of the derivation): the paper
// scenes' simulators built by CMake. Also the simulator cache's key, the runtime library's link
// check, and the generated header's provenance. `pogear generate` and `pogear simulate` against
// generated/ and one matrix exponential: tests/commands/compiled_test.cpp.
#include <algorithm>
#include <filesystem>
#include <fstream>

#include "build_config/build_config.hpp"
#include "sim_support.hpp"
#include "run/simulator_cache.hpp"

namespace pogear::test {
namespace {

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
  // Eigen and the runtime's signals alone (the scene's signals are in the header): no other runtime header.
  const auto include = h.find("#include <pogear/");
  ASSERT_NE(include, npos);
  EXPECT_EQ(h.substr(include, 31), "#include <pogear/signals.hpp>\n\n");
  EXPECT_EQ(h.find("#include <pogear/", include + 1), npos) << "the header needs Eigen and pogear/signals.hpp alone";
  EXPECT_NE(h.find("inline std::vector<pogear::rt::Signal> Elastic_signals() {"), npos);
}

}  // namespace
}  // namespace pogear::test
