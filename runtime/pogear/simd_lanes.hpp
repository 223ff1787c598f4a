// Lanes of GCC/Clang vector extensions for the exact method's kernels (exact_kernel.hpp), the
// AVX2 dispatch, and y += A x for the hybrid engine's small dynamic matrices.
#pragma once

#include <Eigen/Core>
#include <utility>

// Lanes: the step kernels below compute W results at once as GCC/Clang vector extensions (W = 2 is
// one SSE2 register, W = 4 one AVX register), and as plain doubles (W = 1) elsewhere. The arithmetic
// of each lane is the same whatever W, so every width gives the same bits.
#if defined(__GNUC__)
#define POGEAR_RT_INLINE inline __attribute__((always_inline))
#define POGEAR_RT_LAMBDA_INLINE __attribute__((always_inline))
#else
#define POGEAR_RT_INLINE inline
#define POGEAR_RT_LAMBDA_INLINE
#endif
// x86-64 builds without AVX2 (the default: SSE2 only) also get an AVX2 copy of the exact drivers,
// chosen at run time when the CPU has it. target("avx2") does not enable FMA, so the compiler cannot
// contract a*b + c into one rounding there: both copies round alike. Define POGEAR_RT_NO_DISPATCH
// to build only the portable copy.
#if defined(__GNUC__) && defined(__x86_64__) && !defined(__AVX2__) && !defined(POGEAR_RT_NO_DISPATCH)
#define POGEAR_RT_AVX2_DISPATCH 1
#define POGEAR_RT_TARGET_AVX2 __attribute__((target("avx2"), noinline))
#endif

namespace pogear::rt {

namespace detail {

#if defined(POGEAR_RT_AVX2_DISPATCH)
// A user's function (input, observer, discretization) as the AVX2 copies call it: with the upper
// halves of the YMM registers cleared first. Compiled as SSE and entered with them dirty, it pays
// Intel cores' SSE/AVX transition penalty on its vector instructions, and GCC leaves out the
// vzeroupper before a call into its own translation unit whose registers it knows (-fipa-ra).
// Plain inline asm needs no AVX target here; the clobbers keep no value in a vector register
// across it. Used only where the CPU has AVX2, so the instruction exists.
template <class F>
struct CleanUpperCall {
  F& f;
  template <class... A>
  POGEAR_RT_INLINE decltype(auto) operator()(A&&... a) {
    asm volatile("vzeroupper" ::: "xmm0", "xmm1", "xmm2", "xmm3", "xmm4", "xmm5", "xmm6", "xmm7", "xmm8", "xmm9",
                 "xmm10", "xmm11", "xmm12", "xmm13", "xmm14", "xmm15");
    return f(std::forward<A>(a)...);
  }
};
#endif

#if defined(__GNUC__)
typedef double Lanes2 __attribute__((vector_size(16)));
typedef double Lanes4 __attribute__((vector_size(32)));
template <int W>
using Lanes = std::conditional_t<W == 4, Lanes4, std::conditional_t<W == 2, Lanes2, double>>;
// The widest lanes this translation unit's own flags allow (AVX2 builds need no dispatch).
#if defined(__AVX2__)
inline constexpr int kDefaultLanes = 4;
#else
inline constexpr int kDefaultLanes = 2;
#endif
#else
template <int W>
using Lanes = double;
inline constexpr int kDefaultLanes = 1;
#endif

template <class V>
POGEAR_RT_INLINE void load(V& v, const double* p) {
  std::memcpy(&v, p, sizeof v);
}
template <class V>
POGEAR_RT_INLINE void store(double* p, const V& v) {
  std::memcpy(p, &v, sizeof v);
}

// y += A x over A's first m columns, for a dynamic column-major A of a few dozen rows at most (the
// hybrid engine's steps and proofs): 2 W rows at a time, each summed down the columns in order, so
// that every lane width gives the same bits. Eigen's general product is no faster at these sizes.
template <int W>
POGEAR_RT_INLINE void matvec_add_rows(const double* a, Eigen::Index n, Eigen::Index m, const double* x, double* y,
                                      Eigen::Index& i) {
#if defined(__GNUC__)
  using V = Lanes<W>;
  for (; i + 2 * W <= n; i += 2 * W) {
    V s0, s1, v0, v1;
    load(s0, y + i);
    load(s1, y + i + W);
    for (Eigen::Index k = 0; k < m; ++k) {
      load(v0, a + k * n + i);
      load(v1, a + k * n + i + W);
      s0 += v0 * x[k];
      s1 += v1 * x[k];
    }
    store(y + i, s0);
    store(y + i + W, s1);
  }
#endif
}
template <int W>
POGEAR_RT_INLINE void matvec_add_lanes(const double* a, Eigen::Index n, Eigen::Index m, const double* x, double* y) {
  Eigen::Index i = 0;
  if constexpr (W == 4) matvec_add_rows<4>(a, n, m, x, y, i);
  if constexpr (W >= 2) matvec_add_rows<2>(a, n, m, x, y, i);
  for (; i < n; ++i) {
    double s = y[i];
    for (Eigen::Index k = 0; k < m; ++k) s += a[k * n + i] * x[k];
    y[i] = s;
  }
}
#if defined(POGEAR_RT_AVX2_DISPATCH)
POGEAR_RT_TARGET_AVX2 inline void matvec_add_avx2(const double* a, Eigen::Index n, Eigen::Index m, const double* x,
                                                  double* y) {
  matvec_add_lanes<4>(a, n, m, x, y);
}
#endif
inline void small_matvec_add(const Eigen::MatrixXd& A, Eigen::Index m, const double* x, double* y) {
#if defined(POGEAR_RT_AVX2_DISPATCH)
  if (A.rows() >= 8 && __builtin_cpu_supports("avx2")) return matvec_add_avx2(A.data(), A.rows(), m, x, y);
#endif
  matvec_add_lanes<kDefaultLanes>(A.data(), A.rows(), m, x, y);
}

}  // namespace detail

}  // namespace pogear::rt
