// Shared helpers for the derive tests: the paper's models, symbols by name, symbolic equality
// under the geometry relations.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "derive/derivation.hpp"
#include "common/printer.hpp"

namespace pogear::test {

inline Derivation derive_paper(const std::string& model, const std::vector<std::string>& keep) {
  std::optional<std::vector<std::string>> k;
  if (!keep.empty()) k = keep;
  return derive_model(source_path("models/" + model + ".toml"), k, SourceLocation{"--keep", 0, 0});
}

// A model of models/ by name, with its own keep.
inline Derivation derive_file(const std::string& model) {
  return derive_model(source_path("models/" + model + ".toml"), std::nullopt, SourceLocation{model, 0, 0});
}

// The named parameter's or variable's symbol of a derivation (GiNaC symbols compare by identity,
// not by name).
inline GiNaC::ex sym(const Derivation& d, const std::string& name) {
  if (const auto v = find_variable(d.topology, name)) return variable_symbol(d.symbols, *v);
  return parameter_symbol(d.symbols, name);
}

// True when a - b normalizes to 0 once the geometry relations are substituted.
inline bool equal_under_geometry(Derivation& d, const GiNaC::ex& a, const GiNaC::ex& b) {
  const GiNaC::exmap g = geometry_substitutions(d.radius, d.symbols);
  return (a - b).subs(g).normal().is_zero();
}

}  // namespace pogear::test
