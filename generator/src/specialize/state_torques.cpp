// The rows over a system's states its runs read (the slips, the driveline's speeds) and the torques
// of the state: the quadratic loads' form, the vehicle's jerk through them, the engine's and the
// converter's inputs.
#include "specialize/state_torques.hpp"

#include <algorithm>
#include <variant>

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "derive/engagement.hpp"
#include "specialize/gear_equations.hpp"
#include "specialize/linear_form.hpp"
#include "specialize/parameter_folding.hpp"

namespace pogear {

using GiNaC::ex;

int driveline_body(const Scene& scene, VariableKind kind) {
  return kind == VariableKind::engine_torque ? scene.engine->body
         : kind == VariableKind::pump_torque ? scene.converter->pump
                                             : scene.converter->turbine;
}

// An engine's and a converter's torques: inputs after the scene's signals, which the runs compute.
void driveline_inputs_of(const Scene& sc, SpecializedSystem& sys) {
  if (sc.engine) sys.driveline.push_back({VariableKind::engine_torque, 0});
  if (sc.converter)
    for (const VariableKind kind : {VariableKind::pump_torque, VariableKind::turbine_torque}) sys.driveline.push_back({kind, 0});
  for (const Variable v : sys.driveline) sys.inputs.push_back({v, std::nullopt, std::nullopt});
  if (!sys.driveline.empty()) sys.nonlinear = true;
}

// Rows E omega in the system's states: omega itself (elastic), omega = Q1 x1 (rigid); a controller's
// integral enters none.
GiNaC::matrix state_rows(const Derivation& d, const GiNaC::exmap& fold, const GiNaC::matrix& E,
                         const std::vector<Variable>& states, std::size_t gear_states, bool elastic) {
  GiNaC::matrix slip(E.rows(), states.size());
  for (unsigned r = 0; r < E.rows(); ++r)
    for (std::size_t j = 0; j < states.size(); ++j) {
      ex sum = 0;
      for (std::size_t b = 0; b < d.topology.bodies.size(); ++b) {
        if (E(r, b).is_zero() || j >= gear_states) continue;
        if (elastic) sum += states[j] == Variable{VariableKind::velocity, static_cast<int>(b)} ? E(r, b) : ex(0);
        else sum += E(r, b) * d.rigid.Q1(b, j);
      }
      slip(r, j) = folded(sum, fold);
    }
  return slip;
}

// Slips s_k = e_k omega of the engaged elements.
GiNaC::matrix slip_rows(const Derivation& d, const GiNaC::exmap& fold, const std::vector<int>& elements,
                        const std::vector<Variable>& states, std::size_t gear_states, bool elastic) {
  return state_rows(d, fold, engagement_rows(d.topology, elements), states, gear_states, elastic);
}

// The speed of the body each driveline torque acts on.
GiNaC::matrix driveline_speed_rows(const Scene& sc, const Derivation& d, const GiNaC::exmap& fold,
                                   const SpecializedSystem& sys, const std::vector<Variable>& states,
                                   std::size_t gear_states, bool elastic) {
  GiNaC::matrix E(sys.driveline.size(), d.topology.bodies.size());
  for (std::size_t i = 0; i < sys.driveline.size(); ++i)
    E(static_cast<unsigned>(i), static_cast<unsigned>(driveline_body(sc, sys.driveline[i].kind))) = 1;
  return state_rows(d, fold, E, states, gear_states, elastic);
}

// The quadratic loads' columns of dx/dt and speeds over the states, read off as linear_form reads M
// and N: before their temporaries join the rhs's, so that each TQ_ stays a symbol of the rows.
void quadratic_load_form(const SymbolTable& s, const ClosedLoops& loops, SpecializedSystem& sys) {
  if (loops.quadratic.empty()) return;
  // An implicit system's columns are L^-1 Q, which its generated code solves (ImplicitForm::Q).
  if (!sys.implicit) {
    GiNaC::exmap temps;
    for (const auto& a : sys.rhs_temporaries) temps[a.symbol] = a.value.subs(temps, GiNaC::subs_options::no_pattern);
    std::vector<ex> rows, torques;
    for (const ex& row : sys.rhs) rows.push_back(row.subs(temps, GiNaC::subs_options::no_pattern));
    for (const Assignment& q : loops.quadratic) torques.push_back(q.symbol);
    sys.quadratic_columns = linear_coefficients(rows, torques);
  }
  std::vector<ex> states;
  for (const StatePort& x : sys.states) states.push_back(variable_symbol(s, x.variable));
  sys.quadratic_speeds = linear_coefficients(loops.quadratic_speeds, states);
  sys.quadratic_coefficients = loops.quadratic_coefficients;
}

// The elastic model's jerk, (r/i) d/dt of the vehicle body's dx/dt row: M's row times dx/dt, and each
// quadratic load's column times its torque's rate -2 c |s| ds/dt. An input on that row would add its
// own rate, which the outputs cannot read: refused unless constant (the road load's, a constant grade).
ex vehicle_jerk_value(const Scene& sc, const Derivation& d, const SpecializedSystem& sys) {
  const SymbolTable& s = d.symbols;
  const Variable omega{VariableKind::velocity, sc.vehicle->vehicle_body};
  const std::vector<Variable> states = state_variables(sys);
  const auto v = static_cast<unsigned>(std::find(states.begin(), states.end(), omega) - states.begin());
  for (std::size_t i = 0; i < sys.inputs.size(); ++i)
    if (!sys.N(v, static_cast<unsigned>(i)).is_zero() &&
        !(sys.inputs[i].signal && std::holds_alternative<rt::Constant>(*sys.inputs[i].signal)))
      throw InputError(sc.outputs_where,
                       fmt::format("vehicle_jerk would read the rate of {}, which acts on the car's speed and is not "
                                   "constant; drop vehicle_jerk, or make the input constant",
                                   variable_name(s, sys.inputs[i].variable)));
  auto rate = [&](auto coefficient) {  // sum_j coefficient(j) dx_j/dt
    ex sum = 0;
    for (std::size_t j = 0; j < states.size(); ++j)
      if (const ex c = coefficient(static_cast<unsigned>(j)); !c.is_zero()) sum += c * variable_symbol(s, derivative_of(states[j]));
    return sum;
  };
  ex jerk = rate([&](unsigned j) { return sys.M(v, j); });
  for (unsigned q = 0; q < sys.quadratic_coefficients.size(); ++q) {
    if (sys.quadratic_columns(v, q).is_zero()) continue;
    ex speed = 0;
    for (unsigned j = 0; j < states.size(); ++j) speed += sys.quadratic_speeds(q, j) * variable_symbol(s, states[j]);
    jerk += sys.quadratic_columns(v, q) * -2 * sys.quadratic_coefficients[q] * GiNaC::abs(speed) *
            rate([&](unsigned j) { return sys.quadratic_speeds(q, j); });
  }
  return (jerk * exact_number(sc.vehicle->speed_per_omega())).expand();
}

}  // namespace pogear
