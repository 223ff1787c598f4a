// Shared by the engagement tests here and their end-to-end half in tests/commands/: a shipped model
// derived without the rigid model's closed forms (not derive/test_support.hpp's derive_file, which
// derives them; a file includes one or the other).
#pragma once

#include <optional>
#include <string>

#include "../support/files.hpp"
#include "derive/derivation.hpp"
#include "read/topology.hpp"

namespace pogear::test {

inline Derivation derive_file(const std::string& model) {
  const std::string path = source_path("models/" + model + ".toml");
  return derive_topology(parse_topology(path), std::nullopt, SourceLocation{path, 0, 0}, false);
}

}  // namespace pogear::test
