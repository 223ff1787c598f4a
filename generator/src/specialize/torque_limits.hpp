// The controllers with torque limits of a specialized system as the hybrid engine takes them, slip
// controllers with what ties them to their brake or clutch.
#pragma once

#include <vector>

#include "pogear/hybrid_modes.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// In the order of the system's last inputs: name and limits [N m], and a slip controller's element
// (among model.friction), start [s], trigger (its target's, among `triggered`, the system's
// triggered_signals) and integral (among the system's states). The laws are left empty: the system's
// torque_limit_laws give them.
std::vector<rt::TorqueLimitData> torque_limit_data(const SpecializedScene& model, const SpecializedSystem& sys,
                                                   const std::vector<rt::TriggeredSignal>& triggered);

}  // namespace pogear
