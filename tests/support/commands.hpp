// Running commands for the tests (pogear, simulators, scripts): exit status and captured output,
// with a shell or without one, and processes started to be signalled and watched.
#pragma once

#include <fcntl.h>
#include <sys/wait.h>
#include <unistd.h>

#include <chrono>
#include <cstdlib>
#include <filesystem>
#include <string>
#include <thread>
#include <vector>

#include "files.hpp"

namespace pogear::test {

struct Command {
  int status = -1;  // exit status; 128 + signal when killed
  std::string out, err;
};

inline int exit_status(int raw) { return WIFEXITED(raw) ? WEXITSTATUS(raw) : 128 + WTERMSIG(raw); }

// Runs a shell command in `dir` (by default the current directory), capturing its output.
inline Command run_command(const std::string& command, const std::filesystem::path& dir = {}) {
  const auto files = temp_dir("cmd");
  const auto out = files / "out", err = files / "err";
  const std::string in_dir = dir.empty() ? "" : "cd '" + dir.string() + "' && ";
  const std::string cmd = in_dir + "{ " + command + " ; } >'" + out.string() + "' 2>'" + err.string() + "'";
  const int raw = std::system(cmd.c_str());
  Command c{exit_status(raw), read_text(out), read_text(err)};
  std::filesystem::remove_all(files);
  return c;
}

// Runs `args` (the program first) in `dir` without a shell, for arguments that hold newlines and
// quotes; status and output.
inline Command run_argv(const std::filesystem::path& dir, const std::vector<std::string>& args) {
  const auto files = temp_dir("argv");
  const auto out = files / "out", err = files / "err";
  const pid_t pid = ::fork();
  if (pid == 0) {
    if (::chdir(dir.c_str()) != 0) ::_exit(127);
    const int o = ::open(out.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    const int e = ::open(err.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0600);
    ::dup2(o, 1);
    ::dup2(e, 2);
    std::vector<char*> argv;
    for (const auto& a : args) argv.push_back(const_cast<char*>(a.c_str()));
    argv.push_back(nullptr);
    ::execv(argv[0], argv.data());
    ::_exit(127);
  }
  int raw = 0;
  ::waitpid(pid, &raw, 0);
  Command c{exit_status(raw), read_text(out), read_text(err)};
  std::filesystem::remove_all(files);
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
  for (const auto& e : std::filesystem::directory_iterator("/proc")) {
    const std::string name = e.path().filename().string();
    if (name.find_first_not_of("0123456789") == std::string::npos && parent_of(std::stoi(name)) == pid)
      kids.push_back(std::stoi(name));
  }
  return kids;
}

}  // namespace pogear::test
