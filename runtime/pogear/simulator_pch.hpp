// What every generated simulator includes, precompiled once when pogear is built (CMake's
// pogear_simulator_pch) with the very flags `pogear simulate` compiles with: a simulator's compile
// then starts from Eigen and the runtime already parsed. A compile with
// other flags ignores the precompiled form and reads the headers.
// An include guard, not #pragma once: GCC warns of the latter in the file it precompiles.
#ifndef POGEAR_SIMULATOR_PCH_HPP
#define POGEAR_SIMULATOR_PCH_HPP

#include <array>
#include <string_view>

#include <Eigen/Core>

#include "pogear/parameters.hpp"
#include "pogear/run_system.hpp"
#include "pogear/signals.hpp"

#endif  // POGEAR_SIMULATOR_PCH_HPP
