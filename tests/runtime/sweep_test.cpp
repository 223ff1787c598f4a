// Tests of batched exact sweeps (sweep.hpp) and of the exact step kernel's lane widths: a batch of B
// runs must give, bit for bit, the samples of B single runs, and every lane width the same bits.
#include <utility>
#include <vector>

#include <gtest/gtest.h>

#include <pogear/runtime.hpp>

#include "paper_one_stage.hpp"

namespace rt = pogear::rt;

namespace {

// A damped 3-state chain with 2 inputs, its entries of different sizes (as a gear's, which mix
// rad/s and N) so that rounding differences would show.
Eigen::Matrix3d chain_M() {
  Eigen::Matrix3d M;
  M << -1.5, 40, 0, -0.02, -0.3, 1.7, 3, -250, -6;
  return M;
}
Eigen::Matrix<double, 3, 2> chain_N() {
  Eigen::Matrix<double, 3, 2> N;
  N << 0.5, 0, 0, 1.25, -3, 0.1;
  return N;
}

// Inputs of run s: a step and a ramp whose sizes depend on s; their breakpoints (0.25, 0.33) are
// shared by the runs, and 0.33 lies between samples, so the driver splits that interval.
double input(int j, int s, double t) {
  const double a = 1 + 0.1 * s;
  return j == 0 ? rt::value(rt::Step{0.2 * a, -a, 0.25}, t) : rt::value(rt::Ramp{0.33, 2.0 * a, 0.5 - 0.05 * s}, t);
}

template <int B>
void expect_batch_equals_single_runs(const rt::SolverOptions& opt, double t_end) {
  const Eigen::Matrix3d M = chain_M();
  const Eigen::Matrix<double, 3, 2> N = chain_N();
  const double dt = 0.1;
  const std::vector<double> breaks = {0.25, 0.33};
  const rt::ExactDiscretization<3, 2> nominal(M, N, rt::exact_nominal_step(dt, opt.h));
  rt::BatchState<3, B> X0;
  for (int s = 0; s < B; ++s) X0.col(s) = Eigen::Vector3d(0.1 * s, -1 + 0.3 * s, 20.0 * s);
  std::vector<rt::BatchState<3, B>> batch;
  auto ub = [&](double t, rt::BatchInput<2, B>& U) {
    for (int s = 0; s < B; ++s) U(0, s) = input(0, s, t), U(1, s) = input(1, s, t);
  };
  const rt::RunStatus sb = rt::simulate_exact_batch(nominal, M, N, ub, X0, 0.0, t_end, dt, opt,
                                                    [&](double, const rt::BatchState<3, B>& X) { batch.push_back(X); },
                                                    breaks);
  ASSERT_TRUE(sb.ok) << sb.message;
  for (int s = 0; s < B; ++s) {
    std::vector<Eigen::Vector3d> single;
    auto u = [&](double t, Eigen::Vector2d& out) { out << input(0, s, t), input(1, s, t); };
    const rt::RunStatus ss = rt::simulate_exact(nominal, M, N, u, Eigen::Vector3d(X0.col(s)), 0.0, t_end, dt, opt,
                                                [&](double, const Eigen::Vector3d& x) { single.push_back(x); }, breaks);
    ASSERT_TRUE(ss.ok) << ss.message;
    EXPECT_EQ(ss.steps, sb.steps);
    ASSERT_EQ(single.size(), batch.size());
    // Bit for bit: the same discretizations, the same terms summed in the same tree.
    for (std::size_t k = 0; k < single.size(); ++k)
      for (int i = 0; i < 3; ++i) ASSERT_EQ(batch[k](i, s), single[k](i)) << "run " << s << ", sample " << k;
  }
}

}  // namespace

TEST(Sweep, BatchOfEightEqualsSingleRunsBitForBit) {
  rt::SolverOptions opt;
  opt.h = 0.1;
  expect_batch_equals_single_runs<8>(opt, 1.05);  // a partial last interval
}

TEST(Sweep, BatchOfSixWithSubstepsEqualsSingleRunsBitForBit) {
  rt::SolverOptions opt;
  opt.h = 0.03;  // 4 substeps of 0.025 per sample
  expect_batch_equals_single_runs<6>(opt, 1.0);  // 6 runs: 2 per AVX2 operation, not 4
}

// A system of the one-stage paper scene, set up for exact stepping at 1 ms.
template <class System>
struct PaperSystem {
  using Sys = System;
  typename Sys::StateMatrix M;
  typename Sys::InputMatrix N;
  rt::LinearOutputs<Sys::ny, Sys::nx, Sys::nu> lo;
  rt::SolverOptions opt;
  rt::ExactDiscretization<Sys::nx, Sys::nu> disc;

  PaperSystem() : PaperSystem(system_matrices()) {}

 private:
  explicit PaperSystem(const std::pair<typename Sys::StateMatrix, typename Sys::InputMatrix>& mn)
      : M(mn.first), N(mn.second), lo(rt::linear_outputs(Sys{}, {})), opt(), disc(M, N, 1e-3) {
    opt.h = 1e-3;
  }
  static std::pair<typename Sys::StateMatrix, typename Sys::InputMatrix> system_matrices() {
    std::pair<typename Sys::StateMatrix, typename Sys::InputMatrix> mn;
    Sys::matrices({}, mn.first, mn.second);
    return mn;
  }
};
using ElasticPaper = PaperSystem<pogear_generated::paper_one_stage::Elastic>;
using RigidPaper = PaperSystem<pogear_generated::paper_one_stage::Rigid>;

// The kernel gives the same bits whatever its lane width (plain doubles, SSE2 pairs, AVX quads),
// and its result is Phi x + Gamma0 u0 + Gamma1 (u1 - u0) up to rounding.
TEST(Sweep, StepKernelLaneWidthsAgree) {
  using Sys = ElasticPaper::Sys;
  const ElasticPaper paper;
  const auto& disc = paper.disc;
  Sys::State x;
  for (int i = 0; i < 10; ++i) x[i] = i < 6 ? 3.0 - 0.7 * i : 150.0 * (i - 5);
  const Eigen::Matrix<double, 1, 1> u0(100.0), u1(120.0);
  Sys::State a, b, c;
  rt::detail::exact_step<1>(disc.kernel, x.data(), u0.data(), u1.data(), a.data());
  rt::detail::exact_step<2>(disc.kernel, x.data(), u0.data(), u1.data(), b.data());
  rt::detail::exact_step<4>(disc.kernel, x.data(), u0.data(), u1.data(), c.data());
  EXPECT_EQ(a, b);
  EXPECT_EQ(a, c);
  Sys::State d = x;
  rt::detail::exact_step<2>(disc.kernel, d.data(), u0.data(), u1.data(), d.data());  // in place
  EXPECT_EQ(a, d);
  const Sys::State ref = disc.Phi * x + disc.Gamma0 * u0 + disc.Gamma1 * (u1 - u0);
  // Different summation orders: each of the 12 terms rounds once, so a few eps of the largest term.
  const double scale = (disc.Phi.cwiseAbs() * x.cwiseAbs()).maxCoeff() + disc.Gamma0.cwiseAbs().maxCoeff() * 120;
  EXPECT_LE((a - ref).cwiseAbs().maxCoeff(), 8 * 2.2e-16 * scale);
}

// The portable driver and the one simulate_exact dispatches to (AVX2 where the CPU has it) give
// the same bits.
TEST(Sweep, DriverCopiesAgree) {
  using Sys = ElasticPaper::Sys;
  const ElasticPaper paper;
  const auto& [M, N, lo, opt, disc] = paper;
  auto u = [](double t, Sys::Input& out) { out[0] = 100 + 50 * t; };
  std::vector<Sys::State> a, b;
  auto obs_a = [&](double, const Sys::State& x) { a.push_back(x); };
  auto obs_b = [&](double, const Sys::State& x) { b.push_back(x); };
  ASSERT_TRUE(rt::simulate_exact(disc, M, N, u, Sys::State::Zero().eval(), 0.0, 0.5, 1e-3, opt, obs_a).ok);
  Sys::State x0 = Sys::State::Zero();
  const std::vector<double> none;
  auto discretize = [&](double h) { return rt::ExactDiscretization<Sys::nx, Sys::nu>(M, N, h); };
  ASSERT_TRUE(rt::detail::simulate_exact_lanes<2>(disc, discretize, u, x0, 0.0, 0.5, 1e-3, opt, obs_b, none).ok);
  ASSERT_EQ(a.size(), b.size());
  for (std::size_t k = 0; k < a.size(); ++k) ASSERT_EQ(a[k], b[k]) << k;
}

// The paper's rigid model: the batched outputs C x + D u (its velocities and the eq. 8 mesh forces)
// agree with the generated ones to rounding only, because the generated code groups the terms
// differently (through the derivatives of eq. 8).
TEST(Sweep, OutputMatricesOfTheRigidPaperModel) {
  using Sys = pogear_generated::paper_one_stage::Rigid;
  const auto lo = rt::linear_outputs(Sys{}, {});
  // 21 nonzero coefficients of the 30, exactly 0 where the generated expression has no term.
  EXPECT_EQ((lo.C.array() != 0).count() + (lo.D.array() != 0).count(), 21);
  EXPECT_EQ(lo.C.row(0), Eigen::RowVector2d(1, 0));  // omega_c is the first state
  EXPECT_EQ(lo.D(0, 0), 0);
  constexpr int B = 4;
  rt::BatchState<2, B> X;
  rt::BatchInput<1, B> U;
  X << 1.5, -20, 3, 0.25, -7, 4, 0.5, 30;
  U << 100, -3, 0, 55;
  rt::BatchOutput<Sys::ny, B> Y;
  rt::batch_outputs(lo, X, U, Y);
  for (int s = 0; s < B; ++s) {
    Sys::Output y;
    Sys::outputs({}, X.col(s), U.col(s), y);
    // Each output is a sum of at most 3 products against the generated expression's 5: a few eps of
    // the largest term, which the inputs (100) and coefficients (<= 33) bound by ~1e4 here.
    for (int i = 0; i < Sys::ny; ++i) EXPECT_NEAR(Y(i, s), y[i], 1e-11) << "output " << i << ", run " << s;
  }
}

TEST(Sweep, NonFiniteStateStopsTheBatch) {
  const Eigen::Matrix<double, 1, 1> M(1.0), N(1.0);
  const rt::ExactDiscretization<1, 1> disc(M, N, 0.1);
  rt::SolverOptions opt;
  opt.h = 0.1;
  rt::BatchState<1, 2> X0;
  X0 << 1, 1e307;  // the second run overflows within a few steps
  const rt::RunStatus st = rt::simulate_exact_batch(
      disc, M, N, [](double, rt::BatchInput<1, 2>& U) { U.setZero(); }, X0, 0.0, 1000.0, 0.1, opt,
      [](double, const rt::BatchState<1, 2>&) {});
  EXPECT_FALSE(st.ok);
  EXPECT_NE(st.message.find("non-finite"), std::string::npos) << st.message;
}

// Outputs computed in the batch driver take the inputs at the sample time, right-continuous, as the
// generated main does: a step of the input torque at t = 0.5 (on the sample grid) shows in the forces
// at t = 0.5 already. The states are bit for bit those of a single run; the outputs agree with the
// generated outputs function to rounding (terms grouped differently), relative to each output's peak.
TEST(Sweep, BatchOutputsOfTheRigidPaperModel) {
  using Sys = RigidPaper::Sys;
  constexpr int B = 8;
  const RigidPaper paper;
  const auto& [M, N, lo, opt, disc] = paper;
  auto sig = [](int s) { return rt::Step{100.0 * (0.5 + 0.1 * s), 30.0 * s - 80, 0.5}; };
  const std::vector<double> breaks = {0.5};
  std::vector<rt::BatchState<2, B>> xs;
  std::vector<rt::BatchOutput<Sys::ny, B>> ys;
  const rt::RunStatus st = rt::simulate_exact_batch(
      disc, M, N, lo,
      [&](double t, rt::BatchInput<1, B>& U) {
        for (int s = 0; s < B; ++s) U(0, s) = rt::value(sig(s), t);
      },
      rt::BatchState<2, B>(rt::BatchState<2, B>::Zero()), 0.0, 1.0, 1e-3, opt,
      [&](double, const rt::BatchState<2, B>& X, const rt::BatchOutput<Sys::ny, B>& Y) {
        xs.push_back(X);
        ys.push_back(Y);
      },
      breaks);
  ASSERT_TRUE(st.ok) << st.message;
  for (int s = 0; s < B; ++s) {
    std::vector<Sys::State> x1;
    std::vector<Sys::Output> y1;
    auto u = [&](double t, Sys::Input& out) { out[0] = rt::value(sig(s), t); };
    const rt::RunStatus ss = rt::simulate_exact(disc, M, N, u, Sys::State::Zero().eval(), 0.0, 1.0, 1e-3, opt,
                                                [&](double t, const Sys::State& x) {
                                                  Sys::Input uu;
                                                  u(t, uu);
                                                  Sys::Output y;
                                                  Sys::outputs({}, x, uu, y);
                                                  x1.push_back(x);
                                                  y1.push_back(y);
                                                },
                                                breaks);
    ASSERT_TRUE(ss.ok) << ss.message;
    ASSERT_EQ(x1.size(), xs.size());
    Sys::Output peak = Sys::Output::Zero();
    for (const auto& y : y1) peak = peak.cwiseMax(y.cwiseAbs());
    for (std::size_t k = 0; k < x1.size(); ++k) {
      for (int i = 0; i < 2; ++i) ASSERT_EQ(xs[k](i, s), x1[k](i)) << "run " << s << ", sample " << k;
      for (int i = 0; i < Sys::ny; ++i)
        ASSERT_NEAR(ys[k](i, s), y1[k](i), 1e-14 * peak[i]) << "run " << s << ", sample " << k << ", output " << i;
    }
  }
}

// sweep_exact_peaks fuses the reduction into the stepping: the same bits as reducing the outputs
// of simulate_exact_batch with update_peaks (the same operations in the same order).
TEST(Sweep, FusedPeaksEqualObserverPeaks) {
  using Sys = RigidPaper::Sys;
  constexpr int B = 6;
  const RigidPaper paper;
  const auto& [M, N, lo, opt, disc] = paper;
  auto u = [](double t, rt::BatchInput<1, B>& U) {
    for (int s = 0; s < B; ++s) U(0, s) = rt::value(rt::Step{50.0 + 20 * s, -40.0 * s, 0.3}, t);
  };
  rt::BatchState<2, B> X0;
  X0.row(0).setLinSpaced(-1, 1);
  X0.row(1).setConstant(0.5);
  rt::BatchOutput<Sys::ny, B> a = rt::BatchOutput<Sys::ny, B>::Zero(), b = a;
  ASSERT_TRUE(rt::sweep_exact_peaks(disc, M, N, lo, u, X0, 0.0, 1.0, 1e-3, opt, a, {0.3}).ok);
  ASSERT_TRUE(rt::simulate_exact_batch(disc, M, N, lo, u, X0, 0.0, 1.0, 1e-3, opt,
                                       [&](double, const rt::BatchState<2, B>&,
                                           const rt::BatchOutput<Sys::ny, B>& Y) { rt::update_peaks(Y, b); },
                                       {0.3})
                  .ok);
  EXPECT_EQ(a, b);
  EXPECT_GT(a.minCoeff(), 0);
}
