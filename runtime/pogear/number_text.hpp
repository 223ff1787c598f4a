// Numbers as text in the runtime's messages and command lines: read whole, written short.
#pragma once

#include <charconv>
#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <system_error>

namespace pogear::rt::detail {

// A number in messages: ten significant digits, the shortest form that shows them.
inline std::string num(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v, std::chars_format::general, 10).ptr);
}

// The whole of `text` as a finite number, or nothing: "1e-6x", "0.05ms", "", "inf" and "nan" are
// not numbers here (atof would have read a prefix, or 0).
inline std::optional<double> parse_finite(std::string_view text) {
  double v = 0;
  const char* end = text.data() + text.size();
  const auto [ptr, ec] = std::from_chars(text.data(), end, v);
  if (ec != std::errc{} || ptr != end || !std::isfinite(v)) return std::nullopt;
  return v;
}

// The shortest text that reads back as exactly `v`.
inline std::string shortest(double v) {
  char buf[32];
  return std::string(buf, std::to_chars(buf, buf + sizeof buf, v).ptr);
}

}  // namespace pogear::rt::detail
