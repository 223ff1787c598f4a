// The initial state of a scene's systems from its [initial] table: every named speed honoured
// exactly, the freedom they leave fixed by one documented rule (docs/scene-format.md, [initial]).
#pragma once

#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "derive/derivation.hpp"
#include "read/scene.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The rigid model's kept velocities x1 (in the rigid model's order) with Q1 x1 equal to every
// speed the scene names. When the named speeds leave freedom, kept bodies the scene does not name
// are at rest, taken in the kept order while each adds a condition. `values`: every parameter as
// a number. Throws InputError at the scene's [initial] when the named speeds contradict the gear's
// kinematics, naming the bodies and the relation among their speeds that they violate.
std::vector<double> rigid_initial_state(const Scene& scene, const Derivation& d, const GiNaC::exmap& values);

// For an elastic main system whose initial speeds break the rigid kinematics (R omega0 != 0):
// one summary line per mesh they deflect, with its deflection rate and the force that rate meets
// on the mesh's own effective inertia; empty when every mesh starts at rest relative to its mate.
std::string initial_deflection_note(const SpecializedScene& model);

}  // namespace pogear
