// A model too large for fixed-size Eigen types (issue 10, item 16): scripts/make_chain.sh 26 has
// 79 bodies and 52 meshes, 131 states, and did not compile (OBJECT_ALLOCATED_ON_STACK_IS_TOO_BIG);
// `pogear simulate` compiles its simulator and runs it.
#include "codegen/codegen.hpp"
#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

TEST(LargeModels, ChainOf26StagesCompilesAndAgreesWithTheInterpretedPath) {
  const fs::path dir = temp_dir("chain_26");
  const std::string scene = chain_scene_text(26, dir);
  ASSERT_FALSE(HasFailure());
  // A short horizon: the point is the size, not the run.
  write_text(dir / "scene.toml", with_line(scene, "horizon = \"1*s\"", "horizon = \"0.05*s\""));

  const SpecializedScene model = specialize(parse_scene((dir / "scene.toml").string()));
  ASSERT_EQ(model.main.states.size(), 131u);
  const GeneratedSources g = generate_sources(model);
  EXPECT_NE(g.header.find("using StateMatrix = Eigen::MatrixXd;"), std::string::npos);

  ::setenv("POGEAR_CACHE_DIR", (std::string(POGEAR_BINARY_DIR) + "/simulator-cache").c_str(), 1);
  const Command sim = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() +
                                  " -o " + (dir / "out").string());
  ASSERT_EQ(sim.status, 0) << sim.out << sim.err;

  // Both step with exp(M h) of the same M (from the folded expressions, resp. L^-1 A in doubles);
  // entries differ by rounding, amplified by the conditioning of a 131-state exponential over 50
  // steps: well below 1e-8 of each column's scale.
  expect_csv_matches_interpreted(dir / "out" / "chain_26.csv", model, model.main, 1e-8);
  expect_csv_matches_interpreted(dir / "out" / "chain_26.rigid.csv", model, *model.rigid, 1e-8);
}

}  // namespace
}  // namespace pogear::test
