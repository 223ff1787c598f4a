// The exact method's step: the discretized matrices of a linear model and the kernel that applies
// them, x(t+h) = Phi x + (Gamma0 - Gamma1) u0 + Gamma1 u1 (exact.hpp computes the matrices).
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <cstring>
#include <type_traits>
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

// A load of memory that was just stored 16 bytes at a time (Eigen assigns with SSE2 packets, as user
// code fills the inputs): an AVX load spanning two such stores cannot be forwarded from them and
// waits for them to reach the cache, so it is made of two 16-byte loads.
template <class V>
POGEAR_RT_INLINE void load_pairs(V& v, const double* p) {
#if defined(__GNUC__)
  if constexpr (sizeof(V) == 32) {
    Lanes2 lo, hi;
    load(lo, p);
    load(hi, p + 2);
    v = __builtin_shufflevector(lo, hi, 0, 1, 2, 3);
    return;
  }
#endif
  load(v, p);
}

// Builds with FMA enabled (-mfma, -march=native) let the compiler fuse a product into the sum that
// consumes it, wherever it sees fit, so two kernels of the same arithmetic could round differently.
// An empty asm makes each product a value the compiler cannot look into: no fusing, so the kernels
// of one build agree bit for bit (the discretization itself, Eigen's exponential, may still round
// differently from a build without FMA). Without FMA there is nothing to fuse: a no-op.
template <class V>
POGEAR_RT_INLINE void no_fuse(V& v) {
#if defined(__GNUC__) && defined(__FMA__)
  asm("" : "+x"(v));
#else
  (void)v;
#endif
}

// t[Lo] + ... + t[Hi - 1] as a balanced tree: the terms of a step are summed in a fixed order of
// depth log2(K) instead of a chain of K - 1 dependent additions. Consecutive steps depend on each
// other, so this depth, not the number of operations, bounds the speed of a single run.
template <int Lo, int Hi, class V>
POGEAR_RT_INLINE void tree_sum(const V* t, V& out) {
  if constexpr (Hi - Lo == 1) {
    out = t[Lo];
  } else {
    constexpr int Mid = Lo + (Hi - Lo) / 2;
    V a, b;
    tree_sum<Lo, Mid>(t, a);
    tree_sum<Mid, Hi>(t, b);
    out = a + b;
  }
}

// The coefficients of a step, x(t+h)_i = sum_k a[k][i] v_k with v = (x, u0, u1): column k of
// [Phi, Gamma0 - Gamma1, Gamma1], its rows padded with zeros to a multiple of 4 so that any lane
// width loads whole vectors. Only for fixed sizes up to 32 states and 8 inputs (gear scenes);
// larger or dynamic models step with Eigen's products.
template <int NX, int NU>
inline constexpr bool kernel_sizes = NX != Eigen::Dynamic && NU != Eigen::Dynamic && NX >= 1 && NX <= 32 && NU <= 8;
template <int NX, int NU, bool = kernel_sizes<NX, NU>>
struct ExactKernel {
  static constexpr bool enabled = false;
};
template <int NX, int NU>
struct ExactKernel<NX, NU, true> {
  static constexpr bool enabled = true;
  static constexpr int K = NX + 2 * NU, P = (NX + 3) / 4 * 4;
  alignas(32) double a[K][P] = {};
};

// to[0, N) = from[0, N) in 16-byte moves written out one by one: as a loop GCC turns the copy into a
// memcpy and expands that as `rep movs`, whose start-up cost was a fifth of a 10-state exact step.
template <int N>
POGEAR_RT_INLINE void copy_state(double* to, const double* from) {
#if defined(__GNUC__)
  [&]<int... k>(std::integer_sequence<int, k...>) {
    (([&] {
       Lanes2 p;
       load(p, from + 2 * k);
       store(to + 2 * k, p);
     }()),
     ...);
  }(std::make_integer_sequence<int, N / 2>{});
  if constexpr (N % 2 == 1) to[N - 1] = from[N - 1];
#else
  for (int k = 0; k < N; ++k) to[k] = from[k];
#endif
}

// One step of one run: lanes are rows of the state. out may be x (the step reads x first).
template <int W, int NX, int NU>
POGEAR_RT_INLINE void exact_step(const ExactKernel<NX, NU>& kern, const double* x, const double* u0, const double* u1,
                                 double* out) {
  using V = Lanes<W>;
  constexpr int K = NX + 2 * NU, R = (NX + W - 1) / W;
  double v[K];
  copy_state<NX>(v, x);
  for (int j = 0; j < NU; ++j) v[NX + j] = u0[j], v[NX + NU + j] = u1[j];
#pragma GCC unroll 16
  for (int r = 0; r < R; ++r) {
    V t[K], s;
#pragma GCC unroll 48
    for (int k = 0; k < K; ++k) {
      load(t[k], &kern.a[k][r * W]);
      t[k] = t[k] * v[k];
      no_fuse(t[k]);
    }
    tree_sum<0, K>(t, s);
    // Whole vectors go straight to out; an observer that loads the state as wide as it was stored
    // gets it forwarded from the store instead of waiting for the cache.
    if ((r + 1) * W <= NX) {
      store(out + r * W, s);
    } else {
      alignas(32) double o[W];
      store(o, s);
      std::memcpy(out + r * W, o, sizeof(double) * static_cast<std::size_t>(NX - r * W));
    }
  }
}

// One step of B runs in lockstep: lanes are runs. X, U0, U1 and Out hold row i of every run at
// X + i * B (row-major batches); the same terms in the same tree as exact_step, so each run gets
// the bits its own run would get. Out may be X: every result is computed before any is stored, and
// stored as whole vectors, which the next step loads back at the same width (a narrower store read
// back wider cannot be forwarded and would stall the chain of steps).
template <int W, int B, int NX, int NU>
POGEAR_RT_INLINE void exact_step_batch(const ExactKernel<NX, NU>& kern, const double* X, const double* U0,
                                       const double* U1, double* Out) {
  using V = Lanes<W>;
  constexpr int K = NX + 2 * NU, L = B / W;
  static_assert(B % W == 0, "the batch must be a whole number of lanes");
  V res[NX][L];
#pragma GCC unroll 32
  for (int i = 0; i < NX; ++i) {
#pragma GCC unroll 16
    for (int s = 0; s < L; ++s) {
      V t[K];
#pragma GCC unroll 48
      for (int k = 0; k < K; ++k) {
        if (k < NX) load(t[k], X + k * B + s * W);  // stored by the previous step, at this width
        else load_pairs(t[k], (k < NX + NU ? U0 + (k - NX) * B : U1 + (k - NX - NU) * B) + s * W);
        t[k] = kern.a[k][i] * t[k];
        no_fuse(t[k]);
      }
      tree_sum<0, K>(t, res[i][s]);
    }
  }
  for (int i = 0; i < NX; ++i)
    for (int s = 0; s < L; ++s) store(Out + i * B + s * W, res[i][s]);
}

}  // namespace detail

// The largest estimated rounding error of one step (balanced_exp's estimate) that exact stepping
// accepts; simulate_exact refuses a step size whose discretization exceeds it. Ordinary scenes are
// near 1e-16 (the one-stage paper scene at 1 ms: 1.3e-16; K = 1e12 N/m: 2e-14). Above 1e-10 the
// error of 100 steps measured against 80-digit references exceeds 1e-8 (K = 1e21 N/m at 1 ms:
// 1e-10 per step, 7e-8 after 100 steps); a mode that turns by 1e13 rad per step is ~1e-3.
inline constexpr double kExactMaxRounding = 1e-10;

template <int NX, int NU>
struct ExactDiscretization {
  using State = Eigen::Matrix<double, NX, 1>;
  using Input = Eigen::Matrix<double, NU, 1>;
  using StateMatrix = Eigen::Matrix<double, NX, NX>;
  using InputMatrix = Eigen::Matrix<double, NX, NU>;

  StateMatrix Phi;
  InputMatrix Gamma0, Gamma1;
  InputMatrix GammaD;  // Gamma0 - Gamma1, the weight of u0 in step()
  double h = 0;
  double rounding = 0;  // estimated relative error of Phi, Gamma0 and Gamma1 (see balanced_exp)
  // Phi, GammaD and Gamma1 again, laid out for the step kernel; the constructor fills it, so a
  // discretization whose matrices are changed afterwards must be rebuilt (or call pack()).
  [[no_unique_address]] detail::ExactKernel<NX, NU> kernel;

  ExactDiscretization() = default;
  // The discretization of dx/dt = M x + N u for steps of h: defined in exact.hpp, which computes the
  // matrix exponential (Eigen/Dense).
  // measured_rows: the leading states whose accuracy `rounding` estimates (all by default); an
  // augmented system's integrals grow with h and would hide the errors of the states themselves.
  ExactDiscretization(const StateMatrix& M, const InputMatrix& N, double h_, Eigen::Index measured_rows = -1);
  // One computed elsewhere (the compiled runtime's exact_matrices, run_support.hpp), of any size.
  template <class MatPhi, class MatGamma>
  ExactDiscretization(const MatPhi& Phi_, const MatGamma& Gamma0_, const MatGamma& Gamma1_, double h_, double rounding_)
      : Phi(Phi_), Gamma0(Gamma0_), Gamma1(Gamma1_), GammaD(Gamma0 - Gamma1), h(h_), rounding(rounding_) {
    pack();
  }

  // Whether the step can be trusted: NaN and overflow (an infinite estimate) count as not.
  bool accurate() const { return rounding <= kExactMaxRounding; }

  void pack() {
    if constexpr (detail::ExactKernel<NX, NU>::enabled) {
      for (int i = 0; i < NX; ++i) {
        for (int k = 0; k < NX; ++k) kernel.a[k][i] = Phi(i, k);
        for (int j = 0; j < NU; ++j) kernel.a[NX + j][i] = GammaD(i, j), kernel.a[NX + NU + j][i] = Gamma1(i, j);
      }
    }
  }

  // out must not alias x. No allocation for fixed sizes (and none for dynamic ones once out is sized).
  // Computed as Phi x + (Gamma0 - Gamma1) u0 + Gamma1 u1. Consecutive steps form a chain of dependent
  // sums, so latency bounds a single run: for fixed sizes up to 32 states each row is a balanced
  // tree of its NX + 2 NU products, computed for several rows at once (detail::exact_step). That
  // takes 10 instead of 11 ns per step for the 10-state paper model in SSE2 registers, 7.5 in AVX2
  // ones (simulate_exact picks those at run time). Always inlined: as a call, the driver's state
  // round-trips through memory. Larger and dynamic sizes use Eigen's products.
  template <int W = detail::kDefaultLanes>
  EIGEN_ALWAYS_INLINE void step(const State& x, const Input& u0, const Input& u1, State& out) const {
    if constexpr (detail::ExactKernel<NX, NU>::enabled) {
      detail::exact_step<W>(kernel, x.data(), u0.data(), u1.data(), out.data());
    } else {
      out.noalias() = Phi * x;
      if (GammaD.cols() == 0) return;
      out.noalias() += GammaD * u0;
      out.noalias() += Gamma1 * u1;
    }
  }
  State step(const State& x, const Input& u0, const Input& u1) const {
    State out(x.size());
    step(x, u0, u1, out);
    return out;
  }
};


}  // namespace pogear::rt
