// A small recursive-descent parser for parameter expressions. GiNaC's own parser reports every
// syntax error at line 0, column 0; this one knows the column of each token and bounds depth.
#include "common/quantity.hpp"

#include <charconv>
#include <cmath>
#include <numbers>
#include <vector>

#include <fmt/format.h>

namespace pogear {
namespace {

constexpr Dimension dim(int m, int kg, int s, int K = 0) { return Dimension{{m, kg, s, K}}; }

struct Unit {
  std::string_view name;
  double si;
  Dimension dimension;
};

constexpr double pi = std::numbers::pi;
constexpr std::array<Unit, 26> units{{
    {"m", 1.0, dim(1, 0, 0)},         {"meter", 1.0, dim(1, 0, 0)},
    {"meters", 1.0, dim(1, 0, 0)},    {"metre", 1.0, dim(1, 0, 0)},
    {"cm", 1e-2, dim(1, 0, 0)},       {"mm", 1e-3, dim(1, 0, 0)},
    {"kg", 1.0, dim(0, 1, 0)},        {"gram", 1e-3, dim(0, 1, 0)},
    {"s", 1.0, dim(0, 0, 1)},         {"ms", 1e-3, dim(0, 0, 1)},
    {"minute", 60.0, dim(0, 0, 1)},   {"Hz", 1.0, dim(0, 0, -1)},
    {"kHz", 1e3, dim(0, 0, -1)},
    {"N", 1.0, dim(1, 1, -2)},        {"Newton", 1.0, dim(1, 1, -2)},
    {"kN", 1e3, dim(1, 1, -2)},       {"Nm", 1.0, dim(2, 1, -2)},
    {"rad", 1.0, dim(0, 0, 0)},       {"deg", pi / 180.0, dim(0, 0, 0)},
    {"rev", 2.0 * pi, dim(0, 0, 0)},  {"rpm", 2.0 * pi / 60.0, dim(0, 0, -1)},
    {"pi", pi, dim(0, 0, 0)},         {"J", 1.0, dim(2, 1, -2)},
    {"W", 1.0, dim(2, 1, -3)},
    // Temperature differences; an absolute temperature in K or degC is told apart by its unit's name
    // (read/thermal_table.cpp).
    {"K", 1.0, dim(0, 0, 0, 1)},      {"degC", 1.0, dim(0, 0, 0, 1)},
}};

const Unit* find_unit(std::string_view name) {
  for (const auto& u : units)
    if (u.name == name) return &u;
  return nullptr;
}

Dimension operator+(Dimension a, const Dimension& b) {
  for (std::size_t i = 0; i < a.exponent.size(); ++i) a.exponent[i] += b.exponent[i];
  return a;
}
Dimension operator-(Dimension a, const Dimension& b) {
  for (std::size_t i = 0; i < a.exponent.size(); ++i) a.exponent[i] -= b.exponent[i];
  return a;
}
Dimension scaled(Dimension a, int k) {
  for (auto& e : a.exponent) e *= k;
  return a;
}

bool is_ident_start(char c) { return std::isalpha(static_cast<unsigned char>(c)) || c == '_'; }
bool is_ident_char(char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; }

class Parser {
 public:
  Parser(std::string_view text, const std::map<std::string, Quantity>& known, SourceLocation where,
         int column_offset)
      : text_(text), known_(known), where_(std::move(where)), offset_(column_offset) {}

  Quantity parse() {
    skip_space();
    if (pos_ == text_.size()) fail(pos_, "empty expression; write a number with its unit, e.g. 4.8*cm");
    Quantity q = expression(0);
    skip_space();
    if (pos_ != text_.size()) {
      if (const std::string why = non_ascii(pos_); !why.empty()) fail(pos_, why);
      fail(pos_, fmt::format("unexpected '{}'; join factors with '*', e.g. 4.8*cm", text_[pos_]));
    }
    return q;
  }

 private:
  [[noreturn]] void fail(std::size_t at, const std::string& message) const {
    throw InputError(shifted(where_, offset_ + static_cast<int>(at)), message);
  }

  // The complaint about a character outside ASCII at `at`, whole (not its first byte, which alone
  // prints as garbage), with its code point and the ASCII it stands for; "" for ASCII.
  std::string non_ascii(std::size_t at) const {
    const auto byte = [&](std::size_t i) { return static_cast<unsigned char>(text_[i]); };
    if (byte(at) < 0x80) return "";
    std::size_t length = byte(at) >= 0xF0 ? 4 : byte(at) >= 0xE0 ? 3 : byte(at) >= 0xC0 ? 2 : 1;
    char32_t code = length == 4 ? byte(at) & 0x07 : length == 3 ? byte(at) & 0x0F : byte(at) & 0x1F;
    bool valid = length > 1 && at + length <= text_.size();
    for (std::size_t i = 1; valid && i < length; ++i) {
      valid = (byte(at + i) & 0xC0) == 0x80;
      code = (code << 6) | (byte(at + i) & 0x3F);
    }
    if (!valid) return fmt::format("byte 0x{:02X} is not text (not UTF-8); write the expression in ASCII", byte(at));
    const std::string shown(text_.substr(at, length));
    const auto codepoint = static_cast<unsigned>(code);
    // Invisible characters (a byte-order mark, zero-width and no-break spaces, direction marks and
    // overrides, C1 controls) are named, never echoed: raw, they show nothing in the message or,
    // worse, reorder the text around them.
    const bool invisible = (code >= 0x80 && code <= 0xA0) || code == 0xAD || (code >= 0x200B && code <= 0x200F) ||
                           (code >= 0x2028 && code <= 0x202F) || (code >= 0x2060 && code <= 0x206F) || code == 0xFEFF;
    if (invisible)
      return fmt::format("invisible character U+{:04X}{}; delete it: expressions are written in ASCII", codepoint,
                         code == 0xFEFF ? " (a byte-order mark)" : code == 0xA0 ? " (a no-break space)" : "");
    if (code == 0x2212 || code == 0x2013 || code == 0x2012 || code == 0x2010)
      return fmt::format("'{}' (U+{:04X}) is not the minus sign of expressions; write the ASCII '-'", shown, codepoint);
    if (code == 0x00D7 || code == 0x22C5 || code == 0x00B7)
      return fmt::format("'{}' (U+{:04X}) is not the multiplication of expressions; write the ASCII '*'", shown,
                         codepoint);
    return fmt::format("unexpected '{}' (U+{:04X}); expressions are written in ASCII, e.g. 4.8*cm", shown, codepoint);
  }
  void skip_space() {
    while (pos_ < text_.size() && (text_[pos_] == ' ' || text_[pos_] == '\t')) ++pos_;
  }
  bool accept(char c) {
    skip_space();
    if (pos_ < text_.size() && text_[pos_] == c) {
      ++pos_;
      return true;
    }
    return false;
  }
  // Every operation's result is checked where it happens, so the message points at the operator
  // that overflowed: GiNaC and the exact rationals downstream cannot take inf or NaN.
  Quantity checked(Quantity q, std::size_t at) const {
    if (!std::isfinite(q.si))
      fail(at, "the value here is not a finite number (an overflow, or a negative number to a fractional "
               "power); write numbers of a physical size");
    for (int e : q.dimension.exponent)
      if (std::abs(e) > max_unit_power)
        fail(at, fmt::format("the unit {} has a power above {}; no physical parameter has such a unit",
                             describe(q.dimension), max_unit_power));
    return q;
  }
  void enter(int depth) const {
    if (depth > max_expression_depth)
      fail(pos_, fmt::format("expression nested deeper than {} levels; simplify it", max_expression_depth));
  }

  // The left-associative chain `q (op operand)*` over the operators `ops`: `combine` reads
  // the operand after `op` (at `at`) and gives the result so far.
  template <class Combine>
  Quantity chain(Quantity q, std::string_view ops, Combine combine) {
    for (;;) {
      skip_space();
      const std::size_t at = pos_;
      char op = 0;
      for (char c : ops)
        if (op == 0 && accept(c)) op = c;
      if (op == 0) return q;
      q = combine(q, op, at);
    }
  }

  Quantity expression(int depth) {
    enter(depth);
    return chain(term(depth + 1), "+-", [&](const Quantity& q, char op, std::size_t at) {
      return checked(add(q, term(depth + 1), at, op == '+' ? +1 : -1), at);
    });
  }

  Quantity add(const Quantity& a, const Quantity& b, std::size_t at, int sign) const {
    // A bare number has no dimension to check (it is SI by convention), so it adds to anything.
    if (a.has_unit && b.has_unit && !(a.dimension == b.dimension))
      fail(at, fmt::format("adds {} to {}; both sides of '{}' need the same unit", describe(b.dimension),
                           describe(a.dimension), sign > 0 ? '+' : '-'));
    Quantity r;
    r.si = a.si + sign * b.si;
    r.has_unit = a.has_unit || b.has_unit;
    r.dimension = a.has_unit ? a.dimension : b.dimension;
    return r;
  }

  Quantity term(int depth) {
    enter(depth);
    return chain(unary(depth + 1), "*/", [&](const Quantity& q, char op, std::size_t at) {
      if (op == '*') {
        if (pos_ < text_.size() && text_[pos_] == '*') fail(pos_, "'**' is not a power; write '^'");
        Quantity b = unary(depth + 1);
        return checked(Quantity{q.si * b.si, q.dimension + b.dimension, q.has_unit || b.has_unit}, at);
      }
      Quantity b = unary(depth + 1);
      if (b.si == 0.0) fail(at, "division by zero: the divisor is 0; check the value or the parameter it names");
      return checked(Quantity{q.si / b.si, q.dimension - b.dimension, q.has_unit || b.has_unit}, at);
    });
  }

  Quantity unary(int depth) {
    enter(depth);
    if (accept('-')) {
      Quantity q = unary(depth + 1);
      q.si = -q.si;
      return q;
    }
    if (accept('+')) return unary(depth + 1);
    return power(depth + 1);
  }

  Quantity power(int depth) {
    enter(depth);
    Quantity base = primary(depth + 1);
    skip_space();
    const std::size_t at = pos_;
    if (!accept('^')) return base;
    Quantity exponent = unary(depth + 1);
    if (exponent.has_unit && !(exponent.dimension == Dimension{}))
      fail(at + 1, "an exponent must be a plain number");
    const double rounded = std::round(exponent.si);
    if (base.has_unit && !(base.dimension == Dimension{})) {
      if (rounded != exponent.si || std::abs(rounded) > 16)
        fail(at + 1, "a unit can only be raised to a whole power between -16 and 16");
      return checked(Quantity{std::pow(base.si, rounded), scaled(base.dimension, static_cast<int>(rounded)), true}, at);
    }
    return checked(Quantity{std::pow(base.si, exponent.si), base.dimension, base.has_unit}, at);
  }

  Quantity primary(int depth) {
    enter(depth);
    skip_space();
    if (pos_ >= text_.size()) fail(pos_, "the expression ends too early; a number, unit or name is missing");
    const char c = text_[pos_];
    if (c == '(') {
      const std::size_t open = pos_++;
      Quantity q = expression(depth + 1);
      if (!accept(')')) fail(open, "this '(' is never closed");
      return q;
    }
    if (std::isdigit(static_cast<unsigned char>(c)) || c == '.') return number();
    if (is_ident_start(c)) return name();
    if (const std::string why = non_ascii(pos_); !why.empty()) fail(pos_, why);
    fail(pos_, fmt::format("unexpected '{}'; expected a number, a unit or a parameter name", c));
  }

  Quantity number() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() &&
           (std::isdigit(static_cast<unsigned char>(text_[pos_])) || text_[pos_] == '.'))
      ++pos_;
    if (pos_ < text_.size() && (text_[pos_] == 'e' || text_[pos_] == 'E')) {
      std::size_t p = pos_ + 1;
      if (p < text_.size() && (text_[p] == '+' || text_[p] == '-')) ++p;
      if (p < text_.size() && std::isdigit(static_cast<unsigned char>(text_[p]))) {
        pos_ = p;
        while (pos_ < text_.size() && std::isdigit(static_cast<unsigned char>(text_[pos_]))) ++pos_;
      }
    }
    double v = 0.0;
    const auto* first = text_.data() + start;
    const auto* last = text_.data() + pos_;
    const auto r = std::from_chars(first, last, v);
    if (r.ec != std::errc() || r.ptr != last || !std::isfinite(v))
      fail(start, fmt::format("'{}' is not a number", std::string_view(first, last - first)));
    return Quantity{v, Dimension{}, false};
  }

  Quantity name() {
    const std::size_t start = pos_;
    while (pos_ < text_.size() && is_ident_char(text_[pos_])) ++pos_;
    const std::string id(text_.substr(start, pos_ - start));
    if (const Unit* u = find_unit(id)) return Quantity{u->si, u->dimension, true};
    if (auto it = known_.find(id); it != known_.end()) return it->second;
    fail(start, fmt::format("unknown unit or parameter '{}'; units are {}, or name a parameter of this model",
                            id, known_units_list()));
  }

  std::string_view text_;
  const std::map<std::string, Quantity>& known_;
  SourceLocation where_;
  int offset_;
  std::size_t pos_ = 0;
};

}  // namespace

std::string describe(const Dimension& d) {
  static constexpr std::array<const char*, 4> names{"m", "kg", "s", "K"};
  std::string num, den;
  // kg first reads like the usual "kg*m^2"
  for (int i : {1, 0, 2, 3}) {
    const int e = d.exponent[i];
    if (e == 0) continue;
    std::string& side = e > 0 ? num : den;
    side += fmt::format("{}{}", side.empty() ? "" : "*", names[i]);
    if (std::abs(e) != 1) side += fmt::format("^{}", std::abs(e));
  }
  if (num.empty() && den.empty()) return "no unit";
  if (den.find('*') != std::string::npos) den = "(" + den + ")";  // J/K: kg*m^2/(s^2*K)
  return den.empty() ? num : fmt::format("{}/{}", num.empty() ? "1" : num, den);
}

Dimension length_dimension() { return dim(1, 0, 0); }
Dimension inertia_dimension() { return dim(2, 1, 0); }
Dimension rotational_damping_dimension() { return dim(2, 1, -1); }
Dimension stiffness_dimension() { return dim(0, 1, -2); }
Dimension linear_damping_dimension() { return dim(0, 1, -1); }
Dimension torque_dimension() { return dim(2, 1, -2); }
Dimension angular_velocity_dimension() { return dim(0, 0, -1); }
Dimension force_dimension() { return dim(1, 1, -2); }
Dimension time_dimension() { return dim(0, 0, 1); }
Dimension temperature_dimension() { return dim(0, 0, 0, 1); }
Dimension heat_capacity_dimension() { return dim(2, 1, -2, -1); }
Dimension thermal_conductance_dimension() { return dim(2, 1, -3, -1); }

Quantity evaluate_quantity(std::string_view text, const std::map<std::string, Quantity>& known,
                           const SourceLocation& where, int column_offset) {
  if (text.size() > max_expression_length)
    throw InputError(where, fmt::format("expression longer than {} characters; split it into parameters that "
                                        "name each other", max_expression_length));
  return Parser(text, known, where, column_offset).parse();
}

namespace {

// The identifiers of an expression that are units (or not), in order of appearance.
std::vector<std::string> identifiers(std::string_view text, bool units) {
  std::vector<std::string> names;
  std::size_t i = 0;
  while (i < text.size()) {
    if (is_ident_start(text[i]) && (i == 0 || !(is_ident_char(text[i - 1]) || text[i - 1] == '.'))) {
      std::size_t j = i;
      while (j < text.size() && is_ident_char(text[j])) ++j;
      std::string id(text.substr(i, j - i));
      const bool exponent_of_number = (id == "e" || id == "E");
      if ((find_unit(id) != nullptr) == units && !exponent_of_number) names.push_back(std::move(id));
      i = j;
    } else {
      ++i;
    }
  }
  return names;
}

}  // namespace

std::vector<std::string> referenced_names(std::string_view text) { return identifiers(text, false); }
std::vector<std::string> referenced_units(std::string_view text) { return identifiers(text, true); }

bool is_unit_name(std::string_view name) { return find_unit(name) != nullptr; }

std::string known_units_list() {
  std::string s;
  for (const auto& u : units) {
    if (!s.empty()) s += ", ";
    s += u.name;
  }
  return s;
}

}  // namespace pogear
