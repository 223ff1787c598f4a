// Running another program (the compiler, a simulator, gnuplot) with an argument vector, never
// through a shell: no argument is ever parsed as shell syntax, whatever characters it holds.
#pragma once

#include <optional>
#include <string>
#include <vector>

namespace pogear {

struct ChildRequest {
  std::vector<std::string> argv;       // argv[0]: an absolute path, or a name looked up in PATH
  std::optional<std::string> input;    // standard input; none: /dev/null
  bool capture_stdout = false;         // else inherited from pogear
  bool capture_stderr = false;         // else inherited
  bool stderr_to_stdout = false;       // one log of both, in order (with capture_stdout)
};

struct ChildResult {
  int exit_code = 0;    // when the child exited
  int signal = 0;       // when it died of a signal (0 otherwise)
  std::string out, err; // what was captured
  bool ok() const { return signal == 0 && exit_code == 0; }
  // "exit status N" or "signal N (Name)", for messages.
  std::string describe() const;
};

// Runs the child in its own process group and waits for it. A SIGINT, SIGTERM or SIGHUP to pogear
// meanwhile is passed on to that group, and pogear dies of it once the child has ended; the child
// dies with pogear if pogear is killed outright. Throws std::runtime_error when the program cannot
// be started (not found, not executable), with a message naming it.
ChildResult run_child(const ChildRequest& request);

// The absolute path of `name` (as execvp would find it in PATH), or nullopt.
std::optional<std::string> find_program(const std::string& name);

}  // namespace pogear
