// `pogear simulate --param NAME=VALUE`: a tunable parameter's value for one run, read with units as
// the scene's [parameters] are and refused before anything compiles.
#pragma once

#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "specialize/specialization.hpp"

namespace pogear {

struct ParameterOption {
  std::string name;
  double value = 0;  // SI
};

// The tunables `given` sets (NAME=VALUE, a later one for the same name winning), each value read with
// the others applied, as [parameters] reads them. Throws
// InputError at the scene file for a name that is not one of the scene's tunables, or a value its
// [parameters] would refuse (unit, sign, range).
std::vector<ParameterOption> read_parameter_options(const SpecializedScene& model, const std::vector<std::string>& given);

// The scene at the tunables' values `options`: its numeric values (what the interpreted run evaluates
// at) and its derivation's (what the summary's frequencies and step limits are computed at), every
// parameter defined through a tunable following it, as in the generated code's Params.
SpecializedScene at_parameter_options(const SpecializedScene& model, const std::vector<ParameterOption>& options);

}  // namespace pogear
