// Where a scene's simulations start when its [initial] asks for `start = "rigid"` (the elastic model
// on the rigid model's trajectory: its state and its eq. (8) mesh forces) or `start = "steady"` (the
// equilibrium of the inputs' values at t = 0), computed exactly at the scene's values.
#pragma once

#include "specialize/specialization.hpp"

namespace pogear {

// Sets the systems' x0 as the scene's `start` asks; `given` leaves them as specialize_system set
// them. Throws InputError at the scene's `start` when the request cannot be met: brakes or clutches
// engaged, tunable parameters, speeds or forces named that the start computes, a rigid scene asking
// for the rigid start, or inputs without an equilibrium.
void apply_start(SpecializedScene& model);

}  // namespace pogear
