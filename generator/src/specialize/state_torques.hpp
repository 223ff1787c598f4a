// The rows over a system's states its runs read and the torques of the state (state_torques.cpp).
#pragma once

#include <vector>

#include "derive/derivation.hpp"
#include "read/scene.hpp"
#include "specialize/loop_closure.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The body a driveline torque (Tengine, Tpump, Tturbine) acts on.
int driveline_body(const Scene& scene, VariableKind kind);

// The engine's and converter's torques as inputs of sys (after its signals; the runs compute them).
void driveline_inputs_of(const Scene& sc, SpecializedSystem& sys);

// Rows E omega over the system's states: omega itself (elastic), Q1 x1 (rigid); none on a
// controller's integral. The engaged elements' slips; the speed of each driveline torque's body.
GiNaC::matrix state_rows(const Derivation& d, const GiNaC::exmap& fold, const GiNaC::matrix& E,
                         const std::vector<Variable>& states, std::size_t gear_states, bool elastic);
GiNaC::matrix slip_rows(const Derivation& d, const GiNaC::exmap& fold, const std::vector<int>& elements,
                        const std::vector<Variable>& states, std::size_t gear_states, bool elastic);
GiNaC::matrix driveline_speed_rows(const Scene& sc, const Derivation& d, const GiNaC::exmap& fold,
                                   const SpecializedSystem& sys, const std::vector<Variable>& states,
                                   std::size_t gear_states, bool elastic);

// The quadratic loads' columns of dx/dt and speeds over the states (sys.quadratic_*).
void quadratic_load_form(const SymbolTable& s, const ClosedLoops& loops, SpecializedSystem& sys);

// The elastic model's vehicle_jerk, refused where an input on the car's row is not constant.
GiNaC::ex vehicle_jerk_value(const Scene& sc, const Derivation& d, const SpecializedSystem& sys);

}  // namespace pogear
