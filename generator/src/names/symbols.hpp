// The GiNaC symbols of one model, made once from its topology: GiNaC tells symbols apart by
// identity, not by name, so every stage draws them from this table, and a lookup never makes one.
#pragma once

#include <map>
#include <string>

#include <ginac/ginac.h>

#include "common/exact_algebra.hpp"
#include "names/model_variables.hpp"

namespace pogear {

struct SymbolTable {
  // Every parameter the model file gives or a role names (radii the geometry derives included).
  std::map<std::string, GiNaC::realsymbol> parameters;
  // Every variable of the equations; a parameter of the same name is another symbol.
  std::map<Variable, GiNaC::realsymbol> variables;
};

SymbolTable make_symbol_table(const Topology& t);

// The symbol of a parameter or a variable of the table; a name the table lacks is a bug of pogear
// (the readers check every name), reported as std::logic_error.
const GiNaC::realsymbol& parameter_symbol(const SymbolTable& s, const std::string& name);
const GiNaC::realsymbol& variable_symbol(const SymbolTable& s, Variable v);

// Substitutes numeric SI values, as exact rationals, for the parameters named.
GiNaC::exmap numeric_substitutions(const SymbolTable& s, const std::map<std::string, double>& values);

}  // namespace pogear
