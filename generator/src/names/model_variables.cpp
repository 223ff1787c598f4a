// Variable names are a prefix and a body or mesh name; recognizing one compares it with the
// names the model has, so `omega_` of a body named `x_y` and a mesh `y` can never be confused.
#include "names/model_variables.hpp"

#include <array>
#include <stdexcept>

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
    case VariableKind::spring_force: return {"Fspring_", "N"};
    case VariableKind::friction_torque: return {"Tf_", "N m"};
    case VariableKind::load_torque: return {"TL_", "N m"};
    case VariableKind::controller_torque: return {"Tc_", "N m"};
    case VariableKind::controller_integral: return {"theta_", "rad"};
    case VariableKind::controller_error: return {"e_", "rad/s"};
    case VariableKind::set_point: return {"ref_", "rad/s"};
    case VariableKind::vehicle_speed: return {"vehicle_speed", "km/h"};
    case VariableKind::vehicle_acceleration: return {"vehicle_acceleration", "m/s^2"};
    case VariableKind::vehicle_jerk: return {"vehicle_jerk", "m/s^3"};
    case VariableKind::engine_torque: return {"Tengine", "N m"};
    case VariableKind::pump_torque: return {"Tpump", "N m"};
    case VariableKind::turbine_torque: return {"Tturbine", "N m"};
  }
  return {"", ""};
}

constexpr std::array all_kinds{VariableKind::velocity,  VariableKind::acceleration,  VariableKind::torque,
                               VariableKind::force,     VariableKind::force_rate,    VariableKind::mesh_velocity,
                               VariableKind::transmitted_force, VariableKind::spring_force, VariableKind::friction_torque,
                               VariableKind::load_torque, VariableKind::controller_torque,
                               VariableKind::controller_integral, VariableKind::controller_error,
                               VariableKind::set_point};

}  // namespace

bool of_body(VariableKind kind) {
  return kind == VariableKind::velocity || kind == VariableKind::acceleration || kind == VariableKind::torque ||
         kind == VariableKind::load_torque;
}

bool of_vehicle(VariableKind kind) {
  return kind == VariableKind::vehicle_speed || kind == VariableKind::vehicle_acceleration ||
         kind == VariableKind::vehicle_jerk;
}

bool of_driveline(VariableKind kind) {
  return kind == VariableKind::engine_torque || kind == VariableKind::pump_torque || kind == VariableKind::turbine_torque;
}

bool of_controller(VariableKind kind) {
  return kind == VariableKind::controller_torque || kind == VariableKind::controller_integral ||
         kind == VariableKind::controller_error || kind == VariableKind::set_point;
}

std::size_t variable_count(const Topology& t, VariableKind kind) {
  if (kind == VariableKind::friction_torque) return t.friction_elements.size();
  if (of_controller(kind) || of_vehicle(kind) || of_driveline(kind)) return 0;  // a scene's
  return of_body(kind) ? t.bodies.size() : t.meshes.size();
}

namespace {

// A shaft's row of R has no radius: its "force" is a torque and its "mesh velocity" a twist rate.
KindText shaft_text(VariableKind kind) {
  switch (kind) {
    case VariableKind::force: return {"T_", "N m"};
    case VariableKind::force_rate: return {"dT_", "N m/s"};
    case VariableKind::mesh_velocity: return {"v_", "rad/s"};
    case VariableKind::transmitted_force: return {"w_", "N m"};
    case VariableKind::spring_force: return {"Tspring_", "N m"};
    default: return text_of(kind);
  }
}

bool of_shaft(const Topology& t, Variable v) {
  return !of_body(v.kind) && !of_controller(v.kind) && !of_vehicle(v.kind) && !of_driveline(v.kind) &&
         v.kind != VariableKind::friction_torque &&
         t.meshes.at(static_cast<std::size_t>(v.index)).shaft;
}

}  // namespace

std::string variable_name(const Topology& t, Variable v) {
  if (of_vehicle(v.kind) || of_driveline(v.kind)) return std::string(text_of(v.kind).prefix);
  if (of_controller(v.kind))
    throw std::logic_error("a controller's variable is the scene's: its name comes from the symbol table");
  const auto i = static_cast<std::size_t>(v.index);
  const std::string& owner = v.kind == VariableKind::friction_torque ? t.friction_elements.at(i).name
                             : of_body(v.kind)                       ? t.bodies.at(i).name
                                                                     : t.meshes.at(i).name;
  return std::string((of_shaft(t, v) ? shaft_text(v.kind) : text_of(v.kind)).prefix) + owner;
}

std::string controller_variable_name(VariableKind kind, std::string_view controller) {
  return std::string(text_of(kind).prefix) + std::string(controller);
}

std::string element_torque_name(std::string_view element) { return "T_" + std::string(element); }

std::string fixed_body_torque_name(std::string_view body) { return "T_" + std::string(body); }
std::string element_slip_name(std::string_view element) { return "slip_" + std::string(element); }
std::string capacity_parameter_name(std::string_view element) { return "Tcap_" + std::string(element); }
std::string quadratic_load_name(std::string_view body) { return "TQ_" + std::string(body); }

Variable derivative_of(Variable state) {
  if (state.kind == VariableKind::controller_integral) return {VariableKind::controller_error, state.index};
  return {state.kind == VariableKind::force ? VariableKind::force_rate : VariableKind::acceleration, state.index};
}

std::string_view unit_of(const Topology& t, Variable v) {
  if (of_controller(v.kind) || of_vehicle(v.kind) || of_driveline(v.kind)) return text_of(v.kind).unit;
  return (of_shaft(t, v) ? shaft_text(v.kind) : text_of(v.kind)).unit;
}

std::optional<Variable> find_variable(const Topology& t, std::string_view name,
                                      std::initializer_list<VariableKind> kinds) {
  for (const VariableKind kind : kinds) {
    const std::size_t count = variable_count(t, kind);
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
