// The gear's equations are GiNaC expressions in the scene's own variables, with the mesh velocities
// v = R omega (and damped forces w = F + B_K v) as the shared temporaries.
#include "specialize/gear_equations.hpp"

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "read/model_parameters.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

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

}  // namespace

GiNaC::ex body_torque(const SymbolTable& s, const OpenInputs& in, std::size_t body) {
  ex sum = 0;
  for (std::size_t j = 0; j < in.variables.size(); ++j)
    if (!in.torques(body, j).is_zero()) sum += in.torques(body, j) * variable_symbol(s, in.variables[j]);
  return sum;
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

}  // namespace pogear
