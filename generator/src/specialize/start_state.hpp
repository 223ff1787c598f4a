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

// The initial states the scene's `start` asks for; nothing for `given`, which leaves them as
// specialize_system set them. Throws InputError at the scene's `start` when the request cannot be
// met: brakes or clutches engaged, tunable parameters, speeds or forces named that the start
// computes, a rigid scene asking for the rigid start, or inputs without an equilibrium.
std::optional<StartState> start_state(const SpecializedScene& model);

}  // namespace pogear
