// A scene's [actuators]: per brake or clutch the fill delay and first-order lag between its command
// and its engagement (scene-format.md, "Actuators").
#pragma once

#include <vector>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// [actuators] as `<element> = { fill_delay, time_constant }`, in element order.
std::vector<ActuatorSpec> read_actuators(const SceneReader& r, const toml::node& n);

// Refuses an actuator on an element the scene does not engage, on a one-way element, or on one a
// slip controller commands.
void check_actuators(const Scene& s);

}  // namespace pogear
