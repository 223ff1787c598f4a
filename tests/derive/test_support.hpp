// Shared helpers for the derive tests: the paper's models, symbols by name, symbolic equality
// under the geometry relations.
#pragma once

#include <fstream>
#include <sstream>
#include <string>

#include <gtest/gtest.h>

#include "derivation.hpp"
#include "printer.hpp"

namespace pogear::test {

inline std::string source_path(const std::string& relative) {
  return std::string(POGEAR_SOURCE_DIR) + "/" + relative;
}

inline std::string read_text(const std::string& path) {
  std::ifstream in(path);
  std::ostringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

inline Derivation derive_paper(const std::string& model, const std::vector<std::string>& keep) {
  std::optional<std::vector<std::string>> k;
  if (!keep.empty()) k = keep;
  return derive_model(source_path("models/" + model + ".toml"), k, SourceLocation{"--keep", 0, 0});
}

// The named symbol of a derivation (GiNaC symbols compare by identity, not by name).
inline GiNaC::ex sym(Derivation& d, const std::string& name) { return symbol(d.symbols, name); }

// True when a - b normalizes to 0 once the geometry relations are substituted.
inline bool equal_under_geometry(Derivation& d, const GiNaC::ex& a, const GiNaC::ex& b) {
  const GiNaC::exmap g = geometry_substitutions(d.radius, d.symbols);
  return (a - b).subs(g).normal().is_zero();
}

}  // namespace pogear::test
