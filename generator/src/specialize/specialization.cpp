// Specialized equations are built as GiNaC expressions in the scene's own variables, with the
// mesh velocities v = R omega (and damped forces w = F + B_K v) as the shared temporaries.
#include "specialize/specialization.hpp"
#include "specialize/start_state.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "specialize/initial_state.hpp"
#include "specialize/linear_form.hpp"
#include "specialize/loop_closure.hpp"
#include "read/model_parameters.hpp"
#include "specialize/operation_count.hpp"
#include "specialize/parameter_folding.hpp"
#include "common/printer.hpp"
#include "specialize/tunable_parameters.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

bool contains(const std::vector<Variable>& v, Variable x) { return std::find(v.begin(), v.end(), x) != v.end(); }

std::vector<Variable> requested_outputs(const Scene& sc, const Topology& t) {
  if (!sc.outputs.empty()) return sc.outputs;
  std::vector<Variable> out;
  for (std::size_t b = 0; b < t.bodies.size(); ++b) out.push_back({VariableKind::velocity, static_cast<int>(b)});
  if (sc.effects.mesh_forces)
    for (std::size_t i = 0; i < t.meshes.size(); ++i) out.push_back({VariableKind::force, static_cast<int>(i)});
  for (std::size_t c = 0; c < sc.controllers.size(); ++c) out.push_back({VariableKind::controller_torque, static_cast<int>(c)});
  return out;
}

void inputs_of(const Scene& sc, const Topology& t, SpecializedSystem& sys) {
  for (const InputSpec& in : sc.inputs) {
    if (identically_zero(in.signal)) continue;  // a zero input is not an input
    add_input(t, {VariableKind::torque, in.body}, sys);
    sys.input_signals.push_back(in.signal);
  }
}

// Engaged brakes and clutches: their torques are inputs after the scene's (an element whose command
// is zero at every time stays open and leaves no term).
void friction_inputs_of(const Scene& sc, const Topology& t, SpecializedSystem& sys) {
  for (const EngagementSpec& e : sc.engagement) {
    if (identically_zero(e.command)) continue;
    add_input(t, {VariableKind::friction_torque, e.element}, sys);
    sys.friction_elements.push_back(e.element);
  }
}

// The inputs of the gear's equations, before the loops are closed, and the torque each applies to
// each body (input_torques).
struct OpenInputs {
  std::vector<Variable> variables;
  GiNaC::matrix torques;
};

// The torque on a body from every input: its own tau_, its load and controller, and the engaged
// elements' -e_k^T Tf_k.
ex body_torque(const SymbolTable& s, const OpenInputs& in, std::size_t body) {
  ex sum = 0;
  for (std::size_t j = 0; j < in.variables.size(); ++j)
    if (!in.torques(body, j).is_zero()) sum += in.torques(body, j) * variable_symbol(s, in.variables[j]);
  return sum;
}

ex folded(const ex& e, const GiNaC::exmap& fold) { return e.subs(fold, GiNaC::subs_options::no_pattern).expand(); }

// What `--param` accepts for a tunable, and the sign its roles in the model ask for.
TunableParameter tunable_parameter(const Topology& t, const std::string& name, double value) {
  TunableParameter p{name, value, {}, ""};
  const Parameter* given = find_parameter(t, name);
  if (given) {
    if (auto unit = written_unit(*given)) p.units.push_back({unit->first, unit->second});
    if (given->value.has_unit && !(given->value.dimension == Dimension{}) &&
        (p.units.empty() || p.units[0].unit != describe(given->value.dimension)))
      p.units.push_back({describe(given->value.dimension), 1.0});
    if (given->value.has_unit && !(given->value.dimension == Dimension{}))
      for (const auto& spelling : common_unit_spellings(given->value.dimension))
        if (std::none_of(p.units.begin(), p.units.end(), [&](const UnitSpelling& u) { return u.unit == spelling.first; }))
          p.units.push_back({spelling.first, spelling.second});
  }
  bool positive = false, non_negative = false;
  for (const auto& b : t.bodies) {
    positive = positive || b.inertia_parameter == name || (b.axis == AxisKind::carried && b.distance_parameter == name);
    non_negative = non_negative || b.friction_parameter == name;
    for (const auto& w : b.wheels) positive = positive || w.radius_parameter == name;
  }
  for (const auto& m : t.meshes) {
    positive = positive || m.stiffness_parameter == name;
    non_negative = non_negative || m.damping_parameter == name;
  }
  p.sign = positive ? "positive" : non_negative ? "non-negative" : "";
  return p;
}

// A given radius cannot follow a tunable through a geometry relation: it keeps its number, which
// the relation then contradicts at every other value of the tunable.
void check_tunable_geometry(const Scene& sc, const Derivation& d, const GiNaC::exmap& fold) {
  const SymbolTable& s = d.symbols;
  for (const auto& g : d.radius.relations) {
    const ex lhs = parameter_symbol(s, g.parameter).subs(fold, GiNaC::subs_options::no_pattern);
    const ex rhs = g.rhs.subs(fold, GiNaC::subs_options::no_pattern);
    if ((lhs - rhs).expand().is_zero()) continue;
    std::string tunables;
    for (const auto& name : sc.tunable)
      if (lhs.has(parameter_symbol(s, name)) || rhs.has(parameter_symbol(s, name))) tunables += (tunables.empty() ? "'" : ", '") + name + "'";
    if (tunables.empty()) continue;  // rounding of given values, checked when the model was read
    throw InputError(sc.tunable_where,
                     fmt::format("tunable {} enters the geometry relation {} = {} of {}, but '{}' is given in the "
                                 "model and would keep its value; leave '{}' out of the model so that it is derived, "
                                 "or define it through the tunable, or do not tune a radius of this relation",
                                 tunables, g.parameter, print_expression(g.rhs, Notation::ginac),
                                 describe_mesh(d.topology, g.mesh), g.parameter, g.parameter));
  }
}

// E = x^T L x / 2, the energy stored in the specialized system's states, which a run is checked
// against (the power balance bounds it; runtime/pogear/run_system.hpp): L = diag(J, K^-1) for the
// elastic model, L1 = Q1^T J Q1 for the rigid one, folded like the equations (tunables stay symbols).
GiNaC::matrix energy_matrix(const Derivation& d, const GiNaC::exmap& fold, bool elastic) {
  const ElasticModel& e = d.elastic;
  if (elastic) {
    GiNaC::matrix L(e.L.rows(), e.L.cols());
    for (unsigned i = 0; i < e.L.rows(); ++i)
      for (unsigned j = 0; j < e.L.cols(); ++j) L(i, j) = folded(e.L(i, j), fold);
    return L;
  }
  const GiNaC::matrix& Q1 = d.rigid.Q1;
  GiNaC::matrix L(Q1.cols(), Q1.cols());
  // Every J and Q1 entry folds to an exact rational (no tunable among them): L1's entries are sums
  // of rational products of the folded entries, the same numbers as folding each closed-form sum
  // (substitution commutes with exact arithmetic) without expanding (k+1)^2/2 sums of products of
  // the gear's ratios (at k = 40 that expansion was 40% of `generate`).
  std::vector<GiNaC::numeric> J(Q1.rows());
  std::vector<std::vector<GiNaC::numeric>> q(Q1.cols(), std::vector<GiNaC::numeric>(Q1.rows()));
  bool rational = true;
  auto rational_value = [&](const ex& v, GiNaC::numeric& out) {
    const ex f = folded(v, fold);
    rational = rational && GiNaC::is_a<GiNaC::numeric>(f) && GiNaC::ex_to<GiNaC::numeric>(f).is_rational();
    if (rational) out = GiNaC::ex_to<GiNaC::numeric>(f);
  };
  for (unsigned b = 0; b < Q1.rows() && rational; ++b) rational_value(e.J(b, b), J[b]);
  for (unsigned i = 0; i < Q1.cols() && rational; ++i)
    for (unsigned b = 0; b < Q1.rows() && rational; ++b) rational_value(Q1(b, i), q[i][b]);
  if (rational) {
    // Summed as integers over one common denominator per entry and reduced once: a sum of
    // rationals reduces at every addition, and Q1 of a long chain has long numbers.
    auto scale_to_integers = [](std::vector<GiNaC::numeric>& v) {
      GiNaC::numeric d = 1;
      for (const auto& x : v) d = GiNaC::lcm(d, x.denom());
      for (auto& x : v) x = x.mul(d);
      return d;
    };
    const GiNaC::numeric dJ = scale_to_integers(J);
    std::vector<GiNaC::numeric> dq(Q1.cols());
    for (unsigned i = 0; i < Q1.cols(); ++i) dq[i] = scale_to_integers(q[i]);
    for (unsigned i = 0; i < Q1.cols(); ++i)
      for (unsigned j = 0; j <= i; ++j) {
        GiNaC::numeric sum = 0;
        for (unsigned b = 0; b < Q1.rows(); ++b)
          if (!q[i][b].is_zero() && !q[j][b].is_zero()) sum = sum.add(J[b].mul(q[i][b]).mul(q[j][b]));
        L(i, j) = L(j, i) = sum.div(dJ.mul(dq[i]).mul(dq[j]));
      }
    return L;
  }
  for (unsigned i = 0; i < Q1.cols(); ++i)
    for (unsigned j = 0; j <= i; ++j) {
      ex sum = 0;
      for (unsigned b = 0; b < Q1.rows(); ++b) sum += e.J(b, b) * Q1(b, i) * Q1(b, j);
      L(i, j) = L(j, i) = folded(sum, fold);
    }
  return L;
}

// The gear's equations, before loads and controllers close into them: its states (the model's
// variables), the rhs's temporaries and dx/dt, or the implicit form the generated code solves.
struct GearEquations {
  std::string description;  // one line, for the generated header comment
  std::vector<Variable> states;
  std::vector<Assignment> temporaries;
  std::vector<ex> rhs;
  std::optional<ImplicitForm> implicit;
};

// The mesh temporaries v = R omega and, for a damped mesh, w = F + B_K v. Readers of the generated
// code would take a temporary for the parameter of the same name, so a model that has one is refused.
std::vector<Assignment> mesh_temporaries(const Derivation& d, const GiNaC::exmap& fold) {
  const SymbolTable& s = d.symbols;
  const Topology& t = d.topology;
  auto temporary = [&](Variable v) {
    const std::string name = variable_name(t, v);
    if (const Parameter* p = find_parameter(t, name))  // the model's line is where to rename it
      throw InputError(p->where, fmt::format("the model has a parameter named '{}', which pogear's generated code "
                                             "uses for a mesh velocity; rename the parameter", name));
    return Assignment{name, 0, variable_symbol(s, v)};
  };
  std::vector<Assignment> out;
  for (std::size_t i = 0; i < t.meshes.size(); ++i) {
    const Variable vi{VariableKind::mesh_velocity, static_cast<int>(i)}, wi{VariableKind::transmitted_force, static_cast<int>(i)};
    ex v = 0;
    for (std::size_t k = 0; k < t.bodies.size(); ++k)
      v += d.elastic.R(i, k) * variable_symbol(s, {VariableKind::velocity, static_cast<int>(k)});
    out.push_back(temporary(vi));
    out.back().value = folded(v, fold);
    const ex damping = folded(d.elastic.B_K(i, i), fold);
    if (damping.is_zero()) continue;
    out.push_back(temporary(wi));
    out.back().value = folded(variable_symbol(s, {VariableKind::force, static_cast<int>(i)}) + damping * variable_symbol(s, vi), fold);
  }
  return out;
}

// Eqs. (2-3): J omega' = tau - B_J omega - R^T w, K^-1 F' = R omega, w the force each mesh passes on.
GearEquations elastic_equations(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in) {
  const SymbolTable& s = d.symbols;
  const std::size_t n = d.topology.bodies.size(), m = d.topology.meshes.size();
  GearEquations eq{"elastic POG model (eqs. 2-3): J omega' = tau - B_J omega - R^T (B_K R omega + F), "
                   "K^-1 F' = R omega", {}, mesh_temporaries(d, fold), {}, std::nullopt};
  for (std::size_t k = 0; k < n; ++k) eq.states.push_back({VariableKind::velocity, static_cast<int>(k)});
  for (std::size_t i = 0; i < m; ++i) eq.states.push_back({VariableKind::force, static_cast<int>(i)});
  std::vector<ex> w(m);
  for (std::size_t i = 0; i < m; ++i) {
    const bool damped = !folded(d.elastic.B_K(i, i), fold).is_zero();
    w[i] = variable_symbol(s, {damped ? VariableKind::transmitted_force : VariableKind::force, static_cast<int>(i)});
  }
  for (std::size_t k = 0; k < n; ++k) {
    ex torque = body_torque(s, in, k) - d.elastic.B_J(k, k) * variable_symbol(s, {VariableKind::velocity, static_cast<int>(k)});
    for (std::size_t i = 0; i < m; ++i) torque -= d.elastic.R(i, k) * w[i];
    eq.rhs.push_back(folded(torque / d.elastic.J(k, k), fold));
  }
  for (std::size_t i = 0; i < m; ++i)
    eq.rhs.push_back(folded(d.elastic.K(i, i) * variable_symbol(s, {VariableKind::mesh_velocity, static_cast<int>(i)}), fold));
  return eq;
}

// Every parameter a number: x1' = L1^-1 (A1 x1 + B1 tau) exactly, and as A1 = -Q1^T B_J Q1 and
// B1 = Q1^T, that is L1^-1 Q1^T applied to the torques -B_J Q1 (one column per kept velocity) and
// to the inputs' unit vectors: one sparse exact solve (exact_rigid_response), neither L1 nor A1
// formed (the closed forms of a long chain are megabytes to substitute into).
std::vector<ex> rigid_rhs(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in,
                          const std::vector<Variable>& states) {
  const SymbolTable& s = d.symbols;
  const std::size_t n = d.topology.bodies.size(), k1 = states.size(), nu = in.variables.size();
  const GiNaC::matrix Q1 = exact_matrix(d.rigid.Q1, fold);
  GiNaC::matrix torques(n, k1 + nu);
  for (std::size_t b = 0; b < n; ++b) {
    const GiNaC::numeric friction = as_number(exact_value(d.elastic.B_J(b, b), fold));
    for (std::size_t j = 0; j < k1 && !friction.is_zero(); ++j)
      if (!Q1(b, j).is_zero()) torques(b, j) = -friction.mul(as_number(Q1(b, j)));
  }
  for (std::size_t b = 0; b < n; ++b)
    for (std::size_t c = 0; c < nu; ++c) torques(b, k1 + c) = in.torques(b, c);
  const GiNaC::matrix X = exact_rigid_response(d.rigid, d.elastic, fold, torques);
  std::vector<ex> rhs;
  for (std::size_t j = 0; j < k1; ++j) {
    GiNaC::exvector f;
    for (std::size_t i = 0; i < k1; ++i) f.push_back(X(j, i) * variable_symbol(s, states[i]));
    for (std::size_t c = 0; c < nu; ++c) f.push_back(X(j, k1 + c) * variable_symbol(s, in.variables[c]));
    rhs.push_back(folded(GiNaC::add(f), fold));
  }
  return rhs;
}

// With tunables among the inertias, frictions or radii: L1 = Q1^T J Q1, A1 = -Q1^T B_J Q1 and the
// inputs' columns of B1 = Q1^T, entry by entry from the folded Q1, J and B_J: short sums of monomials
// in the tunables. The generated code solves L1 x1' = A1 x1 + B1 tau numerically.
ImplicitForm rigid_implicit_form(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in, std::size_t k1) {
  const std::size_t n = d.topology.bodies.size(), nu = in.variables.size();
  GiNaC::matrix Q1(n, k1);
  for (std::size_t b = 0; b < n; ++b)
    for (std::size_t j = 0; j < k1; ++j) Q1(b, j) = folded(d.rigid.Q1(b, j), fold);
  ImplicitForm f{GiNaC::matrix(k1, k1), GiNaC::matrix(k1, k1), GiNaC::matrix(k1, nu)};
  for (std::size_t i = 0; i < k1; ++i)
    for (std::size_t j = 0; j < k1; ++j) {
      ex l = 0, a = 0;
      for (std::size_t b = 0; b < n; ++b) {
        if (Q1(b, i).is_zero() || Q1(b, j).is_zero()) continue;
        l += d.elastic.J(b, b) * Q1(b, i) * Q1(b, j);
        a -= d.elastic.B_J(b, b) * Q1(b, i) * Q1(b, j);
      }
      f.L(i, j) = folded(l, fold);
      f.A(i, j) = folded(a, fold);
    }
  for (std::size_t c = 0; c < nu; ++c)
    for (std::size_t i = 0; i < k1; ++i) {
      ex sum = 0;
      for (std::size_t b = 0; b < n; ++b) sum += Q1(b, i) * in.torques(b, c);
      f.B(i, c) = folded(sum, fold);
    }
  return f;
}

// Eq. (7): L1 x1' = A1 x1 + B1 tau over the kept velocities, solved exactly when every inertia,
// friction and radius it reads is a number (tunables that are stiffnesses or dampings do not enter it).
GearEquations rigid_equations(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in) {
  GearEquations eq{"rigid reduced POG model (eq. 7): L1 x1' = A1 x1 + B1 tau, omega = Q1 x1, F from eq. (8)",
                   {}, {}, {}, std::nullopt};
  for (int k : d.rigid.kept) eq.states.push_back({VariableKind::velocity, k});
  const std::size_t n = d.topology.bodies.size();
  bool numeric = true;
  for (std::size_t b = 0; b < n; ++b)
    numeric = numeric && GiNaC::is_a<GiNaC::numeric>(folded(d.elastic.J(b, b), fold)) &&
              GiNaC::is_a<GiNaC::numeric>(folded(d.elastic.B_J(b, b), fold));
  for (std::size_t i = 0; i < d.topology.meshes.size(); ++i)
    for (std::size_t b = 0; b < n; ++b) numeric = numeric && GiNaC::is_a<GiNaC::numeric>(folded(d.elastic.R(i, b), fold));
  if (numeric) eq.rhs = rigid_rhs(d, fold, in, eq.states);
  else eq.implicit = rigid_implicit_form(d, fold, in, eq.states.size());
  return eq;
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
      x0.push_back(v.kind == VariableKind::force ? it->second * mesh_count(t, t.meshes[v.index]) : it->second);
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
    x0[gear_states + c] = (given->second - k.kp * (rt::value(k.set_point, 0.0) - omega)) / k.ki;
  }
}

// The outputs the scene asks for, with their values in the system's states and inputs.
struct SystemOutputs {
  std::vector<Variable> variables;
  std::vector<std::string> units;
  std::vector<ex> values;
  bool reads_derivatives = false;  // a rigid system's mesh forces read dx/dt (eq. 8)
};

// One output's value: a state, a controller's law (with limits its input), omega = Q1 x1 of a rigid
// system, or eq. (8)'s force, which reads the torque on each body from the inputs.
ex output_value(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in, const GiNaC::exmap& loop_outputs,
                const std::vector<Variable>& states, std::size_t gear_states, bool elastic, Variable out) {
  const SymbolTable& s = d.symbols;
  if (out.kind == VariableKind::controller_torque) {
    const auto law = loop_outputs.find(variable_symbol(s, out));
    return law != loop_outputs.end() ? law->second : ex(variable_symbol(s, out));
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
    ex value = output_value(d, fold, in, loop_outputs, states, gear_states, elastic, y);
    std::string unit(unit_of(y.kind));
    out.reads_derivatives = out.reads_derivatives || (!elastic && !contains(states, y) &&
                                                      y.kind != VariableKind::controller_torque &&
                                                      y.kind != VariableKind::velocity);
    if (y.kind == VariableKind::force && mesh_count(t, t.meshes[y.index]) > 1)
      value = folded(value / mesh_count(t, t.meshes[y.index]), fold);
    if (y.kind == VariableKind::velocity && sc.speeds_in_rpm) {
      value = folded(value * exact_number(rpm_per_rad_per_s), fold);
      unit = "rpm";
    }
    out.variables.push_back(y);
    out.units.push_back(unit);
    out.values.push_back(value);
  }
  return out;
}

// Slips s_k = e_k omega in the system's states: omega itself (elastic), omega = Q1 x1 (rigid); a
// controller's integral enters no slip.
GiNaC::matrix slip_rows(const Derivation& d, const GiNaC::exmap& fold, const std::vector<int>& elements,
                        const std::vector<Variable>& states, std::size_t gear_states, bool elastic) {
  const GiNaC::matrix E = engagement_rows(d.topology, elements);
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

// The loads' and controllers' laws as the outputs read them: with the quadratic loads' TQ_ written
// out, as the outputs have no temporaries.
GiNaC::exmap loop_output_laws(const ClosedLoops& loops) {
  GiNaC::exmap laws = loops.torques;
  for (const Assignment& q : loops.quadratic)
    for (auto& [symbol, law] : laws) law = law.subs(GiNaC::exmap{{q.symbol, q.value}}, GiNaC::subs_options::no_pattern);
  return laws;
}

void count_system_operations(SpecializedSystem& sys) {
  sys.rhs_ops = sys.implicit ? implicit_operations(*sys.implicit) : count_all(sys.rhs_temporaries, sys.rhs);
  sys.output_ops = count_all({}, sys.output_values);
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
  inputs_of(sc, t, sys);
  loop_inputs_of(sc, t, sys);
  friction_inputs_of(sc, t, sys);
  const OpenInputs open_inputs{sys.input_variables, input_torques(t, sc.controllers, sys.input_variables)};
  GearEquations gear = elastic ? elastic_equations(d, fold, open_inputs) : rigid_equations(d, fold, open_inputs);
  sys.equations = std::move(gear.description);
  for (const Variable v : gear.states) add_state(t, v, sys);
  sys.rhs_temporaries = std::move(gear.temporaries);
  sys.rhs = std::move(gear.rhs);
  sys.implicit = std::move(gear.implicit);
  const std::size_t gear_states = sys.states.size();  // before the controllers' integrals
  const ClosedLoops loops = close_loops(sc, d, elastic, fold, sys);
  sys.x0 = initial_state(sc, d, values.numbers, sys.state_variables, gear_states, elastic);
  start_controllers_at_given_torques(sc, d, values.numbers, sys.state_variables, gear_states, elastic, sys.x0);
  if (!sys.implicit) linear_form(d.symbols, sys);
  limit_laws(d.symbols, loops, sys);
  // After the linear form, which reads a temporary it does not know as a constant, and leaves it out.
  sys.rhs_temporaries.insert(sys.rhs_temporaries.end(), loops.quadratic.begin(), loops.quadratic.end());
  SystemOutputs outputs =
      system_outputs(sc, d, fold, open_inputs, loop_output_laws(loops), sys.state_variables, gear_states, elastic);
  for (const Variable y : outputs.variables) sys.outputs.push_back(variable_name(t, y));
  sys.output_variables = std::move(outputs.variables);
  sys.output_units = std::move(outputs.units);
  sys.output_values = std::move(outputs.values);
  sys.output_derivatives = outputs.reads_derivatives;
  count_system_operations(sys);
  sys.L = sc.controllers.empty() ? energy_matrix(d, fold, elastic) : GiNaC::matrix(0, 0);
  sys.slip = slip_rows(d, fold, sys.friction_elements, sys.state_variables, gear_states, elastic);
  return sys;
}

void add_state(const Topology& t, Variable v, SpecializedSystem& sys) {
  sys.state_variables.push_back(v);
  sys.states.push_back(variable_name(t, v));
  sys.state_units.emplace_back(unit_of(v.kind));
}

void add_input(const Topology& t, Variable v, SpecializedSystem& sys) {
  sys.input_variables.push_back(v);
  sys.inputs.push_back(variable_name(t, v));
}

GiNaC::matrix input_torques(const Topology& t, const std::vector<ControllerSpec>& controllers,
                            const std::vector<Variable>& inputs) {
  GiNaC::matrix G(t.bodies.size(), inputs.size());
  for (std::size_t j = 0; j < inputs.size(); ++j) {
    const VariableKind kind = inputs[j].kind;
    if (kind == VariableKind::torque || kind == VariableKind::load_torque) {
      G(inputs[j].index, j) = 1;
    } else if (kind == VariableKind::controller_torque) {
      G(controllers.at(static_cast<std::size_t>(inputs[j].index)).body, j) = 1;
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
          .limits_torque = !model.main.limited_controllers.empty()};
}

SpecializedScene specialize(const Scene& scene) {
  SpecializedScene model;
  model.scene = scene;
  std::optional<std::vector<std::string>> keep;
  if (!scene.keep.empty()) keep = scene.keep;
  // With every parameter a number the rigid system needs no closed forms of L1 and A1.
  model.derivation = derive_topology(scene.model, keep, scene.keep_where, !scene.tunable.empty());
  const bool rigid_forces = scene.effects.mesh_forces && (!scene.effects.mesh_compliance || scene.compare_rigid);
  if (model.derivation.rigid.redundant_meshes && rigid_forces && !scene.tunable.empty())
    throw InputError(SourceLocation{scene.file, 0, 0},
                     "this model has redundant meshes, whose rigid load split depends on every stiffness and "
                     "radius; it is computed at fixed values, so it cannot be combined with tunable parameters: "
                     "drop 'tunable' or 'mesh_forces'");
  model.values = scene_values(scene, model.derivation);
  if (!scene.tunable.empty()) check_tunable_geometry(scene, model.derivation, model.values.equations);
  model.main = specialize_system(scene, model.derivation, model.values, scene.effects.mesh_compliance);
  if (scene.compare_rigid) model.rigid = specialize_system(scene, model.derivation, model.values, false);
  const Topology& t = model.derivation.topology;
  for (const EngagementSpec& e : scene.engagement) {
    if (identically_zero(e.command)) continue;
    const FrictionElement& f = t.friction_elements[static_cast<std::size_t>(e.element)];
    model.friction.push_back(FrictionRun{e.element, f.name, parameter_value(t, f.capacity_parameter),
                                         static_friction_ratio(t, f), e.command, f.one_way});
  }
  if (const std::optional<StartState> start = start_state(model)) {
    model.main.x0 = start->main;
    if (model.rigid) model.rigid->x0 = start->rigid;
  }
  return model;
}

}  // namespace pogear
