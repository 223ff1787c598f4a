// Runs with brakes and clutches that the hybrid engine stops, with the messages docs/errors.md
// shows: a chattering sequence of events, and stuck elements whose constraints repeat one another.
#include <gtest/gtest.h>

#include "error_support.hpp"
#include "pogear/hybrid.hpp"

namespace pogear::test {
namespace {

// One inertia (J = 1) driven by a torque of 10 N m, with brakes on it: slip = omega, the brakes'
// torques -T each.
rt::HybridSystem braked_inertia(std::vector<rt::FrictionElementData> brakes) {
  rt::HybridSystem sys;
  const auto ne = static_cast<Eigen::Index>(brakes.size());
  sys.M = Eigen::MatrixXd::Zero(1, 1);
  sys.N = Eigen::MatrixXd::Constant(1, 1 + ne, -1.0);
  sys.N(0, 0) = 1;
  sys.S = Eigen::MatrixXd::Ones(ne, 1);
  sys.elements = std::move(brakes);
  sys.inputs = {rt::Constant{10}};
  return sys;
}

rt::RunStatus run(const rt::HybridSystem& sys, double horizon, double sample, Eigen::VectorXd x0) {
  rt::HybridEngine engine(sys, horizon);
  return engine.run(x0, sample, [](double, const rt::HybridSample&) { return true; }, [](const rt::HybridEvent&) {});
}

// A command switching between 0 and 1 every 2 us: the brake changes state at every switch, 500
// times within the first 1 ms sample. The run stops at the 101st change, not after the horizon.
TEST(Hybrid, ChatteringStopsTheRun) {
  rt::Table command;
  for (int i = 0; i <= 1000; ++i) {
    const double t = 1e-6 * (i + 1), before = i % 2 ? 1 : 0;
    command.t.insert(command.t.end(), {t, t});
    command.v.insert(command.v.end(), {before, 1 - before});
  }
  Eigen::VectorXd x0(1);
  x0 << 5;  // turning: the brake slips whenever engaged
  const rt::RunStatus st = run(braked_inertia({{"B1", 1, 1, command}}), 0.01, 1e-3, x0);
  ASSERT_FALSE(st.ok);
  EXPECT_LT(st.t_reached, 1e-3);
  expect_documented(st.message.substr(0, st.message.find(", at t = ")),
                    "chattering: B1 changed state more than 100 times within one sample period");
  EXPECT_NE(docs().find("; shorten the sample period if the changes are real, or check the engagement commands"),
            std::string::npos);
}

// Two brakes on the same body, both holding it at rest: the torque each carries is undetermined.
TEST(Hybrid, RedundantStuckElementsStopTheRun) {
  const rt::RunStatus st =
      run(braked_inertia({{"B1", 100, 1, rt::Constant{1}}, {"B2", 100, 1, rt::Constant{1}}}), 0.1, 1e-3,
          Eigen::VectorXd::Zero(1));
  ASSERT_FALSE(st.ok);
  expect_documented(st.message, "the stuck elements B1, B2 constrain the gear more than once at t = 0 s (their torques "
                                "are undetermined); engage fewer elements at a time");
}

}  // namespace
}  // namespace pogear::test
