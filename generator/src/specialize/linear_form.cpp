// See linear_form.hpp: each term of an expanded row is matched to the one variable it holds.
#include "specialize/linear_form.hpp"

#include <map>

namespace pogear {
namespace {

using GiNaC::ex;

using VariableIndex = std::map<ex, int, GiNaC::ex_is_less>;

// Whether e holds any of the variables.
bool has_variable(const ex& e, const VariableIndex& vars) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return vars.count(e) > 0;
  for (const ex& op : e)
    if (has_variable(op, vars)) return true;
  return false;
}

// The variable a term of an expanded linear form is proportional to: -1 for none, -2 when the
// term is not of the form (variable-free factors) * variable.
int variable_of(const ex& term, const VariableIndex& vars) {
  if (GiNaC::is_a<GiNaC::symbol>(term)) {
    const auto it = vars.find(term);
    return it == vars.end() ? -1 : it->second;
  }
  if (!GiNaC::is_exactly_a<GiNaC::mul>(term)) return has_variable(term, vars) ? -2 : -1;
  int found = -1;
  for (const ex& factor : term) {
    const auto it = GiNaC::is_a<GiNaC::symbol>(factor) ? vars.find(factor) : vars.end();
    if (it != vars.end()) {
      if (found != -1) return -2;
      found = it->second;
    } else if (has_variable(factor, vars)) {
      return -2;
    }
  }
  return found;
}

}  // namespace

GiNaC::matrix linear_coefficients(const std::vector<ex>& rows, const std::vector<ex>& variables) {
  VariableIndex index;
  for (std::size_t j = 0; j < variables.size(); ++j) index.emplace(variables[j], static_cast<int>(j));
  GiNaC::matrix coefficients(rows.size(), variables.size());
  for (std::size_t i = 0; i < rows.size(); ++i) {
    const ex f = rows[i].expand();
    std::vector<GiNaC::exvector> parts(variables.size());
    bool linear = true;
    auto take = [&](const ex& term) {
      const int v = variable_of(term, index);
      if (v == -2) linear = false;
      if (v >= 0) parts[v].push_back(term.diff(GiNaC::ex_to<GiNaC::symbol>(variables[v])));
    };
    if (GiNaC::is_exactly_a<GiNaC::add>(f)) {
      for (const ex& term : f) take(term);
    } else {
      take(f);
    }
    for (std::size_t j = 0; j < variables.size(); ++j)
      coefficients(i, j) = !linear ? f.diff(GiNaC::ex_to<GiNaC::symbol>(variables[j]))
                           : parts[j].empty() ? ex(0) : GiNaC::add(parts[j]);
  }
  return coefficients;
}

void linear_form(const SymbolTable& s, SpecializedSystem& sys) {
  GiNaC::exmap temps;
  for (const auto& a : sys.rhs_temporaries) temps[a.symbol] = a.value.subs(temps, GiNaC::subs_options::no_pattern);
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size();
  std::vector<ex> variables, rows;
  for (const StatePort& x : sys.states) variables.push_back(variable_symbol(s, x.variable));
  for (const InputPort& u : sys.inputs) variables.push_back(variable_symbol(s, u.variable));
  for (const ex& row : sys.rhs) rows.push_back(row.subs(temps, GiNaC::subs_options::no_pattern));
  const GiNaC::matrix coefficients = linear_coefficients(rows, variables);
  sys.M = GiNaC::matrix(nx, nx);
  sys.N = GiNaC::matrix(nx, nu);
  for (std::size_t i = 0; i < nx; ++i)
    for (std::size_t j = 0; j < nx + nu; ++j) {
      if (j < nx) sys.M(i, j) = coefficients(i, j); else sys.N(i, j - nx) = coefficients(i, j);
    }
}

}  // namespace pogear
