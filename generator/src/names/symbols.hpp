// The GiNaC symbols of one model, made once from its topology: GiNaC tells symbols apart by
// identity, not by name, so every stage draws them from this table, and a lookup never makes one.
#pragma once

#include <map>
#include <vector>
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
// A scene's speed controllers add their variables (theta_, e_, ref_, Tc_ of each, by index) to the
// table of the model they are closed around.
void add_controller_symbols(SymbolTable& s, const std::vector<std::string>& controllers);
// A scene's [vehicle]: vehicle_speed, vehicle_acceleration and vehicle_jerk.
void add_vehicle_symbols(SymbolTable& s);
// A scene's [engine] and [converter]: Tengine, Tpump and Tturbine.
void add_driveline_symbols(SymbolTable& s);

// The symbol of a parameter or a variable of the table; a name the table lacks is a bug of pogear
// (the readers check every name), reported as std::logic_error.
const GiNaC::realsymbol& parameter_symbol(const SymbolTable& s, const std::string& name);
const GiNaC::realsymbol& variable_symbol(const SymbolTable& s, Variable v);
// A variable's name, the controllers' included: its symbol's.
std::string variable_name(const SymbolTable& s, Variable v);

// The bodies' speeds, accelerations and torques, which a printed product puts after the parameters
// (print_expression's printed_last), as the paper writes J_p r_r1 domega_r.
GiNaC::exset body_variable_symbols(const SymbolTable& s);

// Substitutes numeric SI values, as exact rationals, for the parameters named.
GiNaC::exmap numeric_substitutions(const SymbolTable& s, const std::map<std::string, double>& values);

}  // namespace pogear
