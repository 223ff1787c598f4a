// Scene files: what to simulate on a model — effects, inputs, initial state, parameter
// overrides and tunables, outputs, horizon, solver — read and checked against the model.
#pragma once

#include <cmath>
#include <limits>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "pogear/driveline.hpp"
#include "pogear/hybrid_observe.hpp"
#include "pogear/signals.hpp"
#include "pogear/solver.hpp"
#include "names/model_variables.hpp"
#include "read/topology.hpp"

namespace pogear {

struct Effects {
  bool mesh_compliance = false;   // the toothed meshes are springs
  bool shaft_compliance = false;  // the shafts are springs
  bool mesh_damping = false;      // the meshes' B_K (needs mesh_compliance)
  bool shaft_damping = false;     // the shafts' B_K (needs shaft_compliance)
  bool bearing_friction = false;  // B_J
  bool mesh_forces = false;       // force and shaft torque outputs
  // The elastic model (meshes and shafts compliant: the scene reader refuses one without the other);
  // without it the rigid model.
  bool elastic() const { return mesh_compliance || shaft_compliance; }
};

// A speed or a slip crossing a value: the magnitude of brake or clutch `slip_of`'s slip, or the
// speed of body `body` (signed, in its arrow's sense), crossing `value` [rad/s] upward or downward.
struct CrossingStart {
  int slip_of = -1;  // index into Topology::friction_elements
  int body = -1;     // index into Topology::bodies
  double value = 0;
  bool upward = false;
};

// A signal that starts on an event (docs/scene-format.md, "Triggered signals"): its times count from
// the instant brake or clutch `element` first slips or sticks after the start, or `crossing` first
// happens, plus `delay` [s]. Until then it is `before`, a signal of time (without one: the value the
// signal has before its own times).
struct SignalStart {
  int element = -1;  // index into Topology::friction_elements; -1 with a crossing
  rt::ElementState state = rt::ElementState::stuck;
  std::optional<CrossingStart> crossing;
  double delay = 0;
  SourceLocation where;
  std::optional<rt::Signal> before;
};

// The signal's value at t = 0: a triggered one's before it starts (rt::held_until_start).
double value_at_start(const rt::Signal& signal, const std::optional<SignalStart>& start);

// An input torque of the scene, in SI units, as the runtime evaluates it.
struct InputSpec {
  int body = -1;  // the driven body; the input is tau_<body>
  rt::Signal signal;
  SourceLocation where;
  std::optional<SignalStart> start;
};

// The engagement command p(t) in [0, 1] of a brake or clutch of the model.
struct EngagementSpec {
  int element = -1;  // index into Topology::friction_elements
  rt::Signal command;
  SourceLocation where;
  std::optional<SignalStart> start;
};

// A brake's or clutch's lumped temperature (scene-format.md, "Temperatures"): heat capacity [J/K],
// conductance to the ambient [W/K] (0: adiabatic), ambient and initial temperatures [degC].
struct ThermalSpec {
  int element = -1;  // index into Topology::friction_elements
  double heat_capacity = 0, conductance = 0, ambient = 0, initial = 0;
  SourceLocation where;
};

// A brake's or clutch's actuator (scene-format.md, "Actuators"): the command reaches the element
// after a fill delay [s], through a first-order lag [s].
struct ActuatorSpec {
  int element = -1;  // index into Topology::friction_elements
  double fill_delay = 0, time_constant = 0;
  SourceLocation where;
};

// A load on a body (scene-format.md, "Loads"): the torque -(constant + linear omega + quadratic
// omega |omega|) in SI units. The constant part is a constant input, the linear one a damping that
// keeps the scene linear, the quadratic one makes it nonlinear.
struct LoadSpec {
  int body = -1;
  double constant = 0, linear = 0, quadratic = 0;
  // The input TL_<body> when the constant part varies in time (a grade's, a GradeLoad of -constant);
  // `constant` is then its value at t = 0.
  std::optional<rt::Signal> varying;
  SourceLocation where;
};

// A scene's [vehicle]: the car and its wheels on half-shafts from `body` through a final drive, as a
// body `vehicle` of the model turning at `body`'s speed scale (read/vehicle_table.hpp).
struct VehicleSpec {
  int body = -1;          // the body that drives the final drive
  int vehicle_body = -1;  // the body the vehicle adds
  double mass = 0, wheel_radius = 0, final_drive = 1, wheel_inertia = 0;
  double rolling_resistance = 0, grade = 0;  // grade: the road's angle [rad], at t = 0 when it varies
  std::optional<rt::Table> grade_table;      // the road's angle [rad] against time, when it varies
  double drag = 0;                           // rho c_d A / 2 [kg/m]
  SourceLocation where;
  // vehicle_speed = r omega_vehicle / i [m/s per rad/s]
  double speed_per_omega() const { return wheel_radius / final_drive; }
};

// A scene's [engine]: a body `engine` (crank, flywheel, the converter's pump) driven by its map's
// torque at its speed and the throttle signal (read/driveline_table.hpp).
struct EngineSpec {
  int body = -1;
  rt::EngineData map;  // SI: rad/s, N m
  rt::Signal throttle;
  SourceLocation where, throttle_where;
};

// A scene's [converter] between a pump body and a turbine body (its lock-up clutch, when it has one,
// is a clutch of the model named `lockup`).
struct ConverterSpec {
  int pump = -1, turbine = -1;
  rt::ConverterData curves;  // capacity factor in (rad/s)/sqrt(N m)
  SourceLocation where;
};

// A PI speed controller (scene-format.md, "Controllers"): the torque kp e + ki theta on `body`, with
// e = set_point(t) - omega_<measured> and theta its integral (a state of the scene).
struct ControllerSpec {
  std::string name;
  int body = -1, measured = -1;
  rt::Signal set_point;
  std::optional<SignalStart> set_point_start;
  double kp = 0, ki = 0;
  // Torque limits [N m]: the torque stays within them, held at a limit while the law asks for more;
  // events at both ends, as for brakes and clutches. At a limit the integral tracks it (anti-windup
  // by back-calculation): theta' = e + (T - law) / (ki tracking_time).
  double torque_min = -std::numeric_limits<double>::infinity(), torque_max = std::numeric_limits<double>::infinity();
  double tracking_time = 0;  // [s], with limits and ki > 0
  // tracking_time is its default kp / ki: then theta' = (T - ki theta) / kp exactly, the error's
  // terms cancelling (in doubles kp / ki times ki is not kp).
  bool integral_time_tracking = false;
  SourceLocation where;
  // A slip controller ([slip_control], read/slip_control.hpp): its torque is brake or clutch
  // `supplies`'s (a pair on its bodies), the speed it measures that element's slip, its gains the
  // command's times the element's capacity (negative: more slip, more torque); it runs from `start`
  // [s] or from its set-point's trigger until the element locks.
  int supplies = -1;
  double start = 0;
  bool limited() const { return std::isfinite(torque_min) || std::isfinite(torque_max); }
};

// Whether the signal is zero at every time: such an input is no input.
bool identically_zero(const rt::Signal& signal);
// The same for a signal that may start on an event: it and what it is before.
bool identically_zero(const rt::Signal& signal, const std::optional<SignalStart>& start);

using rt::Solver;

// Where a scene starts (docs/scene-format.md, "Initial state"): from the speeds and forces [initial]
// names; on the rigid model's trajectory (its state and its eq. (8) mesh forces); or at the
// equilibrium of the inputs' values at t = 0.
enum class Start { given, rigid, steady };

struct Scene {
  std::string file;
  std::string digest;  // of the scene file's text (text_digest)
  std::string name;
  std::string model_file;  // resolved relative to the scene file
  std::string model_ref;   // as the scene file writes it
  // The model, read once, with the scene's [parameters] applied: every quantity of the scene is
  // evaluated against it, and every later stage reads it (never the file again).
  Topology model;
  Effects effects;
  std::vector<std::string> keep;  // empty: the model's default
  bool compare_rigid = false;
  bool speeds_in_rpm = false;  // speed outputs (CSV, figures) in rpm instead of rad/s
  std::vector<InputSpec> inputs;
  // Commands of the brakes and clutches the scene engages, in the model's order; an element not
  // listed, or whose command is zero at every time, is open throughout and leaves no term.
  std::vector<EngagementSpec> engagement;
  std::vector<LoadSpec> loads;  // in body order, at most one per body
  std::optional<VehicleSpec> vehicle;
  std::optional<EngineSpec> engine;
  std::optional<ConverterSpec> converter;
  // In the order of Topology::controllers, which names them for their variables.
  std::vector<ControllerSpec> controllers;
  bool solver_given = false;  // a quadratic load makes dopri5 the default
  std::map<Variable, double> initial;  // velocities [rad/s] and forces [N]
  Start start = Start::given;
  SourceLocation start_where;
  // [initial] gear = "<name>" or engaged = [...]: the brakes and clutches stuck at t = 0 (indices,
  // ascending), the start ("rigid" unless "steady") then that mode's (specialize/gear_start.hpp).
  std::vector<int> initial_engaged;
  std::string initial_gear;  // the gear's name in the model's [gears]; empty for engaged = [...]
  SourceLocation initial_engaged_where;
  std::vector<std::string> tunable;
  std::vector<ThermalSpec> thermal;  // in element order
  std::vector<ActuatorSpec> actuators;  // in element order
  std::vector<Variable> outputs;  // velocities and forces; empty: every velocity, and every force with mesh_forces
  double horizon = 1.0;
  double sample = 1e-3;
  Solver solver = Solver::exact;
  double tolerance = 1e-8;  // adaptive methods, relative
  double step = 1e-4;       // fixed-step methods
  long max_steps = 10000000;  // adaptive methods: a stiff scene stops with an error, not a hang
  SourceLocation loads_where, controllers_where;
  SourceLocation solver_where, outputs_where, keep_where, tunable_where, sample_where, initial_where;
};

// Reads a scene and its model, applies the scene's parameter overrides to the model, and checks
// the scene against the result (bodies, meshes, parameter names, units).
// Whether the scene engages brake or clutch `element` (an index into Topology::friction_elements):
// gives it a command that is not zero throughout. Only such an element slips, sticks or heats.
bool engages(const Scene& s, int element);

Scene parse_scene(const std::string& path);
// Whether a load of the scene is quadratic in speed.
bool has_quadratic_load(const Scene& scene);
// Whether it has such a load, an engine or a converter: its equations are then nonlinear.
bool nonlinear(const Scene& scene);
Scene parse_scene_text(const std::string& text, const std::string& path);

// The solver `name` (rt::parse_solver), or an InputError at `where`.
Solver parse_solver(const std::string& name, const SourceLocation& where);

}  // namespace pogear
