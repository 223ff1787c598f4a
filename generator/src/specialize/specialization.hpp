// Specialization: the equations a scene calls for and nothing more. Effects left out leave no
// term, zero inputs are not inputs, unrequested outputs are not computed, and every parameter
// that is not tunable is folded to a number.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <string_view>
#include <vector>

#include "derive/derivation.hpp"
#include "specialize/operation_count.hpp"
#include "specialize/parameter_folding.hpp"
#include "specialize/reference_model.hpp"
#include "read/scene.hpp"

namespace pogear {

// `const double name = value;` in generated code.
struct Assignment {
  std::string name;
  GiNaC::ex value;
  GiNaC::ex symbol;  // what the expressions after it read for it
};

// How `--param NAME=VALUE` of a generated simulator may write a tunable's value: a plain number
// (SI), or NUMBER*UNIT with one of these units (the model's own spelling and the SI one).
struct UnitSpelling {
  std::string unit;  // e.g. "Newton/mm"
  double si = 1;     // its value in SI, e.g. 1000
};

struct TunableParameter {
  std::string name;
  double value = 0;  // SI, the scene's value
  std::vector<UnitSpelling> units;
  std::string sign;  // "positive", "non-negative", or empty when no role of the model bounds it
};

// L dx/dt = A x + B u, which the generated code solves numerically (L symmetric positive definite).
struct ImplicitForm {
  GiNaC::matrix L, A, B;
  // With quadratic loads, their torques' columns: L dx/dt = A x + B u + Q TQ (0 x 0 without).
  GiNaC::matrix Q = GiNaC::matrix(0, 0);
};

enum class SystemKind { elastic, rigid };
inline std::string_view kind_name(SystemKind k) { return k == SystemKind::elastic ? "elastic" : "rigid"; }
inline std::ostream& operator<<(std::ostream& out, SystemKind k) { return out << kind_name(k); }

// A state of a system: which variable it is (its name and unit, as printed, come from the
// variable) and the value it starts from.
struct StatePort {
  Variable variable;
  double initial = 0;  // the controllers' integrals theta_ start at zero
};

// An input: the signal the runs read for it, or none for the inputs the hybrid runs set (the
// friction torques Tf_ and the limited controllers' torques Tc_, which come last).
struct InputPort {
  Variable variable;
  std::optional<rt::Signal> signal;
  std::optional<SignalStart> start;  // a signal that starts on an event
};

// An output: its value in the system's states and inputs (and dx/dt when the system says so).
struct OutputPort {
  Variable variable;
  GiNaC::ex value;
  bool in_rpm = false;  // a speed the scene asks in rpm; its value is in rpm already
};

struct SpecializedSystem {
  SystemKind kind = SystemKind::elastic;
  std::string equations;  // one line, for the generated header comment
  std::vector<StatePort> states;
  // The scene's nonzero torques tau_<body>, the constant parts of its loads (TL_<body>), the
  // controllers' set-points (ref_<controller>), each with its signal; then the friction torques
  // Tf_<element> of the engaged brakes and clutches and the limited controllers' torques.
  std::vector<InputPort> inputs;
  // Brakes and clutches the scene engages (indices into Topology::friction_elements): their torques
  // Tf_<element> are inputs after the scene's, and their slips are s = slip x.
  std::vector<int> friction_elements;
  GiNaC::matrix slip;
  // Controllers with torque limits (indices into Scene::controllers): their torques Tc_<controller>
  // are the very last inputs, after the friction torques, and the hybrid runs apply their laws
  // T = limit_law_x x + limit_law_u u (one row each, exact) within the limits.
  std::vector<int> limited_controllers;
  GiNaC::matrix limit_law_x, limit_law_u;
  std::vector<TunableParameter> params;
  std::vector<Assignment> rhs_temporaries;
  std::vector<GiNaC::ex> rhs;  // dx/dt, one per state
  std::vector<OutputPort> outputs;
  GiNaC::matrix M, N;  // dx/dt = M x + N u (every scene pogear knows is linear); 0 x 0 with `implicit`
  // A rigid system with tunables: dx/dt from L1 x1' = A1 x1 + B1 tau, solved by the generated code
  // (rhs and M, N are then empty): the symbolic L1^-1 over one common denominator grows fast with
  // the tunables, with exact coefficients beyond doubles.
  std::optional<ImplicitForm> implicit;
  bool output_derivatives = false;  // the outputs read dx/dt as d<state>, computed by rhs
  OperationCount rhs_ops, output_ops;
  // Energy E = x^T L x / 2 (symmetric positive definite), for the runner's divergence check; empty
  // with controllers, which feed power in that no bound of the inputs limits.
  GiNaC::matrix L;
  // A quadratic load makes the equations nonlinear: rhs then holds its torques -c omega |omega|
  // (temporaries TQ_<body>), which M and N leave out, and exact stepping is refused. The hybrid runs
  // take each as an input of the state: TQ = -c s |s| with s = quadratic_speeds x (a row each), its
  // column of dx/dt in quadratic_columns, c in quadratic_coefficients.
  bool nonlinear = false;
  GiNaC::matrix quadratic_columns, quadratic_speeds;
  std::vector<GiNaC::ex> quadratic_coefficients;
  // A scene's engine and converter (nonlinear too): their torques Tengine, Tpump, Tturbine, those the
  // scene has, are inputs right after the signals', without a signal (the hybrid runs compute them
  // from the state), each on its body; driveline_speeds holds, in their order, the speed over the
  // states of the body each acts on (engine, pump, turbine).
  std::vector<Variable> driveline;
  GiNaC::matrix driveline_speeds;
};

// A brake or clutch of a scene at the scene's values: capacity [N m], static ratio, and command.
// A friction curve that does not vary is a constant ratio, folded into the capacity; one that does is
// friction_curve (over |slip| [rad/s]), else empty.
struct FrictionRun {
  int element = -1;
  std::string name;
  double capacity = 0, static_ratio = 1;
  rt::Signal command;
  bool one_way = false;
  std::optional<SignalStart> start;  // a command that starts on an event
  rt::Table friction_curve;
  double fill_delay = 0, time_constant = 0;  // its actuator's ([actuators]), 0 without
  // The capacity in the tunables (a number when none enters it), what a run at other --param values
  // takes: the generated friction_elements(p), and at_parameter_options.
  GiNaC::ex tuned_capacity;
  bool held_at_start = false;  // stuck at t = 0 by the scene's start in a gear
};


// The element as the runtime's runs take it.
inline rt::FrictionElementData element_data(const FrictionRun& f) {
  return {f.name,         f.capacity,   f.static_ratio,  f.command,      f.one_way,
          f.friction_curve, f.fill_delay, f.time_constant, f.held_at_start};
}

struct SpecializedScene {
  Scene scene;
  std::vector<FrictionRun> friction;  // the engaged elements, in the order of the systems' Tf_ inputs
  Derivation derivation;  // with the scene's overrides applied
  SceneValues values;     // the parameters folded once for the scene
  SpecializedSystem main;
  std::optional<SpecializedSystem> rigid;  // the comparison, when the scene asks for it
};

// 60 / 2 pi, rounded once: a speed output in rpm is this times the speed in rad/s.
inline constexpr double rpm_per_rad_per_s = 9.5492965855137201;

SpecializedScene specialize(const Scene& scene);

// Brake or clutch `element`'s index among model.friction (the engaged elements), or
// model.friction.size() when the scene does not engage it.
int friction_run_index(const SpecializedScene& model, int element);

// Whether some element's capacity follows a tunable parameter.
bool has_tuned_capacity(const SpecializedScene& model);

// What the scene's systems hold that some solvers cannot run, for rt::solver_refusal.
rt::SystemTraits solver_traits(const SpecializedScene& model);

// What an output of a mesh's or shaft's force is the model's F times, exactly: one planet's share of a
// lumped planet's mesh (1 / count), a shaft's output_scale (a vehicle's half-shafts at the wheels).
GiNaC::numeric output_per_model_force(const Topology& t, const Mesh& m);

// What a system's ports are, in their order: their variables, the signals of the inputs that have
// one (a prefix of the inputs), the initial state, the outputs' values.
std::vector<Variable> state_variables(const SpecializedSystem& sys);
std::vector<Variable> input_variables(const SpecializedSystem& sys);
std::vector<Variable> output_variables(const SpecializedSystem& sys);
std::vector<rt::Signal> input_signals(const SpecializedSystem& sys);
std::vector<double> initial_values(const SpecializedSystem& sys);
std::vector<GiNaC::ex> output_values(const SpecializedSystem& sys);
// Names and units as the generated code and the CSV files write them.
std::vector<std::string> port_names(const SymbolTable& s, const std::vector<Variable>& ports);
std::vector<std::string> state_units(const Topology& t, const SpecializedSystem& sys);
std::vector<std::string> output_units(const Topology& t, const SpecializedSystem& sys);
// The elastic or the rigid system of a scene, at its folded values: the gear's equations, its
// loads and controllers closed in, initial state, outputs, slips of the engaged elements.
SpecializedSystem specialize_system(const Scene& scene, const Derivation& d, const SceneValues& values, bool elastic);

// The torque each input applies to each body (bodies x inputs, exact): a unit column for tau_<body>,
// a load's TL_<body> and a controller's Tc_ (on its body), -e_k^T for a friction torque Tf_<k> (-T
// on the element's first body, +T on its second, arrows taken into account), none for a set-point.
GiNaC::matrix input_torques(const Topology& t, const Scene& scene, const std::vector<Variable>& inputs);


}  // namespace pogear
