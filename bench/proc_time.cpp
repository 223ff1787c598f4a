// Wall time of a whole process (e.g. `pogear derive MODEL`), repeated: the generator's own cost as a
// user meets it, start-up included. Appends one CSV row: label,runs,median_s,min_s,max_s,status.
// Usage: bench_proc_time --csv FILE --label L [--min-total S] [--max-runs N] [--timeout S] -- CMD ARGS...
#include <signal.h>
#include <spawn.h>
#include <sys/wait.h>
#include <fcntl.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <string>
#include <vector>

extern char** environ;

namespace {

struct Outcome {
  double seconds = 0;
  std::string status = "ok";
};

// One run with stdout and stderr to /dev/null. SIGCHLD is blocked and awaited with sigtimedwait, so
// the end of the child is seen at once (no polling delay) and a hung child is killed at the timeout.
Outcome run_once(char** argv, double timeout) {
  Outcome r;
  posix_spawn_file_actions_t fa;
  posix_spawn_file_actions_init(&fa);
  posix_spawn_file_actions_addopen(&fa, 1, "/dev/null", O_WRONLY, 0);
  posix_spawn_file_actions_addopen(&fa, 2, "/dev/null", O_WRONLY, 0);
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  posix_spawnattr_t attr;
  posix_spawnattr_init(&attr);
  sigset_t none;
  sigemptyset(&none);
  posix_spawnattr_setsigmask(&attr, &none);  // the child must not inherit the blocked SIGCHLD
  posix_spawnattr_setflags(&attr, POSIX_SPAWN_SETSIGMASK);
  const auto t0 = std::chrono::steady_clock::now();
  pid_t pid = 0;
  if (posix_spawnp(&pid, argv[0], &fa, &attr, argv, environ) != 0) {
    r.status = "cannot start";
    return r;
  }
  int status = 0;
  for (;;) {
    const double left = timeout - std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
    if (left <= 0) {
      kill(pid, SIGKILL);
      waitpid(pid, &status, 0);
      r.status = "timeout";
      break;
    }
    timespec ts{static_cast<time_t>(left), static_cast<long>((left - static_cast<double>(static_cast<time_t>(left))) * 1e9)};
    sigtimedwait(&chld, nullptr, &ts);
    if (waitpid(pid, &status, WNOHANG) == pid) {
      if (!WIFEXITED(status) || WEXITSTATUS(status) != 0)
        r.status = "failed (exit " + std::to_string(WIFEXITED(status) ? WEXITSTATUS(status) : -1) + ")";
      break;
    }
  }
  r.seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  posix_spawn_file_actions_destroy(&fa);
  posix_spawnattr_destroy(&attr);
  return r;
}

}  // namespace

int main(int argc, char** argv) {
  std::string csv, label;
  double min_total = 0.5, timeout = 60;
  int max_runs = 20, cmd = -1;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    if (a == "--") {
      cmd = i + 1;
      break;
    }
    if (i + 1 >= argc) break;
    if (a == "--csv") csv = argv[++i];
    else if (a == "--label") label = argv[++i];
    else if (a == "--min-total") min_total = std::atof(argv[++i]);
    else if (a == "--max-runs") max_runs = std::max(1, std::atoi(argv[++i]));
    else if (a == "--timeout") timeout = std::atof(argv[++i]);
  }
  if (cmd < 0 || cmd >= argc || csv.empty()) {
    std::fprintf(stderr, "usage: %s --csv FILE --label L [--min-total S] [--max-runs N] [--timeout S] -- CMD ARGS...\n",
                 argv[0]);
    return 1;
  }
  sigset_t chld;
  sigemptyset(&chld);
  sigaddset(&chld, SIGCHLD);
  sigprocmask(SIG_BLOCK, &chld, nullptr);
  std::vector<double> times;
  std::string status = "ok";
  double total = 0;
  // At least 3 runs for a median, more until min_total is spent; one only if a run fails or is slow.
  while (static_cast<int>(times.size()) < max_runs && (times.size() < 3 || total < min_total)) {
    const Outcome o = run_once(argv + cmd, timeout);
    if (o.status != "ok") {
      status = o.status;
      if (o.status == "timeout") times.push_back(o.seconds);
      break;
    }
    times.push_back(o.seconds);
    total += o.seconds;
    if (o.seconds > 10) break;  // a slow configuration: one run says enough
  }
  std::sort(times.begin(), times.end());
  const std::size_t n = times.size();
  const double med = n == 0 ? 0 : n % 2 ? times[n / 2] : 0.5 * (times[n / 2 - 1] + times[n / 2]);
  std::FILE* f = std::fopen(csv.c_str(), "a");
  if (!f) {
    std::fprintf(stderr, "%s: error: cannot append to %s\n", argv[0], csv.c_str());
    return 2;
  }
  std::fprintf(f, "%s,%zu,%.6g,%.6g,%.6g,%s\n", label.c_str(), n, med, n ? times.front() : 0.0,
               n ? times.back() : 0.0, status.c_str());
  std::fclose(f);
  std::printf("  %-32s %s: median %.4g s (min %.4g, max %.4g, %zu runs)\n", label.c_str(), status.c_str(), med,
              n ? times.front() : 0.0, n ? times.back() : 0.0, n);
  return status == "ok" ? 0 : 3;
}
