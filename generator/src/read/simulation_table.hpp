// Reads a scene's [simulation] (docs/scene-format.md, "Keys") into the scene.
#pragma once

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// Sets s.horizon, sample, solver (solver_given, solver_where), tolerance, step and max_steps.
void read_simulation(const SceneReader& r, const toml::node& n, Scene& s);

}  // namespace pogear
