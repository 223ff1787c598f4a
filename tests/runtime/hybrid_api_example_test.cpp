// The worked example of docs/simulator-api.md, "Brakes and clutches from C++", compiled and run:
// the code between the markers is the page's, verbatim (checked), and its run is checked against
// the closed form of the locked pair's spin-up.
#include <gtest/gtest.h>

#include <cmath>
#include <fstream>
#include <sstream>
#include <string>

// docs: begin
#include <pogear/hybrid.hpp>

#include <cstdio>
#include <vector>

namespace rt = pogear::rt;

// Two bodies, x = [omega_1, omega_2]: J1 omega_1' = tau - T, J2 omega_2' = -b omega_2 + T, with the
// clutch's torque T acting -T on its first body and +T on its second, its slip s = omega_1 - omega_2.
rt::HybridSystem clutch_between_two_bodies() {
  const double J1 = 0.2, J2 = 1.0, b = 0.5;  // kg m^2, kg m^2, N m s/rad
  rt::HybridSystem sys;
  sys.M = Eigen::Matrix2d{{0, 0}, {0, -b / J2}};
  sys.N = Eigen::Matrix2d{{1 / J1, -1 / J1}, {0, 1 / J2}};  // columns: tau, then T
  sys.S = Eigen::RowVector2d{1, -1};
  sys.inputs = {rt::Constant{20.0}};  // tau [N m]
  // 40 N m kinetic capacity, static 1.2 times that, its command ramping in from 0.5 s to 1 s.
  sys.elements = {{"clutch", 40.0, 1.2, rt::Table{{0.0, 0.5, 1.0}, {0.0, 0.0, 1.0}}, false}};
  return sys;
}

struct ExampleRun {
  rt::RunStatus status;
  std::vector<rt::HybridEvent> events;
  std::vector<double> t, omega_1, omega_2, heat;
};

ExampleRun run_example() {
  const rt::HybridSystem sys = clutch_between_two_bodies();
  rt::HybridEngine engine(sys, 3.0, {rt::Solver::exact, {}});  // horizon [s]; keeps its modes between runs
  Eigen::VectorXd x0(2);
  x0 << 100.0, 0.0;  // rad/s
  ExampleRun r;
  r.status = engine.run(
      x0, 1e-3,  // sample period [s]
      [&](double t, const rt::HybridSample& s) {
        // s.x the state, s.w the inputs with the clutch's torque, s.slip, s.energy(0) the clutch's heat
        // [J] so far, s.mode bit 0 set while the clutch is stuck.
        r.t.push_back(t);
        r.omega_1.push_back(s.x(0));
        r.omega_2.push_back(s.x(1));
        r.heat.push_back(s.energy(0));
        return true;  // false stops the run
      },
      [&](const rt::HybridEvent& e) { r.events.push_back(e); });
  for (const rt::HybridEvent& e : r.events)
    std::printf("%.9f s: %s %s -> %s\n", e.t, sys.elements[static_cast<std::size_t>(e.element)].name.c_str(),
                rt::state_name(e.from), rt::state_name(e.to));
  return r;
}
// docs: end

namespace {

TEST(HybridApi, DocumentedExampleIsThisFile) {
  auto text = [](const std::string& path) {
    std::ifstream in(path);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  const std::string self = text(std::string(POGEAR_SOURCE_DIR) + "/tests/runtime/hybrid_api_example_test.cpp");
  const std::string begin = "// docs: begin\n", end = "// docs: end\n";
  const auto a = self.find(begin), b = self.find(end);
  ASSERT_NE(a, std::string::npos);
  ASSERT_NE(b, std::string::npos);
  const std::string example = self.substr(a + begin.size(), b - a - begin.size());
  EXPECT_NE(text(std::string(POGEAR_SOURCE_DIR) + "/docs/simulator-api.md").find("```cpp\n" + example + "```"),
            std::string::npos)
      << "docs/simulator-api.md does not show tests/runtime/hybrid_api_example_test.cpp's example";
}

// The clutch slips from 0.5 s (open before), locks, and from then the pair spins up as one body:
// (J1 + J2) omega' = tau - b omega, omega(t) = 40 + (omega_L - 40) exp(-b (t - t_L) / (J1 + J2)).
// Exact stepping is exact to rounding: 1e-9 of the speed bounds what the samples' rounding
// accumulates over 2000 steps. The heat stays at its lock-up value.
TEST(HybridApi, DocumentedExampleLocksAndSpinsUpAsOneBody) {
  const ExampleRun r = run_example();
  ASSERT_TRUE(r.status.ok) << r.status.message;
  ASSERT_EQ(r.events.size(), 2u);
  EXPECT_EQ(r.events[0].to, rt::ElementState::slipping);
  EXPECT_EQ(r.events[1].to, rt::ElementState::stuck);
  const double locked = r.events[1].t;
  ASSERT_GT(locked, 0.5);
  ASSERT_LT(locked, 2.5);
  std::size_t i = 0;
  while (r.t[i] < locked) ++i;
  const double omega_L = r.omega_1[i], t_L = r.t[i], heat_L = r.heat[i];
  EXPECT_GT(heat_L, 0);
  for (; i < r.t.size(); ++i) {
    const double expected = 40 + (omega_L - 40) * std::exp(-0.5 * (r.t[i] - t_L) / 1.2);
    EXPECT_NEAR(r.omega_1[i], expected, 1e-9 * 100) << r.t[i];
    EXPECT_NEAR(r.omega_2[i], r.omega_1[i], 1e-9 * 100) << r.t[i];
    EXPECT_EQ(r.heat[i], heat_L) << r.t[i];
  }
}

}  // namespace
