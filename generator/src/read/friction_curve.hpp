// A brake's or clutch's kinetic friction against slip speed (friction_curve in [[brake]] and
// [[clutch]]): read and checked, and what a run of the element makes of it.
#pragma once

#include <toml++/toml.h>

#include "names/model.hpp"
#include "read/toml_reader.hpp"

namespace pogear {

// friction_curve = [["0*rad/s", 1.15], ["20*rad/s", 1], ...]: rows of a slip speed with its unit and
// the ratio of the kinetic torque there to the capacity, the first at zero slip, the slips strictly
// increasing, each ratio in (0, 10]. Sets e.curve_slip (rad/s), e.curve_ratio and where it is.
void read_friction_curve(const TomlReader& r, const toml::node& n, FrictionElement& e);

// Whether the element's kinetic torque depends on its slip: a curve whose ratios are not all equal
// (an equal one is a constant ratio, which folds into the capacity: constant_friction_ratio).
bool varies_with_slip(const FrictionElement& e);
// The ratio folded into the element's kinetic capacity: a constant curve's ratio; 1 without a curve
// or with one that varies, which the runtime applies along the slip.
double constant_friction_ratio(const FrictionElement& e);

}  // namespace pogear
