// Files for the tests: paths into the source tree, whole-file reads and writes, and scratch
// directories of their own (ctest runs tests in parallel processes).
#pragma once

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <unistd.h>

namespace pogear::test {

#ifdef POGEAR_SOURCE_DIR
inline std::string source_path(const std::string& relative) { return std::string(POGEAR_SOURCE_DIR) + "/" + relative; }
#endif

// The whole file; "" when it cannot be read.
inline std::string read_text(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `text` with the first occurrence of each `from` replaced by its `to`, in order (a shipped scene
// edited for a test); a `from` that is not there fails the test.
inline std::string with_edits(std::string text, const std::vector<std::pair<std::string, std::string>>& edits) {
  for (const auto& [from, to] : edits) {
    const auto at = text.find(from);
    if (at == std::string::npos) {
      ADD_FAILURE() << "no `" << from << "` to replace";
      continue;
    }
    text.replace(at, from.size(), to);
  }
  return text;
}

inline void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream(path, std::ios::binary) << text;
}

// A fresh empty directory `pogear_TAG_PID` in the temp directory.
inline std::filesystem::path temp_dir(const std::string& tag) {
  const auto dir = std::filesystem::temp_directory_path() / ("pogear_" + tag + "_" + std::to_string(::getpid()));
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// A fresh empty directory `pogear_TAG_SUITE_TEST` named after the running test.
inline std::filesystem::path test_dir(const std::string& tag) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto dir = std::filesystem::temp_directory_path() /
                   ("pogear_" + tag + "_" + info->test_suite_name() + "_" + info->name());
  std::filesystem::remove_all(dir);
  std::filesystem::create_directories(dir);
  return dir;
}

// The names in `dir`, sorted: a temporary file left behind shows up here.
inline std::vector<std::string> names_in(const std::filesystem::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : std::filesystem::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

}  // namespace pogear::test
