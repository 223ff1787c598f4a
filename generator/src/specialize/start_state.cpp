// Both starts are solved in exact rationals on the rigid model and rounded once, so a run that
// starts steady stays there to rounding, and one that starts rigid meets eq. (8) at t = 0 to rounding.
#include "specialize/start_state.hpp"

#include <algorithm>

#include <fmt/format.h>
#include <pogear/driveline.hpp>

#include "common/exact_algebra.hpp"
#include "specialize/gear_start.hpp"
#include "specialize/initial_state.hpp"
#include "names/symbols.hpp"
#include "specialize/tunable_parameters.hpp"

namespace pogear {
namespace {

GiNaC::matrix as_column(const std::vector<GiNaC::numeric>& v) {
  GiNaC::matrix m(static_cast<unsigned>(v.size()), 1);
  for (std::size_t b = 0; b < v.size(); ++b) m(static_cast<unsigned>(b), 0) = v[b];
  return m;
}

}  // namespace

std::vector<GiNaC::numeric> torques_at_start(const Scene& sc, std::size_t bodies) {
  std::vector<GiNaC::numeric> tau(bodies, 0);
  for (const InputSpec& in : sc.inputs) tau[static_cast<std::size_t>(in.body)] += exact_number(value_at_start(in.signal, in.start));
  return tau;
}

void add_speed_dependent_torques(const Scene& sc, const GiNaC::matrix& omega, std::vector<GiNaC::numeric>& tau) {
  for (const LoadSpec& l : sc.loads) {
    const auto b = static_cast<std::size_t>(l.body);
    const GiNaC::numeric w = GiNaC::ex_to<GiNaC::numeric>(omega(static_cast<unsigned>(b), 0));
    tau[b] -= exact_number(l.constant) + exact_number(l.linear) * w + exact_number(l.quadratic) * w * abs(w);
  }
  // The engine's and the converter's torques, as the runtime evaluates them from the state at t = 0.
  auto speed = [&](int body) { return to_double(omega(static_cast<unsigned>(body), 0)); };
  if (sc.engine) {
    const double throttle = rt::value(sc.engine->throttle, 0.0);
    tau[static_cast<std::size_t>(sc.engine->body)] += exact_number(rt::engine_torque(sc.engine->map, speed(sc.engine->body), throttle).torque);
  }
  if (sc.converter) {
    const rt::ConverterTorques c = rt::converter_torques(sc.converter->curves, speed(sc.converter->pump), speed(sc.converter->turbine));
    tau[static_cast<std::size_t>(sc.converter->pump)] += exact_number(c.pump);
    tau[static_cast<std::size_t>(sc.converter->turbine)] += exact_number(c.turbine);
  }
}

GiNaC::matrix rigid_acceleration(const RigidValues& rv, const GiNaC::matrix& x, const std::vector<GiNaC::numeric>& tau) {
  return exact_solve(rv.L1, exact_product(rv.A1, x).add(exact_product(rv.Q1.transpose(), as_column(tau))));
}

GiNaC::matrix steady_rigid_state(const Scene& sc, const RigidValues& rv, std::vector<GiNaC::numeric>& tau) {
  const unsigned k = rv.Q1.cols();
  // The loads' constant parts drive, their linear parts damp: A1 - Q1^T diag(c1) Q1 (a quadratic
  // part is refused when the scene is read: the equilibrium would not be linear).
  std::vector<GiNaC::numeric> driving_tau = tau, c1(tau.size(), 0);
  for (const LoadSpec& l : sc.loads) {
    driving_tau[static_cast<std::size_t>(l.body)] -= exact_number(l.constant);
    c1[static_cast<std::size_t>(l.body)] += exact_number(l.linear);
  }
  GiNaC::matrix damped = rv.A1;
  for (unsigned i = 0; i < k; ++i)
    for (unsigned j = 0; j < k; ++j)
      for (std::size_t b = 0; b < c1.size(); ++b)
        if (!c1[b].is_zero())
          damped(i, j) = damped(i, j) - rv.Q1(static_cast<unsigned>(b), i) * c1[b] * rv.Q1(static_cast<unsigned>(b), j);
  const GiNaC::matrix drive = exact_product(rv.Q1.transpose(), as_column(driving_tau)).mul_scalar(-1);
  bool undriven = true;
  for (unsigned j = 0; j < k; ++j) undriven = undriven && drive(j, 0).is_zero();
  // Nothing drives at t = 0: rest is an equilibrium, with or without bearing friction (without,
  // every constant speed is one too; the steady start is the one that does not move).
  GiNaC::matrix x(k, 1);
  if (undriven) {
    for (unsigned j = 0; j < k; ++j) x(j, 0) = 0;
  } else try {
    x = exact_solve(damped, drive);
  } catch (const std::domain_error&) {
    throw InputError(sc.start_where,
                     "start = \"steady\": the gear has no equilibrium (a rigid motion meets no bearing friction, so "
                     "a constant torque accelerates it for ever); add bearing_friction to the effects, or start "
                     "from given speeds");
  }
  add_speed_dependent_torques(sc, exact_product(rv.Q1, x), tau);  // at the equilibrium speeds
  return x;
}

namespace {

// The states on the rigid model's trajectory at x1 (exact, in the kept order) moving at dx1: the rigid
// system's x1 and the elastic one's speeds Q1 x1 with eq. (8)'s mesh forces (the split by stiffness
// for redundant meshes).
StartState start_on_rigid_trajectory(const SpecializedScene& model, const GiNaC::exmap& values, const RigidValues& rv,
                                     const std::vector<GiNaC::numeric>& tau, const GiNaC::matrix& x,
                                     const GiNaC::matrix& dx) {
  const Derivation& d = model.derivation;
  const std::size_t n = d.topology.bodies.size();
  const GiNaC::matrix omega = exact_product(rv.Q1, x), domega = exact_product(rv.Q1, dx);
  GiNaC::exmap at_start = values;
  const SymbolTable& s = d.symbols;
  for (std::size_t b = 0; b < n; ++b) {
    const int i = static_cast<int>(b);
    at_start[variable_symbol(s, {VariableKind::velocity, i})] = omega(b, 0);
    at_start[variable_symbol(s, {VariableKind::acceleration, i})] = domega(b, 0);
    at_start[variable_symbol(s, {VariableKind::torque, i})] = tau[b];
  }
  auto state = [&](const SpecializedSystem& sys) {
    std::vector<double> x0;
    for (std::size_t i = 0; i < sys.states.size(); ++i) {
      const Variable v = sys.states[i].variable;
      x0.push_back(sys.kind == SystemKind::rigid       ? to_double(x(static_cast<unsigned>(i), 0))
                   : v.kind == VariableKind::velocity ? to_double(omega(static_cast<unsigned>(v.index), 0))
                                                      : to_double(exact_value(d.rigid.force_recovery.at(
                                                                                  static_cast<std::size_t>(v.index)),
                                                                              at_start)));
    }
    return x0;
  };
  return {state(model.main), model.rigid ? state(*model.rigid) : std::vector<double>{}};
}

// start = "rigid": x1 from the named speeds, moving as eq. (7) says: L1 x1' = A1 x1 + Q1^T tau.
// start = "steady": the rigid equilibrium A1 x1 + Q1^T tau = 0, at rest relative to it. The elastic
// model's equilibrium is that one: R omega = 0 stops the springs, Q1^T of its speed equation is the
// rigid one, and from unloaded springs the redundant meshes' forces split by stiffness.
StartState start_from_rigid_model(const SpecializedScene& model, const GiNaC::exmap& values) {
  const Derivation& d = model.derivation;
  const RigidValues rv = exact_rigid_values(d.rigid, d.elastic, values);
  const Scene& sc = model.scene;
  std::vector<GiNaC::numeric> tau = torques_at_start(sc, d.topology.bodies.size());
  const unsigned k = rv.Q1.cols();
  GiNaC::matrix x(k, 1), dx(k, 1);
  if (sc.start == Start::rigid) {
    const std::vector<double> x1 = rigid_initial_state(sc, d, values);
    for (unsigned j = 0; j < k; ++j) x(j, 0) = exact_number(x1[j]);
    add_speed_dependent_torques(sc, exact_product(rv.Q1, x), tau);  // at the given speeds
    dx = rigid_acceleration(rv, x, tau);
  } else {
    x = steady_rigid_state(sc, rv, tau);
  }
  return start_on_rigid_trajectory(model, values, rv, tau, x, dx);
}

}  // namespace

std::optional<StartState> start_state(const SpecializedScene& model) {
  const Scene& sc = model.scene;
  if (sc.start == Start::given) return std::nullopt;
  const Topology& t = model.derivation.topology;
  const std::string start = sc.start == Start::rigid ? "rigid" : "steady";
  auto refuse = [&](const std::string& why) {
    throw InputError(sc.start_where, fmt::format("start = \"{}\" {}", start, why));
  };
  // A gear's state does not depend on the capacities, which only bound its stuck torques: those are
  // checked again at --param's values (simulate_scene) and by the engine at t = 0 (held_at_start).
  if (!sc.initial_engaged.empty()) {
    std::vector<std::string> moved = sc.tunable;
    for (const auto& [name, value] : tunable_dependents(t.parameters, sc.tunable, model.derivation.symbols))
      moved.push_back(name);
    for (const std::string& name : moved)
      if (std::none_of(t.friction_elements.begin(), t.friction_elements.end(),
                       [&](const FrictionElement& f) { return f.capacity_parameter == name; }))
        throw InputError(sc.initial_engaged_where,
                         fmt::format("a start in a gear is computed at the scene's parameter values, which tunable "
                                     "parameters other than brakes' and clutches' capacities change at run time ('{}' "
                                     "is not a capacity); set it in [parameters], or start from given speeds", name));
    return start_in_gear(model);
  }
  if (!sc.tunable.empty())
    refuse("is computed at the scene's parameter values, which tunable parameters change at run time; set them in "
           "[parameters], or start from given speeds");
  if (!model.friction.empty())
    refuse("is not available with brakes or clutches engaged (whether each one sticks at t = 0 is a choice of its "
           "own); start in a gear ([initial] gear = \"1\"), or from given speeds");
  for (const auto& [v, value] : sc.initial) {
    if (sc.start == Start::steady)
      refuse(fmt::format("computes the whole state from the inputs at t = 0; remove {} from [initial]", variable_name(t, v)));
    if (v.kind == VariableKind::force)
      refuse(fmt::format("takes the mesh forces from the rigid model; remove {} from [initial]", variable_name(t, v)));
  }
  if (sc.start == Start::rigid && model.main.kind == SystemKind::rigid)
    refuse("starts the elastic model on the rigid model's trajectory; this scene simulates the rigid model (no "
           "mesh_compliance), which starts there already: remove start");
  return start_from_rigid_model(model, model.values.numbers);
}

}  // namespace pogear
