// Reads one [[body]] table of a model file: its axis, arrow, inertia and friction names, its
// toothed wheels (by radius, or by teeth and module) and, for lumped planets, their count.
#pragma once

#include <string>

#include <toml++/toml.h>

#include "read/toml_reader.hpp"
#include "read/topology.hpp"

namespace pogear {

Body read_body(const TomlReader& r, const toml::table& t);

// A `module` value (of a wheel, a body or a mesh), or another length such as a mesh's
// `centre_distance` (`key`): a length expression, or a number in metres.
void read_module(const TomlReader& r, const toml::node& n, std::string& text, SourceLocation& where, int& column_offset,
                 std::string_view key = "module");

}  // namespace pogear
