// A file of the derive stage including vibrate/, which sits above it: the build must refuse it
// (derive's include root has no vibrate/ in it), so this must not compile.
#include "vibrate/vibration_modes.hpp"

int pogear_probe_forbidden() { return 0; }
