// One specialized system as a generated C++ struct that needs Eigen alone: its sizes, names and
// units, tunable parameters, rhs, outputs, and their linear forms (M, N) and (C, D).
#pragma once

#include "common/cpp_text.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// `t` names the variables the expressions hold (see model_variables.hpp).
CppText system_struct(const SpecializedSystem& sys, const Scene& scene, const Derivation& d, const CppText& struct_name);

// Numbers as a C++ initializer list's entries, and a signal as the runtime's value of it.
CppText numbers(const std::vector<double>& v);
CppText signal_code(const rt::Signal& signal);

// "38 operations (24 multiplications, 14 additions)".
CppText operation_text(const OperationCount& c);

}  // namespace pogear
