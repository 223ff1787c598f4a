// CSV output of simulation runs: numbers in std::to_chars' shortest round-trip form, buffered and
// written to PATH.tmp, which replaces PATH only when the run is over (complete or marked incomplete).
#pragma once

#include <cerrno>
#include <charconv>
#include <cstdio>
#include <cstring>
#include <initializer_list>
#include <string>
#include <vector>

namespace pogear::rt {

// Usage: CsvWriter w(path, {"t [s]", "omega_c [rad/s]", "F_ps [N]"}); check w.ok(); then w.row(t, x)
// or field()...end_row() per sample; finally commit() or commit_incomplete(reason). Destroyed
// without either, it removes PATH.tmp, so a crashed or abandoned run never leaves a half-written
// file, and never touches an existing PATH. Errors (open, write, rename) end up in error().
class CsvWriter {
 public:
  CsvWriter(std::string path, const std::vector<std::string>& columns)
      : path_(std::move(path)), tmp_(path_ + ".tmp") {
    file_ = std::fopen(tmp_.c_str(), "wb");
    if (!file_) {
      set_error("cannot open for writing");
      return;
    }
    std::setvbuf(file_, nullptr, _IONBF, 0);  // rows are already buffered here, in large chunks
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
  ~CsvWriter() {
    if (file_) std::fclose(file_);
    if (!committed_) std::remove(tmp_.c_str());
  }

  bool ok() const { return error_.empty(); }
  const std::string& error() const { return error_; }
  const std::string& path() const { return path_; }

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

  void set_error(const char* what) {
    if (error_.empty()) error_ = tmp_ + ": " + what + ": " + std::strerror(errno);
  }
  void write_buffer() {
    if (file_ && ok() && !buf_.empty() && std::fwrite(buf_.data(), 1, buf_.size(), file_) != buf_.size())
      set_error("write failed");
    buf_.clear();
  }
  bool finish() {
    if (!file_) return false;
    write_buffer();
    if (std::fflush(file_) != 0) set_error("write failed");
    if (std::fclose(file_) != 0) set_error("close failed");
    file_ = nullptr;
    // rename() replaces PATH atomically on POSIX file systems: readers see the old or the new file.
    if (ok() && std::rename(tmp_.c_str(), path_.c_str()) != 0) set_error("cannot rename to final path");
    committed_ = ok();
    return committed_;
  }

  std::string path_, tmp_, buf_, error_;
  std::FILE* file_ = nullptr;
  bool in_row_ = false, committed_ = false;
};

}  // namespace pogear::rt
