// See tunable_checks.hpp.
#include "specialize/tunable_checks.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "common/input_error.hpp"
#include "common/printer.hpp"
#include "derive/radius_matrix.hpp"
#include "read/model_parameters.hpp"
#include "specialize/tunable_parameters.hpp"

namespace pogear {

using GiNaC::ex;

// What `--param` accepts for a tunable, and the sign its roles in the model ask for.
TunableParameter tunable_parameter(const Topology& t, const std::string& name, double value) {
  TunableParameter p{name, value, {}, ""};
  const Parameter* given = find_parameter(t, name);
  if (given) {
    if (auto unit = written_unit(*given)) p.units.push_back({unit->first, unit->second});
    if (given->value.has_unit && !(given->value.dimension == Dimension{}) &&
        (p.units.empty() || p.units[0].unit != describe(given->value.dimension)))
      p.units.push_back({describe(given->value.dimension), 1.0});
    if (given->value.has_unit && !(given->value.dimension == Dimension{}))
      for (const auto& spelling : common_unit_spellings(given->value.dimension))
        if (std::none_of(p.units.begin(), p.units.end(), [&](const UnitSpelling& u) { return u.unit == spelling.first; }))
          p.units.push_back({spelling.first, spelling.second});
  }
  bool positive = false, non_negative = false;
  for (const Body* b : every_body(t)) {
    positive = positive || b->inertia_parameter == name || (b->axis == AxisKind::carried && b->distance_parameter == name);
    non_negative = non_negative || b->friction_parameter == name;
    for (const auto& w : b->wheels) positive = positive || w.radius_parameter == name;
  }
  for (const auto& m : t.meshes) {
    positive = positive || m.stiffness_parameter == name;
    non_negative = non_negative || m.damping_parameter == name;
  }
  for (const FrictionElement& e : t.friction_elements) positive = positive || e.capacity_parameter == name;
  p.sign = positive ? "positive" : non_negative ? "non-negative" : "";
  return p;
}

// A given radius cannot follow a tunable through a geometry relation: it keeps its number, which
// the relation then contradicts at every other value of the tunable.
void check_tunable_geometry(const Scene& sc, const Derivation& d, const GiNaC::exmap& fold) {
  const SymbolTable& s = d.symbols;
  for (const auto& g : d.radius.relations) {
    const ex lhs = parameter_symbol(s, g.parameter).subs(fold, GiNaC::subs_options::no_pattern);
    const ex rhs = g.rhs.subs(fold, GiNaC::subs_options::no_pattern);
    if ((lhs - rhs).expand().is_zero()) continue;
    std::string tunables;
    for (const auto& name : sc.tunable)
      if (lhs.has(parameter_symbol(s, name)) || rhs.has(parameter_symbol(s, name))) tunables += (tunables.empty() ? "'" : ", '") + name + "'";
    if (tunables.empty()) continue;  // rounding of given values, checked when the model was read
    throw InputError(sc.tunable_where,
                     fmt::format("tunable {} enters the geometry relation {} = {} of {}, but '{}' is given in the "
                                 "model and would keep its value; leave '{}' out of the model so that it is derived, "
                                 "or define it through the tunable, or do not tune a radius of this relation",
                                 tunables, g.parameter, print_expression(g.rhs, Notation::ginac),
                                 describe_mesh(d.topology, g.mesh), g.parameter, g.parameter));
  }
}

}  // namespace pogear
