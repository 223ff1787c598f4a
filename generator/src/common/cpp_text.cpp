// Escaping and checking of everything a user wrote that ends up in generated C++: scene and file
// names, paths, titles, parameter and body names, units, and the numbers of expressions.
#include "common/cpp_text.hpp"

#include <algorithm>
#include <cmath>
#include <set>
#include <stdexcept>

#include "common/exact_algebra.hpp"
#include "common/printer.hpp"

namespace pogear {
namespace {

bool printable_ascii(unsigned char c) { return c >= 0x20 && c < 0x7f; }

// The code point of the UTF-8 sequence at text[i] and its length; length 0 when it is not UTF-8.
std::pair<char32_t, std::size_t> decode_utf8(std::string_view text, std::size_t i) {
  const auto byte = [&](std::size_t k) { return static_cast<unsigned char>(text[k]); };
  const unsigned char lead = byte(i);
  std::size_t length = lead >= 0xf0 && lead < 0xf5 ? 4 : lead >= 0xe0 ? 3 : lead >= 0xc2 ? 2 : 0;
  if (lead >= 0xf5) length = 0;
  if (length == 0 || i + length > text.size()) return {0, 0};
  char32_t cp = lead & (0x7f >> length);
  for (std::size_t k = 1; k < length; ++k) {
    if ((byte(i + k) & 0xc0) != 0x80) return {0, 0};
    cp = (cp << 6) | (byte(i + k) & 0x3f);
  }
  const char32_t smallest[] = {0, 0, 0x80, 0x800, 0x10000};
  if (cp < smallest[length] || cp > 0x10ffff || (cp >= 0xd800 && cp <= 0xdfff)) return {0, 0};
  return {cp, length};
}

void check_identifier(std::string_view name) {
  const bool ok = !name.empty() && (std::isalpha(static_cast<unsigned char>(name[0])) || name[0] == '_') &&
                  std::all_of(name.begin(), name.end(), [](char c) {
                    return std::isalnum(static_cast<unsigned char>(c)) || c == '_';
                  });
  if (!ok || is_cpp_reserved(std::string(name)))
    throw std::invalid_argument(fmt::format("'{}' cannot be a C++ identifier", std::string(comment_text(name).str())));
}

void check_symbols(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) check_identifier(GiNaC::ex_to<GiNaC::symbol>(e).get_name());
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    bool finite = false;
    try {  // CLN may signal an overflow of the conversion instead of giving inf
      finite = std::isfinite(GiNaC::ex_to<GiNaC::numeric>(e).to_double());
    } catch (const std::exception&) {
    }
    if (!finite) throw std::invalid_argument("a number of the generated code is not finite as a double");
  }
  for (const GiNaC::ex& op : e) check_symbols(op);
}

}  // namespace

bool is_cpp_reserved(const std::string& name) {
  static const std::set<std::string> reserved{
      "alignas", "alignof", "and", "and_eq", "asm", "auto", "bitand", "bitor", "bool", "break", "case", "catch",
      "char", "char8_t", "char16_t", "char32_t", "class", "compl", "concept", "const", "consteval", "constexpr",
      "constinit", "const_cast", "continue", "co_await", "co_return", "co_yield", "decltype", "default", "delete",
      "do", "double", "dynamic_cast", "else", "enum", "explicit", "export", "extern", "false", "float", "for",
      "friend", "goto", "if", "inline", "int", "long", "mutable", "namespace", "new", "noexcept", "not", "not_eq",
      "nullptr", "operator", "or", "or_eq", "private", "protected", "public", "register", "reinterpret_cast",
      "requires", "return", "short", "signed", "sizeof", "static", "static_assert", "static_cast", "struct",
      "switch", "template", "this", "thread_local", "throw", "true", "try", "typedef", "typeid", "typename",
      "union", "unsigned", "using", "virtual", "void", "volatile", "wchar_t", "while", "xor", "xor_eq",
      "errno", "assert", "stdin", "stdout", "stderr", "EOF", "NULL", "BUFSIZ", "INFINITY", "NAN", "HUGE_VAL",
      "EXIT_SUCCESS", "EXIT_FAILURE", "RAND_MAX"};
  return reserved.count(name) || name.rfind("M_", 0) == 0 || name.rfind("EIGEN_", 0) == 0 || name.rfind("FP_", 0) == 0;
}

CppText comment_text(std::string_view text) {
  std::string out;
  for (std::size_t i = 0; i < text.size();) {
    const auto c = static_cast<unsigned char>(text[i]);
    if (printable_ascii(c) && c != '\\' && !(c == '*' && i + 1 < text.size() && text[i + 1] == '/')) {
      out += static_cast<char>(c);
      ++i;
    } else if (c < 0x80) {
      out += fmt::format("<U+{:04X}>", c);
      ++i;
    } else if (const auto [cp, length] = decode_utf8(text, i); length > 0) {
      out += fmt::format("<U+{:04X}>", static_cast<std::uint32_t>(cp));
      i += length;
    } else {
      out += fmt::format("<0x{:02X}>", c);
      ++i;
    }
  }
  return cpp_text_detail::Maker::make(std::move(out));
}

CppText string_literal(std::string_view text) {
  std::string out = "\"";
  for (const char ch : text) {
    const auto c = static_cast<unsigned char>(ch);
    if (printable_ascii(c) && c != '"' && c != '\\') out += ch;
    else out += fmt::format("\\{:03o}", c);
  }
  return cpp_text_detail::Maker::make(out + "\"");
}

CppText identifier(std::string_view name) {
  check_identifier(name);
  return cpp_text_detail::Maker::make(std::string(name));
}

CppText number_code(double v) {
  if (!std::isfinite(v)) throw std::invalid_argument("a number of the generated code is not finite");
  return cpp_text_detail::Maker::make(cpp_double(v));
}

CppText integer_code(long long v) { return cpp_text_detail::Maker::make(fmt::format("{}", v)); }

CppText join(const std::vector<CppText>& parts, const CppText& separator) {
  CppText s;
  for (std::size_t i = 0; i < parts.size(); ++i) s += (i ? separator : CppText{}) + parts[i];
  return s;
}

CppText expression_code(const GiNaC::ex& e, const GiNaC::exset& printed_last) {
  check_symbols(e);
  return cpp_text_detail::Maker::make(print_expression(e, Notation::cpp, printed_last));
}

}  // namespace pogear
