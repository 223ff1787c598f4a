// The signals and commands of a specialized scene that start on an event (scene-format.md,
// "Triggered signals"), as the hybrid engine takes them.
#pragma once

#include <optional>
#include <string>
#include <vector>

#include "pogear/hybrid_modes.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// The system's signals and the scene's commands that start on an event (rt::TriggeredSignal): an
// input's index among the system's signals, a command's among model.friction, the trigger's element
// among model.friction too.
std::vector<rt::TriggeredSignal> triggered_signals(const SpecializedScene& model, const SpecializedSystem& sys);

// The name an element's triggered command has in the events file.
std::string started_command_name(const std::string& element);

// A signal as a run applied it, once its start is known (`started`, infinite when it never came): its
// `before` until then, then its own times from there; a table through the pieces of both (a jump at
// the start), or the signal itself when it does not wait for an event. For what the run's files
// are read against (shift metrics); piecewise linear signals only (a started one is, and so is a
// command's `before`).
rt::Signal signal_as_run(const rt::Signal& signal, const std::optional<SignalStart>& start, double started, double horizon);

}  // namespace pogear
