// Regression tests of the adversarial review (issue "Hardening") that need no pogear process: the
// simulator cache's checks of its directory, figures thinned without losing a peak, FIFOs and
// numbers in tables, model paths and invisible characters, a simulation that wrote no CSV. Those
// that run pogear: tests/commands/hardening_test.cpp; the Hardening fixture: error_support.hpp.
#include <sys/stat.h>

#include "error_support.hpp"
#include "common/gnuplot.hpp"
#include "run/simulator_cache.hpp"

namespace pogear::test {
namespace {

// ---------------------------------------------------------------- code and command execution

TEST_F(Hardening, CacheChecksEveryStepOnTheWay) {
  fs::create_directories("private/abc");
  fs::permissions("private", fs::perms::owner_all);
  fs::permissions("private/abc", fs::perms::owner_all);
  EXPECT_EQ(why_not_private("private"), "");
  fs::permissions("private/abc", fs::perms::group_write, fs::perm_options::add);
  EXPECT_EQ(why_not_private("private/abc"), "writable by others (mode 0720)");
  fs::create_directory_symlink(dir_ / "private", "link");
  EXPECT_EQ(why_not_private("link"), "a symbolic link");
  write_text("file", "");
  EXPECT_EQ(why_not_private("file"), "not a directory");
}

// ---------------------------------------------------------------- data loss and corruption

TEST_F(Hardening, ThinnedFiguresKeepEveryPeak) {
  // 1e5 rows of a sawtooth whose single spike per 7 rows a plain decimation would miss.
  std::string csv = "t [s],a [1]\n";
  for (int i = 0; i < 100000; ++i) csv += fmt::format("{},{}\n", i * 1e-5, i % 7 == 3 ? 10.0 : 0.0);
  write_text("big.csv", csv);
  const auto rows = thinned_csv_rows("big.csv", 1.0);
  EXPECT_LE(rows.size(), 4 * plot_buckets);
  std::size_t spikes = 0;
  for (std::size_t i = 1; i < rows.size(); ++i) EXPECT_LT(rows[i - 1][0], rows[i][0]);
  for (const auto& r : rows) spikes += r[1] == 10.0;
  EXPECT_GE(spikes, plot_buckets - 1);  // one in every bucket of 50 rows
}

// ---------------------------------------------------------------- crashes and hangs

TEST_F(Hardening, FifoAsTable) {
  ASSERT_EQ(::mkfifo("torque.csv", 0600), 0);
  expect_documented(scene_error(edited(base_scene(), {{R"(tau_c = { constant = "100*Nm" })", R"(tau_c = { table = "torque.csv" })"}})),
      R"~(scene.toml:9:19: error: table 'torque.csv': a FIFO, not a regular file)~");
}

// Item 14: a first line with a number in it is data with a mistake, not a header to drop.
TEST_F(Hardening, TableFirstLineWithANumber) {
  write_text("torque.csv", "x0,0\n1,100\n");
  expect_documented(scene_error(edited(base_scene(), {{R"(tau_c = { constant = "100*Nm" })", R"(tau_c = { table = "torque.csv" })"}})),
      R"~(torque.csv:1: error: bad number 'x0' in column 1 (time); the table needs two columns: time [s], torque [N m])~");
}

// ---------------------------------------------------------------- messages

TEST_F(Hardening, EmptyModelPath) {
  expect_scene_error({{R"(model = "gear.toml")", R"(model = "")"}},
      R"~(scene.toml:3:9: error: the model path is empty; give the path of the model file, e.g. model = "gear.toml")~");
}

TEST_F(Hardening, NulInModelPath) {
  expect_scene_error({{R"(model = "gear.toml")", R"(model = "gear.toml\u0000.txt")"}},
      R"~(scene.toml:3:9: error: the model path contains a NUL character; give the path of the model file)~");
}

TEST_F(Hardening, ModelPathInASymlinkLoop) {
  fs::create_symlink("loop_b.toml", "loop_a.toml");
  fs::create_symlink("loop_a.toml", "loop_b.toml");
  expect_scene_error({{R"(model = "gear.toml")", R"(model = "loop_a.toml")"}},
      R"~(scene.toml:3:9: error: model file 'loop_a.toml' cannot be opened (Too many levels of symbolic links); check the path and its links)~");
}

TEST_F(Hardening, UnicodeMinus) {
  expect_model_error({{R"(r_s1 = "10*cm")", "r_s1 = \"\xE2\x88\x92" "10*cm\""}},
      R"~(gear.toml:37:9: error: '−' (U+2212) is not the minus sign of expressions; write the ASCII '-')~");
}

// A byte-order mark inside a value (pasted from a Windows editor) is named, not echoed: raw, the
// message showed '' around an invisible character (issue 31, item 14).
TEST_F(Hardening, ByteOrderMarkInAValue) {
  expect_model_error({{R"(r_s1 = "10*cm")", "r_s1 = \"\xEF\xBB\xBF" "10*cm\""}},
      R"~(gear.toml:37:9: error: invisible character U+FEFF (a byte-order mark); delete it: expressions are written in ASCII)~");
}

TEST_F(Hardening, SimulationWroteNoCsv) {
  EXPECT_THROW(
      {
        try {
          thinned_csv_rows("out/none.csv", 1.0);
        } catch (const std::runtime_error& e) {
          expect_documented(e.what(), "the simulation wrote no out/none.csv; run the simulator by hand to see why");
          throw;
        }
      },
      std::runtime_error);
}

}  // namespace
}  // namespace pogear::test
