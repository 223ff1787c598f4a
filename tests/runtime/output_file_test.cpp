// Tests of OutputFile, the one way pogear and its simulators write outputs: what stands at the
// path decides how it is written (replaced, written in place, or refused), and concurrent writers
// and planted links cannot mix or redirect outputs.
#include <gtest/gtest.h>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <fcntl.h>
#include <sys/stat.h>
#include <unistd.h>

#include <pogear/output_file.hpp>

#include "../support/files.hpp"

namespace fs = std::filesystem;
namespace rt = pogear::rt;

namespace {

using pogear::test::names_in;
using pogear::test::read_text;

fs::path test_dir() { return pogear::test::test_dir("rt_out"); }

bool write_whole(const std::string& path, const std::string& text) {
  rt::OutputFile out(path);
  return out.write(text) && out.commit();
}

}  // namespace

TEST(OutputFile, ReplacesARegularFileOnlyOnCommit) {
  const fs::path dir = test_dir();
  std::ofstream(dir / "a.txt") << "old";
  {
    rt::OutputFile out((dir / "a.txt").string());
    ASSERT_TRUE(out.ok()) << out.error();
    ASSERT_TRUE(out.write("new contents"));
    EXPECT_EQ(read_text(dir / "a.txt"), "old");
  }  // abandoned
  EXPECT_EQ(read_text(dir / "a.txt"), "old");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"a.txt"});
  ASSERT_TRUE(write_whole((dir / "a.txt").string(), "new"));
  EXPECT_EQ(read_text(dir / "a.txt"), "new");
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"a.txt"});
}

TEST(OutputFile, NewFileGetsTheUmaskPermissions) {
  const fs::path dir = test_dir();
  const mode_t old = ::umask(022);
  ASSERT_TRUE(write_whole((dir / "b.txt").string(), "x"));
  ::umask(old);
  struct stat st {};
  ASSERT_EQ(::stat((dir / "b.txt").c_str(), &st), 0);
  EXPECT_EQ(st.st_mode & 0777, 0644u);
}

// A link at the target is neither followed (the victim stays intact) nor silently replaced.
TEST(OutputFile, RefusesASymbolicLink) {
  const fs::path dir = test_dir();
  std::ofstream(dir / "victim") << "precious";
  fs::create_symlink(dir / "victim", dir / "out.csv");
  rt::OutputFile out((dir / "out.csv").string());
  EXPECT_FALSE(out.ok());
  EXPECT_EQ(out.error(), (dir / "out.csv").string() +
                             " is a symbolic link; pogear does not write through links: give the link's target or "
                             "remove the link");
  EXPECT_FALSE(out.write("x"));
  EXPECT_FALSE(out.commit());
  EXPECT_EQ(read_text(dir / "victim"), "precious");
  EXPECT_TRUE(fs::is_symlink(dir / "out.csv"));
}

// A character device is written in place: before the fix `-o /dev/null` replaced /dev/null by a
// regular file. The test's device is /dev/null itself, whose identity must survive.
TEST(OutputFile, WritesACharacterDeviceInPlace) {
  struct stat before {}, after {};
  ASSERT_EQ(::stat("/dev/null", &before), 0);
  ASSERT_TRUE(write_whole("/dev/null", "discarded"));
  ASSERT_EQ(::stat("/dev/null", &after), 0);
  EXPECT_TRUE(S_ISCHR(after.st_mode));
  EXPECT_EQ(before.st_ino, after.st_ino);
  EXPECT_EQ(before.st_rdev, after.st_rdev);
}

TEST(OutputFile, WritesAFifoInPlace) {
  const fs::path dir = test_dir();
  const fs::path fifo = dir / "pipe";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  std::string received;
  std::thread reader([&] {
    std::ifstream in(fifo);  // blocks until the writer opens
    std::stringstream ss;
    ss << in.rdbuf();
    received = ss.str();
  });
  // Until the reader has opened its end, the FIFO is refused (see the next test): retry until then.
  bool written = false;
  for (int i = 0; i < 500 && !written; ++i) {
    rt::OutputFile out(fifo.string());
    if (out.ok()) {
      written = out.write("through the pipe") && out.commit();
    } else {
      std::this_thread::sleep_for(std::chrono::milliseconds(10));
    }
  }
  reader.join();
  EXPECT_TRUE(written);
  EXPECT_EQ(received, "through the pipe");
  struct stat st {};
  ASSERT_EQ(::lstat(fifo.c_str(), &st), 0);
  EXPECT_TRUE(S_ISFIFO(st.st_mode));
}

TEST(OutputFile, FifoWithoutReaderIsRefusedAtOnce) {
  const fs::path dir = test_dir();
  ASSERT_EQ(::mkfifo((dir / "pipe").c_str(), 0600), 0);
  rt::OutputFile out((dir / "pipe").string());
  EXPECT_FALSE(out.ok());
  EXPECT_EQ(out.error(), (dir / "pipe").string() + " is a FIFO that nobody reads; start its reader first");
}

TEST(OutputFile, RefusesADirectoryAndAnEmptyPath) {
  const fs::path dir = test_dir();
  EXPECT_EQ(rt::OutputFile(dir.string()).error(), dir.string() + " is a directory; give the path of a file to write");
  EXPECT_EQ(rt::OutputFile("").error(), "the output path '' names no file; give a file name");
  EXPECT_EQ(rt::OutputFile((dir / "").string()).error(),
            "the output path '" + (dir / "").string() + "' names no file; give a file name");
}

// The old fixed temporary name, planted as a link to a victim, is not followed: temporary files
// have names (or no name) nobody can predict.
TEST(OutputFile, PlantedTemporaryLinkIsNotFollowed) {
  const fs::path dir = test_dir();
  std::ofstream(dir / "victim") << "precious";
  for (const char* name : {"out.csv.tmp", ".out.csv.tmp", ".out.csv.tmp0"})
    fs::create_symlink(dir / "victim", dir / name);
  ASSERT_TRUE(write_whole((dir / "out.csv").string(), "result"));
  EXPECT_EQ(read_text(dir / "victim"), "precious");
  EXPECT_EQ(read_text(dir / "out.csv"), "result");
}

// Writers of one path at once: each commit replaces the whole file, so the result is one writer's
// complete output, never a mix, and no temporary file stays behind.
TEST(OutputFile, ConcurrentWritersNeverMix) {
  const fs::path dir = test_dir();
  const std::string path = (dir / "out.csv").string();
  constexpr int kWriters = 8;
  std::vector<std::string> contents;
  for (int w = 0; w < kWriters; ++w) contents.push_back(std::string(200000 + w, static_cast<char>('a' + w)));
  std::vector<std::thread> threads;
  std::vector<int> ok(kWriters, 0);
  for (int w = 0; w < kWriters; ++w)
    threads.emplace_back([&, w] {
      rt::OutputFile out(path);
      for (std::size_t i = 0; i < contents[w].size(); i += 4096)
        out.write(std::string_view(contents[w]).substr(i, 4096));
      ok[w] = out.commit();
    });
  for (auto& t : threads) t.join();
  EXPECT_EQ(std::count(ok.begin(), ok.end(), 1), kWriters);
  const std::string result = read_text(path);
  EXPECT_NE(std::find(contents.begin(), contents.end(), result), contents.end()) << "a mix of writers";
  EXPECT_EQ(names_in(dir), std::vector<std::string>{"out.csv"});
}
