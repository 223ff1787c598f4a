// Reads a scene's [vehicle] and adds it to the scene's model: the wheels and the car as one inertia
// on a half-shaft from the gear's output, reflected through the final drive, with the road load.
#pragma once

#include <filesystem>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// The vehicle body and half-shaft it adds to the model, named so, and its road load (a LoadSpec on
// the vehicle body, appended to s.loads): s.model and s.loads change, s.vehicle is set.
inline constexpr const char* vehicle_body_name = "vehicle";
inline constexpr const char* half_shaft_name = "half_shafts";

void read_vehicle(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir, Scene& s);

// After [loads]: the vehicle's road load joins them (a load of the user's on the vehicle is refused).
void add_road_load(Scene& s);

// Once the whole scene is read: vehicle_jerk only where the run can give it (the elastic model alone).
void check_vehicle_jerk(const Scene& s);

}  // namespace pogear
