// Errors in users' input files, carrying the position they refer to, and their one-line form
// `FILE:LINE:COL: error: what is wrong; what to do`.
#pragma once

#include <stdexcept>
#include <string>

#include <fmt/format.h>

namespace pogear {

struct SourceLocation {
  std::string file;
  int line = 0;    // 1-based; 0 when the error concerns the whole file
  int column = 0;  // 1-based; 0 when unknown
};

class InputError : public std::runtime_error {
 public:
  InputError(SourceLocation where, const std::string& message)
      : std::runtime_error(format(where, message)), where_(std::move(where)), message_(message) {}
  const SourceLocation& where() const { return where_; }
  const std::string& message() const { return message_; }

  static std::string format(const SourceLocation& where, const std::string& message) {
    if (where.line > 0 && where.column > 0)
      return fmt::format("{}:{}:{}: error: {}", where.file, where.line, where.column, message);
    if (where.line > 0) return fmt::format("{}:{}: error: {}", where.file, where.line, message);
    return fmt::format("{}: error: {}", where.file, message);
  }

 private:
  SourceLocation where_;
  std::string message_;
};

// Moves a location `offset` characters to the right, for positions inside a quoted value.
inline SourceLocation shifted(SourceLocation where, int offset) {
  if (where.column > 0) where.column += offset;
  return where;
}

}  // namespace pogear
