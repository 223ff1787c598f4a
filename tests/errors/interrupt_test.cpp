// Interrupted runs: whatever the moment, a previous good output stays intact, and no temporary file
// stays behind: outputs are written to unnamed files (O_TMPFILE) that get a name only when whole,
// so even SIGKILL, which nothing can handle, leaves nothing; pogear's handler removes the named
// temporaries it has (the simulator being compiled) and passes the signal on to its child.
#include <algorithm>
#include <chrono>
#include <optional>
#include <csignal>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>

#include "error_support.hpp"
#include "common/interrupts.hpp"

namespace pogear::test {
namespace {

using namespace std::chrono_literals;

// The raw wait status of `pid`.
int finish(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return status;
}

std::uintmax_t size_of(const fs::path& p) {
  std::error_code ec;
  const auto s = fs::file_size(p, ec);
  return ec ? 0 : s;
}

// Bytes written so far by `pid` or a child of it to a file in `dir` that has no name yet (an
// O_TMPFILE file shows in /proc as "DIR/#inode (deleted)"); nullopt when there is none.
std::optional<std::uintmax_t> unnamed_output_size(pid_t pid, const fs::path& dir) {
  const std::string prefix = fs::absolute(dir).lexically_normal().string() + "/#";
  std::vector<pid_t> pids = children_of(pid);
  pids.push_back(pid);
  std::optional<std::uintmax_t> size;
  for (const pid_t p : pids) {
    std::error_code ec;
    for (const auto& fd : fs::directory_iterator("/proc/" + std::to_string(p) + "/fd", ec)) {
      const std::string target = fs::read_symlink(fd.path(), ec).string();
      if (!ec && target.rfind(prefix, 0) == 0) size = std::max(size.value_or(0), size_of(fd.path()));
    }
  }
  return size;
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

TEST_F(Interrupt, DeriveInterruptedAtAnyMoment) {
  // SIGINT at moments spread over a whole run (derive, format, write, rename): the report is the
  // old one or the whole new one, and no other file appears.
  ASSERT_EQ(run(pogear() + " derive gear.toml -o reference.txt").status, 0);
  const std::string reference = read_text("reference.txt");
  fs::remove("reference.txt");
  for (int i = 0; i < 40; ++i) {
    write_text("report.txt", "the good report\n");
    const pid_t pid = start(pogear() + " derive gear.toml -o report.txt >/dev/null 2>&1");
    std::this_thread::sleep_for(std::chrono::microseconds(1000 * i));
    ::kill(pid, SIGINT);
    const int status = finish(pid);
    EXPECT_TRUE(WIFSIGNALED(status) || (WIFEXITED(status) && WEXITSTATUS(status) == 0)) << status;
    const std::string report = read_text("report.txt");
    EXPECT_TRUE(report == "the good report\n" || report == reference) << "a partial report after " << i << " ms";
    EXPECT_EQ(names_in("."), (std::vector<std::string>{"gear.toml", "report.txt", "scene.toml"}));
  }
}

// SIGINT or SIGKILL to `pogear simulate --interpreted` once it has written 1 MiB of its CSV.
void interrupt_interpreted_run(const fs::path& dir, int sig) {
  fs::create_directory(dir / "out");
  write_text(dir / "out/endurance.csv", "the good csv\n");
  write_text(dir / "endurance.toml", long_scene("endurance"));
  const pid_t pid =
      start("'" + std::string(POGEAR_EXECUTABLE) + "' simulate endurance.toml --interpreted -o out >/dev/null 2>&1");
  eventually([&] { return unnamed_output_size(pid, dir / "out").value_or(0) > (1u << 20) || ended(pid); });
  ASSERT_GT(unnamed_output_size(pid, dir / "out").value_or(0), 1u << 20) << "pogear wrote no CSV";
  ::kill(pid, sig);
  const int status = finish(pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
  EXPECT_EQ(read_text(dir / "out/endurance.csv"), "the good csv\n");
}

TEST_F(Interrupt, InterpretedSimulationSigint) {
  interrupt_interpreted_run(dir_, SIGINT);
  EXPECT_EQ(names_in("out"), std::vector<std::string>{"endurance.csv"});
}

TEST_F(Interrupt, InterpretedSimulationSigkill) {
  interrupt_interpreted_run(dir_, SIGKILL);
  // Nothing runs after SIGKILL, and nothing needs to: the partial CSV never had a name.
  EXPECT_EQ(names_in("out"), std::vector<std::string>{"endurance.csv"});
}

TEST_F(Interrupt, SimulatorKilled) {
  // A generated simulator (no handler of its own, and none needed) killed mid-run, here in a long
  // rk4 run.
  fs::create_symlink(POGEAR_SIM_ONE_STAGE, "paper_one_stage");
  fs::create_directory("out");
  write_text("out/paper_one_stage.csv", "the good csv\n");
  for (int sig : {SIGINT, SIGKILL}) {
    const pid_t pid =
        start("./paper_one_stage --solver rk4 --step 1e-8 --max-steps 1000000000 --out out >/dev/null 2>&1");
    eventually([&] { return unnamed_output_size(pid, "out").has_value() || ended(pid); });
    ASSERT_TRUE(unnamed_output_size(pid, "out").has_value()) << "the simulator opened no CSV";
    std::this_thread::sleep_for(100ms);  // well into the run: 1e-8 s steps take minutes
    ::kill(pid, sig);
    const int status = finish(pid);
    EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == sig) << status;
    EXPECT_EQ(read_text("out/paper_one_stage.csv"), "the good csv\n");
    EXPECT_EQ(names_in("out"), std::vector<std::string>{"paper_one_stage.csv"});
  }
}

TEST_F(Interrupt, CompiledSimulationCtrlC) {
  // Ctrl-C in a terminal signals pogear's process group; the simulator runs in a group of its own,
  // and pogear passes the signal on to it, waits for it to end, and dies of the signal itself.
  fs::create_directory("out");
  write_text("out/endurance.csv", "the good csv\n");
  write_text("endurance.toml", long_scene("endurance"));
  // The first run compiles the simulator (cached by the hash of its sources afterwards).
  const pid_t pid = start(pogear() + " simulate endurance.toml -o out >/dev/null 2>&1");
  eventually([&] { return unnamed_output_size(pid, "out").value_or(0) > (1u << 20) || ended(pid); }, 600s);
  ASSERT_GT(unnamed_output_size(pid, "out").value_or(0), 1u << 20) << "pogear wrote no CSV";
  ::kill(-pid, SIGINT);
  const int status = finish(pid);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(read_text("out/endurance.csv"), "the good csv\n");
  EXPECT_EQ(names_in("out"), std::vector<std::string>{"endurance.csv"});
}

}  // namespace
}  // namespace pogear::test
