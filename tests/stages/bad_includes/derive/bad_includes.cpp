// Fixture of stage_include_check_refuses_bad_includes: every include below breaks a rule of
// check_includes.cmake, which must name each of them.
#include "../vibrate/vibration_modes.hpp"
#include "kept_velocities.hpp"
#include "vibrate/vibration_modes.hpp"
#include <derive/rigid_model.hpp>
