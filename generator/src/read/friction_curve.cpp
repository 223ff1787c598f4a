// See friction_curve.hpp: the rows of a friction curve, each refused at the value that is wrong.
#include "read/friction_curve.hpp"

#include <algorithm>
#include <cmath>
#include <functional>
#include <initializer_list>
#include <string>
#include <vector>

#include <fmt/format.h>

#include "common/quantity.hpp"

namespace pogear {

void read_friction_curve(const TomlReader& r, const toml::node& n, FrictionElement& e) {
  const std::string form = fmt::format("friction_curve of '{}' is a list of rows [slip speed, ratio to the capacity], "
                                       "from zero slip, e.g. [[\"0*rad/s\", 1.1], [\"50*rad/s\", 1]]",
                                       e.name);
  if (!n.is_array() || n.as_array()->size() < 2) r.fail(n, form + "; it needs two rows at least");
  e.friction_curve_where = r.loc(n);
  for (const toml::node& row : *n.as_array()) {
    if (!row.is_array() || row.as_array()->size() != 2) r.fail(row, form);
    const toml::node& s = *row.as_array()->get(0);
    const toml::node& f = *row.as_array()->get(1);
    // A speed needs its unit, an angle's over time, and names no parameter: the curve is data of the
    // element. Hz and a bare 1/s are refused: as a speed either reads as rad/s, 2 pi short of the
    // revolutions per second it usually means.
    const char* speed = "a slip speed of friction_curve is a speed with its unit, e.g. \"10*rad/s\" or \"100*rpm\"";
    if (!s.is_string()) r.fail(s, speed);
    const std::string text = *s.value<std::string>();
    if (const std::vector<std::string> names = referenced_names(text); !names.empty())
      r.fail(s, fmt::format("a slip speed of friction_curve names '{}'; the curve is data of the element, not of its "
                            "parameters: give a number with its unit, e.g. \"10*rad/s\"", names.front()));
    const Quantity q = evaluate_quantity(text, {}, r.loc(s), 1);
    if (!q.has_unit || !(q.dimension == angular_velocity_dimension())) r.fail(s, speed);
    const std::vector<std::string> units = referenced_units(text);
    const auto named = [&](std::initializer_list<const char*> any) {
      return std::any_of(units.begin(), units.end(),
                         [&](const std::string& u) { return std::find(any.begin(), any.end(), u) != any.end(); });
    };
    if (named({"Hz", "kHz"}))
      r.fail(s, "a slip speed of friction_curve is in Hz, which could mean rev/s or rad/s; give it in rpm or rad/s");
    if (!named({"rad", "deg", "rev", "rpm"}))
      r.fail(s, "a slip speed of friction_curve is in 1/s, which could mean rev/s or rad/s; give it in rpm or rad/s");
    if (!std::isfinite(q.si)) r.fail(s, "a slip speed of friction_curve is not finite");
    if (e.curve_slip.empty() && q.si != 0)
      r.fail(s, fmt::format("friction_curve of '{}' starts at zero slip, \"0*rad/s\" (the kinetic ratio as the element "
                            "locks); its first row is at {} rad/s", e.name, q.si));
    if (!e.curve_slip.empty() && !(q.si > e.curve_slip.back()))
      r.fail(s, fmt::format("the slip speeds of friction_curve must increase strictly ({} rad/s follows {} rad/s)", q.si,
                            e.curve_slip.back()));
    if (!f.is_integer() && !f.is_floating_point())
      r.fail(f, "a ratio of friction_curve is a plain number, the kinetic torque over the capacity at that slip");
    const double ratio = *f.value<double>();
    // As static_ratio: no material pair's friction changes tenfold with slip.
    if (!(ratio > 0 && ratio <= 10))
      r.fail(f, fmt::format("a ratio of friction_curve is {}; it is positive, at most 10 (the kinetic torque over the "
                            "capacity at that slip)", ratio));
    e.curve_slip.push_back(q.si);
    e.curve_ratio.push_back(ratio);
  }
}

bool varies_with_slip(const FrictionElement& e) {
  return std::adjacent_find(e.curve_ratio.begin(), e.curve_ratio.end(), std::not_equal_to<>()) != e.curve_ratio.end();
}

double constant_friction_ratio(const FrictionElement& e) {
  return e.curve_ratio.empty() || varies_with_slip(e) ? 1.0 : e.curve_ratio.front();
}

}  // namespace pogear
