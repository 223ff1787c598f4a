// Helpers for the simulate tests (here and their end-to-end half in tests/commands/): scene variants,
// in-memory runs, external commands, the paper scenes' simulators, a hybrid run's files.
#pragma once

#include <filesystem>
#include <fstream>
#include <regex>
#include <sstream>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../derive/test_support.hpp"
#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/gaps.hpp"
#include "../support/json.hpp"
#include "run/interpreted_run.hpp"
#include "run/simulate_scene.hpp"
#include "vibrate/diagnostics.hpp"

namespace pogear::test {

inline std::string scene_text(const std::string& name) { return read_text(source_path("models/scenes/" + name + ".toml")); }

// A scene from text, as if it stood in models/scenes/ (its model path is relative to that).
inline SpecializedScene scene_model(const std::string& text) {
  return specialize(parse_scene_text(text, source_path("models/scenes/variant.toml")));
}

inline std::string with_effects(std::string text, const std::string& effects) {
  return std::regex_replace(text, std::regex("effects = \\[[^\\]]*\\]"), "effects = [" + effects + "]");
}

inline std::string with_line(std::string text, const std::string& from, const std::string& to) {
  const auto pos = text.find(from);
  EXPECT_NE(pos, std::string::npos) << from;
  if (pos != std::string::npos) text.replace(pos, from.size(), to);
  return text;
}

// `text` with each of the lines `from` replaced by its `to`, in order.
inline std::string with_lines(std::string text, const std::vector<std::pair<std::string, std::string>>& edits) {
  for (const auto& [from, to] : edits) text = with_line(std::move(text), from, to);
  return text;
}

// Appends a [parameters] table (the paper scenes have none).
inline std::string with_parameters(const std::string& text, const std::string& lines) {
  return text + "\n[parameters]\n" + lines + "\n";
}

// The gear's matrices at the derivation's values, for power balances: stored energy
// omega^T J omega / 2 + F^T K^-1 F / 2, losses omega^T B_J omega + (R omega)^T B_K (R omega).
struct GearMatrices {
  Eigen::MatrixXd J, BJ, K, BK, R, Q1;
};
inline GearMatrices gear_matrices(const Derivation& d) {
  const GiNaC::exmap& v = d.values;
  return {evaluate_matrix(d.elastic.J, v), evaluate_matrix(d.elastic.B_J, v), evaluate_matrix(d.elastic.K, v),
          evaluate_matrix(d.elastic.B_K, v), evaluate_matrix(d.elastic.R, v), evaluate_matrix(d.rigid.Q1, v)};
}

inline rt::SceneRun run_settings(const SpecializedScene& m, rt::Solver solver = rt::Solver::exact) {
  rt::SceneRun r = scene_run(m.scene);
  r.solver = solver;
  return r;
}

// An interpreted run of `sys` with the scene's solver as CSV rows (t, then the outputs), to compare
// with a simulator's CSV.
inline std::vector<std::vector<double>> interpreted_rows(const SpecializedScene& model, const SpecializedSystem& sys) {
  const Trajectory tr = interpret_trajectory(model, sys, run_settings(model, model.scene.solver));
  EXPECT_TRUE(tr.status.ok) << tr.status.message;
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; i < tr.t.size(); ++i) {
    std::vector<double> row{tr.t[i]};
    for (Eigen::Index j = 0; j < tr.y[i].size(); ++j) row.push_back(tr.y[i](j));
    rows.push_back(row);
  }
  return rows;
}

// A simulator's CSV of `sys` against the interpreted run of the same model: each output column's
// largest gap relative to its scale (column_error) below `tolerance`.
inline void expect_csv_matches_interpreted(const std::filesystem::path& csv_file, const SpecializedScene& model,
                                           const SpecializedSystem& sys, double tolerance) {
  const Csv csv = read_csv(csv_file.string());
  const std::vector<std::vector<double>> interpreted = interpreted_rows(model, sys);
  ASSERT_EQ(csv.rows.size(), interpreted.size()) << csv_file;
  for (std::size_t col = 1; col < csv.header.size(); ++col)
    EXPECT_LT(column_error(csv.rows, interpreted, col), tolerance) << sys.kind << " " << csv.header[col];
}

// scripts/make_chain.sh K: writes the model to DIR/chain.toml and returns the text of its own scene
// (every effect, compare_rigid).
inline std::string chain_scene_text(int k, const std::filesystem::path& dir) {
  const std::string script = source_path("scripts/make_chain.sh");
  const Command model = run_command(script + " " + std::to_string(k));
  EXPECT_EQ(model.status, 0) << model.err;
  write_text(dir / "chain.toml", model.out);
  const Command scene = run_command(script + " " + std::to_string(k) + " --scene chain.toml");
  EXPECT_EQ(scene.status, 0) << scene.err;
  return scene.out;
}

// The paper scene the bad-scene tests break.
inline const std::string base = scene_text("paper_one_stage");

// A paper scene and its simulator, built by CMake from generated/.
struct PaperScene {
  std::string name;
  std::string simulator;  // the CMake-built generated/ simulator
};

class PaperScenes : public ::testing::TestWithParam<PaperScene> {};

// A hybrid run's CSV and the rows of its events file (t, element, from, to), as `pogear simulate`
// writes them to DIR/<scene><suffix>.
struct HybridRun {
  Csv csv;
  std::vector<std::tuple<double, std::string, std::string, std::string>> events;
};
inline HybridRun read_hybrid_run(const std::filesystem::path& dir, const std::string& name) {
  HybridRun out;
  out.csv = read_csv((dir / (name + ".csv")).string());
  std::ifstream events(dir / (name + ".events.csv"));
  std::string line;
  std::getline(events, line);  // header
  while (std::getline(events, line)) {
    std::stringstream fields(line);
    std::string t, element, from, to;
    std::getline(fields, t, ',');
    std::getline(fields, element, ',');
    std::getline(fields, from, ',');
    std::getline(fields, to, ',');
    out.events.emplace_back(std::stod(t), element, from, to);
  }
  return out;
}

}  // namespace pogear::test
