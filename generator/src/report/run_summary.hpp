// The summary `generate` and `simulate` print of a scene: each system's size, operations and
// diagnostics, and what the scene's loads, controllers, sine inputs and fixed steps make of it.
#pragma once

#include <string>

#include "specialize/specialization.hpp"

namespace pogear {

// "rhs: 38 operations (24 multiplications, 14 additions); outputs: ..." for each system, with the
// notes below.
std::string operation_summary(const SpecializedScene& model);

// What exact stepping's linear hold costs each sine input of the scene ("" for another solver).
std::string sine_inputs_note(const SpecializedScene& model);

// What rk4's fixed step costs on the system's modes: its error per step ("" for another solver).
std::string rk4_step_note(const SpecializedScene& model, const SpecializedSystem& system);

// What a nonlinear scene's adaptive run costs against exact stepping: the longest step that dopri5's
// stability on the linear part's stiffest mode, or the event check of its fastest oscillation, allows
// ("" for rk4, or where neither bound is below a sample period).
std::string nonlinearity_cost_note(const SpecializedScene& model);

}  // namespace pogear
