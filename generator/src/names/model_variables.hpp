// The variables of a model's equations (velocities, torques, mesh forces, their derivatives and the
// generated code's mesh temporaries), named and recognized in one place: no name is parsed back.
#pragma once

#include <compare>
#include <optional>
#include <string>
#include <string_view>

#include "names/model.hpp"

namespace pogear {

enum class VariableKind {
  velocity,           // omega_<body> [rad/s]
  acceleration,       // domega_<body> = d omega/dt [rad/s^2]
  torque,             // tau_<body> [N m], an input
  force,              // F_<mesh> [N], positive from the first terminal to the second
  force_rate,         // dF_<mesh> = dF/dt [N/s]
  mesh_velocity,      // v_<mesh> = R omega, a temporary of the generated rhs [m/s]
  transmitted_force,  // w_<mesh> = F + b v, the force a damped mesh passes on [N], a temporary of the rhs
  spring_force,       // Fspring_<mesh> = F, the elastic model's spring force alone [N], an output
  friction_torque,    // Tf_<element> [N m]: a brake's or clutch's torque, -T on its first body, +T on its second
  load_torque,        // TL_<body> [N m]: a scene's load on the body (its constant part, an input)
  controller_torque,  // Tc_<controller> [N m]: a speed controller's torque on its body
  controller_integral,  // theta_<controller> [rad]: the integral of its speed error, a state
  controller_error,   // e_<controller> = d theta/dt [rad/s]: set-point less measured speed
  set_point,          // ref_<controller> [rad/s]: its set-point, an input
  vehicle_speed,         // vehicle_speed [km/h]: a scene's [vehicle], r_w omega_wheels, an output
  vehicle_acceleration,  // vehicle_acceleration [m/s^2]: its derivative, an output
  vehicle_jerk,          // vehicle_jerk [m/s^3]: the acceleration's derivative, an output of the elastic model
  engine_torque,   // Tengine [N m]: a scene's [engine], its map's torque on its body, an input the run computes
  pump_torque,     // Tpump [N m]: a scene's [converter], its torque on the pump (-T_p in drive), likewise
  turbine_torque,  // Tturbine [N m]: its torque on the turbine (TR T_p in drive), likewise
};

// A variable of body or mesh `index`, as the kind says.
struct Variable {
  VariableKind kind = VariableKind::velocity;
  int index = 0;
  friend auto operator<=>(const Variable&, const Variable&) = default;
};

// velocity, acceleration, torque and load_torque are of a body; friction_torque of a friction element;
// controller_* and set_point of a controller; the others of a mesh.
bool of_body(VariableKind kind);
bool of_controller(VariableKind kind);
bool of_vehicle(VariableKind kind);  // a scene's [vehicle]: named here, index 0
bool of_driveline(VariableKind kind);  // a scene's [engine] and [converter]: named here, index 0
// How many variables of this kind the model has (its bodies, meshes or friction elements; none of
// a controller's kinds: controllers are a scene's, not the model's).
std::size_t variable_count(const Topology& t, VariableKind kind);
// A model variable's name; a controller's variable has none here (std::logic_error): its name is
// its symbol's, made by add_controller_symbols (symbols.hpp).
// A shaft's variables (a row of R like a mesh's) are torques and twist rates: T_<shaft> [N m],
// dT_, v_ [rad/s], w_ and Tspring_ [N m].
std::string variable_name(const Topology& t, Variable v);
std::string_view unit_of(const Topology& t, Variable v);  // SI, as CSV headers write it: "rad/s", "N", ...

// A controller's variable (a controller_* or set_point kind) by the controller's name.
std::string controller_variable_name(VariableKind kind, std::string_view controller);

// Names outside the equations' variables. A brake's or clutch's torque, slip and dissipated energy
// as the reports and the simulations' CSV files print them (T_, slip_; the runtime writes E_), and
// the default name of its capacity parameter, Tcap_, which is not its torque.
std::string element_torque_name(std::string_view element);
// The torque the housing holds a fixed body with: T_<body> (a brake or clutch never has that name:
// the model file refuses it).
std::string fixed_body_torque_name(std::string_view body);
std::string element_slip_name(std::string_view element);
std::string capacity_parameter_name(std::string_view element);
// A quadratic load's torque -c omega |omega| on a body, a temporary TQ_ of the generated rhs.
std::string quadratic_load_name(std::string_view body);

// d/dt of a velocity (an acceleration) or of a force (a force rate); outputs read them.
Variable derivative_of(Variable state);

// The variable of the model that `name` denotes, found among the model's own names, or nothing.
std::optional<Variable> find_variable(const Topology& t, std::string_view name);
// The same, only among the given kinds (a scene's [initial] takes omega_ and F_, its inputs tau_).
std::optional<Variable> find_variable(const Topology& t, std::string_view name,
                                      std::initializer_list<VariableKind> kinds);

}  // namespace pogear
