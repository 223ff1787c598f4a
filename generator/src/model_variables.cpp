// Variable names are a prefix and a body or mesh name; recognizing one compares it with the
// names the model has, so `omega_` of a body named `x_y` and a mesh `y` can never be confused.
#include "model_variables.hpp"

#include <array>

namespace pogear {
namespace {

struct KindText {
  std::string_view prefix, unit;
};

KindText text_of(VariableKind kind) {
  switch (kind) {
    case VariableKind::velocity: return {"omega_", "rad/s"};
    case VariableKind::acceleration: return {"domega_", "rad/s^2"};
    case VariableKind::torque: return {"tau_", "N m"};
    case VariableKind::force: return {"F_", "N"};
    case VariableKind::force_rate: return {"dF_", "N/s"};
    case VariableKind::mesh_velocity: return {"v_", "m/s"};
    case VariableKind::transmitted_force: return {"w_", "N"};
  }
  return {"", ""};
}

constexpr std::array all_kinds{VariableKind::velocity,  VariableKind::acceleration,  VariableKind::torque,
                               VariableKind::force,     VariableKind::force_rate,    VariableKind::mesh_velocity,
                               VariableKind::transmitted_force};

}  // namespace

bool of_body(VariableKind kind) {
  return kind == VariableKind::velocity || kind == VariableKind::acceleration || kind == VariableKind::torque;
}

std::string variable_name(const Topology& t, Variable v) {
  const std::string& owner = of_body(v.kind) ? t.bodies.at(static_cast<std::size_t>(v.index)).name
                                             : t.meshes.at(static_cast<std::size_t>(v.index)).name;
  return std::string(text_of(v.kind).prefix) + owner;
}

Variable derivative_of(Variable state) {
  return {state.kind == VariableKind::force ? VariableKind::force_rate : VariableKind::acceleration, state.index};
}

std::string_view unit_of(VariableKind kind) { return text_of(kind).unit; }

std::optional<Variable> find_variable(const Topology& t, std::string_view name,
                                      std::initializer_list<VariableKind> kinds) {
  for (const VariableKind kind : kinds) {
    const std::size_t count = of_body(kind) ? t.bodies.size() : t.meshes.size();
    for (std::size_t i = 0; i < count; ++i) {
      const Variable v{kind, static_cast<int>(i)};
      if (variable_name(t, v) == name) return v;
    }
  }
  return std::nullopt;
}

std::optional<Variable> find_variable(const Topology& t, std::string_view name) {
  for (const VariableKind kind : all_kinds)
    if (auto v = find_variable(t, name, {kind})) return v;
  return std::nullopt;
}

}  // namespace pogear
