// POGEAR_RT_API marks the runtime's functions that libpogear_runtime compiles once (run_support.hpp);
// with POGEAR_RT_HEADER_ONLY defined they are inline instead, and need no library.
#pragma once

#include <Eigen/Core>

#if defined(POGEAR_RT_HEADER_ONLY)
#define POGEAR_RT_API inline
#else
#define POGEAR_RT_API
#endif

// The library's declarations sit in an inline namespace named after how Eigen allocates memory in
// the unit that includes them: its alignment (16 bytes by default, 32 with -mavx, 64 with
// -mavx512f) and whether AddressSanitizer is on (Eigen then stops relying on malloc's alignment).
// Eigen requires every unit of a program to agree on both; a simulator compiled otherwise than the
// library (-march=native, or -fsanitize=address against a plain library) would free memory with
// the wrong allocator and crash. With the tag it fails to link instead, naming the mismatch
// (docs/simulator-api.md); such a simulator builds header-only.
#if defined(__SANITIZE_ADDRESS__)
#define POGEAR_RT_ABI_ASAN _asan
#else
#define POGEAR_RT_ABI_ASAN
#endif
#define POGEAR_RT_ABI_JOIN2(a, b, c) a##b##c
#define POGEAR_RT_ABI_JOIN(a, b, c) POGEAR_RT_ABI_JOIN2(a, b, c)
#define POGEAR_RT_ABI_TAG POGEAR_RT_ABI_JOIN(eigen_align, EIGEN_DEFAULT_ALIGN_BYTES, POGEAR_RT_ABI_ASAN)
#define POGEAR_RT_ABI_BEGIN inline namespace POGEAR_RT_ABI_TAG {
#define POGEAR_RT_ABI_END }
