// Users' functions called from the exact drivers' AVX2 copies are entered with the upper halves of
// the YMM registers clean: compiled as SSE, a callback entered dirty pays the SSE/AVX transition
// penalty of Intel cores on every instruction (simd_lanes.hpp, CleanUpperCall). The callbacks
// below read XINUSE on entry, which works on any CPU with AVX2 and XGETBV1, AMD's as well.
#include <cpuid.h>

#include <vector>

#include <gtest/gtest.h>

#include <pogear/runtime.hpp>

namespace rt = pogear::rt;

namespace {

#if defined(POGEAR_RT_AVX2_DISPATCH)

bool has_avx2_and_xgetbv1() {
  unsigned a = 0, b = 0, c = 0, d = 0;
  if (!__builtin_cpu_supports("avx2")) return false;
  if (!__get_cpuid(1, &a, &b, &c, &d) || !(c & bit_OSXSAVE)) return false;
  if (__get_cpuid_max(0, nullptr) < 0xD) return false;
  __cpuid_count(0xD, 1, a, b, c, d);
  return (a & (1u << 2)) != 0;  // CPUID.(EAX=0DH, ECX=1):EAX[2], XGETBV with ECX = 1
}

// XINUSE bit 2 (XGETBV with ECX = 1): the upper halves of YMM0–15 may be non-zero. It reads no
// vector register, so reading it disturbs nothing it reports.
[[gnu::noinline]] bool upper_ymm_in_use() {
  unsigned eax = 0, edx = 0;
  asm volatile("xgetbv" : "=a"(eax), "=d"(edx) : "c"(1));
  return (eax & (1u << 2)) != 0;
}

// Entries into each kind of callback, and those that found the upper halves dirty. Out of line,
// in this translation unit, as GCC's interprocedural register allocation sees it: that is the
// case in which it leaves out the vzeroupper of its own accord.
struct Entries {
  long calls = 0;
  long dirty = 0;
};
Entries input_entries, observer_entries, discretize_entries;

[[gnu::noinline]] void enter(Entries& e) {
  ++e.calls;
  if (upper_ymm_in_use()) ++e.dirty;
}

// A 4-state damped chain with 2 inputs (4 states: the AVX2 copy steps 4 rows per operation).
Eigen::Matrix4d chain_M() {
  Eigen::Matrix4d M;
  M << -1.5, 40, 0, 0, -0.02, -0.3, 1.7, 0, 0, 3, -25, 6, 0.1, 0, -2, -6;
  return M;
}
Eigen::Matrix<double, 4, 2> chain_N() {
  Eigen::Matrix<double, 4, 2> N;
  N << 0.5, 0, 0, 1.25, -3, 0.1, 0, 2;
  return N;
}

[[gnu::noinline]] void chain_input(double t, Eigen::Vector2d& u) {
  enter(input_entries);
  u << (t < 0.333 ? 1.0 : -1.0), 0.5 * t;
}
[[gnu::noinline]] bool chain_observer(double, const Eigen::Vector4d&) {
  enter(observer_entries);
  return true;
}
template <int B>
[[gnu::noinline]] void batch_input(double t, rt::BatchInput<2, B>& U) {
  enter(input_entries);
  for (int s = 0; s < B; ++s) U(0, s) = (t < 0.25 ? 1.0 : -1.0) * (1 + s), U(1, s) = 0.5 * t;
}
template <int B>
[[gnu::noinline]] bool batch_observer(double, const rt::BatchState<4, B>&) {
  enter(observer_entries);
  return true;
}

class CleanUpper : public ::testing::Test {
 protected:
  void SetUp() override {
    if (!has_avx2_and_xgetbv1()) GTEST_SKIP() << "this CPU has no AVX2 or no XGETBV1: no AVX2 copy to check";
    input_entries = observer_entries = discretize_entries = {};
  }
};

TEST_F(CleanUpper, SimulateExactCallsUsersFunctionsClean) {
  const Eigen::Matrix4d M = chain_M();
  const Eigen::Matrix<double, 4, 2> N = chain_N();
  rt::SolverOptions opt;
  opt.h = 0.01;
  const double dt = 0.1;
  const rt::ExactDiscretization<4, 2> nominal(M, N, rt::exact_nominal_step(dt, opt.h));
  // A breakpoint between samples makes the driver discretize another step on the way.
  auto discretize = [&](double h) {
    enter(discretize_entries);
    return rt::ExactDiscretization<4, 2>(M, N, h);
  };
  const rt::RunStatus st = rt::simulate_exact_with(nominal, discretize, chain_input, Eigen::Vector4d(1, 0, -1, 2), 0.0,
                                                   1.0, dt, opt, chain_observer, std::vector<double>{0.333});
  ASSERT_TRUE(st.ok) << st.message;
  ASSERT_GT(input_entries.calls, 100);
  ASSERT_EQ(observer_entries.calls, 11);
  ASSERT_GT(discretize_entries.calls, 0);
  EXPECT_EQ(input_entries.dirty, 0) << "of " << input_entries.calls << " input calls";
  EXPECT_EQ(observer_entries.dirty, 0) << "of " << observer_entries.calls << " observer calls";
  EXPECT_EQ(discretize_entries.dirty, 0) << "of " << discretize_entries.calls << " discretizations";
}

TEST_F(CleanUpper, BatchedSweepsCallUsersFunctionsClean) {
  constexpr int B = 8;
  const Eigen::Matrix4d M = chain_M();
  const Eigen::Matrix<double, 4, 2> N = chain_N();
  rt::SolverOptions opt;
  opt.h = 0.01;
  const double dt = 0.1;
  const rt::ExactDiscretization<4, 2> nominal(M, N, rt::exact_nominal_step(dt, opt.h));
  const rt::BatchState<4, B> X0 = rt::BatchState<4, B>::Constant(0.5);
  const rt::RunStatus st = rt::simulate_exact_batch(nominal, M, N, batch_input<B>, X0, 0.0, 1.0, dt, opt,
                                                    batch_observer<B>, std::vector<double>{0.25});
  ASSERT_TRUE(st.ok) << st.message;
  ASSERT_GT(input_entries.calls, 100);
  ASSERT_EQ(observer_entries.calls, 11);
  EXPECT_EQ(input_entries.dirty, 0) << "of " << input_entries.calls << " input calls";
  EXPECT_EQ(observer_entries.dirty, 0) << "of " << observer_entries.calls << " observer calls";

  // With the outputs at each sample, and with the peaks reduced in the stepping.
  input_entries = observer_entries = {};
  const rt::LinearOutputs<1, 4, 2> lo{Eigen::Matrix<double, 1, 4>(1, 0, 0, 0), Eigen::Matrix<double, 1, 2>::Zero()};
  auto with_outputs = [](double, const rt::BatchState<4, B>&, const rt::BatchOutput<1, B>&) {
    enter(observer_entries);
    return true;
  };
  ASSERT_TRUE(rt::simulate_exact_batch(nominal, M, N, lo, batch_input<B>, X0, 0.0, 1.0, dt, opt, with_outputs).ok);
  rt::BatchOutput<1, B> peak = rt::BatchOutput<1, B>::Zero();
  ASSERT_TRUE(rt::sweep_exact_peaks(nominal, M, N, lo, batch_input<B>, X0, 0.0, 1.0, dt, opt, peak).ok);
  EXPECT_EQ(input_entries.dirty, 0) << "of " << input_entries.calls << " input calls";
  EXPECT_EQ(observer_entries.dirty, 0) << "of " << observer_entries.calls << " observer calls";
}

#else

TEST(CleanUpper, NoAvx2CopyOnThisTarget) { GTEST_SKIP() << "the exact drivers have no AVX2 copy on this target"; }

#endif

}  // namespace
