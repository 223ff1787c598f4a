// Reads the gears a model names ([gears]) and the gear a scene starts in ([initial] gear or
// engaged): each a set of the model's brakes and clutches, refused at the value that is wrong.
#pragma once

#include <string>
#include <vector>

#include <toml++/toml.h>

#include "read/scene_reader.hpp"
#include "read/toml_reader.hpp"
#include "read/topology.hpp"

namespace pogear {

// The model's [gears], "<name>" = ["<element>", ...], in the order written, each with its elements
// ascending. Whether each is a gear between an input and an output is for `pogear ratios` to check.
std::vector<NamedGear> read_gears(const TomlReader& r, const toml::node& n, const Topology& t);

// A scene's start in a gear: the elements stuck at t = 0, ascending; the gear's name in the model's
// [gears], empty for engaged = [...]; where it is written.
struct InitialGear {
  std::vector<int> engaged;
  std::string name;
  SourceLocation where;
};

// [initial] gear = "<name>" (`key` "gear") or engaged = ["<element>", ...] (`key` "engaged").
InitialGear read_initial_gear(const SceneReader& r, const toml::node& value, const std::string& key, const Topology& t);

}  // namespace pogear
