// A model too large for fixed-size Eigen types (issue 10, item 16): scripts/make_chain.sh 26 has
// 79 bodies and 52 meshes, 131 states, and did not compile (OBJECT_ALLOCATED_ON_STACK_IS_TOO_BIG).
#include <fstream>

#include "sim_support.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

TEST(LargeModels, ChainOf26StagesCompilesAndAgreesWithTheInterpretedPath) {
  const fs::path dir = temp_dir("chain_26");
  const std::string script = source_path("scripts/make_chain.sh");
  const Command model_text = run_command(script + " 26");
  ASSERT_EQ(model_text.status, 0) << model_text.err;
  std::ofstream(dir / "chain.toml") << model_text.out;
  const Command scene = run_command(script + " 26 --scene chain.toml");
  ASSERT_EQ(scene.status, 0) << scene.err;
  // A short horizon: the point is the size, not the run.
  std::string text = with_line(scene.out, "horizon = \"1*s\"", "horizon = \"0.05*s\"");
  std::ofstream(dir / "scene.toml") << text;

  const SimModel model = specialize(parse_scene((dir / "scene.toml").string()));
  ASSERT_EQ(model.main.states.size(), 131u);
  const GeneratedSources g = generate_sources(model);
  EXPECT_NE(g.header.find("using StateMatrix = Eigen::MatrixXd;"), std::string::npos);

  ::setenv("POGEAR_CACHE_DIR", (std::string(POGEAR_BINARY_DIR) + "/simulator-cache").c_str(), 1);
  const Command sim = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() +
                                  " -o " + (dir / "out").string());
  ASSERT_EQ(sim.status, 0) << sim.out << sim.err;

  for (const SimSystem* sys : {&model.main, &*model.rigid}) {
    const Csv csv = read_csv((dir / "out" / (sys->kind == "rigid" ? "chain_26.rigid.csv" : "chain_26.csv")).string());
    const std::vector<std::vector<double>> interpreted = interpreted_rows(model, *sys);
    ASSERT_EQ(csv.rows.size(), interpreted.size());
    // Both step with exp(M h) of the same M (from the folded expressions, resp. L^-1 A in
    // doubles); entries differ by rounding, amplified by the conditioning of a 131-state
    // exponential over 50 steps: well below 1e-8 of each column's scale.
    for (std::size_t col = 1; col < csv.header.size(); ++col)
      EXPECT_LT(column_error(csv.rows, interpreted, col), 1e-8) << sys->kind << " " << csv.header[col];
  }
}

}  // namespace
}  // namespace pogear::test
