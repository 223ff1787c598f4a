// The scene's slip controllers ([slip_control]): a PI controller of a brake's or clutch's slip speed
// that sets its command, read as a speed controller of that slip (ControllerSpec::supplies).
#pragma once

#include <filesystem>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// [slip_control]: a table of <element> = { target, kp, ki, tracking_time, start }, each appended to
// the scene's controllers as slip_<element>. After [controllers] and [engagement], which must list
// the element (its command until the controller starts).
void read_slip_control(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir, Scene& s);

// Once the horizon is known: the sign of each target's first value other than zero gives the torque
// limits (0 and the element's capacity in that direction); a slip controller takes no start torque.
void check_slip_control(Scene& s);

bool has_slip_control(const Scene& s);
// The scene's slip controller of brake or clutch `element` (an index into the controllers), or -1.
int slip_controller_of(const Scene& s, int element);

}  // namespace pogear
