// Exact discretization of linear models dx/dt = M x + N u with a first-order hold on the inputs:
// one matrix exponential per step size at setup, then each step is three matrix-vector products.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <type_traits>

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

// Over a step [t, t+h] the input is taken as the straight line through u0 = u(t) and u1 = u(t+h):
//   x(t+h) = Phi x(t) + Gamma0 u0 + Gamma1 (u1 - u0)
//   Phi = e^{M h},  Gamma0 = int_0^h e^{M s} ds N,  Gamma1 = (1/h) int_0^h e^{M (h-s)} s ds N.
// This is the exact solution (up to rounding) whenever u is linear over the step, constant included;
// for other inputs the error is that of linear interpolation of u, O(h^2 max|u''|) per unit time.
// All three come from one exponential (Van Loan, 1978) of the augmented system x' = Mx + Nu,
// u' = w/h, w' = 0, whose start value w = u1 - u0 makes u the line above:
//   exp([[M h, N h, 0], [0, 0, I], [0, 0, 0]]) = [[Phi, Gamma0, Gamma1], [0, I, I], [0, 0, I]].
// NU may be 0 (no inputs); NX and NU may be Eigen::Dynamic for the interpreted mode.
// e^C through a balanced matrix: C' = D^-1 C D with D diagonal, powers of 2 chosen so that each
// row and column of C' have about the same norm (Parlett & Reinsch 1969, LAPACK's dgebal without
// permutations), then e^C = D e^C' D^-1. The scaling is exact in floating point. It matters for gear
// models: their states mix velocities (rad/s) and mesh forces (N), so M h has entries from ~1e-3 to
// ~200 (the stiff K rows) while its eigenvalues are O(1). Balanced, the norm drops to O(1): scaling
// and squaring needs fewer squarings, and Phi's rounding error, which the lightly damped modes
// accumulate over thousands of steps, drops from ~1e-14 to ~1e-16 relative (on the one-stage paper
// scene the sampled error of exact stepping falls from 6e-12 to ~1e-13).
namespace detail {
// A B: a lazy product for fixed sizes up to 24 (for the 12x12 augmented matrix of the 10-state
// paper model, Eigen's blocked products (packing, kernels) made up half of the setup), a blocked one
// for larger and dynamic sizes.
template <class Mat>
Mat mat_mul(const Mat& A, const Mat& B) {
  if constexpr (Mat::RowsAtCompileTime != Eigen::Dynamic && Mat::RowsAtCompileTime <= 24)
    return A.lazyProduct(B);
  else
    return A * B;
}

// e^A by Eigen's own method (MatrixExponential.h: Higham's scaling and squaring with the Pade
// approximant its 1-norm calls for; the same coefficients and the same steps), with one change
// in the squaring: it squares D = e^(A/2^s) - I as D <- 2 D + D^2 instead of E <- E^2. Squaring E
// turns a rounding error of one ulp in an eigenvalue 1 of e^(A/2^s) into (1 - 2^-53)^(2^s): the
// modes that do not move (a frictionless rotation, the input hold of the augmented matrix) lose
// e^(-2^s eps) of their value, and 2^s ~ ||A||. At h = 1e14 s that made Gamma0 e^-4 times its value
// (every velocity 54.6 times too small) and from h = 1e18 s zero. In D those eigenvalues are 0 and
// stay 0. extra_squarings > 0 takes the degree-13 approximant with that many more squarings (the
// independent evaluation ExactDiscretization checks against). Without squarings E is (V-U)^-1 (U+V),
// as before: the same bits.
template <class Mat>
Mat small_exp(const Mat& A, int extra_squarings = 0) {
  const Mat I = Mat::Identity(A.rows(), A.cols());
  Mat U, V;
  int squarings = 0;
  const double l1norm = A.cwiseAbs().colwise().sum().maxCoeff();
  if (extra_squarings > 0) {
    // below: the degree-13 branch
  } else if (l1norm < 1.495585217958292e-002) {
    const double b[] = {120., 60., 12., 1.};
    const Mat A2 = mat_mul(A, A);
    const Mat tmp = b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[2] * A2 + b[0] * I;
  } else if (l1norm < 2.539398330063230e-001) {
    const double b[] = {30240., 15120., 3360., 420., 30., 1.};
    const Mat A2 = mat_mul(A, A), A4 = mat_mul(A2, A2);
    const Mat tmp = b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[4] * A4 + b[2] * A2 + b[0] * I;
  } else if (l1norm < 9.504178996162932e-001) {
    const double b[] = {17297280., 8648640., 1995840., 277200., 25200., 1512., 56., 1.};
    const Mat A2 = mat_mul(A, A), A4 = mat_mul(A2, A2), A6 = mat_mul(A4, A2);
    const Mat tmp = b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * I;
  } else if (l1norm < 2.097847961257068e+000) {
    const double b[] = {17643225600., 8821612800., 2075673600., 302702400., 30270240.,
                        2162160.,     110880.,     3960.,       90.,        1.};
    const Mat A2 = mat_mul(A, A), A4 = mat_mul(A2, A2), A6 = mat_mul(A4, A2), A8 = mat_mul(A6, A2);
    const Mat tmp = b[9] * A8 + b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(A, tmp);
    V = b[8] * A8 + b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * I;
  }
  if (extra_squarings > 0 || !(l1norm < 2.097847961257068e+000)) {
    std::frexp(l1norm / 5.371920351148152, &squarings);
    squarings = std::max(squarings, 0) + extra_squarings;
    const Mat As = A * std::ldexp(1.0, -squarings);
    const double b[] = {64764752532480000., 32382376266240000., 7771770303897600., 1187353796428800.,
                        129060195264000.,   10559470521600.,    670442572800.,     33522128640.,
                        1323241920.,        40840800.,          960960.,           16380.,
                        182.,               1.};
    const Mat A2 = mat_mul(As, As), A4 = mat_mul(A2, A2), A6 = mat_mul(A4, A2);
    V = b[13] * A6 + b[11] * A4 + b[9] * A2;
    Mat tmp = mat_mul(A6, V);
    tmp += b[7] * A6 + b[5] * A4 + b[3] * A2 + b[1] * I;
    U = mat_mul(As, tmp);
    tmp = b[12] * A6 + b[10] * A4 + b[8] * A2;
    V = mat_mul(A6, tmp);
    V += b[6] * A6 + b[4] * A4 + b[2] * A2 + b[0] * I;
  }
  const Mat denom = V - U;
  if (squarings == 0) return denom.partialPivLu().solve(U + V);
  Mat D = 2 * denom.partialPivLu().solve(U);  // (V-U)^-1 (U+V) - I
  for (int i = 0; i < squarings; ++i) D = (2 * D + mat_mul(D, D)).eval();
  return D + I;
}
}  // namespace detail

// Every size goes through detail::small_exp, dynamic ones too (the interpreted mode), so that both
// square e^A - I. Fixed-size matrices keep the setup off the heap, and up to 24x24 their products
// lazy: a sixth of a whole 2000-step run of the 10-state paper scene went into Eigen's dynamic
// exponential.
// With rounding given, it also receives an estimate of the relative error of e^C: the difference
// of e^C' and a second evaluation with three more squarings (another scaled matrix, other roundings,
// so errors that do not cancel), over max(1, ||e^C'||_1), both balanced so that velocities and
// forces weigh alike. Scaling and squaring amplifies rounding by about 2^s ~ ||C||: a mode turning
// by 1e13 rad per step carries phase errors of ~1e-3, and at 1e25 rad the computed e^C overflows.
// The second evaluation, with 8 times the amplification, errs about as much as the first or more,
// so the difference is the size of the error (measured over 100 steps of stiff undamped scenes
// against 80-digit references: each step errs by 1 to 11 times it).
template <class Mat>
Mat balanced_exp(Mat C, double* rounding = nullptr) {
  const Eigen::Index n = C.rows();
  Eigen::Matrix<double, Mat::RowsAtCompileTime, 1> d = Eigen::Matrix<double, Mat::RowsAtCompileTime, 1>::Ones(n);
  // Bounded passes and factors (2^-64 ... 2^64 per pass): balancing converges in a few passes, and
  // the bounds keep non-finite or extreme entries from looping or overflowing.
  bool done = false;
  for (int pass = 0; pass < 50 && !done; ++pass) {
    done = true;
    for (Eigen::Index i = 0; i < n; ++i) {
      const double c = C.col(i).cwiseAbs().sum() - std::abs(C(i, i));
      const double r = C.row(i).cwiseAbs().sum() - std::abs(C(i, i));
      if (!(c > 0) || !(r > 0) || !std::isfinite(c) || !std::isfinite(r)) continue;  // nothing to balance
      double f = 1, cs = c;
      for (int k = 0; k < 64 && cs < r / 2; ++k) f *= 2, cs *= 4;
      for (int k = 0; k < 64 && cs > 2 * r; ++k) f /= 2, cs /= 4;
      if ((cs + r) / f < 0.95 * (c + r)) {  // row i scaled by 1/f, column i by f
        done = false;
        d(i) *= f;
        C.row(i) /= f;
        C.col(i) *= f;
      }
    }
  }
  Mat E = detail::small_exp(C);
  if (rounding) {
    const double norm = E.cwiseAbs().colwise().sum().maxCoeff();
    *rounding = (E - detail::small_exp(C, 3)).cwiseAbs().colwise().sum().maxCoeff() / std::max(1.0, norm);
    if (!std::isfinite(norm)) *rounding = std::numeric_limits<double>::infinity();
  }
  for (Eigen::Index j = 0; j < n; ++j)
    for (Eigen::Index i = 0; i < n; ++i) E(i, j) *= d(i) / d(j);
  return E;
}

namespace detail {

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

// One step of one run: lanes are rows of the state. out may be x (the step reads x first).
template <int W, int NX, int NU>
POGEAR_RT_INLINE void exact_step(const ExactKernel<NX, NU>& kern, const double* x, const double* u0, const double* u1,
                                 double* out) {
  using V = Lanes<W>;
  constexpr int K = NX + 2 * NU, R = (NX + W - 1) / W;
  double v[K];
  for (int k = 0; k < NX; ++k) v[k] = x[k];
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
  ExactDiscretization(const StateMatrix& M, const InputMatrix& N, double h_) : h(h_) {
    eigen_assert(M.rows() == M.cols() && N.rows() == M.rows());
    const Eigen::Index n = M.rows(), m = N.cols();
    constexpr int NA = NX == Eigen::Dynamic || NU == Eigen::Dynamic ? Eigen::Dynamic : NX + 2 * NU;
    using Aug = Eigen::Matrix<double, NA, NA>;
    Aug C = Aug::Zero(n + 2 * m, n + 2 * m);
    C.topLeftCorner(n, n) = M * h;
    C.block(0, n, n, m) = N * h;
    C.block(n, n + m, m, m).setIdentity();
    const Aug E = balanced_exp(C, &rounding);
    Phi = E.topLeftCorner(n, n);
    Gamma0 = E.block(0, n, n, m);
    Gamma1 = E.block(0, n + m, n, m);
    GammaD = Gamma0 - Gamma1;
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
