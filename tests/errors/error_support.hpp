// Helpers for the error tests (here and those that run pogear, in tests/commands/): a scratch working
// directory holding the example model and scene of docs/errors.md, edits of them, the check that an
// error's exact text is documented, and the fixtures of suites with tests in both places.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "codegen/codegen.hpp"
#include "report/model_errors.hpp"

namespace pogear::test {

namespace fs = std::filesystem;

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

// The edits, then more.
inline Edits with(Edits edits, const Edits& more) {
  edits.insert(edits.end(), more.begin(), more.end());
  return edits;
}

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
    } catch (const GeometryConflict& e) {  // the derivation's typed errors, as the command line prints them
      return input_error_of(e).what();
    } catch (const TiedVelocities& e) {
      return input_error_of(e).what();
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
    } catch (const GeometryConflict& e) {  // the derivation's typed errors, as the command line prints them
      return input_error_of(e).what();
    } catch (const TiedVelocities& e) {
      return input_error_of(e).what();
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
  Command run(const std::string& command) const { return run_command(command, dir_); }
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

// Scenes that command brakes and clutches: gear.toml with a brake on the ring and a clutch joining
// sun and carrier, and scene.toml with an [engagement] table after its last line.
class EngagementCommands : public ErrorTest {
 protected:
  static std::string shift_model() {
    return edited(base_model(), {{"[parameters]", "[[brake]]\nname = \"B1\"\nbody = \"r\"\n\n[[clutch]]\nname = \"C1\"\n"
                                                  "bodies = [\"s\", \"c\"]\n\n[parameters]"},
                                 {R"(b_sg = "b_ps")", "b_sg = \"b_ps\"\nTcap_B1 = \"50*N*m\"\nTcap_C1 = \"50*N*m\""}});
  }
  void expect_error(const std::string& engagement, const std::string& expected, const Edits& scene_edits = {}) {
    expect_documented(scene_error(edited(base_scene(), scene_edits) + "\n[engagement]\n" + engagement, shift_model()),
                      expected);
  }
};

// Scenes with loads and speed controllers: scene.toml with a [loads] or [controllers] table after
// its last line (gear.toml's bodies are c, p, s, r, g).
class LoadsAndControllers : public ErrorTest {
 protected:
  // gear.toml and a scene.toml run by dopri5 with a quadratic load on r, for the commands that refuse it.
  static void write_nonlinear_scene() {
    write_text("gear.toml", base_model());
    write_text("scene.toml", edited(base_scene(), {{R"(solver = "exact")", R"(solver = "dopri5")"}}) +
                                 "\n[loads]\nr = { quadratic = \"0.01*N*m*s^2\" }\n");
  }
  void expect_error(const std::string& tables, const std::string& expected, const Edits& scene_edits = {},
                    const std::string& model = base_model()) {
    expect_documented(scene_error(edited(base_scene(), scene_edits) + "\n" + tables, model), expected);
  }
};

// The regression tests of the adversarial review (hardening_test.cpp).
class Hardening : public ErrorTest {
 protected:
  // `scene.toml` with `edits`, then its model and scene as pogear reads them.
  SpecializedScene scene_model(const Edits& edits) {
    write_text("scene.toml", edited(base_scene(), edits));
    return specialize(parse_scene("scene.toml"));
  }
};

}  // namespace pogear::test
