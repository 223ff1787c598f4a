// A file of the derive stage including stages derive builds on: it must compile, so that the
// failure of forbidden_include.cpp is the include's and not the probe's setup.
#include "common/exact_algebra.hpp"
#include "derive/derivation.hpp"
#include "names/symbols.hpp"
#include "read/topology.hpp"

int pogear_probe_allowed() { return static_cast<int>(pogear::max_bodies); }
