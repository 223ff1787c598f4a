// The symbol table: one symbol per parameter name and per variable, made in a fixed order.
#include "names/symbols.hpp"

#include <algorithm>
#include <stdexcept>

namespace pogear {

SymbolTable make_symbol_table(const Topology& t) {
  SymbolTable s;
  auto parameter = [&](const std::string& name) {
    if (!name.empty() && !s.parameters.count(name)) s.parameters.emplace(name, GiNaC::realsymbol(name));
  };
  // GiNaC orders terms by when their symbols were made, and the expressions pogear prints (normal
  // forms among them) follow that order: the file's parameters by name, then the radii the
  // geometry derives, then the variables, as the stages have always met them.
  std::vector<std::string> given;
  for (const auto& p : t.parameters) given.push_back(p.name);
  std::sort(given.begin(), given.end());
  for (const auto& name : given) parameter(name);
  for (const Body* b : every_body(t)) {
    parameter(b->inertia_parameter);
    parameter(b->friction_parameter);
    parameter(b->distance_parameter);
    for (const auto& w : b->wheels) parameter(w.radius_parameter);
  }
  for (const auto& m : t.meshes) {
    if (!m.shaft) {
      parameter(contact_radius(t, m, m.first));
      parameter(contact_radius(t, m, m.second));
    }
    parameter(m.stiffness_parameter);
    parameter(m.damping_parameter);
  }
  for (const VariableKind kind : {VariableKind::torque, VariableKind::acceleration, VariableKind::velocity,
                                  VariableKind::force, VariableKind::force_rate, VariableKind::mesh_velocity,
                                  VariableKind::transmitted_force, VariableKind::spring_force, VariableKind::friction_torque,
                                  VariableKind::load_torque}) {
    const std::size_t count = variable_count(t, kind);
    for (std::size_t i = 0; i < count; ++i) {
      const Variable v{kind, static_cast<int>(i)};
      s.variables.emplace(v, GiNaC::realsymbol(variable_name(t, v)));
    }
  }
  return s;
}

void add_controller_symbols(SymbolTable& s, const std::vector<std::string>& controllers) {
  for (const VariableKind kind : {VariableKind::controller_torque, VariableKind::controller_integral,
                                  VariableKind::controller_error, VariableKind::set_point})
    for (std::size_t c = 0; c < controllers.size(); ++c)
      s.variables.emplace(Variable{kind, static_cast<int>(c)}, GiNaC::realsymbol(controller_variable_name(kind, controllers[c])));
}

void add_vehicle_symbols(SymbolTable& s) {
  for (const VariableKind kind : {VariableKind::vehicle_speed, VariableKind::vehicle_acceleration, VariableKind::vehicle_jerk})
    s.variables.emplace(Variable{kind, 0}, GiNaC::realsymbol(variable_name(Topology{}, {kind, 0})));
}

void add_driveline_symbols(SymbolTable& s) {
  for (const VariableKind kind : {VariableKind::engine_torque, VariableKind::pump_torque, VariableKind::turbine_torque})
    s.variables.emplace(Variable{kind, 0}, GiNaC::realsymbol(variable_name(Topology{}, {kind, 0})));
}

std::string variable_name(const SymbolTable& s, Variable v) { return variable_symbol(s, v).get_name(); }

const GiNaC::realsymbol& parameter_symbol(const SymbolTable& s, const std::string& name) {
  const auto it = s.parameters.find(name);
  if (it == s.parameters.end()) throw std::logic_error("no symbol for the parameter '" + name + "'");
  return it->second;
}

const GiNaC::realsymbol& variable_symbol(const SymbolTable& s, Variable v) {
  const auto it = s.variables.find(v);
  if (it == s.variables.end()) throw std::logic_error("no symbol for a variable of kind " + std::to_string(static_cast<int>(v.kind)));
  return it->second;
}

GiNaC::exset body_variable_symbols(const SymbolTable& s) {
  GiNaC::exset last;
  for (const auto& [v, symbol] : s.variables)
    if (v.kind == VariableKind::velocity || v.kind == VariableKind::acceleration || v.kind == VariableKind::torque)
      last.insert(symbol);
  return last;
}

GiNaC::exmap numeric_substitutions(const SymbolTable& s, const std::map<std::string, double>& values) {
  GiNaC::exmap m;
  for (const auto& [name, v] : values) m[parameter_symbol(s, name)] = exact_number(v);
  return m;
}

}  // namespace pogear
