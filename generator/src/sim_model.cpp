// Specialized equations are built as GiNaC expressions in the scene's own variables, with the
// mesh velocities v = R omega (and damped forces w = F + B_K v) as the shared temporaries.
#include "sim_model.hpp"

#include <algorithm>
#include <map>
#include <set>

#include <fmt/format.h>

#include "printer.hpp"
#include "tunable_parameters.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

bool contains(const std::vector<std::string>& v, const std::string& x) {
  return std::find(v.begin(), v.end(), x) != v.end();
}

// Values of every non-tunable parameter; zeros for the parameters of effects left out.
GiNaC::exmap folding(const Scene& sc, Derivation& d, bool keep_tunables) {
  Symbols& s = d.symbols;
  GiNaC::exmap fold;
  std::set<std::string> tunable(sc.tunable.begin(), sc.tunable.end());
  if (!keep_tunables) tunable.clear();
  // Parameters defined through a tunable follow it (K_pr = "K_ps").
  const std::map<std::string, ex> dependents =
      tunable.empty() ? std::map<std::string, ex>{} : tunable_dependents(d.topology.parameters, sc.tunable, s);
  for (const auto& [name, v] : d.radius.values) {
    if (tunable.count(name)) continue;
    const auto it = dependents.find(name);
    fold[symbol(s, name)] = it != dependents.end() ? it->second : ex(exact_number(v));
  }
  // A derived radius (one the model leaves out) follows a tunable one through the geometry
  // relations; a given one keeps its value, and check_tunable_geometry refuses the contradiction.
  for (const auto& g : d.radius.relations) {
    if (std::find(d.radius.derived.begin(), d.radius.derived.end(), g.parameter) == d.radius.derived.end()) continue;
    const ex value = g.rhs.subs(fold, GiNaC::subs_options::no_pattern).expand();
    if (!GiNaC::is_a<GiNaC::numeric>(value)) fold[symbol(s, g.parameter)] = value;
  }
  if (!sc.effects.bearing_friction)
    for (const auto& b : d.topology.bodies) fold[symbol(s, b.friction)] = 0;
  if (!sc.effects.mesh_damping)
    for (const auto& m : d.topology.meshes) fold[symbol(s, m.damping)] = 0;
  return fold;
}

std::vector<std::string> requested_outputs(const Scene& sc, const Derivation& d) {
  if (!sc.outputs.empty()) return sc.outputs;
  std::vector<std::string> out = d.elastic.velocities;
  if (sc.effects.mesh_forces) out.insert(out.end(), d.elastic.forces.begin(), d.elastic.forces.end());
  return out;
}

std::string unit_of(const std::string& name) { return name.rfind("F_", 0) == 0 ? "N" : "rad/s"; }

void inputs_of(const Scene& sc, SimSystem& sys) {
  for (std::size_t i = 0; i < sc.inputs.size(); ++i) {
    if (sc.inputs[i].signal.identically_zero()) continue;  // a zero input is not an input
    sys.inputs.push_back("tau_" + sc.inputs[i].body);
    sys.input_signal.push_back(static_cast<int>(i));
  }
}

ex input_or_zero(Symbols& s, const SimSystem& sys, const std::string& torque) {
  return contains(sys.inputs, torque) ? ex(symbol(s, torque)) : ex(0);
}

using VariableIndex = std::map<ex, int, GiNaC::ex_is_less>;

// Whether e holds any of the variables.
bool has_variable(const ex& e, const VariableIndex& vars) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) return vars.count(e) > 0;
  for (const ex& op : e)
    if (has_variable(op, vars)) return true;
  return false;
}

// The variable a term of an expanded linear form is proportional to: -1 for none, -2 when the
// term is not of the form (variable-free factors) * variable.
int variable_of(const ex& term, const VariableIndex& vars) {
  if (GiNaC::is_a<GiNaC::symbol>(term)) {
    const auto it = vars.find(term);
    return it == vars.end() ? -1 : it->second;
  }
  if (!GiNaC::is_exactly_a<GiNaC::mul>(term)) return has_variable(term, vars) ? -2 : -1;
  int found = -1;
  for (const ex& factor : term) {
    const auto it = GiNaC::is_a<GiNaC::symbol>(factor) ? vars.find(factor) : vars.end();
    if (it != vars.end()) {
      if (found != -1) return -2;
      found = it->second;
    } else if (has_variable(factor, vars)) {
      return -2;
    }
  }
  return found;
}

// dx/dt = M x + N u, read off the (linear) right-hand side with the temporaries substituted.
// Each term of a row is differentiated once, by its own variable: differentiating the whole row
// by every variable re-added the row's big numbers (k^3 additions for a rigid chain of k states).
// The sums of the derivatives are the same canonical expressions diff gives; a row with a term
// of another shape goes through diff.
void linear_form(Symbols& s, SimSystem& sys) {
  GiNaC::exmap temps;
  for (const auto& a : sys.rhs_temporaries) temps[symbol(s, a.name)] = a.value.subs(temps, GiNaC::subs_options::no_pattern);
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size();
  std::vector<ex> variables;
  VariableIndex index;
  for (const auto& name : sys.states) variables.push_back(symbol(s, name));
  for (const auto& name : sys.inputs) variables.push_back(symbol(s, name));
  for (std::size_t j = 0; j < variables.size(); ++j) index.emplace(variables[j], static_cast<int>(j));
  sys.M = GiNaC::matrix(nx, nx);
  sys.N = GiNaC::matrix(nx, nu);
  for (std::size_t i = 0; i < nx; ++i) {
    const ex f = sys.rhs[i].subs(temps, GiNaC::subs_options::no_pattern).expand();
    std::vector<GiNaC::exvector> parts(variables.size());
    bool linear = true;
    auto take = [&](const ex& term) {
      const int v = variable_of(term, index);
      if (v == -2) linear = false;
      if (v >= 0) parts[v].push_back(term.diff(GiNaC::ex_to<GiNaC::symbol>(variables[v])));
    };
    if (GiNaC::is_exactly_a<GiNaC::add>(f)) {
      for (const ex& term : f) take(term);
    } else {
      take(f);
    }
    for (std::size_t j = 0; j < variables.size(); ++j) {
      const ex c = !linear ? f.diff(GiNaC::ex_to<GiNaC::symbol>(variables[j]))
                   : parts[j].empty() ? ex(0) : GiNaC::add(parts[j]);
      if (j < nx) sys.M(i, j) = c; else sys.N(i, j - nx) = c;
    }
  }
}

OperationCount count_all(const std::vector<Assignment>& temps, const std::vector<ex>& values) {
  OperationCount c;
  auto add = [&](const ex& e) {
    const OperationCount o = count_operations(e);
    c.multiplications += o.multiplications;
    c.additions += o.additions;
  };
  for (const auto& a : temps) add(a.value);
  for (const auto& v : values) add(v);
  return c;
}

// The entries of L, A and B, one Cholesky factorization of L, its solves for M = L^-1 A and
// N = L^-1 B, and M x + N u: what the generated rhs computes (the solve's counts are the usual
// leading terms, not a count of Eigen's code).
OperationCount implicit_operations(const ImplicitForm& f) {
  std::vector<ex> entries;
  for (const GiNaC::matrix* m : {&f.L, &f.A, &f.B})
    for (unsigned i = 0; i < m->rows(); ++i)
      for (unsigned j = 0; j < m->cols(); ++j) entries.push_back((*m)(i, j));
  OperationCount c = count_all({}, entries);
  const int k = static_cast<int>(f.L.rows()), columns = static_cast<int>(f.A.cols() + f.B.cols());
  c.multiplications += k * k * k / 6 + k + columns * k * k + columns * k;
  c.additions += k * k * k / 6 + columns * k * (k - 1) + columns * k;
  return c;
}

// What `--param` accepts for a tunable, and the sign its roles in the model ask for.
TunableParameter tunable_parameter(const Topology& t, const std::string& name, double value) {
  TunableParameter p{name, value, {}, ""};
  const Parameter* given = find_parameter(t, name);
  if (given) {
    if (auto unit = written_unit(*given)) p.units.push_back({unit->first, unit->second});
    if (given->value.has_unit && !(given->value.dimension == Dimension{}) &&
        (p.units.empty() || p.units[0].unit != describe(given->value.dimension)))
      p.units.push_back({describe(given->value.dimension), 1.0});
  }
  bool positive = false, non_negative = false;
  for (const auto& b : t.bodies) {
    positive = positive || b.inertia == name || (b.axis == AxisKind::carried && b.distance == name);
    non_negative = non_negative || b.friction == name;
    for (const auto& w : b.wheels) positive = positive || w.radius == name;
  }
  for (const auto& m : t.meshes) {
    positive = positive || m.stiffness == name;
    non_negative = non_negative || m.damping == name;
  }
  p.sign = positive ? "positive" : non_negative ? "non-negative" : "";
  return p;
}

// A given radius cannot follow a tunable through a geometry relation: it keeps its number, which
// the relation then contradicts at every other value of the tunable.
void check_tunable_geometry(const Scene& sc, Derivation& d) {
  const GiNaC::exmap fold = folding(sc, d, true);
  Symbols& s = d.symbols;
  for (const auto& g : d.radius.relations) {
    const ex lhs = symbol(s, g.parameter).subs(fold, GiNaC::subs_options::no_pattern);
    const ex rhs = g.rhs.subs(fold, GiNaC::subs_options::no_pattern);
    if ((lhs - rhs).expand().is_zero()) continue;
    std::string tunables;
    for (const auto& name : sc.tunable)
      if (lhs.has(symbol(s, name)) || rhs.has(symbol(s, name))) tunables += (tunables.empty() ? "'" : ", '") + name + "'";
    if (tunables.empty()) continue;  // rounding of given values, checked when the model was read
    throw InputError(sc.tunable_where,
                     fmt::format("tunable {} enters the geometry relation {} = {} of {}, but '{}' is given in the "
                                 "model and would keep its value; leave '{}' out of the model so that it is derived, "
                                 "or define it through the tunable, or do not tune a radius of this relation",
                                 tunables, g.parameter, print_expression(g.rhs, Notation::ginac),
                                 describe_mesh(d.topology, g.mesh), g.parameter, g.parameter));
  }
}

}  // namespace

OperationCount count_operations(const ex& e) {
  OperationCount c;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    c.additions += static_cast<int>(e.nops()) - 1;
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    int factors = 0;
    for (const ex& f : e)
      if (!(GiNaC::is_a<GiNaC::numeric>(f) && (f.is_equal(-1) || f.is_equal(1)))) ++factors;
    c.multiplications += std::max(0, factors - 1);
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    if (GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer()) {
      const int p = std::abs(GiNaC::ex_to<GiNaC::numeric>(e.op(1)).to_int());
      c.multiplications += std::max(0, p - 1) + (GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_negative() ? 1 : 0);
    } else {
      c.multiplications += 1;
    }
  }
  for (const ex& op : e) {
    const OperationCount o = count_operations(op);
    c.multiplications += o.multiplications;
    c.additions += o.additions;
  }
  return c;
}

// E = x^T L x / 2, the energy stored in the specialized system's states, which a run is checked
// against (the power balance bounds it; runtime/pogear/scene_runner.hpp): L = diag(J, K^-1) for the
// elastic model, L1 = Q1^T J Q1 for the rigid one, folded like the equations (tunables stay symbols).
GiNaC::matrix energy_matrix(const Scene& sc, Derivation& d, bool elastic) {
  const GiNaC::exmap fold = folding(sc, d, true);
  auto folded = [&](const ex& e) { return e.subs(fold, GiNaC::subs_options::no_pattern).expand(); };
  const ElasticModel& e = d.elastic;
  if (elastic) {
    GiNaC::matrix L(e.L.rows(), e.L.cols());
    for (unsigned i = 0; i < e.L.rows(); ++i)
      for (unsigned j = 0; j < e.L.cols(); ++j) L(i, j) = folded(e.L(i, j));
    return L;
  }
  const GiNaC::matrix& Q1 = d.rigid.Q1;
  GiNaC::matrix L(Q1.cols(), Q1.cols());
  for (unsigned i = 0; i < Q1.cols(); ++i)
    for (unsigned j = 0; j <= i; ++j) {
      ex sum = 0;
      for (unsigned b = 0; b < Q1.rows(); ++b) sum += e.J(b, b) * Q1(b, i) * Q1(b, j);
      L(i, j) = L(j, i) = folded(sum);
    }
  return L;
}

SimSystem specialize_system(const Scene& sc, Derivation& d, bool elastic) {
  Symbols& s = d.symbols;
  const Topology& t = d.topology;
  const std::size_t n = t.bodies.size();
  const std::size_t m = t.meshes.size();
  const GiNaC::exmap fold = folding(sc, d, true);
  auto folded = [&](const ex& e) { return e.subs(fold, GiNaC::subs_options::no_pattern).expand(); };
  SimSystem sys;
  sys.kind = elastic ? "elastic" : "rigid";
  for (const auto& name : sc.tunable) sys.params.push_back(tunable_parameter(t, name, d.radius.values.at(name)));
  inputs_of(sc, sys);

  // Names of temporaries must not shadow anything else in the generated function.
  auto fresh = [&](const std::string& name) {
    if (d.radius.values.count(name)) {
      const Parameter* p = find_parameter(t, name);  // the model's line is where to rename it
      throw InputError(p ? p->where : SourceLocation{sc.file, 0, 0},
                       fmt::format("the model has a parameter named '{}', which pogear's generated code uses for a "
                                   "mesh velocity; rename the parameter", name));
    }
    return name;
  };

  if (elastic) {
    sys.equations = "elastic POG model (eqs. 2-3): J omega' = tau - B_J omega - R^T (B_K R omega + F), "
                    "K^-1 F' = R omega";
    for (std::size_t k = 0; k < n; ++k) sys.states.push_back(d.elastic.velocities[k]);
    for (std::size_t i = 0; i < m; ++i) sys.states.push_back(d.elastic.forces[i]);
    std::vector<ex> w(m);  // the force each mesh passes on, damping included
    for (std::size_t i = 0; i < m; ++i) {
      ex v = 0;
      for (std::size_t k = 0; k < n; ++k) v += d.elastic.R(i, k) * symbol(s, d.elastic.velocities[k]);
      const std::string vname = fresh("v_" + t.meshes[i].name);
      sys.rhs_temporaries.push_back({vname, folded(v)});
      const ex damping = folded(d.elastic.B_K(i, i));
      if (damping.is_zero()) {
        w[i] = symbol(s, d.elastic.forces[i]);
      } else {
        const std::string wname = fresh("w_" + t.meshes[i].name);
        sys.rhs_temporaries.push_back({wname, folded(symbol(s, d.elastic.forces[i]) + damping * symbol(s, vname))});
        w[i] = symbol(s, wname);
      }
    }
    for (std::size_t k = 0; k < n; ++k) {
      ex torque = input_or_zero(s, sys, d.elastic.torques[k]) - d.elastic.B_J(k, k) * symbol(s, d.elastic.velocities[k]);
      for (std::size_t i = 0; i < m; ++i) torque -= d.elastic.R(i, k) * w[i];
      sys.rhs.push_back(folded(torque / d.elastic.J(k, k)));
    }
    for (std::size_t i = 0; i < m; ++i)
      sys.rhs.push_back(folded(d.elastic.K(i, i) * symbol(s, "v_" + t.meshes[i].name)));
  } else {
    sys.equations = "rigid reduced POG model (eq. 7): L1 x1' = A1 x1 + B1 tau, omega = Q1 x1, "
                    "F from eq. (8)";
    for (int k : d.rigid.kept) sys.states.push_back(d.elastic.velocities[k]);
    const std::size_t k1 = sys.states.size();
    // Whether every inertia, friction and radius the rigid system reads is a number (tunables that
    // are stiffnesses or dampings do not enter it).
    bool numeric = true;
    for (std::size_t b = 0; b < n; ++b)
      numeric = numeric && GiNaC::is_a<GiNaC::numeric>(folded(d.elastic.J(b, b))) &&
                GiNaC::is_a<GiNaC::numeric>(folded(d.elastic.B_J(b, b)));
    for (std::size_t i = 0; i < m; ++i)
      for (std::size_t b = 0; b < n; ++b) numeric = numeric && GiNaC::is_a<GiNaC::numeric>(folded(d.elastic.R(i, b)));
    if (numeric) {
      // Every parameter is a number: x1' = L1^-1 (A1 x1 + B1 tau) exactly, and as A1 = -Q1^T B_J Q1
      // and B1 = Q1^T, that is L1^-1 Q1^T applied to the torques -B_J Q1 (one column per kept
      // velocity) and to the inputs' unit vectors: one sparse exact solve (exact_rigid_response),
      // neither L1 nor A1 formed (the closed forms of a long chain are megabytes to substitute into).
      const GiNaC::matrix Q1 = exact_matrix(d.rigid.Q1, fold);
      std::vector<std::size_t> driven;  // bodies with an input torque
      for (std::size_t b = 0; b < n; ++b)
        if (!input_or_zero(s, sys, d.elastic.torques[b]).is_zero()) driven.push_back(b);
      GiNaC::matrix torques(n, k1 + driven.size());
      for (std::size_t b = 0; b < n; ++b) {
        const GiNaC::numeric friction = as_number(exact_value(d.elastic.B_J(b, b), fold));
        for (std::size_t j = 0; j < k1 && !friction.is_zero(); ++j)
          if (!Q1(b, j).is_zero()) torques(b, j) = -friction.mul(as_number(Q1(b, j)));
      }
      for (std::size_t c = 0; c < driven.size(); ++c) torques(driven[c], k1 + c) = 1;
      const GiNaC::matrix X = exact_rigid_response(d.rigid, d.elastic, fold, torques);
      for (std::size_t j = 0; j < k1; ++j) {
        GiNaC::exvector f;
        for (std::size_t i = 0; i < k1; ++i) f.push_back(X(j, i) * symbol(s, sys.states[i]));
        for (std::size_t c = 0; c < driven.size(); ++c) f.push_back(X(j, k1 + c) * symbol(s, d.elastic.torques[driven[c]]));
        sys.rhs.push_back(folded(GiNaC::add(f)));
      }
    } else {
      // L1 = Q1^T J Q1, A1 = -Q1^T B_J Q1 and the inputs' columns of B1 = Q1^T, entry by entry from
      // the folded Q1, J and B_J: short sums of monomials in the tunables. The generated code
      // solves L1 x1' = A1 x1 + B1 tau numerically (see SimSystem::implicit).
      GiNaC::matrix Q1(n, k1);
      for (std::size_t b = 0; b < n; ++b)
        for (std::size_t j = 0; j < k1; ++j) Q1(b, j) = folded(d.rigid.Q1(b, j));
      ImplicitForm f{GiNaC::matrix(k1, k1), GiNaC::matrix(k1, k1), GiNaC::matrix(k1, sys.inputs.size())};
      for (std::size_t i = 0; i < k1; ++i)
        for (std::size_t j = 0; j < k1; ++j) {
          ex l = 0, a = 0;
          for (std::size_t b = 0; b < n; ++b) {
            if (Q1(b, i).is_zero() || Q1(b, j).is_zero()) continue;
            l += d.elastic.J(b, b) * Q1(b, i) * Q1(b, j);
            a -= d.elastic.B_J(b, b) * Q1(b, i) * Q1(b, j);
          }
          f.L(i, j) = folded(l);
          f.A(i, j) = folded(a);
        }
      for (std::size_t c = 0; c < sys.inputs.size(); ++c) {
        const std::size_t b = static_cast<std::size_t>(find_body(t, sys.inputs[c].substr(4)));
        for (std::size_t i = 0; i < k1; ++i) f.B(i, c) = Q1(b, i);
      }
      sys.implicit = std::move(f);
    }
  }
  for (std::size_t i = 0; i < sys.states.size(); ++i) {
    auto it = sc.initial.find(sys.states[i]);
    sys.x0.push_back(it == sc.initial.end() ? 0.0 : it->second);
    sys.state_units.push_back(unit_of(sys.states[i]));
  }
  if (!sys.implicit) linear_form(s, sys);

  // Outputs: only those asked for.
  const std::vector<std::string> wanted = requested_outputs(sc, d);
  bool need_derivatives = false;
  for (const auto& name : wanted) {
    sys.outputs.push_back(name);
    sys.output_units.push_back(unit_of(name));
    if (elastic || contains(sys.states, name)) {
      sys.output_values.push_back(symbol(s, name));
      continue;
    }
    if (name.rfind("omega_", 0) == 0) {
      const int b = find_body(t, name.substr(6));
      ex w = 0;
      for (std::size_t j = 0; j < sys.states.size(); ++j) w += d.rigid.Q1(b, j) * symbol(s, sys.states[j]);
      sys.output_values.push_back(folded(w));
    } else {
      std::size_t i = 0;
      while (d.elastic.forces[i] != name) ++i;
      GiNaC::exmap zero_inputs;
      for (const auto& tau : d.elastic.torques)
        if (!contains(sys.inputs, tau)) zero_inputs[symbol(s, tau)] = 0;
      sys.output_values.push_back(folded(d.rigid.force_recovery.at(i).subs(zero_inputs)));
      need_derivatives = true;
    }
  }
  if (need_derivatives && sys.implicit) sys.output_derivatives = true;
  else if (need_derivatives)
    for (std::size_t j = 0; j < sys.states.size(); ++j)
      sys.output_temporaries.push_back({"d" + sys.states[j], sys.rhs[j]});
  sys.rhs_ops = sys.implicit ? implicit_operations(*sys.implicit) : count_all(sys.rhs_temporaries, sys.rhs);
  sys.output_ops = count_all(sys.output_temporaries, sys.output_values);
  if (sys.output_derivatives) {  // the outputs call rhs
    sys.output_ops.multiplications += sys.rhs_ops.multiplications;
    sys.output_ops.additions += sys.rhs_ops.additions;
  }
  sys.L = energy_matrix(sc, d, elastic);
  return sys;
}

SimModel specialize(const Scene& scene) {
  SimModel model;
  model.scene = scene;
  Topology t = apply_overrides(parse_topology(scene.model_file), scene);
  std::optional<std::vector<std::string>> keep;
  if (!scene.keep.empty()) keep = scene.keep;
  // With every parameter a number the rigid system needs no closed forms of L1 and A1.
  model.derivation = derive_topology(std::move(t), keep, scene.keep_where, !scene.tunable.empty());
  const bool rigid_forces = scene.effects.mesh_forces && (!scene.effects.mesh_compliance || scene.compare_rigid);
  if (model.derivation.rigid.redundant_meshes && rigid_forces && !scene.tunable.empty())
    throw InputError(SourceLocation{scene.file, 0, 0},
                     "this model has redundant meshes, whose rigid load split depends on every stiffness and "
                     "radius; it is computed at fixed values, so it cannot be combined with tunable parameters: "
                     "drop 'tunable' or 'mesh_forces'");
  if (!scene.tunable.empty()) check_tunable_geometry(scene, model.derivation);
  model.main = specialize_system(scene, model.derivation, scene.effects.mesh_compliance);
  if (scene.compare_rigid) model.rigid = specialize_system(scene, model.derivation, false);
  return model;
}

NumericSystem numeric_system(const SimModel& model, const SimSystem& sys) {
  Derivation d = model.derivation;  // symbols are shared handles
  const GiNaC::exmap values = folding(model.scene, d, false);
  const ElasticModel& e = d.elastic;
  // Exact rational arithmetic on the assembled matrices, rounded once at the end: the same
  // numbers the specialized expressions give, by another formula.
  auto exact = [&](const GiNaC::matrix& m) { return exact_matrix(m, values); };
  auto doubles = [](const GiNaC::matrix& m) { return evaluate_matrix(m, {}); };
  NumericSystem out;
  std::vector<int> input_bodies;
  for (const auto& tau : sys.inputs)
    input_bodies.push_back(static_cast<int>(std::find(e.torques.begin(), e.torques.end(), tau) - e.torques.begin()));
  auto input_columns = [&](const GiNaC::matrix& B) {
    GiNaC::matrix out(B.rows(), input_bodies.size());
    for (unsigned i = 0; i < B.rows(); ++i)
      for (std::size_t j = 0; j < input_bodies.size(); ++j) out(i, j) = B(i, input_bodies[j]);
    return out;
  };
  const std::size_t nx = sys.states.size(), ny = sys.outputs.size(), nu = sys.inputs.size();
  out.C = Eigen::MatrixXd::Zero(ny, nx);
  out.D = Eigen::MatrixXd::Zero(ny, nu);
  out.E = Eigen::MatrixXd::Zero(ny, nx);
  out.x0 = Eigen::Map<const Eigen::VectorXd>(sys.x0.data(), nx);
  auto state_index = [&](const std::string& name) {
    return static_cast<Eigen::Index>(std::find(sys.states.begin(), sys.states.end(), name) - sys.states.begin());
  };
  if (sys.kind == "elastic") {
    const GiNaC::matrix L = exact(e.L);
    out.L = doubles(L);
    out.M = doubles(exact_solve(L, exact(e.A)));
    out.N = doubles(exact_solve(L, input_columns(exact(e.B))));
    for (std::size_t i = 0; i < ny; ++i) out.C(i, state_index(sys.outputs[i])) = 1;
  } else {
    // L1, A1 and Q1 from Q1's entries, not by substituting into the closed forms (the same numbers).
    const RigidValues v = exact_rigid_values(d.rigid, e, values);
    const GiNaC::matrix& Q1 = v.Q1;
    const GiNaC::matrix R = exact(e.R), J = exact(e.J), BJ = exact(e.B_J);
    out.L = doubles(v.L1);
    out.M = doubles(exact_solve(v.L1, v.A1));
    out.N = doubles(exact_solve(v.L1, input_columns(Q1.transpose())));
    // Eq. (8) literally, F = (R R^T)^-1 R g with g = tau - J Q1 x1' - B_J Q1 x1; with redundant
    // meshes the stiffness-weighted split F = K R (R^T K R)^+ g, which equals
    // K R (R^T K R + Q1 Q1^T)^-1 g because g is orthogonal to ker R = span Q1. The inverse is
    // applied to the columns needed, [B_J Q1, J Q1, the inputs' unit vectors], not formed.
    const unsigned n = Q1.rows(), k = Q1.cols();
    GiNaC::matrix G(n, 2 * k + nu);
    for (unsigned b = 0; b < n; ++b)
      for (unsigned j = 0; j < k; ++j) {
        G(b, j) = BJ(b, b) * Q1(b, j);
        G(b, k + j) = J(b, b) * Q1(b, j);
      }
    for (std::size_t j = 0; j < nu; ++j) G(input_bodies[j], 2 * k + j) = 1;
    GiNaC::matrix PG;  // P G
    if (!d.rigid.redundant_meshes) {
      PG = exact_solve(exact_product(R, R.transpose()), exact_product(R, G));
    } else {
      const GiNaC::matrix K = exact(e.K);
      const GiNaC::matrix S = exact_product(exact_product(R.transpose(), K), R).add(exact_product(Q1, Q1.transpose()));
      PG = exact_product(exact_product(K, R), exact_solve(S, G));
    }
    const Eigen::MatrixXd PGn = doubles(PG), Q1n = doubles(Q1);
    const Eigen::MatrixXd C_F = -PGn.leftCols(k), E_F = -PGn.middleCols(k, k);
    for (std::size_t i = 0; i < ny; ++i) {
      const std::string& name = sys.outputs[i];
      if (name.rfind("omega_", 0) == 0) {
        out.C.row(i) = Q1n.row(find_body(d.topology, name.substr(6)));
      } else {
        const auto f = std::find(e.forces.begin(), e.forces.end(), name) - e.forces.begin();
        out.C.row(i) = C_F.row(f);
        out.E.row(i) = E_F.row(f);
        for (std::size_t j = 0; j < nu; ++j) out.D(i, j) = PGn(f, 2 * k + j);
      }
    }
  }
  return out;
}

Eigen::MatrixXd state_matrix(const SimModel& model, const SimSystem& sys) {
  Derivation d = model.derivation;
  const GiNaC::exmap values = folding(model.scene, d, false);
  if (!sys.implicit) return evaluate_matrix(sys.M, values);
  return evaluate_matrix(sys.implicit->L, values).llt().solve(evaluate_matrix(sys.implicit->A, values));
}

Diagnostics system_diagnostics(const SimModel& model, const SimSystem& sys) {
  Derivation d = model.derivation;
  const GiNaC::exmap values = folding(model.scene, d, false);
  // The specialized system's own M, exact in the tunable parameters, at their values: the numbers
  // numeric_system computes by another formula (the tests compare them), without solving again.
  // L1 holds inertias and radii only, which the folding leaves at the model's values.
  return diagnose(state_matrix(model, sys), evaluate_matrix(d.rigid_values.L1, {}),
                  evaluate_matrix(d.elastic.R, values), model.scene.sample);
}

}  // namespace pogear
