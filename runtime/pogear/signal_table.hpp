// Table signals read from two-column CSV files, strictly and within bounds: what a scene's
// `table = "FILE"` input loads.
#pragma once

#include <charconv>
#include <cmath>
#include <optional>
#include <sstream>
#include <string>
#include <string_view>
#include <vector>

#include "pogear/input_file.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

namespace detail {
inline std::string_view trim(std::string_view s) {
  const auto b = s.find_first_not_of(" \t\r");
  if (b == std::string_view::npos) return {};
  return s.substr(b, s.find_last_not_of(" \t\r") - b + 1);
}

// Whole-field parse: "1.5x" or "" is an error, not 1.5 or 0.
inline std::optional<double> parse_double(std::string_view s) {
  s = trim(s);
  if (!s.empty() && s.front() == '+') s.remove_prefix(1);  // from_chars refuses a leading '+'
  double v = 0;
  const auto [end, ec] = std::from_chars(s.data(), s.data() + s.size(), v);
  if (s.empty() || ec != std::errc() || end != s.data() + s.size()) return std::nullopt;
  return v;
}
}  // namespace detail

// Bounds on a table file, so that a hostile one (or /dev/zero) cannot exhaust memory or time: the
// table is embedded in generated code, where 1e5 rows are already a 5 MB source file.
inline constexpr std::size_t max_table_rows = 100000;
inline constexpr std::size_t max_table_bytes = std::size_t{16} << 20;  // 1e5 rows of ~50 characters, with room

// Why a table could not be loaded: the file as a whole (kind other than bad_row, line 0) or one of
// its rows (bad_row, with its line).
enum class TableErrorKind { cannot_open, not_regular, too_large, read_error, bad_row, no_data_rows };

struct TableError {
  TableErrorKind kind = TableErrorKind::bad_row;
  std::string path;
  long line = 0;        // 1-based line of the row at fault; 0 when the whole file is concerned
  std::string message;  // what is wrong, e.g. "bad number 'abc' in column 2 (value)"

  // "PATH:LINE: message", or "PATH: message" when no line is concerned.
  std::string text() const {
    std::string t = path;
    if (line > 0) t += ':' + std::to_string(line);
    t += ": ";
    t += message;
    return t;
  }
};

// Reads a two-column CSV "t,value". The first line may be a header (none of its fields is a number);
// blank lines and lines starting with '#' are skipped. On failure returns nullopt and sets `error`.
// Never throws for bad input; only std::bad_alloc can escape.
inline std::optional<Table> load_table_csv(const std::string& path, TableError& error) {
  error = TableError{};
  auto file_error = [&](TableErrorKind kind, std::string message) {
    error = TableError{kind, path, 0, std::move(message)};
    return std::nullopt;
  };
  InputFile in = read_regular_file(path, max_table_bytes);
  switch (in.status) {
    case InputFileStatus::ok: break;
    case InputFileStatus::cannot_open:
      return file_error(TableErrorKind::cannot_open, "cannot open file (" + in.reason + ")");
    case InputFileStatus::directory:
    case InputFileStatus::not_regular:
      return file_error(TableErrorKind::not_regular, in.reason + ", not a regular file");
    case InputFileStatus::too_large:
      return file_error(TableErrorKind::too_large, "larger than " + std::to_string(max_table_bytes) +
                                                       " bytes; a table has at most " +
                                                       std::to_string(max_table_rows) + " rows");
    case InputFileStatus::read_error: return file_error(TableErrorKind::read_error, "read error");
  }
  std::string& content = in.text;
  // A byte order mark (spreadsheets write one) is not part of the first field.
  if (content.rfind("\xEF\xBB\xBF", 0) == 0) content.erase(0, 3);
  std::istringstream lines(content);
  Table tab;
  std::string line;
  long lineno = 0;
  bool seen_content = false;
  auto fail = [&](std::string what) {
    error = TableError{TableErrorKind::bad_row, path, lineno, std::move(what)};
    return std::nullopt;
  };
  // A field quoted in a message, cut short: a garbage line may be megabytes long.
  auto shown = [](std::string_view f) { return f.size() <= 40 ? std::string(f) : std::string(f.substr(0, 40)) + "..."; };
  while (std::getline(lines, line)) {
    ++lineno;
    const std::string_view l = detail::trim(line);
    if (l.empty() || l.front() == '#') continue;
    const bool first = !seen_content;
    seen_content = true;
    const auto comma = l.find(',');
    if (comma != std::string_view::npos && l.find(',', comma + 1) != std::string_view::npos)
      return fail("expected 2 columns 't,value', found more");
    const std::string_view f1 = detail::trim(l.substr(0, comma));
    const auto t = detail::parse_double(f1);
    const std::string_view f2 = comma == std::string_view::npos ? std::string_view{} : detail::trim(l.substr(comma + 1));
    const auto v = detail::parse_double(f2);
    // A header names the columns: no field of it is a number. A first line with one number in it
    // is a data row with a mistake, reported as such rather than dropped.
    if (first && !t && !v) continue;
    if (comma == std::string_view::npos) return fail("expected 2 columns 't,value', found 1");
    if (!t) return fail("bad number '" + shown(f1) + "' in column 1 (time)");
    if (!v) return fail("bad number '" + shown(f2) + "' in column 2 (value)");
    if (!std::isfinite(*t) || !std::isfinite(*v)) return fail("non-finite number");
    if (!tab.t.empty() && *t < tab.t.back()) return fail("time " + shown(f1) + " is before the previous row's");
    if (tab.t.size() == max_table_rows)
      return fail("more than " + std::to_string(max_table_rows) + " rows; resample the table more coarsely");
    tab.t.push_back(*t);
    tab.v.push_back(*v);
  }
  if (tab.t.empty()) return file_error(TableErrorKind::no_data_rows, "no data rows");
  return tab;
}

}  // namespace pogear::rt
