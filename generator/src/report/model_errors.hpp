// The messages of the derivation's errors (derive/derivation_errors.hpp), as the InputError the
// command line prints, located at the value each concerns.
#pragma once

#include "common/input_error.hpp"
#include "derive/derivation_errors.hpp"

namespace pogear {

InputError input_error_of(const GeometryConflict& e);
InputError input_error_of(const TiedVelocities& e);

}  // namespace pogear
