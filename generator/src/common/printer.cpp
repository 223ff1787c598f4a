// Sums print in the paper's order (fewest symbols first, then alphabetically: J_c before
// J_p r_c^2/r_p^2); products print their coefficient first, then factors by name.
#include "common/printer.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <unordered_map>
#include <vector>

#include <fmt/format.h>

#include "common/exact_algebra.hpp"

namespace pogear {
namespace {

using GiNaC::ex;
using GiNaC::numeric;

// Integers print the same way every run; only sums and products need our ordering.
std::string digits(const numeric& v) {
  static const numeric small(1000000000000000000L);  // fits a long: no stream needed
  if (v.is_integer() && GiNaC::abs(v) < small) return fmt::format("{}", v.to_long());
  std::ostringstream os;
  os << v;
  return os.str();
}

struct Factor {
  ex base;
  numeric exponent;  // nonzero
};

// A monomial: coefficient times factors.
struct Term {
  numeric coefficient{1};
  std::vector<Factor> factors;
};

Term split_term(const ex& e) {
  Term t;
  auto add_factor = [&](const ex& f) {
    if (GiNaC::is_a<numeric>(f)) {
      t.coefficient *= GiNaC::ex_to<numeric>(f);
    } else if (GiNaC::is_a<GiNaC::power>(f) && GiNaC::is_a<numeric>(f.op(1))) {
      t.factors.push_back({f.op(0), GiNaC::ex_to<numeric>(f.op(1))});
    } else {
      t.factors.push_back({f, numeric(1)});
    }
  };
  if (GiNaC::is_a<GiNaC::mul>(e)) {
    t.factors.reserve(e.nops());
    for (const ex& f : e) add_factor(f);
  } else {
    add_factor(e);
  }
  return t;
}

// How many different symbols e holds. Symbols are told apart by identity (GiNaC's order), which
// is much cheaper than by name and the same: pogear has one symbol per name (symbols.hpp).
std::size_t count_symbols(const ex& e) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return 1;
  GiNaC::exvector found;
  for (GiNaC::const_preorder_iterator it = e.preorder_begin(); it != e.preorder_end(); ++it)
    if (GiNaC::is_a<GiNaC::symbol>(*it)) found.push_back(*it);
  std::sort(found.begin(), found.end(), GiNaC::ex_is_less());
  return static_cast<std::size_t>(std::unique(found.begin(), found.end(), GiNaC::ex_is_equal()) - found.begin());
}

// One printer per expression. It remembers what it printed: the ordering keys print every
// factor, and a sum that is a factor is printed again, so without the memory the work grows
// with the nesting depth times the size.
class Printer {
 public:
  Printer(Notation n, const GiNaC::exset& last) : n_(n), last_(last) {}

  std::string print(const ex& e) {
    if (GiNaC::is_a<GiNaC::symbol>(e) && n_ != Notation::latex) return GiNaC::ex_to<GiNaC::symbol>(e).get_name();
    const auto known = printed_.find(e);
    if (known != printed_.end()) return known->second;
    std::string s;
    if (GiNaC::is_a<GiNaC::symbol>(e)) {
      s = latex_symbol(GiNaC::ex_to<GiNaC::symbol>(e).get_name());
    } else if (GiNaC::is_a<GiNaC::relational>(e)) {
      const char* op = n_ == Notation::latex ? " = " : (n_ == Notation::ginac ? "==" : " == ");
      s = print(e.op(0)) + op + print(e.op(1));
    } else if (GiNaC::is_a<GiNaC::add>(e)) {
      s = sum(e);
    } else if (GiNaC::is_a<GiNaC::function>(e)) {
      s = function(e);  // a term of one factor would print that factor again
    } else {
      s = term(canonical(split_term(e)));
    }
    printed_.emplace(e, s);
    return s;
  }

 private:
  // A term's factors printed and in order, numerator and denominator, without the coefficient.
  struct Parts {
    std::vector<std::string> up, down;
  };

  std::string number(const numeric& v) const {
    if (n_ == Notation::cpp) return cpp_double(v.to_double());
    if (v.is_integer()) return digits(v);
    if (v.is_rational()) {
      if (n_ == Notation::latex) return fmt::format("\\frac{{{}}}{{{}}}", digits(v.numer()), digits(v.denom()));
      return digits(v.numer()) + "/" + digits(v.denom());
    }
    return fmt::format("{}", v.to_double());
  }

  // A factor that must stand alone in a product: parenthesize sums. `printed` is print(e); a
  // symbol, a function and Pi print as themselves.
  std::string atom(const ex& e, const std::string& printed) {
    if (GiNaC::is_a<numeric>(e)) {
      const numeric& v = GiNaC::ex_to<numeric>(e);
      const std::string s = number(v);
      return (v.is_negative() || (!v.is_integer() && n_ != Notation::cpp)) ? paren(s) : s;
    }
    if (GiNaC::is_a<GiNaC::symbol>(e)) return printed;
    if (GiNaC::is_a<GiNaC::function>(e)) return function(e);
    if (e.is_equal(GiNaC::Pi)) return n_ == Notation::latex ? "\\pi" : (n_ == Notation::cpp ? "3.141592653589793" : "Pi");
    return paren(printed);
  }

  std::string paren(const std::string& s) const {
    return n_ == Notation::latex ? "\\left(" + s + "\\right)" : "(" + s + ")";
  }

  std::string function(const ex& e) {
    std::string name = GiNaC::ex_to<GiNaC::function>(e).get_name();
    std::string args;
    for (std::size_t i = 0; i < e.nops(); ++i) args += (i ? ", " : "") + print(e.op(i));
    if (n_ == Notation::cpp && name == "abs") return "std::abs(" + args + ")";  // a quadratic load's omega |omega|
    if (n_ != Notation::latex) return name + "(" + args + ")";
    // The closed-form eigenvalues of a cubic (vibration_modes.cpp) use cos and acos.
    if (name == "cos" || name == "sin") name = "\\" + name;
    else if (name == "acos") name = "\\arccos";
    else name = "\\operatorname{" + name + "}";
    return name + "\\left(" + args + "\\right)";
  }

  std::string raised(const Factor& f, const std::string& printed_base) {
    const numeric p = GiNaC::abs(f.exponent);
    const std::string base = atom(f.base, printed_base);
    if (p == 1) return base;
    if (n_ == Notation::cpp) {
      if (p.is_integer() && p <= 4) {
        std::string s = base;
        for (int i = 1; i < p.to_int(); ++i) s += "*" + base;
        return s;
      }
      return fmt::format("std::pow({}, {})", base, cpp_double(p.to_double()));
    }
    if (n_ == Notation::latex) return fmt::format("{}^{{{}}}", base, p.is_integer() ? digits(p) : number(p));
    return base + "^" + (p.is_integer() ? digits(p) : "(" + number(p) + ")");
  }

  void append_product(std::string& s, const std::vector<std::string>& parts) const {
    const char* sep = n_ == Notation::latex ? " " : "*";
    for (std::size_t i = 0; i < parts.size(); ++i) {
      if (i) s += sep;
      s += parts[i];
    }
  }

  // GiNaC's normal() may return -(a - b) in one run and (b - a) in the next. Fix the sign of
  // every sum factor so that its first term in our order is positive.
  Term canonical(Term t) {
    for (auto& f : t.factors) {
      if (!GiNaC::is_a<GiNaC::add>(f.base)) continue;
      std::optional<ex> first;  // by value: GiNaC's iterators hand out temporaries
      std::pair<std::size_t, std::string> best;
      for (const ex& op : f.base) {
        const Term u = split_term(op);
        std::pair<std::size_t, std::string> key{count_symbols(op), compose(numeric(1), parts(u))};
        if (u.factors.empty()) key.first = std::numeric_limits<std::size_t>::max();  // numbers last
        if (!first || key < best) {
          first = op;
          best = std::move(key);
        }
      }
      if (!first || !split_term(*first).coefficient.is_negative()) continue;
      if (!f.exponent.is_integer()) continue;
      f.base = (-f.base).expand();
      if (f.exponent.is_odd()) t.coefficient = -t.coefficient;
    }
    return t;
  }

  Parts parts(const Term& t) {
    // Parameters first, then compound factors, then the variables the caller names (printed_last):
    // J_p r_r1 domega_r and (J_c r_p^2 + J_p r_c^2) domega_c, as the paper writes them.
    struct Keyed {
      int rank;
      std::string base;  // printed
      const Factor* factor;
    };
    auto rank = [&](const ex& base) {
      if (!GiNaC::is_a<GiNaC::symbol>(base)) return 1;
      return last_.count(base) ? 2 : 0;
    };
    std::vector<Keyed> up, down;
    for (const auto& f : t.factors)
      (f.exponent.is_negative() ? down : up).push_back({rank(f.base), print(f.base), &f});
    auto order = [](const Keyed& a, const Keyed& b) {
      if (a.rank != b.rank) return a.rank < b.rank;
      return a.base < b.base;
    };
    std::sort(up.begin(), up.end(), order);
    std::sort(down.begin(), down.end(), order);
    Parts p;
    p.up.reserve(up.size());
    p.down.reserve(down.size());
    for (const auto& k : up) p.up.push_back(raised(*k.factor, k.base));
    for (const auto& k : down) p.down.push_back(raised(*k.factor, k.base));
    return p;
  }

  // Prints c times the factors, c > 0.
  std::string compose(const numeric& c, const Parts& p) const {
    std::vector<std::string> num, den;
    if (n_ == Notation::cpp) {
      // One correctly rounded double, not numerator/denominator (exact rationals are long).
      if (c != 1 || p.up.empty()) num.push_back(number(c));
    } else if (c.is_rational()) {
      if (c.numer() != 1 || p.up.empty()) num.push_back(number(c.numer()));
      if (c.denom() != 1) den.push_back(number(c.denom()));
    } else {
      num.push_back(number(c));
    }
    // A lone coefficient 1 in front of factors is dropped above; it is restored for "1/x".
    std::string top;
    append_product(top, num);
    if (!num.empty() && !p.up.empty()) top += n_ == Notation::latex ? " " : "*";
    append_product(top, p.up);
    if (top.empty()) top = n_ == Notation::cpp ? "1.0" : "1";
    if (den.empty() && p.down.empty()) return top;
    std::string bottom;
    append_product(bottom, den);
    if (!den.empty() && !p.down.empty()) bottom += n_ == Notation::latex ? " " : "*";
    append_product(bottom, p.down);
    if (n_ == Notation::latex) return fmt::format("\\frac{{{}}}{{{}}}", top, bottom);
    // A product or quotient below the bar needs parentheses; a lone parenthesized sum has them.
    int depth = 0;
    bool compound = false;
    for (char ch : bottom) {
      depth += ch == '(' ? 1 : ch == ')' ? -1 : 0;
      compound = compound || (depth == 0 && (ch == '*' || ch == '/'));
    }
    if (compound) return top + "/(" + bottom + ")";
    return top + "/" + bottom;
  }

  std::string term(const Term& t) {
    const std::string m = compose(GiNaC::abs(t.coefficient), parts(t));
    return t.coefficient.is_negative() ? "-" + m : m;
  }

  std::string sum(const ex& e) {
    struct Keyed {
      std::size_t symbols;
      std::string body;
      Term term;
      Parts parts;
    };
    std::vector<Keyed> terms;
    terms.reserve(e.nops());
    for (const ex& op : e) {
      Term t = canonical(split_term(op));
      Parts p = parts(t);
      std::string body = compose(numeric(1), p);
      terms.push_back({count_symbols(op), std::move(body), std::move(t), std::move(p)});
    }
    std::sort(terms.begin(), terms.end(), [](const Keyed& a, const Keyed& b) {
      // A bare number goes last, as people write it.
      const bool na = a.term.factors.empty(), nb = b.term.factors.empty();
      if (na != nb) return nb;
      if (a.symbols != b.symbols) return a.symbols < b.symbols;
      if (a.body != b.body) return a.body < b.body;
      return a.term.coefficient < b.term.coefficient;
    });
    // Lead with a positive term where there is one: r_cb*r_s1 - 2*r_ca*r_s1 reads better.
    const auto first_positive = std::find_if(terms.begin(), terms.end(),
                                             [](const Keyed& k) { return !k.term.coefficient.is_negative(); });
    if (first_positive != terms.end()) std::rotate(terms.begin(), first_positive, first_positive + 1);
    const bool spaced = n_ != Notation::ginac;
    std::string s;
    for (std::size_t i = 0; i < terms.size(); ++i) {
      const numeric& c = terms[i].term.coefficient;
      const bool negative = c.is_negative();
      if (i == 0) s += negative ? "-" : "";
      else s += spaced ? (negative ? " - " : " + ") : (negative ? "-" : "+");
      // |c| = 1 prints the same as the key already made.
      if (GiNaC::abs(c) == 1) s += terms[i].body;
      else s += compose(GiNaC::abs(c), terms[i].parts);
    }
    return s;
  }

  Notation n_;
  const GiNaC::exset& last_;
  std::unordered_map<ex, std::string, std::hash<ex>, GiNaC::ex_is_equal> printed_;
};

}  // namespace

std::string print_expression(const GiNaC::ex& e, Notation notation) { return Printer(notation, {}).print(e); }

std::string print_expression(const GiNaC::ex& e, Notation notation, const GiNaC::exset& printed_last) {
  return Printer(notation, printed_last).print(e);
}

std::string latex_symbol(const std::string& name) {
  static const std::set<std::string> greek{"alpha", "beta", "gamma", "delta", "omega", "tau", "theta", "phi", "lambda"};
  std::string base = name;
  std::string sub;
  if (auto pos = name.find('_'); pos != std::string::npos) {
    base = name.substr(0, pos);
    sub = name.substr(pos + 1);
  }
  std::string out;
  if (base.size() > 1 && base[0] == 'd' && greek.count(base.substr(1))) out = "\\dot{\\" + base.substr(1) + "}";
  else if (greek.count(base)) out = "\\" + base;
  else if (base.size() > 1) out = "\\mathrm{" + base + "}";
  else out = base;
  if (!sub.empty()) {
    std::string escaped;
    for (char c : sub) escaped += (c == '_') ? std::string("\\_") : std::string(1, c);
    out += "_{" + escaped + "}";
  }
  return out;
}

std::string latex_text(std::string_view text) {
  std::string out;
  for (char c : text) {
    switch (c) {
      case '\\': out += "\\textbackslash{}"; break;
      case '^': out += "\\textasciicircum{}"; break;
      case '~': out += "\\textasciitilde{}"; break;
      case '{': case '}': case '$': case '&': case '%': case '#': case '_': out += '\\'; out += c; break;
      default:
        // A control character (a line break in a file name) would end a comment line or a paragraph.
        if (static_cast<unsigned char>(c) < 0x20 || c == 0x7f) out += '?';
        else out += c;
    }
  }
  return out;
}

std::string markdown_text(std::string_view text) {
  std::string out;
  for (char c : text) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    // CommonMark escapes any ASCII punctuation with a backslash; these are the ones that can start
    // emphasis, code, a link, math ($), a table cell, strike-through, an escape or close a heading.
    else if (std::string_view("\\`*_[]#|$~").find(c) != std::string_view::npos) (out += '\\') += c;
    // A line break would end the heading; other control characters have no place in a report.
    else if (u < 0x20 || u == 0x7f) out += ' ';
    else out += c;
  }
  return out;
}

std::string cpp_double(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

std::string joined(const std::vector<std::string>& v, std::string_view separator) {
  return fmt::format("{}", fmt::join(v, separator));
}

std::string text_matrix(const std::string& label, const std::vector<std::vector<std::string>>& m) {
  std::vector<std::size_t> width;
  for (const auto& row : m)
    for (std::size_t j = 0; j < row.size(); ++j) {
      if (width.size() <= j) width.push_back(0);
      width[j] = std::max(width[j], row[j].size());
    }
  std::string s = label + " =\n";
  for (const auto& row : m) {
    s += "  [";
    for (std::size_t j = 0; j < row.size(); ++j) s += fmt::format(" {:<{}}", row[j], width[j]);
    s += " ]\n";
  }
  return s;
}

std::string latex_matrix(const std::vector<std::vector<std::string>>& m) {
  std::string s = "\\begin{bmatrix}\n";
  for (const auto& row : m) s += "  " + joined(row, " & ") + " \\\\\n";
  return s + "\\end{bmatrix}";
}

std::string latex_vector(const std::vector<std::string>& v) {
  return "\\begin{bmatrix} " + joined(v, " \\\\ ") + " \\end{bmatrix}";
}

std::string markdown_table(const std::vector<std::string>& header, const std::vector<std::vector<std::string>>& rows) {
  auto line = [](const std::vector<std::string>& r) {
    std::string s = "|";
    for (const auto& cell : r) {
      s += ' ';
      for (char c : cell) s += c == '|' ? std::string("\\|") : std::string(1, c);
      s += " |";
    }
    return s + "\n";
  };
  std::string s = line(header) + "|";
  for (std::size_t i = 0; i < header.size(); ++i) s += "---|";
  s += "\n";
  for (const auto& r : rows) s += line(r);
  return s + "\n";
}

std::string six_digits(double v) { return fmt::format("{:.6g}", v == 0.0 ? 0.0 : v); }

}  // namespace pogear
