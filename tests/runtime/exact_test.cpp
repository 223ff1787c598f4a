// Tests of the exact (matrix exponential, first-order hold) discretization and its driver against
// closed-form solutions of a scalar decay and an undamped oscillator.
#include <gtest/gtest.h>

#include <cmath>
#include <pogear/runtime.hpp>
#include <vector>

namespace rt = pogear::rt;

namespace {

// Each exact step rounds at the level of a few eps times the state; over the <= 100 steps below the
// accumulated error stays well under 1e-13 of the solution's scale.
constexpr double kExactTol = 1e-13;

// x' = -a x + b u with u(t) = c + r t (c = const input, r = ramp slope), x(0) = x0.
double decay(double a, double b, double c, double r, double x0, double t) {
  const double xp0 = b * c / a - b * r / (a * a);
  return xp0 + b * r / a * t + (x0 - xp0) * std::exp(-a * t);
}

// q'' = -w^2 q + u, state (q, q'), u(t) = c + r t.
Eigen::Vector2d oscillator(double w, double c, double r, const Eigen::Vector2d& x0, double t) {
  const double A = x0(0) - c / (w * w), B = (x0(1) - r / (w * w)) / w;
  return {(c + r * t) / (w * w) + A * std::cos(w * t) + B * std::sin(w * t),
          r / (w * w) - A * w * std::sin(w * t) + B * w * std::cos(w * t)};
}

}  // namespace

TEST(Exact, ScalarDecayConstantAndRampInputs) {
  const double a = 2, b = 3, x0 = 0.7, h = 0.1;
  const rt::ExactDiscretization<1, 1> disc(Eigen::Matrix<double, 1, 1>(-a), Eigen::Matrix<double, 1, 1>(b), h);
  for (const double r : {0.0, 4.0}) {  // constant input, then a ramp
    const double c = 1.5;
    Eigen::Matrix<double, 1, 1> x(x0);
    for (int k = 0; k < 50; ++k) {
      const Eigen::Matrix<double, 1, 1> u0(c + r * k * h), u1(c + r * (k + 1) * h);
      x = disc.step(x, u0, u1);
      const double ref = decay(a, b, c, r, x0, (k + 1) * h);
      EXPECT_NEAR(x(0), ref, kExactTol * std::max(1.0, std::abs(ref))) << "r = " << r << ", step " << k;
    }
  }
}

TEST(Exact, OscillatorConstantAndRampInputs) {
  const double w = 3, h = 0.05;
  Eigen::Matrix2d M;
  M << 0, 1, -w * w, 0;
  const Eigen::Vector2d N(0, 1), x0(0.4, -1.2);
  const rt::ExactDiscretization<2, 1> disc(M, N, h);
  for (const double r : {0.0, 2.5}) {
    const double c = 0.8;
    Eigen::Vector2d x = x0, xn;
    for (int k = 0; k < 100; ++k) {
      disc.step(x, Eigen::Matrix<double, 1, 1>(c + r * k * h), Eigen::Matrix<double, 1, 1>(c + r * (k + 1) * h), xn);
      x = xn;
      const Eigen::Vector2d ref = oscillator(w, c, r, x0, (k + 1) * h);
      EXPECT_LE((x - ref).norm(), kExactTol * std::max(1.0, ref.norm())) << "r = " << r << ", step " << k;
    }
  }
}

TEST(Exact, DynamicSizesAndNoInputs) {
  const double w = 3, h = 0.05;
  Eigen::MatrixXd M(2, 2);
  M << 0, 1, -w * w, 0;
  const rt::ExactDiscretization<Eigen::Dynamic, Eigen::Dynamic> dyn(M, Eigen::MatrixXd::Zero(2, 0), h);
  const rt::ExactDiscretization<2, 0> fixed(M, Eigen::Matrix<double, 2, 0>(), h);
  Eigen::VectorXd xd = Eigen::Vector2d(1, 0);
  Eigen::Vector2d xf(1, 0);
  for (int k = 0; k < 100; ++k) {
    xd = dyn.step(xd, Eigen::VectorXd(0), Eigen::VectorXd(0));
    xf = fixed.step(xf, Eigen::Matrix<double, 0, 1>(), Eigen::Matrix<double, 0, 1>());
  }
  const Eigen::Vector2d ref = oscillator(w, 0, 0, Eigen::Vector2d(1, 0), 100 * h);
  EXPECT_LE((xd - ref).norm(), kExactTol);
  EXPECT_LE((xf - ref).norm(), kExactTol);
}

// Step and ramp inputs switching between samples: the driver must split the step at the breakpoint
// and use the input's left limit at its end, or the error would be O(h) instead of rounding.
TEST(Exact, DriverLandsOnBreakpointsAndSampleGrid) {
  const Eigen::Matrix<double, 1, 1> M(-1.0), N(1.0);
  const double dt = 0.1, t_end = 2.0, x0 = 0.3;
  struct Case {
    rt::Signal sig;
    double ts;  // switching time
    double c_before, r_before, c_after, r_after;  // u = c + r (t - ts) on each side
  };
  const std::vector<Case> cases = {{rt::Step{0.0, 1.0, 0.25}, 0.25, 0, 0, 1, 0},
                                   {rt::Ramp{0.33, 2.0, 0.5}, 0.33, 0.5, 0, 0.5, 2.0}};
  for (const Case& cs : cases) {
    const double xs = decay(1, 1, cs.c_before, 0, x0, cs.ts);  // state at the switch
    auto ref = [&](double t) {
      return t < cs.ts ? decay(1, 1, cs.c_before, cs.r_before, x0, t)
                       : decay(1, 1, cs.c_after, cs.r_after, xs, t - cs.ts);
    };
    std::vector<double> times;
    rt::SolverOptions opt;
    opt.h = dt;  // piecewise-linear inputs: one exact step per sample is enough
    auto u = [&](double t, Eigen::Matrix<double, 1, 1>& out) { out(0) = rt::value(cs.sig, t); };
    auto obs = [&](double t, const Eigen::Matrix<double, 1, 1>& x) {
      EXPECT_NEAR(x(0), ref(t), kExactTol) << "t = " << t;
      times.push_back(t);
    };
    const rt::RunStatus st = rt::simulate_exact(M, N, u, Eigen::Matrix<double, 1, 1>(x0), 0.0, t_end, dt, opt, obs,
                                                rt::breakpoints(cs.sig, 0.0, t_end));
    ASSERT_TRUE(st.ok) << st.message;
    EXPECT_EQ(st.t_reached, t_end);
    ASSERT_EQ(times.size(), 21u);
    for (std::size_t k = 0; k + 1 < times.size(); ++k) EXPECT_EQ(times[k], static_cast<double>(k) * dt);
    EXPECT_EQ(times.back(), t_end);
    EXPECT_EQ(st.steps, 21);  // 20 sample intervals, one of them split at the breakpoint
  }
}

// A step at t_end itself: the last step ends on the input's left limit, so the final state is the
// run's without the step (a smeared step would move it by O(dt)).
TEST(Exact, StepAtTheEndIsNotSmearedOverTheLastStep) {
  const Eigen::Matrix<double, 1, 1> M(-1.0), N(1.0);
  const double dt = 0.1, t_end = 2.0, x0 = 0.3;
  rt::SolverOptions opt;
  opt.h = dt;
  double last = 0;
  const rt::Signal step = rt::Step{0.0, 1.0, t_end};
  auto u = [&](double t, Eigen::Matrix<double, 1, 1>& out) { out(0) = rt::value(step, t); };
  auto obs = [&](double, const Eigen::Matrix<double, 1, 1>& x) { last = x(0); };
  const rt::RunStatus st = rt::simulate_exact(M, N, u, Eigen::Matrix<double, 1, 1>(x0), 0.0, t_end, dt, opt, obs,
                                              rt::breakpoints(step, 0.0, std::nextafter(t_end, 3.0)));
  ASSERT_TRUE(st.ok) << st.message;
  EXPECT_NEAR(last, decay(1, 1, 0, 0, x0, t_end), kExactTol);
}

TEST(Exact, DriverWithDynamicTypesAndPartialLastInterval) {
  Eigen::MatrixXd M(2, 2);
  M << 0, 1, -9, 0;
  const Eigen::MatrixXd N = Eigen::Vector2d(0, 1);
  rt::SolverOptions opt;
  opt.h = 0.03;  // 0.1 / 0.03 is not whole: 4 substeps of 0.025 per sample, and a shorter last one
  std::vector<double> times;
  Eigen::VectorXd last;
  auto u = [](double, Eigen::VectorXd& out) { out(0) = 0.8; };
  auto obs = [&](double t, const Eigen::VectorXd& x) {
    times.push_back(t);
    last = x;
  };
  const rt::RunStatus st = rt::simulate_exact(M, N, u, Eigen::VectorXd(Eigen::Vector2d(0.4, -1.2)), 0.0, 1.05, 0.1,
                                              opt, obs);
  ASSERT_TRUE(st.ok) << st.message;
  ASSERT_EQ(times.size(), 12u);
  EXPECT_EQ(times.back(), 1.05);
  EXPECT_LE((last - oscillator(3, 0.8, 0, Eigen::Vector2d(0.4, -1.2), 1.05)).norm(), kExactTol);
}

TEST(Exact, DriverWithoutInputs) {
  Eigen::Matrix2d M;
  M << 0, 1, -9, 0;
  Eigen::Vector2d last = Eigen::Vector2d::Zero();
  const rt::RunStatus st = rt::simulate_exact(
      M, Eigen::Matrix<double, 2, 0>(), [](double, Eigen::Matrix<double, 0, 1>&) {}, Eigen::Vector2d(1, 0), 0.0,
      1.0, 0.1, rt::SolverOptions{}, [&](double, const Eigen::Vector2d& x) { last = x; });
  ASSERT_TRUE(st.ok) << st.message;
  EXPECT_EQ(st.steps, 10000);  // h = 1e-4 by default
  // 10^4 steps, each rounding at a few eps: ~1e-12 accumulated, against a state of norm ~3.
  EXPECT_LE((last - oscillator(3, 0, 0, Eigen::Vector2d(1, 0), 1.0)).norm(), 1e-11);
}

// A gear's state mixes units: velocities in rad/s and mesh forces in N, so M h has entries from 1e-6
// to 1e3 while its eigenvalues are O(0.03). The exponential is taken through a balanced matrix
// (exact.hpp, balanced_exp); unbalanced, Phi was off by 1.5e-9 relative here. Expected: each entry
// of Phi to a few eps of itself, and 10^4 steps to ~1e-12 of the amplitude (rounding accumulated,
// plus the closed form's own cos(w t) rounding at w t = 316).
TEST(Exact, BadlyScaledOscillator) {
  const double a = 1e-3, b = 1e6, w = std::sqrt(a * b), h = 1e-3;
  Eigen::Matrix2d M;
  M << 0, -a, b, 0;
  const rt::ExactDiscretization<2, 1> disc(M, Eigen::Vector2d(1, 0), h);
  Eigen::Matrix2d phi;
  phi << std::cos(w * h), -a / w * std::sin(w * h), b / w * std::sin(w * h), std::cos(w * h);
  for (int i = 0; i < 2; ++i)
    for (int j = 0; j < 2; ++j) EXPECT_NEAR(disc.Phi(i, j), phi(i, j), 1e-15 * std::abs(phi(i, j))) << i << "," << j;
  Eigen::Vector2d x(1, 0), xn;
  const Eigen::Matrix<double, 1, 1> u(0.0);
  for (int k = 0; k < 10000; ++k) {
    disc.step(x, u, u, xn);
    x = xn;
  }
  const double t = 10000 * h;
  EXPECT_NEAR(x(0), std::cos(w * t), 1e-11);
  EXPECT_NEAR(x(1) / (b / w), std::sin(w * t), 1e-11);
}

// Sweeps reuse one discretization across runs: the result is the same, bit for bit, as computing
// it inside, and a discretization of another step is refused rather than used.
TEST(Exact, PrecomputedDiscretization) {
  Eigen::Matrix2d M;
  M << 0, 1, -9, -0.5;
  const Eigen::Vector2d N(0, 1);
  rt::SolverOptions opt;
  opt.h = 0.1;
  std::vector<Eigen::Vector2d> a, b;
  auto u = [](double t, Eigen::Matrix<double, 1, 1>& out) { out(0) = 0.8 + t; };
  const rt::RunStatus sa = rt::simulate_exact(M, N, u, Eigen::Vector2d(1, 0), 0.0, 1.05, 0.1, opt,
                                              [&](double, const Eigen::Vector2d& x) { a.push_back(x); });
  const rt::ExactDiscretization<2, 1> disc(M, N, rt::exact_nominal_step(0.1, opt.h));
  const rt::RunStatus sb = rt::simulate_exact(disc, M, N, u, Eigen::Vector2d(1, 0), 0.0, 1.05, 0.1, opt,
                                              [&](double, const Eigen::Vector2d& x) { b.push_back(x); });
  ASSERT_TRUE(sa.ok && sb.ok) << sa.message << sb.message;
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) EXPECT_EQ(a[k], b[k]) << k;
  const rt::ExactDiscretization<2, 1> other(M, N, 0.05);
  const rt::RunStatus sc = rt::simulate_exact(other, M, N, u, Eigen::Vector2d(1, 0), 0.0, 1.05, 0.1, opt,
                                              [](double, const Eigen::Vector2d&) {});
  EXPECT_FALSE(sc.ok);
}
