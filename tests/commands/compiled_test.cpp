// `pogear generate` and `pogear simulate` on the paper scenes: generated/ is what the generator
// writes, and the final state of `simulate --solver exact` is one matrix exponential over the whole
// horizon built from the numbers that `pogear derive --format json` reports; files of an earlier
// run are listed, not removed. The compiled simulators against the interpreted path:
// tests/simulate/compiled_test.cpp (which instantiates PaperScenes, in sim_support.hpp).
#include <chrono>
#include <cmath>
#include <filesystem>

#include <unsupported/Eigen/MatrixFunctions>

#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

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
  // The outputs: the speeds, and the force each mesh transmits, spring and damper, F + b_K R omega.
  Eigen::MatrixXd C = Eigen::MatrixXd::Identity(n + m, n + m);
  C.bottomLeftCorner(m, n) = BK * R;
  const Eigen::VectorXd yT = C * xT;
  // One exponential over T against 1000-2000 exponential steps: both exact, so the difference
  // is rounding accumulated over the steps, ~1e-13 relative; 1e-9 is the issue's bound.
  for (std::size_t k = 0; k < n + m; ++k)
    EXPECT_LT(std::abs(last[k + 1] - yT(k)), 1e-9 * yT.cwiseAbs().maxCoeff()) << csv.header[k + 1];
}

INSTANTIATE_TEST_SUITE_P(Paper, SimulateCommand, ::testing::Values("paper_one_stage", "paper_two_stage"));

// Files of an earlier run of the scene that this run does not write (events of brakes since taken
// out, a shift figure and its metrics) are listed, and left alone: pogear cannot tell them from a user's file.
TEST(SimulateOutputs, FilesOfAnEarlierRunAreListedNotRemoved) {
  const auto dir = temp_dir("stale_outputs");
  const auto an_hour_ago = std::filesystem::file_time_type::clock::now() - std::chrono::hours(1);
  for (const std::string f : {"paper_one_stage.csv", "paper_one_stage.events.csv", "paper_one_stage.shift.svg",
                              "paper_one_stage.shift.json", "paper_one_stage.notes.txt"}) {
    write_text((dir / f).string(), "from an earlier run\n");
    std::filesystem::last_write_time(dir / f, an_hour_ago);
  }
  const Command sim = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " +
                                  source_path("models/scenes/paper_one_stage.toml") + " -o " + dir.string() +
                                  " --interpreted");
  ASSERT_EQ(sim.status, 0) << sim.out << sim.err;
  for (const std::string f : {"paper_one_stage.events.csv", "paper_one_stage.shift.svg", "paper_one_stage.shift.json"}) {
    EXPECT_NE(sim.out.find("note: " + (dir / f).string() + " is from an earlier run; this run did not write it\n"),
              std::string::npos) << sim.out;
    EXPECT_EQ(read_text((dir / f).string()), "from an earlier run\n");
  }
  // Written by this run, or no name of pogear's: not listed.
  EXPECT_EQ(sim.out.find("paper_one_stage.csv is from"), std::string::npos) << sim.out;
  EXPECT_EQ(sim.out.find("notes.txt"), std::string::npos) << sim.out;
  EXPECT_NE(read_text((dir / "paper_one_stage.csv").string()), "from an earlier run\n");
}

}  // namespace
}  // namespace pogear::test
