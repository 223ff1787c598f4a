// Umbrella header of the pogear numeric runtime, included by generated simulators and by the
// interpreted mode: signals, exact discretization, steppers, drivers, batched sweeps and CSV output.
#pragma once

#include "pogear/csv.hpp"
#include "pogear/drivers.hpp"
#include "pogear/exact.hpp"
#include "pogear/signals.hpp"
#include "pogear/steppers.hpp"
#include "pogear/sweep.hpp"
