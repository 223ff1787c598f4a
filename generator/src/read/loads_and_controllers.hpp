// The scene's loads and speed controllers ([loads], [controllers]): read and checked against the
// model, so that specialization can take them as given.
#pragma once

#include <filesystem>
#include <vector>

#include <toml++/toml.h>

#include "read/scene.hpp"
#include "read/scene_reader.hpp"

namespace pogear {

// [loads]: a table of <body> = { constant, linear, quadratic }, in body order.
std::vector<LoadSpec> read_loads(const SceneReader& r, const toml::node& n);

// [controllers]: a table of <name> = { body, speed_of, set_point, kp, ki }; their names name their
// variables (controller_variable_name), which must not be the model's parameters.
std::vector<ControllerSpec> read_controllers(const SceneReader& r, const toml::node& n,
                                             const std::filesystem::path& scene_dir, const Topology& model);

// The names of the scene's speed controllers, in order: they name the controllers' variables.
std::vector<std::string> controller_names(const Scene& scene);
// A variable of the scene by its name, among the given kinds: the model's, or one of its speed
// controllers' (controller_variable_name).
std::optional<Variable> find_scene_variable(const Scene& s, std::string_view name,
                                            std::initializer_list<VariableKind> kinds);

}  // namespace pogear
