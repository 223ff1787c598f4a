// A scene's [thermal]: the brakes and clutches whose temperature a run gives (scene-format.md,
// "Temperatures").
#pragma once

#include <vector>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// [thermal] as `<element> = { heat_capacity, conductance, ambient, initial }`, in element order.
std::vector<ThermalSpec> read_thermal(const SceneReader& r, const toml::node& n);

// Refuses a temperature of an element the scene does not engage (it never heats).
void check_thermal(const Scene& s);

}  // namespace pogear
