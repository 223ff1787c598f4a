// Regression tests of the adversarial review (issue "Hardening") that run pogear: paths that
// reached gnuplot's script, a planted cached binary, outputs onto devices, FIFOs and links,
// concurrent runs into one directory, failed figures reported as written, deep dotted keys, FIFOs
// as inputs, interrupts that left children running, output sizes, and the messages that lacked a
// cause or what to do. The others: tests/errors/hardening_test.cpp; the Hardening fixture:
// tests/errors/error_support.hpp.
#include <atomic>
#include <chrono>
#include <csignal>
#include <thread>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include "build_config/build_config.hpp"
#include "../errors/error_support.hpp"
#include "common/gnuplot.hpp"
#include "run/simulator_cache.hpp"
#include "run/simulate_scene.hpp"

namespace pogear::test {
namespace {

using namespace std::chrono_literals;

bool is_fifo(const fs::path& p) {
  struct stat st {};
  return ::lstat(p.c_str(), &st) == 0 && S_ISFIFO(st.st_mode);
}

// ---------------------------------------------------------------- code and command execution

// Item 2: the output directory was pasted into gnuplot's script; now no path is part of it.
TEST_F(Hardening, OutputPathNeverReachesGnuplotSyntax) {
  const std::string hostile = "x';system('touch pwned');'";
  const Command c = run(pogear() + " simulate scene.toml --interpreted -o \"" + hostile + "\"");
  EXPECT_EQ(c.status, 0) << c.err;
  EXPECT_FALSE(fs::exists("pwned"));
  EXPECT_FALSE(fs::exists(fs::path(hostile) / "pwned"));
  EXPECT_TRUE(fs::exists(fs::path(hostile) / "demo.velocities.svg"));
  // An honest path with a quote in it works too (before: "is gnuplot-nox installed?").
  const Command honest = run(pogear() + " simulate scene.toml --interpreted -o \"O'Brien/out\"");
  EXPECT_EQ(honest.status, 0) << honest.err;
  EXPECT_TRUE(fs::exists("O'Brien/out/demo.forces.svg"));
}

// Item 3: a cache another user can write to is not used, so a binary planted there never runs.
TEST_F(Hardening, PlantedBinaryInASharedCacheIsNotRun) {
  const SpecializedScene model = scene_model({});
  const GeneratedSources sources = generate_sources(model);
  fs::create_directories("shared");
  fs::permissions("shared", fs::perms::all);  // mode 0777, as the shared temporary directory
  const fs::path key_dir = fs::path("shared") / fmt::format("{:016x}", simulator_cache_key(sources, build_config::runtime_include));
  fs::create_directories(key_dir);
  write_text(key_dir / "simulator", "#!/bin/sh\ntouch '" + (dir_ / "planted_ran").string() + "'\n");
  fs::permissions(key_dir / "simulator", fs::perms::owner_all);
  const Command c = run("POGEAR_CACHE_DIR=shared " + pogear() + " simulate scene.toml -o out");
  EXPECT_EQ(c.status, 0) << c.err;
  EXPECT_FALSE(fs::exists("planted_ran"));
  EXPECT_EQ(c.err, "pogear: note: compiling without a cache: shared is writable by others (mode 0777); set "
                   "POGEAR_CACHE_DIR to a directory of your own to keep simulators\n");
  EXPECT_TRUE(fs::exists("out/demo.csv"));
}

// Without HOME the cache is the user's home from the password database, never the shared /tmp.
TEST_F(Hardening, CacheWithoutHomeIsInTheUsersHome) {
  const Command c = run("env -u HOME -u XDG_CACHE_HOME -u POGEAR_CACHE_DIR " + pogear() +
                        " simulate scene.toml -o out >/dev/null; echo $?");
  EXPECT_EQ(c.out, "0\n") << c.err;
  EXPECT_FALSE(fs::exists(fs::temp_directory_path() / "pogear-cache"));
}

// ---------------------------------------------------------------- data loss and corruption

TEST_F(Hardening, OutputOntoAFifoIsWrittenInPlace) {
  ASSERT_EQ(::mkfifo("report", 0600), 0);
  // The reading end is open before pogear starts (pogear refuses a FIFO nobody reads), and a thread
  // drains it while pogear writes, until pogear is done and the pipe is empty.
  const int fd = ::open("report", O_RDONLY | O_NONBLOCK | O_CLOEXEC);
  ASSERT_GE(fd, 0);
  std::atomic<bool> done{false};
  std::string received;
  std::thread reader([&] {
    char buffer[4096];
    for (;;) {
      const ssize_t got = ::read(fd, buffer, sizeof buffer);
      if (got > 0) received.append(buffer, static_cast<std::size_t>(got));
      else if (done) break;
      else std::this_thread::sleep_for(std::chrono::milliseconds(1));
    }
  });
  const Command c = run(pogear() + " derive gear.toml -o report");
  done = true;
  reader.join();
  ::close(fd);
  EXPECT_EQ(c.status, 0) << c.err;
  EXPECT_TRUE(is_fifo("report"));
  EXPECT_NE(received.find("R ="), std::string::npos) << received;
}

TEST_F(Hardening, OutputOntoADeviceIsWrittenInPlace) {
  struct stat before {}, after {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  const Command c = run(pogear() + " derive gear.toml -o /dev/null");
  EXPECT_EQ(c.status, 0) << c.err;
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(before.st_ino, after.st_ino);
}

TEST_F(Hardening, OutputOntoASymlinkIsRefused) {
  write_text("victim", "precious");
  fs::create_symlink("victim", "report.txt");
  expect_pogear_error("derive gear.toml -o report.txt", 2,
      R"~(pogear: error: report.txt is a symbolic link; pogear does not write through links: give the link's target or remove the link)~");
  EXPECT_EQ(read_text("victim"), "precious");
  EXPECT_TRUE(fs::is_symlink("report.txt"));
}

// Item 5: two simulations into one directory at once. Each CSV in the end is one run's whole
// output, byte for byte as that run writes it alone; a link planted at the old temporary name
// redirects nothing.
TEST_F(Hardening, ConcurrentSimulationsIntoOneDirectory) {
  ASSERT_EQ(run(pogear() + " simulate scene.toml --interpreted -o ref_exact >/dev/null").status, 0);
  ASSERT_EQ(run(pogear() + " simulate scene.toml --interpreted --solver dopri5 -o ref_dopri5 >/dev/null").status, 0);
  write_text("victim", "precious");
  fs::create_directory("shared");
  fs::create_symlink(dir_ / "victim", "shared/demo.csv.tmp");
  for (int round = 0; round < 4; ++round) {
    const Command c = run(pogear() + " simulate scene.toml --interpreted -o shared >/dev/null 2>a.err & " + pogear() +
                          " simulate scene.toml --interpreted --solver dopri5 -o shared >/dev/null 2>b.err & "
                          "wait %1; a=$?; wait %2; b=$?; echo $a $b");
    EXPECT_EQ(c.out, "0 0\n") << read_text("a.err") << read_text("b.err");
    for (const std::string name : {"demo.csv", "demo.rigid.csv"}) {
      const std::string got = read_text("shared/" + name);
      EXPECT_TRUE(got == read_text("ref_exact/" + name) || got == read_text("ref_dopri5/" + name))
          << name << " is no single run's output (round " << round << ")";
    }
  }
  EXPECT_EQ(read_text("victim"), "precious");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator("shared")) names.push_back(e.path().filename().string());
  std::sort(names.begin(), names.end());
  EXPECT_EQ(names, (std::vector<std::string>{"demo.csv", "demo.csv.tmp", "demo.forces.svg", "demo.rigid.csv",
                                             "demo.velocities.svg"}));
}

// Item 6: a figure that cannot be written whole fails the run and leaves the old figure. The file
// size limit (60 blocks of 512 bytes in sh) lets the CSV files (~16 KB each) through and stops the
// SVG (~40 KB) partway.
TEST_F(Hardening, FigureThatCannotBeWrittenFailsTheRun) {
  fs::create_directory("out");
  write_text("out/demo.velocities.svg", "the good figure\n");
  const Command c = run("trap '' XFSZ; ulimit -f 60; " + pogear() + " simulate scene.toml --interpreted -o out");
  EXPECT_EQ(c.status, 2) << c.out;
  EXPECT_EQ(c.out.find("wrote out/demo.velocities.svg"), std::string::npos) << c.out;
  EXPECT_EQ(c.err, "pogear: error: cannot write out/demo.velocities.svg: File too large; check the free space and "
                   "the output directory\n");
  EXPECT_EQ(read_text("out/demo.velocities.svg"), "the good figure\n");
}

// ---------------------------------------------------------------- crashes and hangs

TEST_F(Hardening, DeepDottedKeyInAModel) {
  std::string text;
  for (int i = 0; i < 50000; ++i) text += "a.";
  write_text("deep.toml", text + "b = 1\n");
  expect_pogear_error("derive deep.toml", 2,
      R"~(deep.toml:1:2: error: a dotted key of more than 64 parts; keys in pogear's files have at most a few parts: write the key as its table and name)~");
}

TEST_F(Hardening, DeepDottedTableHeaderInAScene) {
  std::string header = "[simulation";
  for (int i = 0; i < 40000; ++i) header += ".a";
  write_text("scene.toml", base_scene() + header + "]\n");
  expect_pogear_error("generate scene.toml", 2,
      R"~(scene.toml:20:12: error: a dotted key of more than 64 parts; keys in pogear's files have at most a few parts: write the key as its table and name)~");
}

// Dots in numbers, strings, comments and lists are no key parts.
TEST_F(Hardening, DotsOutsideKeysAreNotCounted) {
  write_text("scene.toml", base_scene() + "# " + std::string(200, '.') + "\n");
  write_text("gear.toml", base_model() + "# ." + std::string(100, '.') + "\n");
  EXPECT_EQ(run(pogear() + " derive gear.toml >/dev/null").status, 0);
  EXPECT_EQ(run(pogear() + " generate scene.toml -o gen >/dev/null").status, 0);
}

TEST_F(Hardening, FifoAsModel) {
  ASSERT_EQ(::mkfifo("fifo.toml", 0600), 0);
  expect_pogear_error("derive fifo.toml", 2,
      R"~(fifo.toml: error: this is a FIFO, not a regular file; give the path of the file itself)~");
}

TEST_F(Hardening, FifoAsScene) {
  ASSERT_EQ(::mkfifo("fifo.toml", 0600), 0);
  expect_pogear_error("generate fifo.toml", 2,
      R"~(fifo.toml: error: this is a FIFO, not a regular file; give the path of the scene file itself)~");
}

// ---------------------------------------------------------------- interrupts

// Item 10: SIGTERM to pogear alone (not its group) while the simulator runs: the simulator goes
// too, and never replaces the CSV afterwards; pogear dies of the signal, saying nothing.
TEST_F(Hardening, SigtermReachesTheSimulator) {
  fs::create_directory("out");
  write_text("out/endurance.csv", "the good csv\n");
  write_text("endurance.toml", edited(base_scene(), {{R"(name = "demo")", R"(name = "endurance")"},
                                                     {"compare_rigid = true\n", ""},
                                                     {R"(horizon = "0.1*s")", R"(horizon = "600*s")"},
                                                     {R"(solver = "exact")", R"(solver = "rk4")"},
                                                     {R"(step = "0.05*ms")", R"(step = "0.001*ms")"}}));
  const pid_t pid = start(pogear() + " simulate endurance.toml -o out >/dev/null 2>err.txt");
  pid_t simulator = 0;
  // The first run compiles the simulator (cached afterwards); then the simulator runs for minutes.
  ASSERT_TRUE(eventually(
      [&] {
        for (pid_t kid : children_of(pid))
          if (read_text("/proc/" + std::to_string(kid) + "/cmdline").find("--solver") != std::string::npos)
            return (simulator = kid) != 0;
        return false;
      },
      600s))
      << "the simulator never started";
  ::kill(pid, SIGTERM);
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGTERM) << status;
  EXPECT_TRUE(eventually([&] { return ended(simulator); }, 10s)) << "the simulator outlived pogear";
  EXPECT_EQ(read_text("err.txt"), "");
  EXPECT_EQ(read_text("out/endurance.csv"), "the good csv\n");
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator("out")) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"endurance.csv"});
}

// Ctrl-C while the simulator compiles: pogear dies of SIGINT without a word (before: "compiling the
// simulator failed (status 130)"), and the compiler is gone with it.
TEST_F(Hardening, CtrlCDuringCompilation) {
  const pid_t pid = start("env POGEAR_CACHE_DIR=" + (dir_ / "fresh_cache").string() + " " + pogear() +
                          " simulate scene.toml -o out >/dev/null 2>err.txt");
  pid_t compiler = 0;
  ASSERT_TRUE(eventually(
      [&] {
        const auto kids = children_of(pid);
        return !kids.empty() && (compiler = kids.front()) != 0;
      },
      120s))
      << "pogear never started the compiler";
  ::kill(pid, SIGINT);  // as the terminal does, to pogear's process group (the compiler has its own)
  int status = 0;
  ::waitpid(pid, &status, 0);
  EXPECT_TRUE(WIFSIGNALED(status) && WTERMSIG(status) == SIGINT) << status;
  EXPECT_EQ(read_text("err.txt"), "");
  EXPECT_TRUE(eventually([&] { return ended(compiler); }, 10s)) << "the compiler outlived pogear";
}

// ---------------------------------------------------------------- output size

TEST_F(Hardening, OutputSizeIsBoundedBeforeTheRun) {
  write_text("scene.toml", edited(base_scene(), {{R"(horizon = "0.1*s")", R"(horizon = "10*s")"},
                                                 {R"(sample = "1*ms")", R"(sample = "1e-6*s")"}}));
  expect_pogear_error("simulate scene.toml --interpreted -o out", 2,
      R"~(scene.toml:16:10: error: the CSV files of this scene may take up to 4.5 GB (1e+07 samples of 9 columns); the limit is 1.07 GB: raise sample, shorten the horizon or list fewer outputs, or pass --large-output to write them all the same)~");
  EXPECT_FALSE(fs::exists("out/demo.csv"));
  const SpecializedScene model = specialize(parse_scene("scene.toml"));
  EXPECT_NO_THROW(check_output_size(model, true));
}

// ---------------------------------------------------------------- messages

TEST_F(Hardening, RepeatZero) {
  expect_pogear_error("simulate scene.toml --repeat 0", 1, R"~(--repeat: '0' is not a whole number from 1 to 1000000; give how many times to run, e.g. --repeat 5
Run with --help for more information.)~");
}

TEST_F(Hardening, EmptyOutputPath) {
  expect_pogear_error("derive gear.toml -o ''", 1, R"~(--output: the path is empty; give a file or directory name
Run with --help for more information.)~");
}

TEST_F(Hardening, OutputDirectoryCannotBeCreated) {
  write_text("blocker", "a file where the directory should be\n");
  expect_pogear_error("generate scene.toml -o blocker/gen", 2,
      R"~(pogear: error: cannot create the directory blocker/gen: Not a directory; give a directory you can write to)~");
}

TEST_F(Hardening, GnuplotMissing) {
  expect_pogear_error("simulate scene.toml --interpreted -o out", 2,
      R"~(pogear: error: gnuplot is not installed, so no figures were drawn (the CSV files are written); install gnuplot-nox (scripts/install-deps.sh))~",
      "PATH=/nonexistent ");
  EXPECT_TRUE(fs::exists("out/demo.csv"));
}

}  // namespace
}  // namespace pogear::test
