// Tests of the CSV writer: exact round trip of doubles, nothing at PATH before the commit and no
// temporary name left behind, incomplete runs, chunked writing and open errors.
#include <gtest/gtest.h>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <pogear/csv.hpp>
#include <sstream>
#include <string>
#include <vector>

#include "../support/files.hpp"

namespace fs = std::filesystem;
namespace rt = pogear::rt;

namespace {

// out.csv in an empty directory of the test's own.
fs::path temp_path() { return pogear::test::test_dir("rt_csv") / "out.csv"; }

// The names in the directory of `p`: a temporary file would show up here.
std::vector<std::string> names_beside(const fs::path& p) { return pogear::test::names_in(p.parent_path()); }

std::vector<std::string> read_lines(const fs::path& p) {
  std::ifstream in(p);
  std::vector<std::string> lines;
  for (std::string l; std::getline(in, l);) lines.push_back(l);
  return lines;
}

}  // namespace

TEST(CsvWriter, RoundTripsDoublesExactly) {
  const fs::path path = temp_path();
  const std::vector<double> values = {0.1, 1.0 / 3, -2.0 / 7, 1e-300, 5e-324, 1.7976931348623157e308,
                                      -0.0, 123456789.125, std::nextafter(1.0, 2.0), 6.02214076e23};
  {
    rt::CsvWriter w(path.string(), {"t [s]", "omega_c [rad/s]", "F_ps [N]"});
    ASSERT_TRUE(w.ok()) << w.error();
    for (std::size_t i = 0; i + 1 < values.size(); i += 2) w.row(values[i], std::vector<double>{values[i + 1], 1.0});
    EXPECT_TRUE(names_beside(path).empty());  // nothing at PATH, nor anywhere by name, before commit
    ASSERT_TRUE(w.commit()) << w.error();
  }
  EXPECT_EQ(names_beside(path), std::vector<std::string>{"out.csv"});
  const std::vector<std::string> lines = read_lines(path);
  ASSERT_EQ(lines.size(), 1 + values.size() / 2);
  EXPECT_EQ(lines[0], "t [s],omega_c [rad/s],F_ps [N]");
  for (std::size_t r = 1; r < lines.size(); ++r) {
    std::stringstream ss(lines[r]);
    std::vector<double> parsed;
    for (std::string f; std::getline(ss, f, ',');) {
      double v = 0;
      ASSERT_EQ(std::from_chars(f.data(), f.data() + f.size(), v).ec, std::errc()) << f;
      parsed.push_back(v);
    }
    ASSERT_EQ(parsed.size(), 3u);
    // Bit-exact: shortest round-trip formatting parses back to the same double (sign of zero included).
    EXPECT_EQ(std::signbit(parsed[0]), std::signbit(values[2 * (r - 1)]));
    EXPECT_EQ(parsed[0], values[2 * (r - 1)]);
    EXPECT_EQ(parsed[1], values[2 * (r - 1) + 1]);
  }
  fs::remove(path);
}

TEST(CsvWriter, UncommittedRunLeavesNoFile) {
  const fs::path path = temp_path();
  {
    std::ofstream(path) << "previous good result\n";
    rt::CsvWriter w(path.string(), {"t [s]"});
    w.row({0.5});
  }
  EXPECT_EQ(names_beside(path), std::vector<std::string>{"out.csv"});
  EXPECT_EQ(read_lines(path), std::vector<std::string>{"previous good result"});  // untouched
  fs::remove(path);
}

TEST(CsvWriter, IncompleteRunIsKeptAndMarked) {
  const fs::path path = temp_path();
  {
    rt::CsvWriter w(path.string(), {"t [s]", "x [m]"});
    w.row({0.0, 1.0});
    w.field(0.1);  // a row cut short by the failure
    ASSERT_TRUE(w.commit_incomplete("non-finite state at t = 0.1;\nlast finite sample at t = 0"));
  }
  EXPECT_EQ(names_beside(path), std::vector<std::string>{"out.csv"});
  EXPECT_EQ(read_lines(path), (std::vector<std::string>{
                                  "t [s],x [m]", "0,1", "0.1",
                                  "# incomplete: non-finite state at t = 0.1; last finite sample at t = 0"}));
  fs::remove(path);
}

TEST(CsvWriter, WritesLargeOutputInChunks) {
  const fs::path path = temp_path();
  constexpr int kRows = 100000;  // ~2.5 MB: several 1 MiB chunks
  {
    rt::CsvWriter w(path.string(), {"t [s]", "a", "b"});
    for (int i = 0; i < kRows; ++i) w.row({i * 1e-3, std::sin(i * 1e-3), 1.0 / (i + 1)});
    ASSERT_TRUE(w.commit()) << w.error();
  }
  const std::vector<std::string> lines = read_lines(path);
  ASSERT_EQ(lines.size(), kRows + 1u);
  EXPECT_EQ(lines.back(), "99.999,-0.5072277066555313,1e-05");
  fs::remove(path);
}

TEST(CsvWriter, QuotesColumnNamesWithCommas) {
  const fs::path path = temp_path();
  {
    rt::CsvWriter w(path.string(), {"t [s]", "T [N,m]", "say \"hi\""});
    ASSERT_TRUE(w.commit());
  }
  EXPECT_EQ(read_lines(path), std::vector<std::string>{"t [s],\"T [N,m]\",\"say \"\"hi\"\"\""});
  fs::remove(path);
}

TEST(CsvWriter, OpenErrorIsReported) {
  rt::CsvWriter w("/nonexistent/dir/out.csv", {"t [s]"});
  EXPECT_FALSE(w.ok());
  EXPECT_EQ(w.error(), "cannot write /nonexistent/dir/out.csv: No such file or directory; check that the output "
                      "directory exists and is writable");
  w.row({1.0});
  EXPECT_FALSE(w.commit());
}
