// Both starts are solved in exact rationals and rounded once, so a run that starts steady stays
// there to rounding, and one that starts rigid meets eq. (8) at t = 0 to rounding.
#include "start_state.hpp"

#include <fmt/format.h>

#include "exact_algebra.hpp"
#include "initial_state.hpp"
#include "parameter_folding.hpp"
#include "symbols.hpp"

namespace pogear {
namespace {

// The torque on each body at t = 0 from the scene's inputs, exactly as the runtime evaluates them.
std::vector<GiNaC::numeric> torques_at_start(const Scene& sc, std::size_t bodies) {
  std::vector<GiNaC::numeric> tau(bodies, 0);
  for (const InputSpec& in : sc.inputs) tau[static_cast<std::size_t>(in.body)] += exact_number(rt::value(in.signal, 0.0));
  return tau;
}

void start_rigid(SpecializedScene& model, const GiNaC::exmap& values) {
  const Derivation& d = model.derivation;
  const std::size_t n = d.topology.bodies.size();
  const std::vector<double> x1 = rigid_initial_state(model.scene, d, values);
  const RigidValues rv = exact_rigid_values(d.rigid, d.elastic, values);
  const std::vector<GiNaC::numeric> tau = torques_at_start(model.scene, n);
  const unsigned k = rv.Q1.cols();
  GiNaC::matrix x(k, 1), rhs(k, 1);
  for (unsigned j = 0; j < k; ++j) x(j, 0) = exact_number(x1[j]);
  GiNaC::matrix tau_m(n, 1);
  for (std::size_t b = 0; b < n; ++b) tau_m(b, 0) = tau[b];
  // L1 x1' = A1 x1 + Q1^T tau (eq. 7), then omega = Q1 x1 and domega = Q1 x1'.
  const GiNaC::matrix forcing = exact_product(rv.A1, x).add(exact_product(rv.Q1.transpose(), tau_m));
  const GiNaC::matrix dx = exact_solve(rv.L1, forcing);
  const GiNaC::matrix omega = exact_product(rv.Q1, x), domega = exact_product(rv.Q1, dx);
  // Eq. (8) as the rigid model's force outputs read it (the split by stiffness for redundant meshes).
  GiNaC::exmap at_start = values;
  const SymbolTable& s = d.symbols;
  for (std::size_t b = 0; b < n; ++b) {
    const int i = static_cast<int>(b);
    at_start[variable_symbol(s, {VariableKind::velocity, i})] = omega(b, 0);
    at_start[variable_symbol(s, {VariableKind::acceleration, i})] = domega(b, 0);
    at_start[variable_symbol(s, {VariableKind::torque, i})] = tau[b];
  }
  SpecializedSystem& sys = model.main;
  for (std::size_t i = 0; i < sys.state_variables.size(); ++i) {
    const Variable v = sys.state_variables[i];
    sys.x0[i] = v.kind == VariableKind::velocity
                    ? to_double(omega(static_cast<unsigned>(v.index), 0))
                    : to_double(exact_value(d.rigid.force_recovery.at(static_cast<std::size_t>(v.index)), at_start));
  }
}

// dx/dt = M x + N u = 0 for the inputs' values at t = 0.
void start_steady(const SpecializedScene& model, SpecializedSystem& sys) {
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size();
  GiNaC::matrix u(nu, 1);
  for (std::size_t c = 0; c < nu; ++c)
    u(c, 0) = exact_number(rt::value(model.scene.inputs[static_cast<std::size_t>(sys.input_signal[c])].signal, 0.0));
  GiNaC::matrix x;
  try {
    x = exact_solve(sys.M, exact_product(sys.N, u).mul_scalar(-1));
  } catch (const std::domain_error&) {
    throw InputError(model.scene.start_where,
                     fmt::format("start = \"steady\": the {} model has no equilibrium (its state matrix is singular: a "
                                 "body without bearing friction turns freely, so a constant torque accelerates it for "
                                 "ever); add bearing_friction to the effects, or start from given speeds",
                                 kind_name(sys.kind)));
  }
  for (std::size_t i = 0; i < nx; ++i) sys.x0[i] = to_double(x(static_cast<unsigned>(i), 0));
}

}  // namespace

void apply_start(SpecializedScene& model) {
  const Scene& sc = model.scene;
  if (sc.start == Start::given) return;
  const Topology& t = model.derivation.topology;
  const std::string start = sc.start == Start::rigid ? "rigid" : "steady";
  auto refuse = [&](const std::string& why) {
    throw InputError(sc.start_where, fmt::format("start = \"{}\" {}", start, why));
  };
  if (!model.friction.empty())
    refuse("is not available with brakes or clutches engaged (whether each one sticks at t = 0 is a choice of its "
           "own); start from given speeds");
  if (!sc.tunable.empty())
    refuse("is computed at the scene's parameter values, which tunable parameters change at run time; set them in "
           "[parameters], or start from given speeds");
  for (const auto& [v, value] : sc.initial) {
    if (sc.start == Start::steady)
      refuse(fmt::format("computes the whole state from the inputs at t = 0; remove {} from [initial]", variable_name(t, v)));
    if (v.kind == VariableKind::force)
      refuse(fmt::format("takes the mesh forces from the rigid model; remove {} from [initial]", variable_name(t, v)));
  }
  if (sc.start == Start::rigid && model.main.kind == SystemKind::rigid)
    refuse("starts the elastic model on the rigid model's trajectory; this scene simulates the rigid model (no "
           "mesh_compliance), which starts there already: remove start");
  const GiNaC::exmap values = parameter_folding(sc, model.derivation, false);
  if (sc.start == Start::rigid) {
    start_rigid(model, values);
    return;
  }
  start_steady(model, model.main);
  if (model.rigid) start_steady(model, *model.rigid);
}

}  // namespace pogear
