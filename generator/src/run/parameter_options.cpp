// A value is read by the model's own parameter evaluation on a copy of the scene's model, so the
// units, signs and ranges are those of a scene's [parameters].
#include "run/parameter_options.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "common/input_error.hpp"
#include "names/symbols.hpp"
#include "read/model_parameters.hpp"

namespace pogear {

std::vector<ParameterOption> read_parameter_options(const SpecializedScene& model, const std::vector<std::string>& given) {
  const Scene& sc = model.scene;
  const SourceLocation at{sc.file, 0, 0};
  // One copy of the model takes every option in turn, so a value may name another option's parameter
  // in either order, as in [parameters]; each is checked as it comes, so a refusal names its option.
  Topology t = sc.model;
  std::vector<std::string> names;
  for (const std::string& option : given) {
    const auto eq = option.find('=');
    if (eq == std::string::npos || eq == 0 || eq + 1 == option.size())
      throw InputError(at, fmt::format("--param '{}' is not NAME=VALUE; give a tunable parameter and its value, e.g. "
                                       "--param J_c=0.5 or --param K_ps=2000*N/mm", option));
    const std::string name = option.substr(0, eq), text = option.substr(eq + 1);
    if (std::find(sc.tunable.begin(), sc.tunable.end(), name) == sc.tunable.end()) {
      std::string tunables;
      for (const std::string& tunable : sc.tunable) tunables += (tunables.empty() ? "" : ", ") + tunable;
      throw InputError(at, sc.tunable.empty()
                               ? fmt::format("--param {}: the scene has no tunable parameters; list {} in the scene's "
                                             "tunable = [...] to set it at run time, or set it in [parameters]",
                                             name, name)
                               : fmt::format("--param {}: not a tunable parameter of the scene; its tunables are {}",
                                             name, tunables));
    }
    const auto p = std::find_if(t.parameters.begin(), t.parameters.end(), [&](const Parameter& q) { return q.name == name; });
    p->text = text;
    p->where = at;
    p->column_offset = 0;
    try {
      evaluate_parameters(t.parameters);
      check_parameter_roles(t);
    } catch (const InputError& e) {
      throw InputError(at, fmt::format("--param {}: {}", option, e.message()));
    }
    if (std::find(names.begin(), names.end(), name) == names.end()) names.push_back(name);
  }
  std::vector<ParameterOption> out;
  for (const std::string& name : names) out.push_back({name, parameter_value(t, name)});
  return out;
}

SpecializedScene at_parameter_options(const SpecializedScene& model, const std::vector<ParameterOption>& options) {
  const SymbolTable& s = model.derivation.symbols;
  GiNaC::exmap tunables;
  for (const std::string& name : model.scene.tunable) {
    const GiNaC::realsymbol& symbol = parameter_symbol(s, name);
    tunables[symbol] = model.values.numbers.at(symbol);
  }
  for (const ParameterOption& o : options) tunables[parameter_symbol(s, o.name)] = exact_number(o.value);
  SpecializedScene at = model;
  at.values.numbers = tunables;
  for (const auto& [symbol, value] : model.values.equations)
    at.values.numbers[symbol] = value.subs(tunables, GiNaC::subs_options::no_pattern).expand();
  // The derivation's values keep what the scene leaves out (its folding zeroes a friction the scene
  // does not simulate); only the tunables and what the folding leaves in terms of them move.
  for (auto& [symbol, value] : at.derivation.values) {
    const auto folded = model.values.equations.find(symbol);
    if (tunables.count(symbol) || (folded != model.values.equations.end() && !GiNaC::is_a<GiNaC::numeric>(folded->second)))
      value = at.values.numbers.at(symbol);
  }
  const Derivation& d = at.derivation;
  at.derivation.rigid_values = exact_rigid_values(d.rigid, d.elastic, d.values);
  // read_parameter_options has checked every parameter's role at these values, a capacity's sign too.
  for (FrictionRun& f : at.friction)
    if (!GiNaC::is_a<GiNaC::numeric>(f.tuned_capacity))
      f.capacity = to_double(f.tuned_capacity.subs(tunables, GiNaC::subs_options::no_pattern));
  return at;
}

}  // namespace pogear
