// See parameter_folding.hpp: the model's values, the tunables' dependents and the effects left out.
#include "specialize/parameter_folding.hpp"

#include <algorithm>
#include <map>
#include <set>

#include "common/exact_algebra.hpp"
#include "specialize/tunable_parameters.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

GiNaC::exmap parameter_folding(const Scene& sc, const Derivation& d, bool keep_tunables) {
  const SymbolTable& s = d.symbols;
  GiNaC::exmap fold;
  std::set<std::string> tunable(sc.tunable.begin(), sc.tunable.end());
  if (!keep_tunables) tunable.clear();
  // Parameters defined through a tunable follow it (K_pr = "K_ps").
  const std::map<std::string, ex> dependents =
      tunable.empty() ? std::map<std::string, ex>{} : tunable_dependents(d.topology.parameters, sc.tunable, s);
  for (const ParameterValue& p : d.parameters) {
    if (tunable.count(p.name)) continue;
    const auto it = dependents.find(p.name);
    fold[parameter_symbol(s, p.name)] = it != dependents.end() ? it->second : ex(p.exact);
  }
  // A derived radius (one the model leaves out) follows a tunable one through the geometry
  // relations; a given one keeps its value, and check_tunable_geometry refuses the contradiction.
  for (const auto& g : d.radius.relations) {
    if (std::none_of(d.radius.derived.begin(), d.radius.derived.end(),
                     [&](const DerivedRadius& r) { return r.parameter == g.parameter; }))
      continue;
    const ex value = g.rhs.subs(fold, GiNaC::subs_options::no_pattern).expand();
    if (!GiNaC::is_a<GiNaC::numeric>(value)) fold[parameter_symbol(s, g.parameter)] = value;
  }
  if (!sc.effects.bearing_friction)
    for (const auto& b : d.topology.bodies) fold[parameter_symbol(s, b.friction_parameter)] = 0;
  for (const auto& m : d.topology.meshes)
    if (!(m.shaft ? sc.effects.shaft_damping : sc.effects.mesh_damping)) fold[parameter_symbol(s, m.damping_parameter)] = 0;
  return fold;
}

}  // namespace

SceneValues scene_values(const Scene& scene, const Derivation& d) {
  SceneValues v{parameter_folding(scene, d, true), {}};
  v.numbers = scene.tunable.empty() ? v.equations : parameter_folding(scene, d, false);
  return v;
}

}  // namespace pogear
