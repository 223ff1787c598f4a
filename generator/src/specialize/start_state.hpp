// Where a scene's simulations start when its [initial] asks for `start = "rigid"` (the elastic model
// on the rigid model's trajectory: its state and its eq. (8) mesh forces) or `start = "steady"` (the
// equilibrium of the inputs' values at t = 0), computed exactly at the scene's values.
#pragma once

#include <optional>
#include <vector>

#include "specialize/specialization.hpp"

namespace pogear {

// The systems' initial states.
struct StartState {
  std::vector<double> main, rigid;  // rigid: empty without the comparison
};

// The torque on each body at t = 0 from the scene's inputs, exactly as the runtime evaluates them.
std::vector<GiNaC::numeric> torques_at_start(const Scene& sc, std::size_t bodies);
// The loads' torques -(c0 + c1 omega + c2 omega |omega|), the engine's map and the converter's pump
// and turbine torques added to tau at the body speeds omega.
void add_speed_dependent_torques(const Scene& sc, const GiNaC::matrix& omega, std::vector<GiNaC::numeric>& tau);
// The rigid model's x1' at x1 under the torques tau: L1 x1' = A1 x1 + Q1^T tau.
GiNaC::matrix rigid_acceleration(const RigidValues& rv, const GiNaC::matrix& x, const std::vector<GiNaC::numeric>& tau);
// The rigid model's equilibrium A1 x1 + Q1^T tau = 0 with the loads' constant parts driving and
// their linear parts damping; adds the loads' torques at it to tau. Throws InputError at the scene's
// `start` when there is none.
GiNaC::matrix steady_rigid_state(const Scene& sc, const RigidValues& rv, std::vector<GiNaC::numeric>& tau);

// The initial states the scene's `start` asks for; nothing for `given`, which leaves them as
// specialize_system set them. Throws InputError at the scene's `start` when the request cannot be
// met: brakes or clutches engaged, tunable parameters, speeds or forces named that the start
// computes, a rigid scene asking for the rigid start, or inputs without an equilibrium.
std::optional<StartState> start_state(const SpecializedScene& model);

}  // namespace pogear
