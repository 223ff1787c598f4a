// See loop_closure.hpp: substitutions into the built equations, exact.
#include "specialize/loop_closure.hpp"

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "derive/engagement.hpp"
#include "specialize/linear_form.hpp"
#include "read/model_parameters.hpp"
#include "names/model_variables.hpp"

namespace pogear {

using GiNaC::ex;

void loop_inputs_of(const Scene& sc, SpecializedSystem& sys) {
  for (const LoadSpec& l : sc.loads) sys.inputs.push_back({{VariableKind::load_torque, l.body}, std::nullopt, std::nullopt});
  for (std::size_t c = 0; c < sc.controllers.size(); ++c)
    sys.inputs.push_back({{VariableKind::controller_torque, static_cast<int>(c)}, std::nullopt, std::nullopt});
}

namespace {

// A body's speed in the system's states: its own state (elastic), or the row of omega = Q1 x1 (rigid).
class SpeedOf {
 public:
  SpeedOf(const Derivation& d, bool elastic, const GiNaC::exmap& fold, const SpecializedSystem& sys)
      : d_(d), elastic_(elastic), fold_(fold) {
    for (const StatePort& x : sys.states) x1_.push_back(variable_symbol(d.symbols, x.variable));
  }
  ex operator()(int body) const {
    if (elastic_) return variable_symbol(d_.symbols, {VariableKind::velocity, body});
    ex sum = 0;
    for (std::size_t j = 0; j < x1_.size(); ++j)
      sum += d_.rigid.Q1(static_cast<unsigned>(body), static_cast<unsigned>(j)) * x1_[j];
    return sum.subs(fold_, GiNaC::subs_options::no_pattern).expand();
  }

 private:
  const Derivation& d_;
  bool elastic_;
  const GiNaC::exmap& fold_;
  std::vector<ex> x1_;  // the gear's states, before any controller adds its integral
};

// A load's torque -linear omega - quadratic omega |omega| + constant: the constant an input
// TL_<body> (a constant signal), the quadratic part a temporary TQ_<body>.
void close_load(const LoadSpec& l, const Derivation& d, const SpeedOf& speed, SpecializedSystem& sys, ClosedLoops& out) {
  const SymbolTable& s = d.symbols;
  const Topology& t = d.topology;
  const Variable constant{VariableKind::load_torque, l.body};
  ex law = -exact_number(l.linear) * speed(l.body);
  if (l.constant != 0 || l.varying) {
    sys.inputs.push_back({constant, l.varying ? *l.varying : rt::Signal{rt::Constant{-l.constant}}, std::nullopt});
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
    out.quadratic_speeds.push_back(omega);
    out.quadratic_coefficients.push_back(exact_number(l.quadratic));
    law += q;
    sys.nonlinear = true;
  }
  out.torques[variable_symbol(s, constant)] = law;
}

// A PI speed controller: its set-point an input, its integral a state theta' = ref - omega (with
// limits, plus the back-calculation), its torque the law, or with limits an input set by the runs.
// A slip controller's measures its element's slip, E omega (E its row of engagement_rows).
void close_controller(const ControllerSpec& k, int i, const Derivation& d, const SpeedOf& speed,
                      SpecializedSystem& sys, ClosedLoops& out) {
  const SymbolTable& s = d.symbols;
  const Variable ref{VariableKind::set_point, i}, theta{VariableKind::controller_integral, i};
  sys.inputs.push_back({ref, k.set_point, k.set_point_start});
  sys.states.push_back({theta, 0.0});
  ex measured = 0;
  if (k.supplies >= 0) {
    const GiNaC::matrix e = engagement_rows(d.topology, {k.supplies});
    for (unsigned b = 0; b < e.cols(); ++b)
      if (!e(0, b).is_zero()) measured += e(0, b) * speed(static_cast<int>(b));
  } else {
    measured = speed(k.measured);
  }
  const ex error = (variable_symbol(s, ref) - measured).expand();
  const ex law = (exact_number(k.kp) * error + exact_number(k.ki) * variable_symbol(s, theta)).expand();
  if (k.limited() && k.ki != 0) {
    // Back-calculation: T - law is zero within the limits, and at a limit draws the integral
    // towards it with the time constant tracking_time.
    const ex torque = variable_symbol(s, {VariableKind::controller_torque, i});
    const ex tracking = k.integral_time_tracking ? exact_number(k.kp) : exact_number(k.ki) * exact_number(k.tracking_time);
    sys.rhs.push_back((error + (torque - law) / tracking).expand());
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

}  // namespace

ClosedLoops close_loops(const Scene& sc, const Derivation& d, bool elastic, const GiNaC::exmap& fold,
                        SpecializedSystem& sys) {
  ClosedLoops out;
  if (sc.loads.empty() && sc.controllers.empty()) return out;
  const SpeedOf speed(d, elastic, fold, sys);
  // The inputs again, in their final order: the scene's torques, the loads' constant parts, the
  // set-points, the engine's and converter's torques, the friction torques and the limited controllers'
  // torques (last, as the hybrid runs expect).
  std::vector<InputPort> torques, driveline, frictions;
  for (InputPort& u : sys.inputs) {
    if (u.variable.kind == VariableKind::torque) torques.push_back(std::move(u));
    if (of_driveline(u.variable.kind)) driveline.push_back(std::move(u));
    if (u.variable.kind == VariableKind::friction_torque) frictions.push_back(std::move(u));
  }
  sys.inputs = std::move(torques);
  for (const LoadSpec& l : sc.loads) close_load(l, d, speed, sys, out);
  for (std::size_t c = 0; c < sc.controllers.size(); ++c)
    close_controller(sc.controllers[c], static_cast<int>(c), d, speed, sys, out);
  sys.inputs.insert(sys.inputs.end(), driveline.begin(), driveline.end());
  sys.inputs.insert(sys.inputs.end(), frictions.begin(), frictions.end());
  for (const int c : sys.limited_controllers) sys.inputs.push_back({{VariableKind::controller_torque, c}, std::nullopt, std::nullopt});
  for (std::size_t i = 0; i < sys.rhs.size(); ++i)
    sys.rhs[i] = sys.rhs[i].subs(out.torques, GiNaC::subs_options::no_pattern).expand();
  return out;
}

void close_implicit_form(const SymbolTable& s, const ClosedLoops& loops, const std::vector<Variable>& open_inputs,
                         SpecializedSystem& sys) {
  if (!sys.implicit || (loops.torques.empty() && loops.quadratic.empty() && sys.rhs.empty())) return;
  const ImplicitForm& gear = *sys.implicit;
  const unsigned k1 = gear.L.rows(), nx = static_cast<unsigned>(sys.states.size());
  std::vector<ex> rows;
  for (unsigned i = 0; i < k1; ++i) {
    ex row = 0;
    for (unsigned j = 0; j < k1; ++j) row += gear.A(i, j) * variable_symbol(s, sys.states[j].variable);
    for (unsigned c = 0; c < open_inputs.size(); ++c) row += gear.B(i, c) * variable_symbol(s, open_inputs[c]);
    rows.push_back(row.subs(loops.torques, GiNaC::subs_options::no_pattern).expand());
  }
  rows.insert(rows.end(), sys.rhs.begin(), sys.rhs.end());  // the integrals', their torques substituted
  std::vector<ex> variables;
  for (const StatePort& x : sys.states) variables.push_back(variable_symbol(s, x.variable));
  for (const InputPort& u : sys.inputs) variables.push_back(variable_symbol(s, u.variable));
  for (const Assignment& q : loops.quadratic) variables.push_back(q.symbol);
  const GiNaC::matrix coefficients = linear_coefficients(rows, variables);
  const auto nu = static_cast<unsigned>(sys.inputs.size()), nq = static_cast<unsigned>(loops.quadratic.size());
  ImplicitForm f{GiNaC::matrix(nx, nx), GiNaC::matrix(nx, nx), GiNaC::matrix(nx, nu),
                 nq ? GiNaC::matrix(nx, nq) : GiNaC::matrix(0, 0)};
  for (unsigned i = 0; i < nx; ++i) {
    for (unsigned j = 0; j < nx; ++j) {
      f.L(i, j) = i < k1 && j < k1 ? gear.L(i, j) : ex(i == j ? 1 : 0);
      f.A(i, j) = coefficients(i, j);
    }
    for (unsigned c = 0; c < nu; ++c) f.B(i, c) = coefficients(i, nx + c);
    for (unsigned q = 0; q < nq; ++q) f.Q(i, q) = coefficients(i, nx + nu + q);
  }
  sys.implicit = std::move(f);
  sys.rhs.clear();
}

void limit_laws(const SymbolTable& s, const ClosedLoops& loops, SpecializedSystem& sys) {
  if (loops.limited.empty()) return;
  std::vector<ex> variables;
  for (const StatePort& x : sys.states) variables.push_back(variable_symbol(s, x.variable));
  for (const InputPort& u : sys.inputs) variables.push_back(variable_symbol(s, u.variable));
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
