// Specialized equations are built as GiNaC expressions in the scene's own variables, with the
// mesh velocities v = R omega (and damped forces w = F + B_K v) as the shared temporaries.
#include "specialize/specialization.hpp"
#include "specialize/start_state.hpp"
#include "specialize/state_torques.hpp"

#include <algorithm>
#include <variant>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "specialize/gear_equations.hpp"
#include "specialize/initial_state.hpp"
#include "specialize/linear_form.hpp"
#include "specialize/loop_closure.hpp"
#include "read/loads_and_controllers.hpp"
#include "read/model_parameters.hpp"
#include "read/friction_curve.hpp"
#include "read/slip_control.hpp"
#include "specialize/operation_count.hpp"
#include "specialize/parameter_folding.hpp"
#include "common/printer.hpp"
#include "specialize/tunable_checks.hpp"
#include "specialize/tunable_parameters.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// The model's F of a mesh or shaft whose output reads `output` (the inverse of output_per_model_force).
double model_force(const Topology& t, Variable force, double output) {
  const GiNaC::numeric f = output_per_model_force(t, t.meshes[static_cast<std::size_t>(force.index)]);
  return output * f.denom().to_double() / f.numer().to_double();
}

bool contains(const std::vector<Variable>& v, Variable x) { return std::find(v.begin(), v.end(), x) != v.end(); }

std::vector<Variable> requested_outputs(const Scene& sc, const Topology& t) {
  if (!sc.outputs.empty()) return sc.outputs;
  std::vector<Variable> out;
  for (std::size_t b = 0; b < t.bodies.size(); ++b) out.push_back({VariableKind::velocity, static_cast<int>(b)});
  if (sc.effects.mesh_forces)
    for (std::size_t i = 0; i < t.meshes.size(); ++i) out.push_back({VariableKind::force, static_cast<int>(i)});
  for (std::size_t c = 0; c < sc.controllers.size(); ++c) out.push_back({VariableKind::controller_torque, static_cast<int>(c)});
  if (sc.vehicle)
    for (const VariableKind kind : {VariableKind::vehicle_speed, VariableKind::vehicle_acceleration}) out.push_back({kind, 0});
  if (sc.engine) out.push_back({VariableKind::engine_torque, 0});
  if (sc.converter)
    for (const VariableKind kind : {VariableKind::pump_torque, VariableKind::turbine_torque}) out.push_back({kind, 0});
  return out;
}

void inputs_of(const Scene& sc, SpecializedSystem& sys) {
  for (const InputSpec& in : sc.inputs) {
    if (identically_zero(in.signal, in.start)) continue;  // a zero input is not an input
    sys.inputs.push_back({{VariableKind::torque, in.body}, in.signal, in.start});
  }
}

// Engaged brakes and clutches: their torques are inputs after the scene's (an element whose command
// is zero at every time stays open and leaves no term).
void friction_inputs_of(const Scene& sc, SpecializedSystem& sys) {
  for (const EngagementSpec& e : sc.engagement) {
    if (!engages(sc, e.element)) continue;
    sys.inputs.push_back({{VariableKind::friction_torque, e.element}, std::nullopt, std::nullopt});
    sys.friction_elements.push_back(e.element);
  }
}

// The gear's states as the scene names them: exactly as given (a lumped force per planet), else the
// rigid model's from the named speeds (initial_state.hpp), which with compare_rigid the elastic model
// starts from too, unnamed bodies included; the controllers' integrals theta_ at zero.
std::vector<double> initial_state(const Scene& sc, const Derivation& d, const GiNaC::exmap& numbers,
                                  const std::vector<Variable>& states, std::size_t gear_states, bool elastic) {
  const Topology& t = d.topology;
  std::vector<double> rigid_x0;
  if (!elastic || sc.compare_rigid) rigid_x0 = rigid_initial_state(sc, d, numbers);
  Eigen::VectorXd omega;  // left empty from rest: Q1 of a long chain is costly to evaluate
  if (elastic && sc.compare_rigid && std::any_of(rigid_x0.begin(), rigid_x0.end(), [](double x) { return x != 0; }))
    omega = evaluate_matrix(d.rigid.Q1, numbers) *
            Eigen::Map<const Eigen::VectorXd>(rigid_x0.data(), static_cast<Eigen::Index>(rigid_x0.size()));
  std::vector<double> x0;
  for (std::size_t i = 0; i < states.size(); ++i) {
    const Variable v = states[i];
    if (i >= gear_states) x0.push_back(0.0);  // a controller's integral
    else if (const auto it = sc.initial.find(v); it != sc.initial.end())
      x0.push_back(v.kind == VariableKind::force ? model_force(t, v, it->second) : it->second);
    else if (!elastic) x0.push_back(rigid_x0[i]);
    else if (v.kind == VariableKind::velocity && omega.size()) x0.push_back(omega(v.index));
    else x0.push_back(0.0);
  }
  return x0;
}

// A controller started at a given torque Tc0: its integral from kp (ref(0) - omega(0)) + ki theta(0) = Tc0.
void start_controllers_at_given_torques(const Scene& sc, const Derivation& d, const GiNaC::exmap& numbers,
                                        const std::vector<Variable>& states, std::size_t gear_states, bool elastic,
                                        std::vector<double>& x0) {
  for (std::size_t c = 0; c < sc.controllers.size(); ++c) {
    const auto given = sc.initial.find(Variable{VariableKind::controller_torque, static_cast<int>(c)});
    if (given == sc.initial.end()) continue;
    const ControllerSpec& k = sc.controllers[c];
    double omega = 0;
    for (std::size_t j = 0; j < gear_states; ++j) {
      if (elastic) {
        if (states[j] == Variable{VariableKind::velocity, k.measured}) omega = x0[j];
      } else {
        omega += to_double(as_number(exact_value(d.rigid.Q1(static_cast<unsigned>(k.measured), static_cast<unsigned>(j)),
                                                 numbers))) * x0[j];
      }
    }
    x0[gear_states + c] = (given->second - k.kp * (value_at_start(k.set_point, k.set_point_start) - omega)) / k.ki;
  }
}

// The outputs the scene asks for, with their values in the system's states and inputs.
struct SystemOutputs {
  std::vector<OutputPort> ports;
  bool reads_derivatives = false;  // a rigid system's mesh forces read dx/dt (eq. 8)
};

// One output's value: a state, a controller's law (with limits its input), omega = Q1 x1 of a rigid
// system, or eq. (8)'s force, which reads the torque on each body from the inputs.
ex output_value(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in, const GiNaC::exmap& loop_outputs,
                const std::vector<Variable>& states, std::size_t gear_states, bool elastic,
                const std::optional<VehicleSpec>& vehicle, Variable out) {
  const SymbolTable& s = d.symbols;
  if (of_driveline(out.kind)) return variable_symbol(s, out);  // an input the runs compute
  if (out.kind == VariableKind::controller_torque) {
    const auto law = loop_outputs.find(variable_symbol(s, out));
    return law != loop_outputs.end() ? law->second : ex(variable_symbol(s, out));
  }
  if (of_vehicle(out.kind)) {
    // m/s per rad/s of the vehicle body, r / i; the speed in km/h (3.6 = 18/5 exactly).
    const ex per_omega = exact_number(vehicle->speed_per_omega());
    const Variable omega{VariableKind::velocity, vehicle->vehicle_body};
    if (out.kind == VariableKind::vehicle_jerk) return 0;  // vehicle_jerk_value, once M is known
    if (out.kind == VariableKind::vehicle_speed)
      return folded(output_value(d, fold, in, loop_outputs, states, gear_states, elastic, vehicle, omega) * per_omega *
                        GiNaC::numeric(18, 5),
                    fold);
    ex acceleration = 0;
    if (elastic) acceleration = variable_symbol(s, derivative_of(omega));
    else
      for (std::size_t j = 0; j < gear_states; ++j)
        acceleration += d.rigid.Q1(static_cast<unsigned>(omega.index), static_cast<unsigned>(j)) *
                        variable_symbol(s, derivative_of(states[j]));
    return folded(acceleration * per_omega, fold);
  }
  if (out.kind == VariableKind::spring_force) {
    if (elastic) return variable_symbol(s, {VariableKind::force, out.index});
    out.kind = VariableKind::force;  // as K grows, R omega and the damper's share vanish: the spring carries F
  }
  if (elastic && out.kind == VariableKind::force) {
    // What the mesh or shaft passes on: its spring's force and its damper's, F + b_K R omega, which
    // the rigid model's F is the limit of.
    ex rate = 0;
    for (std::size_t k = 0; k < d.topology.bodies.size(); ++k)
      rate += d.elastic.R(out.index, k) * variable_symbol(s, {VariableKind::velocity, static_cast<int>(k)});
    return folded(variable_symbol(s, out) + d.elastic.B_K(out.index, out.index) * rate, fold);
  }
  if (elastic || contains(states, out)) return variable_symbol(s, out);
  if (out.kind == VariableKind::velocity) {
    ex w = 0;
    for (std::size_t j = 0; j < gear_states; ++j) w += d.rigid.Q1(out.index, j) * variable_symbol(s, states[j]);
    return folded(w, fold);
  }
  GiNaC::exmap body_torques;
  for (std::size_t b = 0; b < d.topology.bodies.size(); ++b)
    body_torques[variable_symbol(s, {VariableKind::torque, static_cast<int>(b)})] = body_torque(s, in, b);
  return folded(d.rigid.force_recovery.at(out.index).subs(body_torques).subs(loop_outputs, GiNaC::subs_options::no_pattern),
                fold);
}

// The outputs, only those asked for: a lumped planet's force as one planet's share (the model's is
// its planets' sum), speeds in rpm when the scene asks.
SystemOutputs system_outputs(const Scene& sc, const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in,
                             const GiNaC::exmap& loop_outputs, const std::vector<Variable>& states,
                             std::size_t gear_states, bool elastic) {
  const Topology& t = d.topology;
  SystemOutputs out;
  for (const Variable y : requested_outputs(sc, t)) {
    ex value = output_value(d, fold, in, loop_outputs, states, gear_states, elastic, sc.vehicle, y);
    const bool in_rpm = y.kind == VariableKind::velocity && sc.speeds_in_rpm;
    out.reads_derivatives = out.reads_derivatives || y.kind == VariableKind::vehicle_acceleration ||
                            y.kind == VariableKind::vehicle_jerk ||
                            (!elastic && !contains(states, y) && y.kind != VariableKind::controller_torque &&
                             !of_driveline(y.kind) &&
                             y.kind != VariableKind::velocity && y.kind != VariableKind::vehicle_speed);
    if (y.kind == VariableKind::force || y.kind == VariableKind::spring_force)
      if (const GiNaC::numeric f = output_per_model_force(t, t.meshes[static_cast<std::size_t>(y.index)]); f != 1)
        value = folded(value * f, fold);
    if (in_rpm) value = folded(value * exact_number(rpm_per_rad_per_s), fold);
    out.ports.push_back({y, value, in_rpm});
  }
  return out;
}

// The loads' and controllers' laws as the outputs read them: with the quadratic loads' TQ_ written
// out, as the outputs have no temporaries.
GiNaC::exmap loop_output_laws(const ClosedLoops& loops) {
  GiNaC::exmap laws = loops.torques;
  for (const Assignment& q : loops.quadratic)
    for (auto& [symbol, law] : laws) law = law.subs(GiNaC::exmap{{q.symbol, q.value}}, GiNaC::subs_options::no_pattern);
  return laws;
}

void set_initial_values(const std::vector<double>& x0, SpecializedSystem& sys) {
  for (std::size_t i = 0; i < x0.size(); ++i) sys.states.at(i).initial = x0[i];
}

void count_system_operations(SpecializedSystem& sys) {
  sys.rhs_ops = sys.implicit ? implicit_operations(*sys.implicit) : count_all(sys.rhs_temporaries, sys.rhs);
  if (sys.implicit && sys.nonlinear) {  // the quadratic loads' torques, added to A x + B u before the solve
    const OperationCount q = count_all(sys.rhs_temporaries, {});
    sys.rhs_ops.multiplications += q.multiplications;
    sys.rhs_ops.additions += q.additions;
  }
  sys.output_ops = count_all({}, output_values(sys));
  if (sys.output_derivatives) {  // the outputs call rhs
    sys.output_ops.multiplications += sys.rhs_ops.multiplications;
    sys.output_ops.additions += sys.rhs_ops.additions;
  }
}

}  // namespace

SpecializedSystem specialize_system(const Scene& sc, const Derivation& d, const SceneValues& values, bool elastic) {
  const Topology& t = d.topology;
  const GiNaC::exmap& fold = values.equations;
  SpecializedSystem sys;
  sys.kind = elastic ? SystemKind::elastic : SystemKind::rigid;
  for (const auto& name : sc.tunable) sys.params.push_back(tunable_parameter(t, name, parameter_value(t, name)));
  inputs_of(sc, sys);
  loop_inputs_of(sc, sys);
  driveline_inputs_of(sc, sys);
  friction_inputs_of(sc, sys);
  OpenInputs open_inputs{input_variables(sys), {}};
  open_inputs.torques = input_torques(t, sc, open_inputs.variables);
  GearEquations gear = elastic ? elastic_equations(d, fold, open_inputs) : rigid_equations(d, fold, open_inputs);
  sys.equations = std::move(gear.description);
  for (const Variable v : gear.states) sys.states.push_back({v, 0.0});
  sys.rhs_temporaries = std::move(gear.temporaries);
  sys.rhs = std::move(gear.rhs);
  sys.implicit = std::move(gear.implicit);
  const std::size_t gear_states = sys.states.size();  // before the controllers' integrals
  const ClosedLoops loops = close_loops(sc, d, elastic, fold, sys);
  close_implicit_form(d.symbols, loops, open_inputs.variables, sys);
  const std::vector<Variable> states = state_variables(sys);
  std::vector<double> x0 = initial_state(sc, d, values.numbers, states, gear_states, elastic);
  start_controllers_at_given_torques(sc, d, values.numbers, states, gear_states, elastic, x0);
  set_initial_values(x0, sys);
  if (!sys.implicit) linear_form(d.symbols, sys);
  quadratic_load_form(d.symbols, loops, sys);
  limit_laws(d.symbols, loops, sys);
  // After the linear form, which reads a temporary it does not know as a constant, and leaves it out.
  sys.rhs_temporaries.insert(sys.rhs_temporaries.end(), loops.quadratic.begin(), loops.quadratic.end());
  SystemOutputs outputs = system_outputs(sc, d, fold, open_inputs, loop_output_laws(loops), states, gear_states, elastic);
  sys.outputs = std::move(outputs.ports);
  for (OutputPort& y : sys.outputs)
    if (y.variable.kind == VariableKind::vehicle_jerk) y.value = vehicle_jerk_value(sc, d, sys);
  sys.output_derivatives = outputs.reads_derivatives;
  count_system_operations(sys);
  // Controllers and an engine feed in power that no bound of the inputs limits: no divergence bound.
  sys.L = sc.controllers.empty() && sys.driveline.empty() ? energy_matrix(d, fold, elastic) : GiNaC::matrix(0, 0);
  sys.slip = slip_rows(d, fold, sys.friction_elements, states, gear_states, elastic);
  sys.driveline_speeds = driveline_speed_rows(sc, d, fold, sys, states, gear_states, elastic);
  return sys;
}

namespace {

template <class Port>
std::vector<Variable> variables_of(const std::vector<Port>& ports) {
  std::vector<Variable> v;
  v.reserve(ports.size());
  for (const Port& p : ports) v.push_back(p.variable);
  return v;
}

}  // namespace

std::vector<Variable> state_variables(const SpecializedSystem& sys) { return variables_of(sys.states); }
std::vector<Variable> input_variables(const SpecializedSystem& sys) { return variables_of(sys.inputs); }
std::vector<Variable> output_variables(const SpecializedSystem& sys) { return variables_of(sys.outputs); }

std::vector<rt::Signal> input_signals(const SpecializedSystem& sys) {
  std::vector<rt::Signal> signals;
  for (const InputPort& u : sys.inputs)
    if (u.signal) signals.push_back(*u.signal);
  return signals;
}

std::vector<double> initial_values(const SpecializedSystem& sys) {
  std::vector<double> x0;
  x0.reserve(sys.states.size());
  for (const StatePort& x : sys.states) x0.push_back(x.initial);
  return x0;
}

std::vector<GiNaC::ex> output_values(const SpecializedSystem& sys) {
  std::vector<GiNaC::ex> values;
  values.reserve(sys.outputs.size());
  for (const OutputPort& y : sys.outputs) values.push_back(y.value);
  return values;
}

std::vector<std::string> port_names(const SymbolTable& s, const std::vector<Variable>& ports) {
  std::vector<std::string> names;
  names.reserve(ports.size());
  for (const Variable v : ports) names.push_back(variable_name(s, v));
  return names;
}

std::vector<std::string> state_units(const Topology& t, const SpecializedSystem& sys) {
  std::vector<std::string> units;
  for (const StatePort& x : sys.states) units.emplace_back(unit_of(t, x.variable));
  return units;
}

std::vector<std::string> output_units(const Topology& t, const SpecializedSystem& sys) {
  std::vector<std::string> units;
  for (const OutputPort& y : sys.outputs) units.emplace_back(y.in_rpm ? "rpm" : unit_of(t, y.variable));
  return units;
}

GiNaC::matrix input_torques(const Topology& t, const Scene& scene, const std::vector<Variable>& inputs) {
  const std::vector<ControllerSpec>& controllers = scene.controllers;
  GiNaC::matrix G(t.bodies.size(), inputs.size());
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    const VariableKind kind = inputs[j].kind;
    if (kind == VariableKind::torque || kind == VariableKind::load_torque) {
      G(inputs[j].index, j) = 1;
    } else if (kind == VariableKind::controller_torque && controllers.at(static_cast<std::size_t>(inputs[j].index)).supplies >= 0) {
      // A slip controller's torque acts as its element's does.
      const GiNaC::matrix e = engagement_rows(t, {controllers[static_cast<std::size_t>(inputs[j].index)].supplies});
      for (std::size_t b = 0; b < t.bodies.size(); ++b) G(b, j) = -e(0, b);
    } else if (kind == VariableKind::controller_torque) {
      G(controllers.at(static_cast<std::size_t>(inputs[j].index)).body, j) = 1;
    } else if (of_driveline(kind)) {
      G(static_cast<unsigned>(driveline_body(scene, kind)), j) = 1;
    } else if (kind == VariableKind::set_point) {
      continue;  // a speed, which acts through its controller
    } else {
      const GiNaC::matrix e = engagement_rows(t, {inputs[j].index});
      for (std::size_t b = 0; b < t.bodies.size(); ++b) G(b, j) = -e(0, b);
    }
  }
  return G;
}

rt::SystemTraits solver_traits(const SpecializedScene& model) {
  return {.nonlinear = model.main.nonlinear,
          .engages_friction = !model.friction.empty(),
          .limits_torque = !model.main.limited_controllers.empty(),
          .driveline = !model.main.driveline.empty(),
          .slip_control = has_slip_control(model.scene),
          .friction_curve = std::any_of(model.friction.begin(), model.friction.end(), [](const FrictionRun& f) { return !f.friction_curve.t.empty(); }),
          .actuator_lag = std::any_of(model.friction.begin(), model.friction.end(), [](const FrictionRun& f) { return f.time_constant > 0; })};
}

GiNaC::numeric output_per_model_force(const Topology& t, const Mesh& m) {
  return m.shaft ? exact_number(m.output_scale) : GiNaC::numeric(1, mesh_count(t, m));
}

SpecializedScene specialize(const Scene& scene) {
  SpecializedScene model;
  model.scene = scene;
  std::optional<std::vector<std::string>> keep;
  if (!scene.keep.empty()) keep = scene.keep;
  // With every parameter a number the rigid system needs no closed forms of L1 and A1.
  model.derivation = derive_topology(scene.model, keep, scene.keep_where, !scene.tunable.empty());
  add_controller_symbols(model.derivation.symbols, controller_names(scene));
  if (scene.vehicle) add_vehicle_symbols(model.derivation.symbols);
  if (scene.engine || scene.converter) add_driveline_symbols(model.derivation.symbols);
  const bool rigid_forces = scene.effects.mesh_forces && (!scene.effects.elastic() || scene.compare_rigid);
  if (model.derivation.rigid.redundant_meshes && rigid_forces && !scene.tunable.empty())
    throw InputError(SourceLocation{scene.file, 0, 0},
                     "this model has redundant meshes, whose rigid load split depends on every stiffness and "
                     "radius; it is computed at fixed values, so it cannot be combined with tunable parameters: "
                     "drop 'tunable' or 'mesh_forces'");
  model.values = scene_values(scene, model.derivation);
  if (!scene.tunable.empty()) check_tunable_geometry(scene, model.derivation, model.values.equations);
  model.main = specialize_system(scene, model.derivation, model.values, scene.effects.elastic());
  if (scene.compare_rigid) model.rigid = specialize_system(scene, model.derivation, model.values, false);
  const Topology& t = model.derivation.topology;
  for (const EngagementSpec& e : scene.engagement) {
    if (!engages(scene, e.element)) continue;
    const FrictionElement& f = t.friction_elements[static_cast<std::size_t>(e.element)];
    // A constant curve's ratio r scales the kinetic capacity, not the static one: out of the static
    // ratio, which stays >= 1 (r <= static_ratio).
    const double r = constant_friction_ratio(f);
    // A tunable is no key of the folding: it stands for itself.
    const GiNaC::realsymbol& c = parameter_symbol(model.derivation.symbols, f.capacity_parameter);
    const auto folded = model.values.equations.find(c);
    const GiNaC::ex tuned = (folded != model.values.equations.end() ? folded->second : GiNaC::ex(c)) * exact_number(r);
    model.friction.push_back(FrictionRun{e.element, f.name, parameter_value(t, f.capacity_parameter) * r,
                                         static_friction_ratio(t, f) / r, e.command,
                                         f.one_way, e.start,
                                         varies_with_slip(f) ? rt::Table{f.curve_slip, f.curve_ratio} : rt::Table{},
                                         0.0, 0.0, tuned.expand()});
    for (const ActuatorSpec& a : scene.actuators)
      if (a.element == e.element) {
        model.friction.back().fill_delay = a.fill_delay;
        model.friction.back().time_constant = a.time_constant;
      }
    model.friction.back().held_at_start =
        std::find(scene.initial_engaged.begin(), scene.initial_engaged.end(), e.element) != scene.initial_engaged.end();
  }
  if (const std::optional<StartState> start = start_state(model)) {
    set_initial_values(start->main, model.main);
    if (model.rigid) set_initial_values(start->rigid, *model.rigid);
  }
  return model;
}

bool has_tuned_capacity(const SpecializedScene& model) {
  return std::any_of(model.friction.begin(), model.friction.end(),
                     [](const FrictionRun& f) { return !GiNaC::is_a<GiNaC::numeric>(f.tuned_capacity); });
}

int friction_run_index(const SpecializedScene& model, int element) {
  const auto k = std::find_if(model.friction.begin(), model.friction.end(),
                              [&](const FrictionRun& f) { return f.element == element; });
  return static_cast<int>(k - model.friction.begin());
}

}  // namespace pogear
