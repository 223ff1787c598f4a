// The one way text enters generated C++: a CppText is made only by the functions here, each of
// which makes its input safe for the place it names (a comment, a string literal, an identifier).
#pragma once

#include <concepts>
#include <string>
#include <string_view>
#include <type_traits>
#include <vector>

#include <fmt/format.h>
#include <ginac/ginac.h>

namespace pogear {

class CppText;
namespace cpp_text_detail {
struct Maker;  // the functions below, and nothing in codegen, make CppText from plain text
}

class CppText {
 public:
  CppText() = default;
  const std::string& str() const { return text_; }
  CppText& operator+=(const CppText& more) {
    text_ += more.text_;
    return *this;
  }
  friend CppText operator+(CppText a, const CppText& b) { return a += b; }
  bool empty() const { return text_.empty(); }

 private:
  friend struct cpp_text_detail::Maker;
  explicit CppText(std::string text) : text_(std::move(text)) {}
  std::string text_;
};

namespace cpp_text_detail {
struct Maker {
  static CppText make(std::string text) { return CppText(std::move(text)); }
};
}  // namespace cpp_text_detail

}  // namespace pogear

template <>
struct fmt::formatter<pogear::CppText> : fmt::formatter<std::string_view> {
  template <class Context>
  auto format(const pogear::CppText& t, Context& ctx) const {
    return fmt::formatter<std::string_view>::format(t.str(), ctx);
  }
};

namespace pogear {

// C++ keywords and the macros of the headers generated code includes: no name in it can be one.
bool is_cpp_reserved(const std::string& name);

// Any text, readable inside a `//` or `/* */` comment: no line break, control character or
// backslash (a `\` at a line's end would continue the comment onto the next line), no `*/`;
// those and every non-ASCII character are shown as <U+XXXX> (<0xNN> for bytes that are not UTF-8).
CppText comment_text(std::string_view text);
// Any text as a string literal, quotes included, with `"`, `\` and every byte outside printable
// ASCII escaped (three-digit octal, so no following character can extend an escape).
CppText string_literal(std::string_view text);
// A name used as a C++ identifier: letters, digits and '_', not starting with a digit, not a
// keyword. Throws std::invalid_argument otherwise (the readers check every name before this).
CppText identifier(std::string_view name);
// The shortest round-trip decimal; throws std::invalid_argument for inf and NaN.
CppText number_code(double v);
// An expression in C++ (print_expression, `printed_last` after the other factors), its symbols checked as identifiers, its numbers
// finite; throws std::invalid_argument otherwise.
CppText expression_code(const GiNaC::ex& e, const GiNaC::exset& printed_last);

// Generated code from a fixed pattern (a literal of codegen) and CppText pieces only: a raw
// std::string or a number does not compile here, so no user text can slip in unconverted.
template <class... Args>
CppText code(fmt::format_string<Args...> pattern, Args&&... args)
  requires(std::same_as<std::remove_cvref_t<Args>, CppText> && ...)
{
  return cpp_text_detail::Maker::make(fmt::format(pattern, std::forward<Args>(args)...));
}

// An integer (a size, an index) as code.
CppText integer_code(long long v);

// The parts with `separator` between them (a list, lines).
CppText join(const std::vector<CppText>& parts, const CppText& separator);

}  // namespace pogear
