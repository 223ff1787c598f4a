// Simulated shafts against closed forms: the torque a damped shaft transmits after a torque step,
// its spring's share, and a stiff shaft converging on the rigid join as 1/K.
#include <cmath>
#include <string>

#include <gtest/gtest.h>

#include "sim_support.hpp"

namespace pogear::test {
namespace {

const char* two_inertias = R"(name = "two_inertias"
[[body]]
name = "a"
[[body]]
name = "b"
[[shaft]]
name = "s"
bodies = ["a", "b"]
[parameters]
J_a = "0.2*kg*m^2"
J_b = "0.05*kg*m^2"
b_a = "0"
b_b = "0"
K_s = "2000*N*m/rad"
b_s = "1.5*N*m*s/rad"
)";

SpecializedScene shaft_scene(const std::string& tag, const std::string& input, const std::string& overrides) {
  const auto dir = temp_dir("shaft_" + tag);
  write_text(dir / "two.toml", two_inertias);
  const std::string scene = R"(name = "two_step"
model = "two.toml"
effects = ["shaft_compliance", "shaft_damping", "mesh_forces"]
compare_rigid = true
outputs = ["omega_a", "omega_b", "T_s", "Tspring_s"]
[inputs]
tau_a = )" + input + R"(
[simulation]
horizon = "0.5*s"
sample = "1*ms"
solver = "exact"
)" + (overrides.empty() ? "" : "[parameters]\n" + overrides + "\n");
  write_text(dir / "scene.toml", scene);
  return specialize(parse_scene_text(scene, (dir / "scene.toml").string()));
}

// tau on a from rest, b free: the twist theta obeys mu theta'' + c theta' + k theta = tau J_b / (J_a + J_b),
// mu = J_a J_b / (J_a + J_b), so theta = theta_s (1 - e^(-z w t) (cos w_d t + z / sqrt(1 - z^2) sin w_d t)); the
// shaft transmits k theta + c theta', its spring k theta.
TEST(Shafts, StepTorqueIsTransmittedAsTheDampedOscillatorsClosedForm) {
  const SpecializedScene m = shaft_scene("step", "\"10*N*m\"", "");
  const Trajectory e = interpret_trajectory(m, m.main, run_settings(m));
  const Trajectory r = interpret_trajectory(m, *m.rigid, run_settings(m));
  ASSERT_TRUE(e.status.ok && r.status.ok);
  const double Ja = 0.2, Jb = 0.05, k = 2000, c = 1.5, tau = 10;
  const double mu = Ja * Jb / (Ja + Jb), wn = std::sqrt(k / mu), z = c / (2 * std::sqrt(k * mu));
  const double wd = wn * std::sqrt(1 - z * z), theta_s = tau * Jb / (Ja + Jb) / k;
  double transmitted = 0, spring = 0, rigid = 0;
  for (std::size_t i = 0; i < e.t.size(); ++i) {
    const double t = e.t[i], decay = std::exp(-z * wn * t);
    const double theta = theta_s * (1 - decay * (std::cos(wd * t) + z / std::sqrt(1 - z * z) * std::sin(wd * t)));
    const double rate = theta_s * decay * wn / std::sqrt(1 - z * z) * std::sin(wd * t);
    transmitted = std::max(transmitted, std::abs(e.y[i](2) - (k * theta + c * rate)));
    spring = std::max(spring, std::abs(e.y[i](3) - k * theta));
    // The rigid join: T = J_b omega_b' = tau J_b / (J_a + J_b) from the start, spring or not.
    rigid = std::max({rigid, std::abs(r.y[i](2) - tau * Jb / (Ja + Jb)), std::abs(r.y[i](3) - tau * Jb / (Ja + Jb))});
  }
  // Exact stepping, 500 steps of one exponential each: rounding of ~1e-13 of the peak torque, 2.8 N m
  // (measured 2.8e-13 N m, transmitted and spring; 4.4e-16 N m rigid).
  EXPECT_LT(transmitted, 1e-11) << "transmitted";
  EXPECT_LT(spring, 1e-11) << "spring";
  EXPECT_LT(rigid, 1e-13) << "rigid";
  // The damper's share is not rounding: it peaks at c theta' ~ 0.2 N m.
  double damper = 0;
  for (std::size_t i = 0; i < e.t.size(); ++i) damper = std::max(damper, std::abs(e.y[i](2) - e.y[i](3)));
  EXPECT_GT(damper, 0.1);
}

// A torque ramp (no step to ring the shaft): elastic minus rigid is the quasi-static twist's
// O(1/K), for speeds and torque alike, once the start's transient has decayed.
TEST(Shafts, StiffShaftConvergesOnTheRigidJoinAsOneOverK) {
  auto gaps = [](const std::string& tag, const std::string& stiffness) {
    const SpecializedScene m = shaft_scene(tag, "{ ramp = \"100*N*m/s\" }",
                                           "K_s = \"" + stiffness + "\"\nb_s = \"40*N*m*s/rad\"");
    const Trajectory e = interpret_trajectory(m, m.main, run_settings(m));
    const Trajectory r = interpret_trajectory(m, *m.rigid, run_settings(m));
    EXPECT_TRUE(e.status.ok && r.status.ok);
    double speed = 0, torque = 0, speed_scale = 0, torque_scale = 0;
    for (std::size_t i = 0; i < e.t.size(); ++i) {
      if (e.t[i] < 0.25) continue;
      speed = std::max({speed, std::abs(e.y[i](0) - r.y[i](0)), std::abs(e.y[i](1) - r.y[i](1))});
      torque = std::max(torque, std::abs(e.y[i](2) - r.y[i](2)));
      speed_scale = std::max(speed_scale, std::abs(r.y[i](0)));
      torque_scale = std::max(torque_scale, std::abs(r.y[i](2)));
    }
    return std::pair{speed / speed_scale, torque / torque_scale};
  };
  const auto soft = gaps("soft", "2000*N*m/rad"), stiff = gaps("stiff", "200000*N*m/rad");
  EXPECT_LT(soft.first, 1e-2);
  EXPECT_LT(soft.second, 1e-2);
  // Measured: the 100x stiffer shaft leaves speeds 100.0x closer. The torque a ramp makes the shaft
  // transmit, spring and damper, is the rigid join's exactly once the transient has decayed (the
  // twist's O(1/K) and its rate's damper share cancel), so only what is left of the transient,
  // which the stiffer shaft damps faster, separates them: 4e4x.
  EXPECT_GT(soft.first / stiff.first, 80.0) << soft.first << " " << stiff.first;
  EXPECT_GT(soft.second / stiff.second, 80.0) << soft.second << " " << stiff.second;
}

// 1500 kg on wheels of 0.3 m through a 3:1 final drive from body b of two_inertias.
const std::string car_on_b = R"([vehicle]
body = "b"
mass = "1500*kg"
wheel_radius = "0.3*m"
final_drive = 3
wheel_inertia = "2.4*kg*m^2"
rolling_resistance = 0.01
drag_coefficient = 0.3
frontal_area = "2.2*m^2"
half_shaft_stiffness = "12000*N*m/rad"
)";

// A coast-down: the car of [vehicle] on the two inertias (through the final drive), from 100 km/h
// with no torque, under rolling resistance and drag: m_e v' = -(F0 + c v^2), m_e the mass with the
// inertias reflected to the road, has v(t) = sqrt(F0/c) tan(atan(v0 sqrt(c/F0)) - t sqrt(F0 c)/m_e).
TEST(Vehicle, CoastDownIsTheClosedFormOfRollingResistanceAndDrag) {
  const auto dir = temp_dir("vehicle_coast");
  write_text(dir / "two.toml", two_inertias);
  // 100 km/h at r = 0.3 m through i = 3: omega = 100 / 3.6 / 0.3 * 3 rad/s on the gear side.
  const std::string omega = "277.77777777777777*rad/s";
  const std::string scene = R"(name = "coast"
model = "two.toml"
)" + car_on_b + R"([initial]
omega_a = ")" + omega + "\"\nomega_b = \"" + omega + "\"\nomega_vehicle = \"" + omega + R"("
[simulation]
horizon = "20*s"
sample = "0.1*s"
solver = "dopri5"
tolerance = 1e-12
)";
  write_text(dir / "scene.toml", scene);
  const SpecializedScene m = specialize(parse_scene_text(scene, (dir / "scene.toml").string()));
  const Trajectory run = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::dopri5));
  ASSERT_TRUE(run.status.ok) << run.status.message;
  const double mass = 1500, r = 0.3, i = 3, g = 9.80665;
  const double m_e = mass + 2.4 / (r * r) + (0.2 + 0.05) * i * i / (r * r);
  const double F0 = 0.01 * mass * g, c = 0.5 * 1.2 * 0.3 * 2.2, v0 = 100 / 3.6;
  const auto names = output_variables(m.main);
  const auto col = [&](VariableKind k) {
    return static_cast<Eigen::Index>(std::find(names.begin(), names.end(), Variable{k, 0}) - names.begin());
  };
  const Eigen::Index speed = col(VariableKind::vehicle_speed), acceleration = col(VariableKind::vehicle_acceleration);
  ASSERT_LT(acceleration, static_cast<Eigen::Index>(names.size()));
  double worst_v = 0, worst_a = 0;
  for (std::size_t k = 0; k < run.t.size(); ++k) {
    const double v = std::sqrt(F0 / c) * std::tan(std::atan(v0 * std::sqrt(c / F0)) - run.t[k] * std::sqrt(F0 * c) / m_e);
    worst_v = std::max(worst_v, std::abs(run.y[k](speed) / 3.6 - v));
    worst_a = std::max(worst_a, std::abs(run.y[k](acceleration) + (F0 + c * v * v) / m_e));
  }
  // dopri5 at a relative tolerance of 1e-12 over 20 s (the car slows from 27.8 to 22.6 m/s): the
  // global error of ~1e-11 of the speed (measured 2.8e-11 m/s, 3.5e-13 m/s^2; leaving the wheels'
  // inertia out of m_e would be 0.1 m/s off).
  EXPECT_LT(worst_v, 1e-9) << worst_v;
  EXPECT_LT(worst_a, 1e-9) << worst_a;
}

// vehicle_jerk against the rate of vehicle_acceleration: the coast-down's car on compliant, damped
// half-shafts, released with the wheels 7.8 rad/s slower (gear side) so that they ring, with drag (the
// quadratic load's rate enters the jerk). Central differences of the acceleration over samples
// 0.05 ms apart, dopri5 at 1e-12.
TEST(Vehicle, JerkIsTheRateOfTheAcceleration) {
  const auto dir = temp_dir("vehicle_jerk");
  write_text(dir / "two.toml", two_inertias);
  const std::string omega = "277.77777777777777*rad/s";
  const std::string scene = R"(name = "jerk"
model = "two.toml"
effects = ["shaft_compliance", "shaft_damping"]
outputs = ["vehicle_acceleration", "vehicle_jerk"]
)" + car_on_b + R"(half_shaft_damping = "20*N*m*s/rad"
[initial]
omega_a = ")" + omega + "\"\nomega_b = \"" + omega + R"("
omega_vehicle = "270*rad/s"
[simulation]
horizon = "0.5*s"
sample = "0.05*ms"
solver = "dopri5"
tolerance = 1e-12
)";
  write_text(dir / "scene.toml", scene);
  const SpecializedScene m = specialize(parse_scene_text(scene, (dir / "scene.toml").string()));
  ASSERT_TRUE(m.main.nonlinear);
  const Trajectory run = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::dopri5));
  ASSERT_TRUE(run.status.ok) << run.status.message;
  const double h = 5e-5;
  double worst = 0, peak = 0;
  for (std::size_t k = 1; k + 1 < run.t.size(); ++k) {
    const double rate = (run.y[k + 1](0) - run.y[k - 1](0)) / (2 * h);
    worst = std::max(worst, std::abs(run.y[k](1) - rate));
    peak = std::max(peak, std::abs(run.y[k](1)));
  }
  // The difference quotient errs by (w h)^2 / 6 of the jerk on a mode at w (measured 8e-6 of the peak,
  // and 3.2e-5 at h = 0.1 ms: the h^2 of a truncation error), far above dopri5's error; a jerk without
  // the drag's rate is off by 2e-4 of the peak.
  EXPECT_GT(peak, 10.0);  // the half-shafts ring: 63 m/s^3
  EXPECT_LT(worst, 5e-5 * peak) << worst << " of " << peak;
}

// A grade that follows a table: the road rises from 0 to 6 degrees over 2 s, then stays. The car,
// rigidly on the two inertias and coasting from 50 km/h, slows as m_e v' = -m g (C_rr cos a + sin a)
// with a = k t, whose integral is closed: v = v0 - (m g / m_e)(C_rr sin a - cos a + 1) / k, then
// linear in t at 6 degrees.
TEST(Vehicle, GradeTableSlowsTheCarAsTheClosedForm) {
  const auto dir = temp_dir("vehicle_grade");
  write_text(dir / "two.toml", two_inertias);
  write_text(dir / "road.csv", "t [s],grade [deg]\n0,0\n2,6\n");
  const std::string omega = "138.88888888888889*rad/s";  // 50 km/h at r = 0.3 m through i = 3
  const std::string scene = R"(name = "grade"
model = "two.toml"
outputs = ["vehicle_speed"]
[vehicle]
body = "b"
mass = "1500*kg"
wheel_radius = "0.3*m"
final_drive = 3
wheel_inertia = "2.4*kg*m^2"
rolling_resistance = 0.015
grade = { table = "road.csv" }
half_shaft_stiffness = "12000*N*m/rad"
[initial]
omega_a = ")" + omega + "\"\nomega_b = \"" + omega + "\"\nomega_vehicle = \"" + omega + R"("
[simulation]
horizon = "4*s"
sample = "10*ms"
step = "1*ms"
solver = "exact"
tolerance = 1e-12
)";
  write_text(dir / "scene.toml", scene);
  const SpecializedScene m = specialize(parse_scene_text(scene, (dir / "scene.toml").string()));
  const double mass = 1500, r = 0.3, i = 3, g = 9.80665, crr = 0.015, v0 = 50 / 3.6;
  const double m_e = mass + 2.4 / (r * r) + (0.2 + 0.05) * i * i / (r * r), k = 3 * M_PI / 180, a1 = 6 * M_PI / 180;
  auto v = [&](double t) {
    const double ta = std::min(t, 2.0), a = k * ta;
    const double ramp = (crr * std::sin(a) - std::cos(a) + 1) / k;
    return v0 - mass * g / m_e * (ramp + std::max(t - 2, 0.0) * (crr * std::cos(a1) + std::sin(a1)));
  };
  // exact holds the load linear over 1 ms steps, an error of about (k h)^2 / 12 = 2.3e-10 of the load
  // (measured 2.9e-10 m/s, and 7.3e-11 at 0.5 ms: the h^2 of the hold); dopri5 at 1e-12: 3.1e-11 m/s.
  for (const auto& [solver, tolerance] : {std::pair{rt::Solver::exact, 1e-9}, std::pair{rt::Solver::dopri5, 3e-10}}) {
    const Trajectory run = interpret_trajectory(m, m.main, run_settings(m, solver));
    ASSERT_TRUE(run.status.ok) << run.status.message;
    double worst = 0;
    for (std::size_t n = 0; n < run.t.size(); ++n) worst = std::max(worst, std::abs(run.y[n](0) / 3.6 - v(run.t[n])));
    EXPECT_LT(worst, tolerance) << rt::solver_name(solver);
  }
  // The car lost 1.5 m/s: the grade's work, not rounding.
  EXPECT_GT(v0 - v(4.0), 1.0);
}

}  // namespace
}  // namespace pogear::test
