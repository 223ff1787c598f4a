// See tunable_parameters.hpp: the parameters' texts are parsed again symbolically, with the
// tunables as symbols, and each result checked against the number the model's evaluation gave.
#include "specialize/tunable_parameters.hpp"

#include <cmath>
#include <functional>
#include <set>

#include <fmt/format.h>

#include "common/exact_algebra.hpp"

namespace pogear {

namespace {

// Floating-point numbers of a parsed expression ("4.8" reads as one) as the exact rationals of
// their doubles, like every other number pogear puts into the algebra.
GiNaC::ex exact_numbers(const GiNaC::ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e)) {
    const GiNaC::numeric& v = GiNaC::ex_to<GiNaC::numeric>(e);
    return v.is_rational() ? e : GiNaC::ex(exact_number(v.to_double()));
  }
  return e.map([](const GiNaC::ex& op) { return exact_numbers(op); });
}

}  // namespace

std::map<std::string, GiNaC::ex> tunable_dependents(const std::vector<Parameter>& parameters,
                                                    const std::vector<std::string>& tunables, const SymbolTable& symbols) {
  std::map<std::string, const Parameter*> by_name;
  for (const auto& p : parameters) by_name[p.name] = &p;
  const std::set<std::string> tunable(tunables.begin(), tunables.end());
  std::map<std::string, GiNaC::ex> value;  // every parameter visited: a number, a tunable or an expression
  std::map<std::string, GiNaC::ex> dependents;
  // evaluate_parameters has ruled out cycles and unknown names; the recursion follows its order.
  std::function<GiNaC::ex(const Parameter&)> visit = [&](const Parameter& p) -> GiNaC::ex {
    if (auto it = value.find(p.name); it != value.end()) return it->second;
    if (tunable.count(p.name)) return value[p.name] = parameter_symbol(symbols, p.name);
    GiNaC::symtab table;
    bool follows = false;
    for (const auto& ref : referenced_names(p.text)) {
      auto it = by_name.find(ref);
      if (it == by_name.end()) continue;
      const GiNaC::ex v = visit(*it->second);
      follows = follows || !GiNaC::is_a<GiNaC::numeric>(v);
      table[ref] = v;
    }
    if (!follows) return value[p.name] = exact_number(p.value.si);
    // The units among the text's names, at their SI values (a unit never names a parameter).
    for (std::size_t i = 0; i < p.text.size();) {
      std::size_t j = i;
      while (j < p.text.size() && (std::isalnum(static_cast<unsigned char>(p.text[j])) || p.text[j] == '_')) ++j;
      if (j == i) {
        ++i;
        continue;
      }
      const std::string id = p.text.substr(i, j - i);
      if (is_unit_name(id)) table[id] = exact_number(evaluate_quantity(id, {}, p.where, 0).si);
      i = j;
    }
    // GiNaC's grammar is the quantity parser's but for a power of a signed exponent (`2^-1*b`
    // is 2^(-b) to GiNaC): a result that misses the parameter's own value is refused, not used.
    GiNaC::ex e;
    bool same = false;
    try {
      e = exact_numbers(GiNaC::parser(table, true)(p.text)).expand();
      GiNaC::exmap at_values;
      for (const auto& t : tunables)
        if (auto it = by_name.find(t); it != by_name.end()) at_values[parameter_symbol(symbols, t)] = exact_number(it->second->value.si);
      const GiNaC::ex v = GiNaC::evalf(e.subs(at_values, GiNaC::subs_options::no_pattern));
      same = GiNaC::is_a<GiNaC::numeric>(v) &&
             std::abs(GiNaC::ex_to<GiNaC::numeric>(v).to_double() - p.value.si) <= 1e-12 * std::abs(p.value.si);
    } catch (const std::exception&) {
    }
    if (!same)
      throw InputError(shifted(p.where, p.column_offset),
                       fmt::format("parameter '{}' is defined through a tunable parameter, and pogear cannot keep "
                                   "this expression symbolic; put a signed exponent in parentheses, e.g. 2^(-1), "
                                   "or make '{}' tunable itself", p.name, p.name));
    dependents[p.name] = e;
    return value[p.name] = e;
  };
  for (const auto& p : parameters) visit(p);
  return dependents;
}

std::optional<std::pair<std::string, double>> written_unit(const Parameter& p) {
  const std::string& text = p.text;
  const auto star = text.find('*');
  if (star == std::string::npos) return std::nullopt;
  std::string unit = text.substr(star + 1);
  while (!unit.empty() && unit.back() == ' ') unit.pop_back();
  while (!unit.empty() && unit.front() == ' ') unit.erase(0, 1);
  const std::vector<std::string> names = referenced_names(unit);
  if (unit.empty() || !names.empty()) return std::nullopt;  // names a parameter: not a unit alone
  try {
    const double number = evaluate_quantity(text.substr(0, star), {}, p.where, 0).si;
    const Quantity q = evaluate_quantity(unit, {}, p.where, 0);
    if (!q.has_unit || number == 0 || std::abs(number * q.si - p.value.si) > 1e-12 * std::abs(p.value.si))
      return std::nullopt;  // not NUMBER*UNIT after all, e.g. "2*3*cm"
    return std::pair{unit, q.si};
  } catch (const InputError&) {
    return std::nullopt;
  }
}

std::vector<std::pair<std::string, double>> common_unit_spellings(const Dimension& dimension) {
  // Per quantity the model files use: stiffness, damping, inertia, length, torque, bearing
  // friction, speed, mass, capacity. A spelling applies where its dimension is the parameter's.
  static const char* const candidates[] = {"N/m",    "N/mm",   "kN/mm",  "N*s/m",  "N*s/mm", "kg*m^2", "kg*mm^2",
                                           "m",      "cm",     "mm",     "N*m",    "Nm",     "kN*m",   "N*m*s",
                                           "Nm/rpm", "rad/s",  "rpm",    "kg",     "g"};
  std::vector<std::pair<std::string, double>> out;
  for (const char* text : candidates) {
    try {
      const Quantity q = evaluate_quantity(text, {}, SourceLocation{}, 0);
      if (q.has_unit && q.dimension == dimension) out.emplace_back(text, q.si);
    } catch (const InputError&) {
      // A spelling this build's unit table does not know: not offered.
    }
  }
  return out;
}

}  // namespace pogear
