// Interrupted runs: whatever the moment, a previous good output stays intact. pogear's handler
// for SIGINT and SIGTERM removes its temporary files; SIGKILL cannot be handled, and a generated
// simulator installs no handler, so after those a `name.csv.tmp` stays beside the intact output.
#include <algorithm>
#include <chrono>
#include <csignal>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>

#include "error_support.hpp"
#include "output_file.hpp"

namespace pogear::test {
namespace {

using namespace std::chrono_literals;

// Starts `command` with sh in its own process group (exec'd, so the pid is the command's own).
pid_t start(const std::string& command) {
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::setpgid(0, 0);
    ::execl("/bin/sh", "sh", "-c", ("exec " + command).c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  ::setpgid(pid, pid);  // also here, so that the group exists before we signal it
  return pid;
}

// The raw wait status of `pid`.
int finish(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

// Polls `ready` every 10 ms for up to `limit` (a loaded machine may be slow to get there).
template <class F>
bool eventually(F ready, std::chrono::seconds limit = 60s) {
  for (auto waited = 0ms; waited < limit; waited += 10ms) {
    if (ready()) return true;
    std::this_thread::sleep_for(10ms);
  }
  return false;
}

// True once `pid` has ended (a zombie until finish() reaps it): no use waiting for it further.
bool ended(pid_t pid) {
  const std::string stat = read_text("/proc/" + std::to_string(pid) + "/stat");
  const auto paren = stat.rfind(')');
  return paren == std::string::npos || paren + 2 >= stat.size() || stat[paren + 2] == 'Z';
}

std::uintmax_t size_of(const fs::path& p) {
  std::error_code ec;
  const auto s = fs::file_size(p, ec);
  return ec ? 0 : s;
}

// The names in `dir`, sorted.
std::vector<std::string> listing(const fs::path& dir) {
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir)) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  return names;
}

// A scene that simulates long enough to be interrupted while it writes its CSV: 6e5 samples of
// eight outputs, some 90 MB were it ever to finish.
std::string long_scene(const std::string& name) {
  return edited(base_scene(), {{R"(name = "demo")", "name = \"" + name + "\""},
                               {"compare_rigid = true\n", ""},
                               {R"(horizon = "0.1*s")", R"(horizon = "60*s")"},
                               {R"(sample = "1*ms")", R"(sample = "0.1*ms")"}});
}

class Interrupt : public ErrorTest {};

TEST_F(Interrupt, HandlerRemovesRememberedTemporaries) {
  write_text("partial.csv.tmp", "t [s]\n0\n");
  const pid_t pid = ::fork();
  if (pid == 0) {
    install_interrupt_cleanup();
    remember_temporary("partial.csv.tmp");
    ::raise(SIGINT);
    ::_exit(0);  // not reached: the handler dies of the signal
  }
  const int status = finish(pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_FALSE(fs::exists("partial.csv.tmp"));
}

TEST_F(Interrupt, DeriveInterruptedWhileWritingItsOutput) {
  write_text("report.txt", "the good report\n");
  // The model comes through a FIFO, so pogear waits for it until its temporary file, named after
  // its pid, is a FIFO too: opening that for writing blocks until a reader comes, which holds
  // pogear inside its write for as long as the test needs.
  ASSERT_EQ(::mkfifo("model.toml", 0600), 0);
  const pid_t pid = start(pogear() + " derive model.toml -o report.txt >/dev/null 2>&1");
  const std::string tmp = ".report.txt.tmp" + std::to_string(pid);
  ASSERT_EQ(::mkfifo(tmp.c_str(), 0600), 0);
  write_text("model.toml", base_model());  // blocks until pogear reads
  const std::string wchan = "/proc/" + std::to_string(pid) + "/wchan";
  ASSERT_TRUE(eventually([&] { return read_text(wchan) == "wait_for_partner"; }))
      << "pogear never got to its write";
  ::kill(pid, SIGINT);
  const int status = finish(pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(read_text("report.txt"), "the good report\n");
  EXPECT_EQ(listing("."), (std::vector<std::string>{"gear.toml", "model.toml", "report.txt", "scene.toml"}));
}

// SIGINT or SIGKILL to `pogear simulate --interpreted` once it has written 1 MiB of its CSV.
void interrupt_interpreted_run(const fs::path& dir, int sig) {
  fs::create_directory(dir / "out");
  write_text(dir / "out/endurance.csv", "the good csv\n");
  write_text(dir / "endurance.toml", long_scene("endurance"));
  const pid_t pid =
      start("'" + std::string(POGEAR_EXECUTABLE) + "' simulate endurance.toml --interpreted -o out >/dev/null 2>&1");
  eventually([&] { return size_of(dir / "out/endurance.csv.tmp") > (1u << 20) || ended(pid); });
  ASSERT_GT(size_of(dir / "out/endurance.csv.tmp"), 1u << 20) << "pogear wrote no CSV";
  ::kill(pid, sig);
  const int status = finish(pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
  EXPECT_EQ(read_text(dir / "out/endurance.csv"), "the good csv\n");
}

TEST_F(Interrupt, InterpretedSimulationSigint) {
  interrupt_interpreted_run(dir_, SIGINT);
  EXPECT_EQ(listing("out"), std::vector<std::string>{"endurance.csv"});  // the handler removed endurance.csv.tmp
}

TEST_F(Interrupt, InterpretedSimulationSigkill) {
  interrupt_interpreted_run(dir_, SIGKILL);
  // Nothing runs after SIGKILL: the partial CSV stays beside the good one, under its own name.
  EXPECT_EQ(listing("out"), (std::vector<std::string>{"endurance.csv", "endurance.csv.tmp"}));
}

TEST_F(Interrupt, SimulatorKilled) {
  // A generated simulator (no handler of its own) killed mid-run, here in a long rk4 run.
  fs::create_symlink(POGEAR_SIM_ONE_STAGE, "paper_one_stage");
  fs::create_directory("out");
  write_text("out/paper_one_stage.csv", "the good csv\n");
  for (int sig : {SIGINT, SIGKILL}) {
    const pid_t pid = start("./paper_one_stage --solver rk4 --step 1e-8 --out out >/dev/null 2>&1");
    eventually([&] { return fs::exists("out/paper_one_stage.csv.tmp") || ended(pid); });
    ASSERT_TRUE(fs::exists("out/paper_one_stage.csv.tmp")) << "the simulator wrote no CSV";
    std::this_thread::sleep_for(100ms);  // well into the run: 1e-8 s steps take minutes
    ::kill(pid, sig);
    const int status = finish(pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
    EXPECT_EQ(read_text("out/paper_one_stage.csv"), "the good csv\n");
    EXPECT_EQ(listing("out"), (std::vector<std::string>{"paper_one_stage.csv", "paper_one_stage.csv.tmp"}));
    fs::remove("out/paper_one_stage.csv.tmp");
  }
}

TEST_F(Interrupt, CompiledSimulationCtrlC) {
  // Ctrl-C in a terminal signals the whole process group: the simulator dies of it while pogear,
  // waiting in std::system, ignores it; pogear then removes the simulator's partial CSV.
  fs::create_directory("out");
  write_text("out/endurance.csv", "the good csv\n");
  write_text("endurance.toml", long_scene("endurance"));
  // The first run compiles the simulator (cached by the hash of its sources afterwards).
  const pid_t pid = start(pogear() + " simulate endurance.toml -o out >/dev/null 2>&1");
  eventually([&] { return size_of("out/endurance.csv.tmp") > (1u << 20) || ended(pid); }, 600s);
  ASSERT_GT(size_of("out/endurance.csv.tmp"), 1u << 20) << "pogear wrote no CSV";
  ::kill(-pid, SIGINT);
  const int status = finish(pid);
  EXPECT_TRUE(WIFEXITED(status) && WEXITSTATUS(status) == 128 + SIGINT) << status;
  EXPECT_EQ(read_text("out/endurance.csv"), "the good csv\n");
  EXPECT_EQ(listing("out"), std::vector<std::string>{"endurance.csv"});
}

}  // namespace
}  // namespace pogear::test
