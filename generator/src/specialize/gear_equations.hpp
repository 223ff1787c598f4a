// The gear's own equations for a scene, before its loads and controllers close in: eqs. (2-3) of
// the elastic model, eq. (7) of the rigid one, and the energy E = x^T L x / 2 a run is checked against.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "derive/derivation.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The inputs of the gear's equations, before the loops are closed, and the torque each applies to
// each body (input_torques).
struct OpenInputs {
  std::vector<Variable> variables;
  GiNaC::matrix torques;
};

// The torque on a body from every input: its own tau_, its load and controller, and the engaged
// elements' -e_k^T Tf_k.
GiNaC::ex body_torque(const SymbolTable& s, const OpenInputs& in, std::size_t body);

// An expression at the scene's folded values, expanded.
inline GiNaC::ex folded(const GiNaC::ex& e, const GiNaC::exmap& fold) {
  return e.subs(fold, GiNaC::subs_options::no_pattern).expand();
}

// The gear's equations, before loads and controllers close into them: its states (the model's
// variables), the rhs's temporaries and dx/dt, or the implicit form the generated code solves.
struct GearEquations {
  std::string description;  // one line, for the generated header comment
  std::vector<Variable> states;
  std::vector<Assignment> temporaries;
  std::vector<GiNaC::ex> rhs;
  std::optional<ImplicitForm> implicit;
};

// Eqs. (2-3): J omega' = tau - B_J omega - R^T w, K^-1 F' = R omega, w the force each mesh passes on.
GearEquations elastic_equations(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in);
// Eq. (7): L1 x1' = A1 x1 + B1 tau over the kept velocities, solved exactly when every inertia,
// friction and radius it reads is a number, else left to the generated code (ImplicitForm).
GearEquations rigid_equations(const Derivation& d, const GiNaC::exmap& fold, const OpenInputs& in);

// L = diag(J, K^-1) of the elastic model or L1 = Q1^T J Q1 of the rigid one, folded like the
// equations (tunables stay symbols).
GiNaC::matrix energy_matrix(const Derivation& d, const GiNaC::exmap& fold, bool elastic);

}  // namespace pogear
