// CSV output of simulation runs: numbers in std::to_chars' shortest round-trip form, buffered and
// written through an OutputFile, which puts them at PATH only when the run is over (complete or
// marked incomplete).
#pragma once

#include <charconv>
#include <initializer_list>
#include <string>
#include <vector>

#include "pogear/output_file.hpp"

namespace pogear::rt {

// Usage: CsvWriter w(path, {"t [s]", "omega_c [rad/s]", "F_ps [N]"}); check w.ok(); then w.row(t, x)
// or field()...end_row() per sample; finally commit() or commit_incomplete(reason). Destroyed
// without either, it drops what it wrote, so a crashed or abandoned run never leaves a half-written
// file, and never touches an existing PATH (see OutputFile for what PATH may be). Errors (open,
// write, rename) end up in error().
class CsvWriter {
 public:
  CsvWriter(std::string path, const std::vector<std::string>& columns) : file_(std::move(path)) {
    if (!file_.ok()) return;
    buf_.reserve(kChunk + 4096);
    for (std::size_t i = 0; i < columns.size(); ++i) {
      if (i) buf_ += ',';
      if (columns[i].find_first_of(",\"\n") == std::string::npos) {
        buf_ += columns[i];
      } else {  // RFC 4180 quoting, for names a CSV reader would otherwise split
        buf_ += '"';
        for (char c : columns[i]) {
          if (c == '"') buf_ += '"';
          buf_ += c;
        }
        buf_ += '"';
      }
    }
    buf_ += '\n';
  }
  CsvWriter(const CsvWriter&) = delete;
  CsvWriter& operator=(const CsvWriter&) = delete;

  bool ok() const { return file_.ok(); }
  const std::string& error() const { return file_.error(); }
  const std::string& path() const { return file_.path(); }

  void field(double v) {
    if (in_row_) buf_ += ',';
    in_row_ = true;
    char s[32];  // shortest round-trip form of a double is at most 24 characters
    buf_.append(s, std::to_chars(s, s + sizeof s, v).ptr);
  }
  void end_row() {
    buf_ += '\n';
    in_row_ = false;
    if (buf_.size() >= kChunk) write_buffer();
  }
  // t, then values[0..size) of any vector-like type (Eigen vector, std::vector, std::array).
  template <class V>
  void row(double t, const V& values) {
    field(t);
    for (decltype(values.size()) i = 0; i < values.size(); ++i) field(values[i]);
    end_row();
  }
  void row(std::initializer_list<double> values) {
    for (double v : values) field(v);
    end_row();
  }

  bool commit() { return finish(); }
  // Keeps what was computed, marked: a last line "# incomplete: reason".
  bool commit_incomplete(const std::string& reason) {
    if (in_row_) end_row();
    buf_ += "# incomplete: ";
    for (char c : reason) buf_ += (c == '\n' || c == '\r') ? ' ' : c;  // the mark stays one line
    buf_ += '\n';
    return finish();
  }

 private:
  static constexpr std::size_t kChunk = std::size_t{1} << 20;

  void write_buffer() {
    if (!buf_.empty()) file_.write(buf_);
    buf_.clear();
  }
  bool finish() {
    write_buffer();
    return file_.commit();
  }

  OutputFile file_;
  std::string buf_;
  bool in_row_ = false;
};

}  // namespace pogear::rt
