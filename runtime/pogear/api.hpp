// POGEAR_RT_API marks the runtime's functions that libpogear_runtime compiles once (run_support.hpp);
// with POGEAR_RT_HEADER_ONLY defined they are inline instead, and need no library.
#pragma once

#if defined(POGEAR_RT_HEADER_ONLY)
#define POGEAR_RT_API inline
#else
#define POGEAR_RT_API
#endif
