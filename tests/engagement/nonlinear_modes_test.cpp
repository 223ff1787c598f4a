// A clutch with a quadratic load behind it, against closed forms: stuck, the pair speeds up as
// tanh, and the clutch lets go when its torque reaches its capacity; slipping, each side runs on its
// own (a ramp, and tanh again). dopri5 and TR-BDF2 step these nonlinear modes.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "pogear/hybrid.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

// a (0.2 kg m^2) driven by 30 N m, clutch C (20 N m) to b and a fan f joined to it by a rigid shaft
// (0.03 + 0.02 kg m^2), which the air brakes with 0.01 omega^2 N m.
const double Ja = 0.2, Jb = 0.05, tau = 30, cap = 20, c = 0.01;

SpecializedScene clutch_and_fan(const std::string& solver, const std::string& tolerance) {
  const auto dir = temp_dir("nonlinear_modes_" + solver);
  write_text(dir / "pair.toml", R"(name = "clutch_pair"
[[body]]
name = "a"
[[body]]
name = "b"
[[body]]
name = "f"
[[clutch]]
name = "C"
bodies = ["a", "b"]
[[shaft]]
name = "s"
bodies = ["b", "f"]
[parameters]
J_a = "0.2*kg*m^2"
J_b = "0.03*kg*m^2"
J_f = "0.02*kg*m^2"
b_a = "0"
b_b = "0"
b_f = "0"
K_s = "1e4*N*m/rad"
b_s = "0"
Tcap_C = "20*N*m"
)");
  const std::string scene = R"(name = "fan"
model = "pair.toml"
[inputs]
tau_a = "30*N*m"
[loads]
f = { quadratic = "0.01*N*m*s^2" }
[engagement]
C = "1"
[initial]
omega_a = "0*rad/s"
omega_b = "0*rad/s"
omega_f = "0*rad/s"
[simulation]
horizon = "1*s"
sample = "1*ms"
solver = ")" + solver + R"("
tolerance = )" + tolerance + "\n";
  write_text(dir / "scene.toml", scene);
  return specialize(parse_scene((dir / "scene.toml").string()));
}

struct ClosedForm {
  // Stuck: (Ja + Jb) w' = tau - c w^2 from rest, w = V tanh(t / T); the clutch carries
  // Jb w' + c w^2 = Jb tau / J + c w^2 Ja / J and lets go where that reaches cap.
  double J = Ja + Jb, V = std::sqrt(tau / c), T = J / std::sqrt(tau * c);
  double w_slip = std::sqrt((cap - Jb * tau / J) * J / (c * Ja));
  double t_slip = T * std::atanh(w_slip / V);
  // Slipping: Ja wa' = tau - cap, Jb wb' = cap - c wb^2.
  double Vb = std::sqrt(cap / c), Tb = Jb / std::sqrt(cap * c);
  double wa(double t) const { return t < t_slip ? V * std::tanh(t / T) : w_slip + (tau - cap) / Ja * (t - t_slip); }
  double wb(double t) const {
    return t < t_slip ? wa(t) : Vb * std::tanh(std::atanh(w_slip / Vb) + (t - t_slip) / Tb);
  }
  // The clutch's heat: cap times the integral of wa - wb over the slip.
  double heat(double t) const {
    if (t <= t_slip) return 0;
    const double s = t - t_slip, u0 = std::atanh(w_slip / Vb);
    const double ramp = w_slip * s + 0.5 * (tau - cap) / Ja * s * s;
    const double fan = Vb * Tb * (std::log(std::cosh(u0 + s / Tb)) - std::log(std::cosh(u0)));
    return cap * (ramp - fan);
  }
};

struct FanRun {
  Eigen::Index a = -1, b = -1;  // the states of omega_a and omega_b (or omega_f, the same)
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, w, energy;
  std::vector<rt::HybridEvent> events;
  rt::RunStatus status;
};

FanRun run_fan(const SpecializedScene& m, rt::Solver solver) {
  const NumericSystem ns = numeric_system(m, m.main);
  const rt::HybridSystem hs = hybrid_system(m, m.main, ns);
  rt::HybridMethod method{solver, {}};
  rt::set_tolerance(method.options, m.scene.tolerance);
  rt::HybridEngine engine(hs, m.scene.horizon, method);
  FanRun r;
  const std::vector<std::string> states = port_names(m.derivation.symbols, state_variables(m.main));
  for (std::size_t j = 0; j < states.size(); ++j) {
    if (states[j] == "omega_a") r.a = static_cast<Eigen::Index>(j);
    if (states[j] == "omega_b" || states[j] == "omega_f") r.b = static_cast<Eigen::Index>(j);
  }
  r.status = engine.run(
      ns.x0, m.scene.sample,
      [&](double t, const rt::HybridSample& s) {
        r.t.push_back(t);
        r.x.push_back(s.x);
        r.w.push_back(s.w);
        r.energy.push_back(s.energy);
        return true;
      },
      [&](const rt::HybridEvent& e) { r.events.push_back(e); });
  return r;
}

TEST(NonlinearModes, AClutchLetsGoOfAFanWhereTheClosedFormSays) {
  const ClosedForm f;
  ASSERT_GT(f.t_slip, 0.4);  // 0.459 s: within the horizon, well after the start
  ASSERT_LT(f.t_slip, 0.6);
  // Each method's global error at its tolerance, about ten times what was measured: dopri5 at 1e-11
  // (event 9e-13 s, speeds and torque 1.5e-9 rad/s and 3e-10 N m, heat 1.1e-12 of itself), TR-BDF2,
  // second order, at 1e-9 (1.5e-8 s, 3.2e-6 rad/s, 1.3e-6 N m, 7.6e-8).
  struct Case {
    rt::Solver solver;
    std::string tolerance;
    double event, speed, heat;  // s, rad/s and N m, relative
  };
  for (const Case& k : {Case{rt::Solver::dopri5, "1e-11", 1e-11, 1e-8, 1e-11},
                        Case{rt::Solver::implicit, "1e-9", 1e-7, 3e-5, 1e-6}}) {
    SCOPED_TRACE(std::string(rt::solver_name(k.solver)));
    const SpecializedScene m = clutch_and_fan(std::string(rt::solver_name(k.solver)), k.tolerance);
    ASSERT_TRUE(m.main.nonlinear);
    const FanRun r = run_fan(m, k.solver);
    ASSERT_TRUE(r.status.ok) << r.status.message;
    ASSERT_EQ(r.x[0].size(), 2);  // the shaft is rigid: b and f turn as one
    ASSERT_TRUE(r.a >= 0 && r.b >= 0);
    // One event: C stuck -> slipping at t_slip.
    ASSERT_EQ(r.events.size(), 1u);
    EXPECT_EQ(r.events[0].from, rt::ElementState::stuck);
    EXPECT_EQ(r.events[0].to, rt::ElementState::slipping);
    EXPECT_NEAR(r.events[0].t, f.t_slip, k.event);
    double speed = 0, torque = 0;
    for (std::size_t i = 0; i < r.t.size(); ++i) {
      const double t = r.t[i];
      speed = std::max({speed, std::abs(r.x[i](r.a) - f.wa(t)), std::abs(r.x[i](r.b) - f.wb(t))});
      // The clutch's torque: stuck, Jb tau / J + c w^2 Ja / J (the fan's torque projected through
      // the mode); slipping, its capacity, driving b.
      const double w = f.wa(t), T = t < f.t_slip ? Jb * tau / f.J + c * w * w * Ja / f.J : cap;
      torque = std::max(torque, std::abs(std::abs(r.w[i](r.w[i].size() - 1)) - T));
    }
    EXPECT_LT(speed, k.speed);
    EXPECT_LT(torque, k.speed);
    EXPECT_NEAR(r.energy.back()(0), f.heat(r.t.back()), k.heat * f.heat(r.t.back()));
  }
}

// Exact stepping needs linear modes: the engine itself refuses it a state torque.
TEST(NonlinearModes, ExactSteppingIsRefused) {
  const SpecializedScene m = clutch_and_fan("dopri5", "1e-8");
  const FanRun r = run_fan(m, rt::Solver::exact);
  EXPECT_FALSE(r.status.ok);
  EXPECT_EQ(r.status.message,
            "a quadratic load, a converter or an engine makes the modes nonlinear, which exact stepping does not integrate");
}

}  // namespace
}  // namespace pogear::test
