// Each message says what is wrong, with the numbers and the expression that show it, and what to change.
#include "report/model_errors.hpp"

#include <fmt/format.h>

#include "common/printer.hpp"

namespace pogear {
namespace {

std::string from_mesh(const PinionAxis& axis) {
  return axis.from_mesh.empty() ? std::string{} : fmt::format(" (from mesh {})", axis.from_mesh);
}

std::string message(const ContradictedLength& c) {
  return fmt::format("'{}' = {} ({:.6g} m) contradicts the geometry: {} implies {} = {} = {:.6g} m; correct the value, "
                     "or the layout if the drawing differs",
                     c.parameter, c.text, c.given, c.mesh, c.parameter, print_expression(c.implied, Notation::ginac),
                     c.implied_value);
}

std::string message(const PinionsOutOfReach& p) {
  return fmt::format("{}: pinions {} and {} of carrier {} cannot mesh: their axes are {} = {:.6g} m{} and {} = {:.6g} m{} "
                     "from the central axis, so the centre distance {} = {:.6g} m must lie between {:.6g} m and {:.6g} m; "
                     "correct the radii or the axis distances",
                     p.mesh, p.first.body, p.second.body, p.carrier, p.first.distance_parameter, p.first.distance,
                     from_mesh(p.first), p.second.distance_parameter, p.second.distance, from_mesh(p.second),
                     print_expression(p.centre, Notation::ginac), p.centre_value, p.least, p.most);
}

std::string tie_text(const TiedVelocities::Details& d) {
  switch (d.tie) {
    case TiedVelocities::Tie::at_rest: return fmt::format("{} is 0 in every rigid motion", d.first_speed);
    case TiedVelocities::Tie::in_ratio:
      return fmt::format("{} and {} are tied: {} in every rigid motion", d.first, d.second,
                         print_expression(d.relation, Notation::text, d.speeds));
    case TiedVelocities::Tie::together: break;
  }
  return joined(d.kept, ", ") + " are tied together";
}

}  // namespace

InputError input_error_of(const GeometryConflict& e) {
  return InputError(e.where(), std::visit([](const auto& kind) { return message(kind); }, e.kind()));
}

InputError input_error_of(const TiedVelocities& e) {
  const TiedVelocities::Details& d = e.details();
  std::string valid;
  for (const auto& set : d.valid) valid += (valid.empty() ? "" : "; ") + joined(set, ",");
  return InputError(e.where(), fmt::format("the kept velocities {} do not parametrize the rigid motions: {}; valid "
                                           "choices are {}",
                                           joined(d.kept, ","), tie_text(d), valid));
}

}  // namespace pogear
