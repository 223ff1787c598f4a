// Signals that start on an event (scene-format.md, "Triggered signals"): reading `when`, `delay`
// and `before`, and checking that the event can come.
#pragma once

#include <filesystem>
#include <optional>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// The start on an event that a signal's table gives with `when` and `delay`, or none; `signal` is
// what read_signal read from it.
std::optional<SignalStart> read_signal_start(const SceneReader& r, const toml::node& n, const rt::Signal& signal,
                                             const std::filesystem::path& scene_dir, SignalQuantity what);

// Refuses a signal that waits for an element the scene does not engage (to slip, stick, or cross a
// slip speed: an element without a command has no slip in the runs).
void check_signal_starts(const Scene& s);

}  // namespace pogear
