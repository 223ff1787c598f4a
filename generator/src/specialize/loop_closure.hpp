// Loads and speed controllers closed into a specialized system: their torques are inputs while the
// gear's equations are built, then laws of the state (scene-format.md, "Loads", "Controllers").
#pragma once

#include <vector>

#include <ginac/ginac.h>

#include "derive/derivation.hpp"
#include "read/scene.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The torques of the loads and controllers as inputs (TL_<body>, Tc_<controller>), after the
// scene's own: the gear's equations are built with them.
void loop_inputs_of(const Scene& sc, SpecializedSystem& sys);

// What close_loops leaves to the rest of specialization.
struct ClosedLoops {
  GiNaC::exmap torques;  // TL_ and Tc_ -> their laws, for the outputs
  std::vector<Assignment> quadratic;  // TQ_<body> = -c omega |omega|, temporaries after the linear form
  std::vector<GiNaC::ex> quadratic_speeds, quadratic_coefficients;  // omega and c of each, in its order
  std::vector<GiNaC::ex> limited;  // the laws of the controllers with torque limits
};

// Writes the loads' and controllers' torques as functions of the state: a controller adds its
// integral theta' = ref - omega_measured (with limits, plus its back-calculation) and reads its
// set-point ref as an input; a load keeps its constant part as the input TL_<body> (a constant
// signal) and its quadratic part as a temporary TQ_<body>. A controller with torque limits keeps
// its torque as an input, the very last: the hybrid runs close it while it is within its limits.
// The inputs end up as: the scene's torques, the loads' constant parts, the set-points, the
// friction torques, the limited controllers' torques.
ClosedLoops close_loops(const Scene& sc, const Derivation& d, bool elastic, const GiNaC::exmap& fold,
                        SpecializedSystem& sys);

// A rigid system solved from tunables (SpecializedSystem::implicit) with loads or controllers: its
// implicit form over the closed loop, L dx/dt = A x + B u + Q TQ, the laws substituted into the
// gear's rows (B1's columns over `open_inputs`) and the integrals' rows, explicit, under an identity
// block of L. The integrals' rows leave sys.rhs, which an implicit system does not have.
void close_implicit_form(const SymbolTable& s, const ClosedLoops& loops, const std::vector<Variable>& open_inputs,
                         SpecializedSystem& sys);

// The limited controllers' laws as rows over the states and the inputs (SpecializedSystem::limit_law_x, _u).
void limit_laws(const SymbolTable& s, const ClosedLoops& loops, SpecializedSystem& sys);

}  // namespace pogear
