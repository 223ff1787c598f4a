// Reads a scene's [engine] and [converter] and adds them to the scene's model: the engine's body,
// the converter's lock-up clutch; their torques are the scene's (EngineSpec, ConverterSpec).
#pragma once

#include <filesystem>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// The body [engine] adds, and the clutch [converter] adds between pump and turbine for its lock-up.
inline constexpr const char* engine_body_name = "engine";
inline constexpr const char* lockup_clutch_name = "lockup";

// Engine maps and converter tables are published in these units, and written in them.
inline constexpr double rad_per_s_per_rpm = 0.10471975511965977;  // pi / 30

// [engine]: inertia, the throttle signal, and its map (map_speeds [rpm], map_throttles [0 to 1],
// map_torques [N m], one row per throttle). Adds the body `engine` (after the model's, in the model's
// default kept velocities) and sets s.engine.
void read_engine(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir, Scene& s);

// [converter]: pump (default the engine) and turbine bodies, speed_ratio, capacity_factor [rpm /
// sqrt(N m)] and torque_ratio tables, and a lock-up clutch { capacity, static_ratio } when it has one.
// Sets s.converter.
void read_converter(const SceneReader& r, const toml::node& n, Scene& s);

// Once the whole scene is read: what an engine or a converter cannot be combined with (yet), and a
// throttle from 0 to 1 over the run.
void check_driveline(const Scene& s);

}  // namespace pogear
