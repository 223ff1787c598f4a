// Where a scene starts when its [initial] names a gear (`gear = "1"` or `engaged = [...]`): in that
// mode of the gear, its brakes and clutches stuck, every speed following the named ones and every
// mesh force and stuck torque from eq. (8) with C = [R; E_S], so that the run starts with no event.
#pragma once

#include "specialize/start_state.hpp"

namespace pogear {

// The systems' initial states for the scene's start ("rigid": at the named speeds, moving as the
// mode's rigid model moves under the torques at t = 0; "steady": at that model's equilibrium), in
// exact rationals rounded once. Throws InputError when the gear leaves more or fewer degrees of
// freedom than speeds are named, an engaged element is not commanded at t = 0 (or another one is), or a stuck torque
// exceeds the element's static capacity at t = 0 (or a one-way element would freewheel).
StartState start_in_gear(const SpecializedScene& model);

}  // namespace pogear
