// Helpers for the error tests: a scratch working directory holding the example model and scene
// of docs/errors.md, edits of them, and the check that an error's exact text is documented.
#pragma once

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <optional>
#include <sstream>
#include <string>
#include <thread>
#include <utility>
#include <vector>

#include <gtest/gtest.h>
#include <sys/wait.h>
#include <unistd.h>

#include "codegen.hpp"

namespace pogear::test {

namespace fs = std::filesystem;

inline std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path, std::ios::binary);
  out << text;
}

inline fs::path source_path(const std::string& relative) { return fs::path(POGEAR_SOURCE_DIR) / relative; }

inline const std::string& docs() {
  static const std::string text = read_text(source_path("docs/errors.md"));
  return text;
}
inline const std::string& base_model() {
  static const std::string text = read_text(source_path("tests/errors/gear.toml"));
  return text;
}
inline const std::string& base_scene() {
  static const std::string text = read_text(source_path("tests/errors/scene.toml"));
  return text;
}

using Edits = std::vector<std::pair<std::string, std::string>>;

// `text` with each `from` (which must occur exactly once) replaced by its `to`.
inline std::string edited(std::string text, const Edits& edits) {
  for (const auto& [from, to] : edits) {
    const auto pos = text.find(from);
    if (pos == std::string::npos || text.find(from, pos + 1) != std::string::npos) {
      ADD_FAILURE() << "the edit needs exactly one '" << from << "' in the text";
      continue;
    }
    text.replace(pos, from.size(), to);
  }
  return text;
}

inline std::string current_test_name() {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  return std::string(info->test_suite_name()) + "." + info->name();
}

// The error text must be `expected` to the character, and docs/errors.md must show it verbatim
// and name the test that checks it.
inline void expect_documented(const std::string& actual, const std::string& expected) {
  EXPECT_EQ(actual, expected);
  EXPECT_NE(docs().find(expected), std::string::npos) << "docs/errors.md does not show:\n" << expected;
  EXPECT_NE(docs().find("`" + current_test_name() + "`"), std::string::npos)
      << "docs/errors.md does not name " << current_test_name();
}

struct Command {
  int status = -1;  // exit status; 128 + signal when killed
  std::string out, err;
};

// Runs a shell command in `dir`, capturing its output.
inline Command run_in(const fs::path& dir, const std::string& command) {
  const fs::path out = dir / ".stdout", err = dir / ".stderr";
  const std::string cmd = "cd '" + dir.string() + "' && { " + command + " ; } >'" + out.string() + "' 2>'" +
                          err.string() + "'";
  const int raw = std::system(cmd.c_str());
  Command c;
  c.status = WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw);
  c.out = read_text(out);
  c.err = read_text(err);
  fs::remove(out);
  fs::remove(err);
  return c;
}

// Starts `command` with sh in its own process group (exec'd, so the pid is the command's own), so
// that a test can signal it alone or with its group.
inline pid_t start(const std::string& command) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    ::execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here, so that the group exists before we signal it
  return pid;
}

// Polls `ready` every 10 ms for up to `limit` (a loaded machine may be slow to get there).
template <class F>
bool eventually(F ready, std::chrono::milliseconds limit = std::chrono::seconds(60)) {
  using namespace std::chrono_literals;
  for (auto waited = 0ms; waited < limit; waited += 10ms) {
    if (ready()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

// The parent of process `pid` from /proc/PID/stat; 0 when it is gone.
inline pid_t parent_of(pid_t pid) {
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const auto paren = stat.rfind(')');
  if (paren == std::string::npos || paren + 4 >= stat.size()) return 0;
  return static_cast<pid_t>(std::atoi(stat.c_str() + paren + 4));  // after ") S "
}

// True once `pid` has ended (gone, or a zombie nobody has reaped yet).
inline bool ended(pid_t pid) {
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const auto paren = stat.rfind(')');
  return paren == std::string::npos || paren + 2 >= stat.size() || stat[paren + 2] == 'Z';
}

// The children of `pid`.
inline std::vector<pid_t> children_of(pid_t pid) {
  std::vector<pid_t> kids;
  for (const auto& e : fs::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") == std::string::npos && parent_of(std::stoi(name)) == pid)
      kids.push_back(std::stoi(name));
  }
  return kids;
}

// A fresh scratch directory as the working directory, with gear.toml and scene.toml in it, so
// that messages name files as a user running pogear beside them sees them.
class ErrorTest : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("pogear_errors_" + std::to_string(::getpid()));
    fs::remove_all(dir_);
    fs::create_directories(dir_);
    previous_ = fs::current_path();
    fs::current_path(dir_);
    write_text("gear.toml", base_model());
    write_text("scene.toml", base_scene());
  }
  void TearDown() override {
    fs::current_path(previous_);
    fs::remove_all(dir_);
  }

  // The text of the InputError that deriving `text` (as gear.toml) gives; "" when none.
  static std::string model_error(const std::string& text,
                                 const std::optional<std::vector<std::string>>& keep = std::nullopt) {
    try {
      derive_topology(parse_topology_text(text, "gear.toml"), keep, SourceLocation{"gear.toml", 0, 0});
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
  }
  static std::string model_file_error(const std::string& path) {
    try {
      parse_topology(path);
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
  }
  // The text of the InputError that reading scene.toml (with `scene`) and generating its code
  // gives, with gear.toml holding `model`; "" when none.
  static std::string scene_error(const std::string& scene, const std::string& model = base_model()) {
    write_text("scene.toml", scene);
    write_text("gear.toml", model);
    try {
      generate_sources(specialize(parse_scene("scene.toml")));
    } catch (const InputError& e) {
      return e.what();
    }
    ADD_FAILURE() << "no error";
    return "";
  }
  void expect_model_error(const Edits& edits, const std::string& expected) {
    expect_documented(model_error(edited(base_model(), edits)), expected);
  }
  void expect_scene_error(const Edits& edits, const std::string& expected) {
    expect_documented(scene_error(edited(base_scene(), edits)), expected);
  }
  Command run(const std::string& command) const { return run_in(dir_, command); }
  // Runs pogear with `args` in the scratch directory; checks the exit status and that standard
  // error is exactly `expected` (plus a newline), as docs/errors.md shows it.
  void expect_pogear_error(const std::string& args, int status, const std::string& expected,
                           const std::string& prefix = "") const {
    const Command c = run(prefix + pogear() + " " + args);
    EXPECT_EQ(c.status, status) << c.err;
    expect_documented(c.err, expected + "\n");
  }
  static std::string pogear() { return std::string("'") + POGEAR_EXECUTABLE + "'"; }

  fs::path dir_, previous_;
};

// The paper's one-stage simulator (built by CMake from generated/) as ./paper_one_stage in the
// scratch directory, as a user types it.
class SimulatorTest : public ErrorTest {
 protected:
  void SetUp() override {
    ErrorTest::SetUp();
    fs::create_symlink(POGEAR_SIM_ONE_STAGE, "paper_one_stage");
  }
  // Runs it with `args`; checks the exit status and that standard error is exactly `expected`.
  void expect_simulator_error(const std::string& args, int status, const std::string& expected,
                              const std::string& prefix = "") const {
    const Command c = run(prefix + "./paper_one_stage " + args);
    EXPECT_EQ(c.status, status) << c.err;
    expect_documented(c.err, expected + "\n");
  }
};

}  // namespace pogear::test
