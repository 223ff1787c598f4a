// Sets a generated system's tunable parameters from `--param NAME=VALUE` options: the part of every
// generated main that resolves names and reads values with units.
#pragma once

#include <cmath>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

#include "pogear/number_text.hpp"
#include "pogear/api.hpp"

namespace pogear::rt {

// The magnitudes (SI) a parameter may have other than zero, in model files and through `--param`
// alike: physical gears span about 1e-12 to 1e12, and products of a few such factors stay finite
// within these bounds; beyond them the models' matrices overflow or underflow.
inline constexpr double kSmallestParameter = 1e-30, kLargestParameter = 1e30;

// A unit `--param` accepts for a parameter: VALUE*UNIT means VALUE times `si`.
struct ParameterUnit {
  std::string_view unit;
  double si = 1;
};

// One tunable of a generated system's Params, as the generated main lists it.
struct ParameterField {
  std::string_view name;
  double* value = nullptr;
  std::vector<ParameterUnit> units;  // besides a plain number, which is SI
  std::string_view sign;             // "positive", "non-negative" or "" (any finite value)
};

// The SI value of `text`: a number, or NUMBER*UNIT with one of the field's units exactly as listed.
inline std::optional<double> parameter_value(std::string_view text, const ParameterField& field) {
  if (auto v = detail::parse_finite(text)) return v;
  for (const ParameterUnit& u : field.units) {
    if (text.size() <= u.unit.size() + 1) continue;
    const std::string_view number = text.substr(0, text.size() - u.unit.size() - 1);
    if (text[number.size()] != '*' || text.substr(number.size() + 1) != u.unit) continue;
    if (auto v = detail::parse_finite(number); v && std::isfinite(*v * u.si)) return *v * u.si;
  }
  return std::nullopt;
}

// Applies every NAME=VALUE in order (a later one wins). On an unknown name or a bad value prints
// `PROGRAM: error: what; what to do` and returns false (the caller exits with 1). Compiled into
// libpogear_runtime (see api.hpp).
POGEAR_RT_ABI_BEGIN
POGEAR_RT_API bool set_parameters(const std::vector<std::pair<std::string, std::string>>& given,
                                  const std::vector<ParameterField>& fields, const char* program);
POGEAR_RT_ABI_END

}  // namespace pogear::rt
