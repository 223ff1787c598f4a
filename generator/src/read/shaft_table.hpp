// Reads a model's [[shaft]] tables: torsional spring-dampers between two bodies on the central
// axis, each refused at the value that is wrong.
#pragma once

#include <toml++/toml.h>

#include "read/toml_reader.hpp"
#include "names/model.hpp"

namespace pogear {

// Appends each [[shaft]] to t.meshes (shaft = true), after the toothed meshes, in file order.
void read_shafts(const TomlReader& r, const toml::node& list, Topology& t);

// A shaft's name must differ from every body, mesh, brake and clutch: its torque T_<name> would be
// a brake's, clutch's or fixed body's, its damping b_<name> a body's bearing friction.
void check_shaft_names(const Topology& t);

}  // namespace pogear
