// Reads a scene's `effects`: which physical effects its equations keep, checked against its model
// (an effect on meshes or shafts it does not have, damping without compliance).
#pragma once

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

Effects read_effects(const SceneReader& r, const toml::node& n, const Topology& t);

}  // namespace pogear
