// libFuzzer target for parameter expressions with units (`4.8*cm`, `0.08*Nm/rpm`, `K_ps`): any text
// must give a finite quantity or an InputError located inside the text.
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <map>
#include <string>

#include "common/quantity.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  // Names an expression may use, with and without units, like a model's parameters.
  static const std::map<std::string, pogear::Quantity> known{
      {"r_c", {0.148, pogear::length_dimension(), true}},
      {"b_c", {0.76, pogear::rotational_damping_dimension(), true}},
      {"k", {3.0, {}, false}},
      {"tiny", {1e-300, pogear::length_dimension(), true}},
      {"huge", {1e300, pogear::length_dimension(), true}},
  };
  const pogear::SourceLocation where{"fuzz.toml", 7, 9};
  (void)pogear::referenced_names(text);
  try {
    const pogear::Quantity q = pogear::evaluate_quantity(text, known, where, 1);
    // Everything downstream (exact rationals, GiNaC) assumes finite numbers.
    if (!std::isfinite(q.si)) __builtin_trap();
  } catch (const pogear::InputError& e) {
    // A position outside the quoted expression would point at the wrong thing.
    const int last = where.column + 1 + static_cast<int>(size);
    if (e.where().line != where.line || e.where().column < where.column || e.where().column > last) __builtin_trap();
  }
  return 0;
}
