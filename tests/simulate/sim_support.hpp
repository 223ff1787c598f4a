// Helpers for the simulate tests: scene variants, in-memory runs, external commands.
#pragma once

#include <cstdlib>
#include <filesystem>
#include <regex>
#include <string>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "../derive/test_support.hpp"
#include "../support/csv.hpp"
#include "../support/json.hpp"
#include "simulation.hpp"

namespace pogear::test {

inline std::string scene_text(const std::string& name) { return read_text(source_path("models/scenes/" + name + ".toml")); }

// A scene from text, as if it stood in models/scenes/ (its model path is relative to that).
inline SimModel scene_model(const std::string& text) {
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

// Appends a [parameters] table (the paper scenes have none).
inline std::string with_parameters(const std::string& text, const std::string& lines) {
  return text + "\n[parameters]\n" + lines + "\n";
}

inline rt::SceneRun run_settings(const SimModel& m, const std::string& solver = "exact") {
  rt::SceneRun r;
  r.name = m.scene.name;
  r.horizon = m.scene.horizon;
  r.sample = m.scene.sample;
  r.solver = solver;
  r.options.rtol = m.scene.tolerance;
  r.options.atol = m.scene.tolerance * 1e-2;
  r.options.h = m.scene.step;
  r.options.max_steps = m.scene.max_steps;
  return r;
}

struct Command {
  int status;
  std::string out, err;
};

inline std::filesystem::path temp_dir(const std::string& tag) {
  const auto dir = std::filesystem::temp_directory_path() / ("pogear_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

inline Command run_command(const std::string& cmd) {
  const auto dir = std::filesystem::temp_directory_path() / ("pogear_cmd_" + std::to_string(::getpid()));
  std::filesystem::create_directories(dir);
  const std::string out = (dir / "out").string(), err = (dir / "err").string();
  const int raw = std::system((cmd + " >" + out + " 2>" + err).c_str());
  return Command{WIFEXITED(raw) ? WEXITSTATUS(raw) : -1, read_text(out), read_text(err)};
}

// Largest |a - b| over a column, relative to the largest |b| in it.
inline double column_error(const std::vector<std::vector<double>>& a, const std::vector<std::vector<double>>& b,
                           std::size_t col) {
  double err = 0, scale = 0;
  for (std::size_t i = 0; i < std::min(a.size(), b.size()); ++i) {
    err = std::max(err, std::abs(a[i][col] - b[i][col]));
    scale = std::max(scale, std::abs(b[i][col]));
  }
  return scale > 0 ? err / scale : err;
}

// An interpreted run of `sys` as CSV rows (t, then the outputs), to compare with a simulator's CSV.
inline std::vector<std::vector<double>> interpreted_rows(const SimModel& model, const SimSystem& sys) {
  const Trajectory tr = interpret_trajectory(model, sys, run_settings(model));
  EXPECT_TRUE(tr.status.ok) << tr.status.message;
  std::vector<std::vector<double>> rows;
  for (std::size_t i = 0; i < tr.t.size(); ++i) {
    std::vector<double> row{tr.t[i]};
    for (Eigen::Index j = 0; j < tr.y[i].size(); ++j) row.push_back(tr.y[i](j));
    rows.push_back(row);
  }
  return rows;
}

}  // namespace pogear::test
