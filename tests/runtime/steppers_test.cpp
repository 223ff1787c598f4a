// Tests of RK4, DOPRI5 and TR-BDF2 through the drivers: convergence order, tolerance, sample grid,
// stiffness (accuracy, L-stability, refusal), breakpoints, and failures that must stop a run cleanly.
#include <gtest/gtest.h>

#include <cmath>
#include <pogear/runtime.hpp>
#include <string>
#include <vector>

namespace rt = pogear::rt;
using V2 = Eigen::Vector2d;

namespace {

constexpr double kW = 2.0;  // oscillator angular frequency

// q'' = -w^2 q, state (q, q'), from (1, 0).
void osc_rhs(double, const V2& x, V2& dx) { dx << x(1), -kW * kW * x(0); }
V2 osc_exact(double t) { return {std::cos(kW * t), -kW * std::sin(kW * t)}; }

// Runs a driver and collects the samples.
struct Samples {
  std::vector<double> t;
  std::vector<V2> x;
  auto observer() {
    return [this](double ti, const auto& xi) {
      t.push_back(ti);
      x.push_back(xi);
    };
  }
  double max_error(V2 (*exact)(double)) const {
    double e = 0;
    for (std::size_t k = 0; k < t.size(); ++k) e = std::max(e, (x[k] - exact(t[k])).norm());
    return e;
  }
};

// Stiff linear system with eigenvalues -1 and -1e6, coupled through V: x = V c, c_i' = lambda_i c_i.
const Eigen::Matrix2d kV = (Eigen::Matrix2d() << 1, 1, 0, 1).finished();
const Eigen::Matrix2d kStiff = kV * V2(-1, -1e6).asDiagonal() * kV.inverse();
V2 stiff_exact(double t) { return kV * V2(std::exp(-t), std::exp(-1e6 * t)); }  // from c = (1, 1)

}  // namespace

TEST(Rk4, ConvergesAtOrderFour) {
  std::vector<double> errors;
  for (const double h : {0.02, 0.01, 0.005}) {
    Samples s;
    rt::SolverOptions opt;
    opt.h = h;
    const rt::RunStatus st = rt::simulate_rk4(osc_rhs, V2(1, 0), 0.0, 2.0, 0.1, opt, s.observer());
    ASSERT_TRUE(st.ok) << st.message;
    EXPECT_EQ(st.rhs_evals, 4 * st.steps);
    errors.push_back((s.x.back() - osc_exact(2.0)).norm());
  }
  // Global error C h^4 (1 + O(h w)): halving h divides it by 16, within a few percent at h w <= 0.04.
  EXPECT_NEAR(errors[0] / errors[1], 16.0, 1.0);
  EXPECT_NEAR(errors[1] / errors[2], 16.0, 1.0);
}

TEST(Rk4, StabilityLimit) {
  // Spectral radius 1e6 and 2 (eigenvalues +-2i); eigenvalues come out within ~1e-15 relative.
  EXPECT_NEAR(rt::rk4_stability_limit(kStiff), 2.785e-6, 1e-18);
  Eigen::Matrix2d osc;
  osc << 0, 1, -kW * kW, 0;
  EXPECT_NEAR(rt::rk4_stability_limit(osc), 2.785 / kW, 1e-14);
  EXPECT_EQ(rt::rk4_stability_limit(Eigen::Matrix2d::Zero()), std::numeric_limits<double>::infinity());
}

TEST(Dopri5, MeetsToleranceOnSampleGrid) {
  for (const double tol : {1e-6, 1e-9}) {
    Samples s;
    rt::SolverOptions opt;
    opt.rtol = tol;
    opt.atol = tol;
    const rt::RunStatus st = rt::simulate_dopri5(osc_rhs, V2(1, 0), 0.0, 10.0, 0.01, opt, s.observer());
    ASSERT_TRUE(st.ok) << st.message;
    ASSERT_EQ(s.t.size(), 1001u);
    for (std::size_t k = 0; k + 1 < s.t.size(); ++k) ASSERT_EQ(s.t[k], static_cast<double>(k) * 0.01);
    EXPECT_EQ(s.t.back(), 10.0);
    // Local errors are held at tol per step; over ~3 periods they add up to a global error of a few
    // times tol, also at the dense output points (4th-order extension): measured ~9 tol.
    EXPECT_LT(s.max_error(osc_exact), 20 * tol) << "tol = " << tol;
    EXPECT_LT(st.steps, 1000);  // the samples come from dense output, not from tiny steps
  }
}

// Dopri5 builds its dense-output coefficients on the first dense() after a step, not in accept(), and
// keeps the step's k1 and k7 in each other's place until the next attempt. Whatever the order of
// calls, dense() must describe the last accepted step: steps skipped without dense(), a start() (the
// restart after a breakpoint, which overwrites k1) in between, a dynamic-size state.
template <class X>
void check_dopri5_dense_protocol(const X& x0) {
  auto f = [](double t, const X& x, X& dx) {
    dx.resize(x.size());
    dx[0] = x[1];
    dx[1] = -kW * kW * x[0] + std::cos(t);  // time-dependent, so the stage times matter too
  };
  using S = rt::Dopri5<X, decltype(f)>;
  // Two steppers over the same steps: `eager` asks for dense output after every step, `lazy` only
  // after the last one (and after a start()).
  S eager(f, x0, 1e-8, 1e-10), lazy(f, x0, 1e-8, 1e-10);
  X xe = x0, xl = x0, a = x0, b = x0;
  double t = 0;
  const double h = 0.05;
  eager.start(t, xe);
  lazy.start(t, xl);
  for (int i = 0; i < 5; ++i) {
    // Fixed steps, accepted whatever their error: this is about bookkeeping, not step control.
    ASSERT_TRUE(std::isfinite(eager.attempt(t, xe, h, false)));
    ASSERT_TRUE(std::isfinite(lazy.attempt(t, xl, h, false)));
    const X before = xe;
    eager.accept(t, xe, h);
    lazy.accept(t, xl, h);
    ASSERT_EQ(xe, xl);
    eager.dense(t, a);
    EXPECT_EQ(a, before);            // theta = 0: r1 is the old state, bit for bit
    eager.dense(t + h, a);
    EXPECT_LT((a - xe).norm(), 1e-15);  // theta = 1: x_old + (y1 - x_old)
    eager.dense(t + 0.3 * h, a);
    t += h;
  }
  const double tm = t - 0.37 * h;
  eager.dense(tm, a);
  lazy.dense(tm, b);
  EXPECT_EQ(a, b);
  // A start() between steps (as after a breakpoint) must not change the last step's dense output,
  // whether or not it was built before.
  S lazy2 = lazy;
  lazy2.dense_pending = true;  // as if dense() had not been called yet
  lazy.start(t, xl);
  lazy2.start(t, xl);
  lazy.dense(tm, b);
  EXPECT_EQ(a, b);
  lazy2.dense(tm, b);
  EXPECT_EQ(a, b);
  // And it is the continuous extension: with h w = 0.1 the 4th-order interpolant is good to ~1e-7
  // (against 1000 fine steps, exact to ~1e-15).
  X ref = x0;
  rt::Dopri5<X, decltype(f)> fine(f, x0, 1e-8, 1e-10);
  double tf = 0;
  fine.start(tf, ref);
  const int n = 1000;
  for (int i = 0; i < n; ++i) {
    const double hf = (tm - tf) / (n - i);
    fine.attempt(tf, ref, hf, false);
    fine.accept(tf, ref, hf);
    tf += hf;
  }
  EXPECT_LT((a - ref).norm(), 1e-6);
}

TEST(Dopri5, LazyDenseOutputDescribesTheLastStep) {
  check_dopri5_dense_protocol(V2(1, 0));
  check_dopri5_dense_protocol(Eigen::VectorXd(V2(1, 0)));
}

TEST(Implicit, AccurateOnStiffSystemWithLargeSteps) {
  auto f = [](double, const V2& x, V2& dx) { dx.noalias() = kStiff * x; };
  auto jac = [](double, const V2&, Eigen::Matrix2d& J) { J = kStiff; };
  Samples s;
  rt::SolverOptions opt;
  opt.rtol = 1e-6;
  opt.atol = 1e-9;
  const rt::RunStatus st = rt::simulate_implicit(f, jac, true, stiff_exact(0), 0.0, 5.0, 0.01, opt, s.observer());
  ASSERT_TRUE(st.ok) << st.message;
  ASSERT_EQ(s.t.size(), 501u);
  // The error per step is held at tol = 1e-6; a 2nd-order method needs N ~ tol^(-1/3) steps, so the
  // global error grows like N tol ~ tol^(2/3): measured 1.3e-5 over ~520 steps.
  EXPECT_LT(s.max_error(stiff_exact), 3e-5);
  // Explicit stability would need h < 2.785e-6, i.e. ~1.8e6 steps; the mean step here is > 1000 times that.
  EXPECT_LT(st.steps, 1000);
  EXPECT_EQ(st.jac_evals, 1);  // constant Jacobian: evaluated once
  EXPECT_LE(st.lu_decompositions, st.steps);
  // L-stability: once decayed, the stiff component c_2 stays at rounding level and does not ring
  // (the trapezoidal rule alone would flip its sign each step with |c_2| ~ 1).
  for (std::size_t k = 1; k < s.t.size(); ++k) EXPECT_LT(std::abs(kV.inverse().row(1).dot(s.x[k])), 1e-9) << s.t[k];
}

TEST(Implicit, SingleStepDampsStiffModeLStable) {
  for (const double lambda : {-1e6, -1e9}) {
    auto f = [lambda](double, const Eigen::Matrix<double, 1, 1>& x, Eigen::Matrix<double, 1, 1>& dx) {
      dx = lambda * x;
    };
    auto jac = [lambda](double, const Eigen::Matrix<double, 1, 1>&, Eigen::Matrix<double, 1, 1>& J) { J(0) = lambda; };
    Eigen::Matrix<double, 1, 1> x(1.0);
    rt::TrBdf2<Eigen::Matrix<double, 1, 1>, decltype(f), decltype(jac)> s(f, jac, true, x, 1e-6, 1e-9);
    s.start(0, x);
    s.attempt(0, x, 1.0, false);
    s.accept(0, x, 1.0);
    // The stability function behaves like R(z) ~ sqrt(2) / (d z) ~ 4.8 / z as z = h lambda -> -inf:
    // it vanishes (L-stable), where the trapezoidal rule alone would give R -> -1.
    EXPECT_LT(std::abs(x(0)), 10 / std::abs(lambda)) << lambda;
  }
}

TEST(Implicit, NonlinearWithJacobianUpdates) {
  // Logistic x' = x (1 - x) from 0.1: x = 1 / (1 + 9 e^-t); the Jacobian 1 - 2x changes along the way.
  auto f = [](double, const Eigen::VectorXd& x, Eigen::VectorXd& dx) { dx(0) = x(0) * (1 - x(0)); };
  auto jac = [](double, const Eigen::VectorXd& x, Eigen::MatrixXd& J) { J(0, 0) = 1 - 2 * x(0); };
  double err = 0;
  rt::SolverOptions opt;
  opt.rtol = opt.atol = 1e-7;
  auto obs = [&](double t, const Eigen::VectorXd& x) {
    err = std::max(err, std::abs(x(0) - 1 / (1 + 9 * std::exp(-t))));
  };
  const rt::RunStatus st =
      rt::simulate_implicit(f, jac, false, Eigen::VectorXd::Constant(1, 0.1), 0.0, 10.0, 0.1, opt, obs);
  ASSERT_TRUE(st.ok) << st.message;
  // Error per step 1e-7 over ~200 steps, amplified while x < 1/2 (where the flow expands): measured 3.8e-6.
  EXPECT_LT(err, 1e-5);
  EXPECT_GE(st.jac_evals, 1);
}

// x' = u(t) with u stepping from 0 to 1 at t = 0.35 (between samples): x = max(0, t - 0.35). Every
// method is exact on piecewise-constant rhs when it lands on the switch and sees the left limit.
TEST(Drivers, LandOnBreakpoints) {
  const rt::Signal u = rt::Step{0.0, 1.0, 0.35};
  const std::vector<double> bps = rt::breakpoints(u, 0.0, 1.0);
  ASSERT_EQ(bps, std::vector<double>{0.35});
  using X1 = Eigen::Matrix<double, 1, 1>;
  auto f = [&](double t, const X1&, X1& dx) { dx(0) = rt::value(u, t); };
  auto jac = [](double, const X1&, Eigen::Matrix<double, 1, 1>& J) { J(0) = 0; };
  double err = 0;
  auto obs = [&](double t, const X1& x) { err = std::max(err, std::abs(x(0) - std::max(0.0, t - 0.35))); };
  rt::SolverOptions opt;
  opt.h = 0.03;
  const rt::RunStatus r1 = rt::simulate_rk4(f, X1(0.0), 0.0, 1.0, 0.1, opt, obs, bps);
  const rt::RunStatus r2 = rt::simulate_dopri5(f, X1(0.0), 0.0, 1.0, 0.1, opt, obs, bps);
  const rt::RunStatus r3 = rt::simulate_implicit(f, jac, true, X1(0.0), 0.0, 1.0, 0.1, opt, obs, bps);
  EXPECT_TRUE(r1.ok && r2.ok && r3.ok);
  EXPECT_LT(err, 1e-14);  // linear pieces: only rounding of sums of ~100 steps
  EXPECT_LT(r2.steps, 10);  // no rejections around the switch
}

TEST(Drivers, FixedAndDynamicStatesAgree) {
  using XD = Eigen::VectorXd;
  auto fd = [](double, const XD& x, XD& dx) { dx << x(1), -kW * kW * x(0); };
  auto jf = [](double, const V2&, Eigen::Matrix2d& J) { J << 0, 1, -kW * kW, 0; };
  auto jd = [](double, const XD&, Eigen::MatrixXd& J) { J << 0, 1, -kW * kW, 0; };
  rt::SolverOptions opt;
  for (int method = 0; method < 3; ++method) {
    V2 xf = V2::Zero();
    XD xd;
    auto of = [&](double, const V2& x) { xf = x; };
    auto od = [&](double, const XD& x) { xd = x; };
    const XD x0 = V2(1, 0);
    if (method == 0) {
      rt::simulate_rk4(osc_rhs, V2(1, 0), 0.0, 1.0, 0.1, opt, of);
      rt::simulate_rk4(fd, x0, 0.0, 1.0, 0.1, opt, od);
    } else if (method == 1) {
      rt::simulate_dopri5(osc_rhs, V2(1, 0), 0.0, 1.0, 0.1, opt, of);
      rt::simulate_dopri5(fd, x0, 0.0, 1.0, 0.1, opt, od);
    } else {
      rt::simulate_implicit(osc_rhs, jf, true, V2(1, 0), 0.0, 1.0, 0.1, opt, of);
      rt::simulate_implicit(fd, jd, true, x0, 0.0, 1.0, 0.1, opt, od);
    }
    ASSERT_EQ(xd.size(), 2);
    // Same arithmetic; only vectorization may change the rounding of a few operations per step.
    EXPECT_LT((xf - xd).norm(), 1e-12) << "method " << method;
  }
}

TEST(Drivers, LastSampleAtEndWhenSpanIsNotMultipleOfDt) {
  Samples s;
  rt::SolverOptions opt;
  ASSERT_TRUE(rt::simulate_rk4(osc_rhs, V2(1, 0), 0.0, 1.05, 0.1, opt, s.observer()).ok);
  ASSERT_EQ(s.t.size(), 12u);
  EXPECT_EQ(s.t[10], 1.0);
  EXPECT_EQ(s.t[11], 1.05);
}

TEST(Drivers, ObserverCanStopTheRun) {
  auto obs = [](double t, const V2&) { return t < 0.3; };
  const rt::RunStatus st = rt::simulate_rk4(osc_rhs, V2(1, 0), 0.0, 1.0, 0.1, rt::SolverOptions{}, obs);
  EXPECT_FALSE(st.ok);
  EXPECT_EQ(st.message, "stopped by the observer at t = 0.3");
}

TEST(Failures, Dopri5OnVeryStiffSystemStopsAtMaxSteps) {
  auto f = [](double, const V2& x, V2& dx) { dx << -x(0), -1e9 * x(1); };
  rt::SolverOptions opt;
  opt.max_steps = 1000;
  const rt::RunStatus st = rt::simulate_dopri5(f, V2(1, 1), 0.0, 1.0, 0.01, opt, [](double, const V2&) {});
  EXPECT_FALSE(st.ok);
  EXPECT_EQ(st.message.rfind("dopri5 stalled at t = ", 0), 0u) << st.message;
  EXPECT_NE(st.message.find("the scene is stiff: use --solver exact or --solver implicit"), std::string::npos);
  EXPECT_LT(st.t_reached, 1e-5);  // ~1000 steps at the stability limit 3e-9
}

TEST(Failures, Dopri5StallsBelowMinimumStep) {
  // x = 1 / (1 - t) blows up at t = 1: steps shrink with the remaining time until h < 1e-14 |t|.
  auto f = [](double, const Eigen::Matrix<double, 1, 1>& x, Eigen::Matrix<double, 1, 1>& dx) { dx(0) = x(0) * x(0); };
  const rt::RunStatus st = rt::simulate_dopri5(f, Eigen::Matrix<double, 1, 1>(1.0), 0.0, 2.0, 0.1, rt::SolverOptions{},
                                               [](double, const auto&) {});
  EXPECT_FALSE(st.ok);
  EXPECT_EQ(st.message.rfind("dopri5 stalled at t = ", 0), 0u) << st.message;
  EXPECT_NE(st.message.find("below the minimum"), std::string::npos) << st.message;
  // Where the numerical solution blows up differs from t = 1 by about the tolerance (measured 5e-10).
  EXPECT_NEAR(st.t_reached, 1.0, 1e-6);
}

TEST(Failures, NonFiniteStateStopsEveryMethod) {
  // The rhs turns NaN after t = 0.5 (as a model would taking sqrt of a negative number).
  auto f = [](double t, const V2& x, V2& dx) {
    osc_rhs(t, x, dx);
    if (t > 0.5) dx(0) = std::nan("");
  };
  auto jac = [](double, const V2&, Eigen::Matrix2d& J) { J << 0, 1, -kW * kW, 0; };
  auto none = [](double, const V2&) {};
  rt::SolverOptions opt;
  const rt::RunStatus r1 = rt::simulate_rk4(f, V2(1, 0), 0.0, 1.0, 0.1, opt, none);
  const rt::RunStatus r2 = rt::simulate_dopri5(f, V2(1, 0), 0.0, 1.0, 0.1, opt, none);
  const rt::RunStatus r3 = rt::simulate_implicit(f, jac, false, V2(1, 0), 0.0, 1.0, 0.1, opt, none);
  for (const rt::RunStatus& st : {r1, r2, r3}) {
    EXPECT_FALSE(st.ok);
    EXPECT_EQ(st.message.rfind("non-finite state at t = 0.5", 0), 0u) << st.message;
    EXPECT_LE(st.t_reached, 0.5 + opt.h);  // nothing past the first step into the NaN region
  }
  EXPECT_NE(r1.message.find("; last finite sample at t = 0.5"), std::string::npos) << r1.message;
  EXPECT_NE(r2.message.find("; last finite sample at t = 0.4"), std::string::npos) << r2.message;
}
