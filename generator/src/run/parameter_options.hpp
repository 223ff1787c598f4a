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

// Each NAME=VALUE of `given`, in order (a later one for the same name wins when applied). Throws
// InputError at the scene file for a name that is not one of the scene's tunables, or a value its
// [parameters] would refuse (unit, sign, range).
std::vector<ParameterOption> read_parameter_options(const SpecializedScene& model, const std::vector<std::string>& given);

// The scene's numeric values with the tunables at `options`: every parameter defined through a
// tunable follows it, as in the generated code's Params.
GiNaC::exmap values_at(const SpecializedScene& model, const std::vector<ParameterOption>& options);

}  // namespace pogear
