// Tests of the input signals: values, breakpoints, Table interpolation and CSV table loading errors.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <pogear/signal_table.hpp>
#include <string>

#include <sys/stat.h>

namespace rt = pogear::rt;

namespace {

// A file in the temp directory named after the running test (tests may run in parallel processes).
std::string write_temp(const std::string& content) {
  const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
  const auto path = std::filesystem::temp_directory_path() /
                    (std::string("pogear_rt_") + info->test_suite_name() + "_" + info->name() + ".csv");
  std::ofstream(path) << content;
  return path.string();
}

}  // namespace

TEST(Signals, Values) {
  EXPECT_EQ(rt::value(rt::Constant{2.5}, 7.0), 2.5);
  const rt::Signal step = rt::Step{1.0, -3.0, 0.5};
  EXPECT_EQ(rt::value(step, 0.4999), 1.0);
  EXPECT_EQ(rt::value(step, 0.5), -3.0);  // right-continuous
  const rt::Signal ramp = rt::Ramp{2.0, 0.5, 10.0};
  EXPECT_EQ(rt::value(ramp, 1.0), 10.0);
  EXPECT_EQ(rt::value(ramp, 4.0), 11.0);
  const rt::Signal sine = rt::Sine{2.0, 0.25, 0.0, 1.0};  // period 4 s
  EXPECT_NEAR(rt::value(sine, 1.0), 3.0, 1e-15);  // sin(pi/2) rounds to exactly 1 or 1 - 1 ulp
  EXPECT_NEAR(rt::value(sine, 3.0), -1.0, 1e-15);
}

TEST(Signals, TableInterpolation) {
  const rt::Table tab{{0, 1, 2, 3, 3, 4}, {0, 10, 10, -5, 7, 8}};
  EXPECT_EQ(tab.value(-1), 0);  // held before the first point
  EXPECT_EQ(tab.value(0), 0);
  EXPECT_EQ(tab.value(0.5), 5);
  EXPECT_EQ(tab.value(1), 10);
  EXPECT_EQ(tab.value(1.5), 10);
  EXPECT_EQ(tab.value(2.5), 2.5);
  EXPECT_NEAR(tab.value(2.9999999), -4.9999985, 1e-12);  // linear up to the jump; rounding ~1e-15
  EXPECT_EQ(tab.value(3), 7);  // repeated time: a jump, right-continuous
  EXPECT_EQ(tab.value(3.5), 7.5);
  EXPECT_EQ(tab.value(9), 8);  // held after the last point
  EXPECT_EQ(rt::Table{}.value(1), 0);
}

TEST(Signals, Breakpoints) {
  EXPECT_EQ(rt::breakpoints(rt::Step{0, 1, 0.5}, 0, 1), std::vector<double>{0.5});
  EXPECT_TRUE(rt::breakpoints(rt::Step{0, 1, 0.5}, 0.5, 1).empty());  // open interval
  EXPECT_EQ(rt::breakpoints(rt::Ramp{0.2, 1, 0}, 0, 1), std::vector<double>{0.2});
  EXPECT_TRUE(rt::breakpoints(rt::Sine{1, 1, 0, 0}, 0, 1).empty());
  const rt::Table tab{{0, 0.3, 0.3, 0.7, 2}, {0, 1, 2, 3, 4}};
  EXPECT_EQ(rt::breakpoints(tab, 0, 1), (std::vector<double>{0.3, 0.7}));
  const std::vector<rt::Signal> all = {rt::Step{0, 1, 0.7}, tab, rt::Ramp{0.1, 1, 0}};
  EXPECT_EQ(rt::breakpoints(all, 0, 1), (std::vector<double>{0.1, 0.3, 0.7}));
}

TEST(TableCsv, LoadsWithHeaderCommentsAndBlankLines) {
  const std::string path = write_temp("t [s],torque [N m]\n0,1.5\n\n# comment\n 0.5 , -2e-1\r\n1,+3\n");
  rt::TableError error;
  const auto tab = rt::load_table_csv(path, error);
  ASSERT_TRUE(tab) << error.text();
  EXPECT_TRUE(error.message.empty());
  EXPECT_EQ(tab->t, (std::vector<double>{0, 0.5, 1}));
  EXPECT_EQ(tab->v, (std::vector<double>{1.5, -0.2, 3}));
  EXPECT_DOUBLE_EQ(tab->value(0.75), 1.4);  // -0.2 + 0.5 * 3.2: rounding of a few ulps
  std::filesystem::remove(path);
}

TEST(TableCsv, LoadsWithoutHeader) {
  const std::string path = write_temp("0,1\n2,3\n");
  rt::TableError error;
  const auto tab = rt::load_table_csv(path, error);
  ASSERT_TRUE(tab) << error.text();
  EXPECT_EQ(tab->value(1), 2);
  std::filesystem::remove(path);
}

TEST(TableCsv, MissingFile) {
  rt::TableError error;
  EXPECT_FALSE(rt::load_table_csv("/nonexistent/dir/table.csv", error));
  EXPECT_EQ(error.text(), "/nonexistent/dir/table.csv: cannot open file (No such file or directory)");
}

TEST(TableCsv, ErrorsCarryLineNumbers) {
  const std::vector<std::pair<std::string, std::string>> cases = {
      {"t,value\n0,1\n0.1,abc\n", ":3: bad number 'abc' in column 2 (value)"},
      {"t,value\n0,1\nx1,2\n", ":3: bad number 'x1' in column 1 (time)"},
      {"0,1\n0.1,2.5.1\n", ":2: bad number '2.5.1' in column 2 (value)"},
      {"0,1\n0.1\n", ":2: expected 2 columns 't,value', found 1"},
      {"0,1\n0.1,2,3\n", ":2: expected 2 columns 't,value', found more"},
      {"0,1\n1,2\n0.5,3\n", ":3: time 0.5 is before the previous row's"},
      {"0,1\n1,inf\n", ":2: non-finite number"},
  };
  for (const auto& [content, what] : cases) {
    const std::string path = write_temp(content);
    rt::TableError error;
    EXPECT_FALSE(rt::load_table_csv(path, error)) << content;
    EXPECT_EQ(error.text(), path + what) << content;
    std::filesystem::remove(path);
  }
  const std::string path = write_temp("t,value\n");
  rt::TableError error;
  EXPECT_FALSE(rt::load_table_csv(path, error));
  EXPECT_EQ(error.text(), path + ": no data rows");
  std::filesystem::remove(path);
}

// The reader of a scene points at the row or at the `table =` from these fields, never by taking
// the message apart.
TEST(TableCsv, ErrorsAreTyped) {
  const std::string path = write_temp("t,value\n0,1\n0.1,abc\n");
  rt::TableError error;
  EXPECT_FALSE(rt::load_table_csv(path, error));
  EXPECT_EQ(error.kind, rt::TableErrorKind::bad_row);
  EXPECT_EQ(error.path, path);
  EXPECT_EQ(error.line, 3);
  EXPECT_EQ(error.message, "bad number 'abc' in column 2 (value)");
  std::filesystem::remove(path);
  EXPECT_FALSE(rt::load_table_csv("/nonexistent/dir/table.csv", error));
  EXPECT_EQ(error.kind, rt::TableErrorKind::cannot_open);
  EXPECT_EQ(error.line, 0);
  EXPECT_EQ(error.message, "cannot open file (No such file or directory)");
  const std::string empty = write_temp("t,value\n");
  EXPECT_FALSE(rt::load_table_csv(empty, error));
  EXPECT_EQ(error.kind, rt::TableErrorKind::no_data_rows);
  EXPECT_EQ(error.line, 0);
  std::filesystem::remove(empty);
}

// A spreadsheet's byte order mark must not turn the first data row into a header: with it dropped,
// 100 N m would hold from t = 0 instead of ramping from 0 at t = 0 to 100 at t = 1.
TEST(TableCsv, ByteOrderMarkIsNotPartOfTheFirstRow) {
  const std::string path = write_temp("\xEF\xBB\xBF" "0,0\n1,100\n");
  rt::TableError error;
  const auto tab = rt::load_table_csv(path, error);
  ASSERT_TRUE(tab) << error.text();
  EXPECT_EQ(tab->t, (std::vector<double>{0, 1}));
  EXPECT_EQ(tab->v, (std::vector<double>{0, 100}));
  EXPECT_EQ(tab->value(0.5), 50);
  std::filesystem::remove(path);
}

// The header is told by its content: a first line with a number in one of its fields is a data row
// with a mistake, not a header to skip.
TEST(TableCsv, FirstLineWithANumberIsData) {
  for (const auto& [content, what] : std::vector<std::pair<std::string, std::string>>{
           {"x0,0\n1,100\n", ":1: bad number 'x0' in column 1 (time)"},
           {"0,y\n1,100\n", ":1: bad number 'y' in column 2 (value)"}}) {
    const std::string path = write_temp(content);
    rt::TableError error;
    EXPECT_FALSE(rt::load_table_csv(path, error)) << content;
    EXPECT_EQ(error.text(), path + what) << content;
    std::filesystem::remove(path);
  }
}

// A FIFO with no writer would block a reader forever; it is refused at once.
TEST(TableCsv, FifoIsRefused) {
  const std::string path = write_temp("");
  std::filesystem::remove(path);
  ASSERT_EQ(::mkfifo(path.c_str(), 0600), 0);
  rt::TableError error;
  EXPECT_FALSE(rt::load_table_csv(path, error));
  EXPECT_EQ(error.text(), path + ": a FIFO, not a regular file");
  std::filesystem::remove(path);
}
