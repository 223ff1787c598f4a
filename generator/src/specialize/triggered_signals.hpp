// The signals and commands of a specialized scene that start on an event (scene-format.md,
// "Triggered signals"), as the hybrid engine takes them.
#pragma once

#include <vector>

#include "pogear/hybrid_modes.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The system's signals and the scene's commands that start on an event (rt::TriggeredSignal): an
// input's index among the system's signals, a command's among model.friction, the trigger's element
// among model.friction too.
std::vector<rt::TriggeredSignal> triggered_signals(const SpecializedScene& model, const SpecializedSystem& sys);

}  // namespace pogear
