// Parameter expressions with the paper's units (`4.8*cm`, `0.08*Nm/rpm`): parsing to GiNaC,
// dimensions, and conversion to SI.
#pragma once

#include <array>
#include <map>
#include <string>
#include <string_view>

#include <ginac/ginac.h>

#include "common/input_error.hpp"

namespace pogear {

// Exponents of metre, kilogram, second and kelvin; radians count as dimensionless.
struct Dimension {
  std::array<int, 4> exponent{0, 0, 0, 0};
  bool operator==(const Dimension&) const = default;
};

std::string describe(const Dimension& d);  // "m", "kg*m^2", "N*m*s/rad"-free SI form
Dimension length_dimension();
Dimension inertia_dimension();             // kg m^2
Dimension rotational_damping_dimension();  // N m s / rad
Dimension stiffness_dimension();           // N / m
Dimension linear_damping_dimension();      // N s / m
Dimension torque_dimension();              // N m
Dimension angular_velocity_dimension();    // rad / s
Dimension force_dimension();               // N
Dimension time_dimension();                // s
Dimension temperature_dimension();         // K (a difference: K or degC)
Dimension heat_capacity_dimension();       // J / K
Dimension thermal_conductance_dimension(); // W / K

struct Quantity {
  double si = 0.0;         // value in SI units
  Dimension dimension;
  bool has_unit = false;   // false for a bare number, taken as SI without a dimension check
};

// Limits that keep hostile input bounded.
inline constexpr std::size_t max_expression_length = 4096;
inline constexpr int max_expression_depth = 64;
// No physical parameter has a unit to a power near 64 (stiffness is kg/s^2); the bound keeps the
// exponent arithmetic of `((m^16)^16)^16...` far from int overflow.
inline constexpr int max_unit_power = 64;

// Parses `text` with units and the named symbols in `known` (each with its own quantity).
// Throws InputError located at `where` shifted to the offending character.
// `column_offset` is where `text` starts relative to `where` (1 for a quoted TOML string).
Quantity evaluate_quantity(std::string_view text, const std::map<std::string, Quantity>& known,
                           const SourceLocation& where, int column_offset);

// The names a quantity expression refers to that are not units, in order of appearance.
std::vector<std::string> referenced_names(std::string_view text);
// The units it names, in order of appearance.
std::vector<std::string> referenced_units(std::string_view text);

bool is_unit_name(std::string_view name);
std::string known_units_list();

}  // namespace pogear
