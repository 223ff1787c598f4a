// See loop_closure.hpp: substitutions into the built equations, exact.
#include "specialize/loop_closure.hpp"

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "specialize/linear_form.hpp"
#include "read/model_parameters.hpp"
#include "names/model_variables.hpp"

namespace pogear {

using GiNaC::ex;

void loop_inputs_of(const Scene& sc, const Topology& t, SpecializedSystem& sys) {
  for (const LoadSpec& l : sc.loads) add_input(t, {VariableKind::load_torque, l.body}, sys);
  for (std::size_t c = 0; c < sc.controllers.size(); ++c)
    add_input(t, {VariableKind::controller_torque, static_cast<int>(c)}, sys);
}

ClosedLoops close_loops(const Scene& sc, const Derivation& d, bool elastic, const GiNaC::exmap& fold,
                        SpecializedSystem& sys) {
  const SymbolTable& s = d.symbols;
  const Topology& t = d.topology;
  ClosedLoops out;
  if (sc.loads.empty() && sc.controllers.empty()) return out;
  std::vector<ex> x1;  // the rigid system's kept velocities
  for (const Variable v : sys.state_variables) x1.push_back(variable_symbol(s, v));
  auto speed = [&](int body) -> ex {
    const Variable omega{VariableKind::velocity, body};
    if (elastic) return variable_symbol(s, omega);
    ex sum = 0;
    for (std::size_t j = 0; j < x1.size(); ++j) sum += d.rigid.Q1(static_cast<unsigned>(body), static_cast<unsigned>(j)) * x1[j];
    return sum.subs(fold, GiNaC::subs_options::no_pattern).expand();
  };
  // The inputs again, in their final order: the scene's torques, the loads' constant parts, the
  // set-points, the friction torques (last, as the hybrid runs expect).
  std::vector<Variable> torques, frictions;
  for (const Variable v : sys.input_variables) {
    if (v.kind == VariableKind::torque) torques.push_back(v);
    if (v.kind == VariableKind::friction_torque) frictions.push_back(v);
  }
  sys.input_variables = torques;
  sys.inputs.clear();
  for (const Variable v : torques) sys.inputs.push_back(variable_name(t, v));
  for (const LoadSpec& l : sc.loads) {
    const Variable constant{VariableKind::load_torque, l.body};
    ex law = -exact_number(l.linear) * speed(l.body);
    if (l.constant != 0) {
      add_input(t, constant, sys);
      sys.input_signals.push_back(rt::Constant{-l.constant});
      law += variable_symbol(s, constant);
    }
    if (l.quadratic != 0) {
      const std::string name = quadratic_load_name(t.bodies[static_cast<std::size_t>(l.body)].name);
      if (const Parameter* p = find_parameter(t, name))
        throw InputError(p->where, fmt::format("the model has a parameter named '{}', which pogear's generated code "
                                               "uses for a quadratic load; rename the parameter", name));
      const GiNaC::realsymbol q(name);
      const ex omega = speed(l.body);
      out.quadratic.push_back({name, (-exact_number(l.quadratic) * omega * GiNaC::abs(omega)).expand(), q});
      law += q;
      sys.nonlinear = true;
    }
    out.torques[variable_symbol(s, constant)] = law;
  }
  for (std::size_t c = 0; c < sc.controllers.size(); ++c) {
    const ControllerSpec& k = sc.controllers[c];
    const int i = static_cast<int>(c);
    const Variable ref{VariableKind::set_point, i}, theta{VariableKind::controller_integral, i};
    add_input(t, ref, sys);
    sys.input_signals.push_back(k.set_point);
    add_state(t, theta, sys);
    const ex error = variable_symbol(s, ref) - speed(k.measured);
    const ex law = (exact_number(k.kp) * error + exact_number(k.ki) * variable_symbol(s, theta)).expand();
    if (k.limited() && k.ki != 0) {
      // Back-calculation: T - law is zero within the limits, and at a limit draws the integral
      // towards it with the time constant tracking_time.
      const ex torque = variable_symbol(s, {VariableKind::controller_torque, i});
      sys.rhs.push_back((error + (torque - law) / (exact_number(k.ki) * exact_number(k.tracking_time))).expand());
    } else {
      sys.rhs.push_back(error);
    }
    if (k.limited()) {
      sys.limited_controllers.push_back(i);
      out.limited.push_back(law);
    } else {
      out.torques[variable_symbol(s, {VariableKind::controller_torque, i})] = law;
    }
  }
  for (const Variable v : frictions) add_input(t, v, sys);
  for (const int c : sys.limited_controllers) add_input(t, {VariableKind::controller_torque, c}, sys);
  for (std::size_t i = 0; i < sys.rhs.size(); ++i)
    sys.rhs[i] = sys.rhs[i].subs(out.torques, GiNaC::subs_options::no_pattern).expand();
  return out;
}

void limit_laws(const SymbolTable& s, const ClosedLoops& loops, SpecializedSystem& sys) {
  if (loops.limited.empty()) return;
  std::vector<ex> variables;
  for (const Variable v : sys.state_variables) variables.push_back(variable_symbol(s, v));
  for (const Variable v : sys.input_variables) variables.push_back(variable_symbol(s, v));
  const GiNaC::matrix law = linear_coefficients(loops.limited, variables);
  const auto nx = static_cast<unsigned>(sys.states.size()), nu = static_cast<unsigned>(sys.inputs.size());
  sys.limit_law_x = GiNaC::matrix(law.rows(), nx);
  sys.limit_law_u = GiNaC::matrix(law.rows(), nu);
  for (unsigned r = 0; r < law.rows(); ++r) {
    for (unsigned j = 0; j < nx; ++j) sys.limit_law_x(r, j) = law(r, j);
    for (unsigned j = 0; j < nu; ++j) sys.limit_law_u(r, j) = law(r, nx + j);
  }
}

}  // namespace pogear
