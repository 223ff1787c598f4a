// Sums print in the paper's order (fewest symbols first, then alphabetically: J_c before
// J_p r_c^2/r_p^2); products print their coefficient first, then factors by name.
#include "printer.hpp"

#include <algorithm>
#include <limits>
#include <optional>
#include <set>
#include <sstream>
#include <vector>

#include <fmt/format.h>

namespace pogear {
namespace {

using GiNaC::ex;
using GiNaC::numeric;

// Integers print the same way every run; only sums and products need our ordering.
std::string digits(const numeric& v) {
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
    for (const ex& f : e) add_factor(f);
  } else {
    add_factor(e);
  }
  return t;
}

void count_symbols(const ex& e, std::set<std::string>& names) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    names.insert(GiNaC::ex_to<GiNaC::symbol>(e).get_name());
    return;
  }
  for (const ex& op : e) count_symbols(op, names);
}

class Printer {
 public:
  explicit Printer(Notation n) : n_(n) {}

  std::string print(const ex& e) const {
    if (GiNaC::is_a<GiNaC::relational>(e)) {
      const char* op = n_ == Notation::latex ? " = " : (n_ == Notation::ginac ? "==" : " == ");
      return print(e.op(0)) + op + print(e.op(1));
    }
    if (GiNaC::is_a<GiNaC::add>(e)) return sum(e);
    return term(canonical(split_term(e)));
  }

 private:
  std::string symbol_name(const ex& e) const {
    const std::string name = GiNaC::ex_to<GiNaC::symbol>(e).get_name();
    return n_ == Notation::latex ? latex_symbol(name) : name;
  }

  std::string number(const numeric& v) const {
    if (n_ == Notation::cpp) return cpp_double(v.to_double());
    if (v.is_integer()) return digits(v);
    if (v.is_rational()) {
      if (n_ == Notation::latex) return fmt::format("\\frac{{{}}}{{{}}}", digits(v.numer()), digits(v.denom()));
      return digits(v.numer()) + "/" + digits(v.denom());
    }
    return fmt::format("{}", v.to_double());
  }

  // A factor that must stand alone in a product: parenthesize sums.
  std::string atom(const ex& e) const {
    if (GiNaC::is_a<GiNaC::symbol>(e)) return symbol_name(e);
    if (GiNaC::is_a<numeric>(e)) {
      const numeric& v = GiNaC::ex_to<numeric>(e);
      const std::string s = number(v);
      return (v.is_negative() || (!v.is_integer() && n_ != Notation::cpp)) ? paren(s) : s;
    }
    if (GiNaC::is_a<GiNaC::function>(e)) return function(e);
    if (e.is_equal(GiNaC::Pi)) return n_ == Notation::latex ? "\\pi" : (n_ == Notation::cpp ? "3.141592653589793" : "Pi");
    return paren(print(e));
  }

  std::string paren(const std::string& s) const {
    return n_ == Notation::latex ? "\\left(" + s + "\\right)" : "(" + s + ")";
  }

  std::string function(const ex& e) const {
    std::string s = GiNaC::ex_to<GiNaC::function>(e).get_name();
    s += "(";
    for (std::size_t i = 0; i < e.nops(); ++i) s += (i ? ", " : "") + print(e.op(i));
    return s + ")";
  }

  std::string raised(const Factor& f) const {
    const numeric p = GiNaC::abs(f.exponent);
    const std::string base = atom(f.base);
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

  std::string product(const std::vector<std::string>& parts) const {
    std::string s;
    const char* sep = n_ == Notation::latex ? " " : "*";
    for (const auto& p : parts) s += (s.empty() ? "" : sep) + p;
    return s;
  }

  // GiNaC's normal() may return -(a - b) in one run and (b - a) in the next. Fix the sign of
  // every sum factor so that its first term in our order is positive.
  Term canonical(Term t) const {
    for (auto& f : t.factors) {
      if (!GiNaC::is_a<GiNaC::add>(f.base)) continue;
      std::optional<ex> first;  // by value: GiNaC's iterators hand out temporaries
      std::pair<std::size_t, std::string> best;
      for (const ex& op : f.base) {
        Term u = split_term(op);
        std::set<std::string> names;
        count_symbols(op, names);
        u.coefficient = 1;
        std::pair<std::size_t, std::string> key{names.size(), magnitude(u)};
        if (u.factors.empty()) key.first = std::numeric_limits<std::size_t>::max();  // numbers last
        if (!first || key < best) {
          first = op;
          best = key;
        }
      }
      if (!first || !split_term(*first).coefficient.is_negative()) continue;
      if (!f.exponent.is_integer()) continue;
      f.base = (-f.base).expand();
      if (f.exponent.is_odd()) t.coefficient = -t.coefficient;
    }
    return t;
  }

  // Prints |term| (the sign is the caller's).
  std::string magnitude(const Term& t) const {
    std::vector<const Factor*> up, down;
    for (const auto& f : t.factors) (f.exponent.is_negative() ? down : up).push_back(&f);
    // Parameters first, then compound factors, then the variables (tau, omega, d omega/dt):
    // J_p r_r1 domega_r and (J_c r_p^2 + J_p r_c^2) domega_c, as the paper writes them.
    auto rank = [](const Factor* f) {
      if (!GiNaC::is_a<GiNaC::symbol>(f->base)) return 1;
      const std::string& n = GiNaC::ex_to<GiNaC::symbol>(f->base).get_name();
      const bool variable = n.rfind("tau_", 0) == 0 || n.rfind("omega_", 0) == 0 || n.rfind("domega_", 0) == 0;
      return variable ? 2 : 0;
    };
    auto order = [&](const Factor* a, const Factor* b) {
      if (rank(a) != rank(b)) return rank(a) < rank(b);
      return print(a->base) < print(b->base);
    };
    std::sort(up.begin(), up.end(), order);
    std::sort(down.begin(), down.end(), order);

    const numeric c = GiNaC::abs(t.coefficient);
    std::vector<std::string> num, den;
    if (n_ == Notation::cpp) {
      // One correctly rounded double, not numerator/denominator (exact rationals are long).
      if (c != 1 || up.empty()) num.push_back(number(c));
    } else if (c.is_rational()) {
      if (c.numer() != 1 || up.empty()) num.push_back(number(c.numer()));
      if (c.denom() != 1) den.push_back(number(c.denom()));
    } else {
      num.push_back(number(c));
    }
    for (const Factor* f : up) num.push_back(raised(*f));
    for (const Factor* f : down) den.push_back(raised(*f));
    // A lone coefficient 1 in front of factors is dropped above; restore it for "1/x".
    if (num.empty()) num.push_back(n_ == Notation::cpp ? "1.0" : "1");
    const std::string top = product(num);
    if (den.empty()) return top;
    const std::string bottom = product(den);
    if (n_ == Notation::latex) return fmt::format("\\frac{{{}}}{{{}}}", top, bottom);
    return top + "/" + (bottom.find_first_of("*/") != std::string::npos ? "(" + bottom + ")" : bottom);
  }

  std::string term(const Term& t) const {
    const std::string m = magnitude(t);
    return t.coefficient.is_negative() ? "-" + m : m;
  }

  std::string sum(const ex& e) const {
    struct Keyed {
      std::size_t symbols;
      std::string body;
      Term term;
    };
    std::vector<Keyed> terms;
    for (const ex& op : e) {
      Term t = canonical(split_term(op));
      std::set<std::string> names;
      count_symbols(op, names);
      Term unit = t;
      unit.coefficient = 1;
      terms.push_back({names.size(), magnitude(unit), std::move(t)});
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
      const std::string m = magnitude(terms[i].term);
      const bool negative = terms[i].term.coefficient.is_negative();
      if (i == 0) s = negative ? "-" + m : m;
      else s += spaced ? (negative ? " - " : " + ") + m : (negative ? "-" : "+") + m;
    }
    return s;
  }

  Notation n_;
};

}  // namespace

std::string print_expression(const GiNaC::ex& e, Notation notation) { return Printer(notation).print(e); }

std::string latex_symbol(const std::string& name) {
  static const std::set<std::string> greek{"alpha", "beta", "gamma", "delta", "omega", "tau", "theta", "phi"};
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

std::string cpp_double(double v) {
  std::string s = fmt::format("{}", v);
  if (s.find_first_of(".eEn") == std::string::npos) s += ".0";
  return s;
}

}  // namespace pogear
