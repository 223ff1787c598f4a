// Checks that stepping fixed-size states never touches the heap (generated simulators run millions
// of steps), using Eigen's runtime malloc guard.
// The CMake target defines EIGEN_RUNTIME_NO_MALLOC for all its files (they must agree on Eigen's
// configuration); the fallback keeps this file meaningful when compiled on its own.
#ifndef EIGEN_RUNTIME_NO_MALLOC
#define EIGEN_RUNTIME_NO_MALLOC
#endif
#include <gtest/gtest.h>

#include <pogear/runtime.hpp>

namespace rt = pogear::rt;

namespace {

constexpr int kN = 24;  // a mid-sized generated model: fixed-size products may not spill to the heap
using X = Eigen::Matrix<double, kN, 1>;
using Mat = Eigen::Matrix<double, kN, kN>;

// A chain of damped oscillators, as a gear train is: a well-conditioned, mildly stiff test system.
Mat chain() {
  Mat A = Mat::Zero();
  for (int i = 0; i < kN; i += 2) {
    A(i, i + 1) = 1;
    A(i + 1, i) = -4 - i;
    A(i + 1, i + 1) = -0.5;
    if (i + 2 < kN) A(i + 1, i + 2) = A(i + 3, i) = 1;
  }
  return A;
}

// Turns Eigen's malloc guard on for a scope.
struct NoMalloc {
  NoMalloc() { Eigen::internal::set_is_malloc_allowed(false); }
  ~NoMalloc() { Eigen::internal::set_is_malloc_allowed(true); }
};

}  // namespace

TEST(NoAlloc, GuardIsActive) {
  NoMalloc guard;
  EXPECT_DEATH_IF_SUPPORTED((void)Eigen::VectorXd(3), "");  // proves the guard would catch a heap allocation
}

TEST(NoAlloc, SteppersAndExactWithFixedSizes) {
  const Mat A = chain();
  const Eigen::Matrix<double, kN, 2> B = Eigen::Matrix<double, kN, 2>::Ones();
  auto f = [&](double t, const X& x, X& dx) {
    dx.noalias() = A * x;
    dx(1) += std::sin(t);
  };
  auto jac = [&](double, const X&, Mat& J) { J = A; };
  const X x0 = X::Ones();
  const rt::ExactDiscretization<kN, 2> disc(A, B, 1e-3);  // the exponential itself may allocate
  rt::SolverOptions opt;
  opt.rtol = 1e-6;
  double sum = 0;
  auto obs = [&](double, const X& x) { sum += x(0); };
  rt::RunStatus r1, r2, r3;
  X x = x0, xn;
  {
    NoMalloc guard;
    r1 = rt::simulate_rk4(f, x0, 0.0, 1.0, 0.01, opt, obs);
    r2 = rt::simulate_dopri5(f, x0, 0.0, 1.0, 0.01, opt, obs);
    r3 = rt::simulate_implicit(f, jac, true, x0, 0.0, 1.0, 0.01, opt, obs);
    const Eigen::Vector2d u(0.5, -1);
    for (int k = 0; k < 1000; ++k) {
      disc.step(x, u, u, xn);
      x = xn;
    }
  }
  EXPECT_TRUE(r1.ok) << r1.message;
  EXPECT_TRUE(r2.ok) << r2.message;
  EXPECT_TRUE(r3.ok) << r3.message;
  EXPECT_GT(r2.steps, 10);
  EXPECT_TRUE(x.allFinite());
  EXPECT_TRUE(std::isfinite(sum));
}
