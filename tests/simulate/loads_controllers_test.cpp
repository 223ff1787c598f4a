// Scene loads and speed controllers against closed forms written here: a P and a PI controller's
// closed loop, constant, linear and quadratic loads, torque limits, and the power balance of the
// power-split drive with its loads and its controller's work. The compiled simulators against the
// interpreted run (`pogear simulate`): tests/commands/loads_controllers_test.cpp.
#include <algorithm>
#include <cmath>
#include <tuple>

#include "specialize/reference_model.hpp"
#include "sim_support.hpp"
#include "../support/ports.hpp"

namespace pogear::test {
namespace {

// tests/vibration/pair.toml: wheel a (r_a = 10 cm, J_a = 0.02 kg m^2) meshing wheel b (r_b = 25 cm,
// J_b = 0.3 kg m^2), no bearing friction. Rigid, it has one degree of freedom; seen from a, its
// inertia is J_a + J_b (r_a / r_b)^2 whichever way b turns.
constexpr double r_a = 0.10, r_b = 0.25, J_a = 0.02, J_b = 0.3;
constexpr double ratio = r_a / r_b;
constexpr double J_seen_from_a = J_a + J_b * ratio * ratio;

std::string pair_scene(const std::string& tables, const std::string& initial = "omega_a = \"0*rpm\"",
                       const std::string& solver = "exact") {
  return "name = \"pair_scene\"\nmodel = \"../../tests/vibration/pair.toml\"\nkeep = [\"a\"]\n"
         "effects = [\"bearing_friction\"]\n" +
         tables + "\n[initial]\n" + initial + "\n\n[simulation]\nhorizon = \"2*s\"\nsample = \"1*ms\"\nsolver = \"" +
         solver + "\"\ntolerance = 1e-11\n";
}

// The column of output `name` in a run of `sys`.
std::vector<double> column(const Trajectory& tr, const SpecializedScene& m, const std::string& name) {
  const std::vector<std::string> outputs = output_names(m, m.main);
  const auto it = std::find(outputs.begin(), outputs.end(), name);
  EXPECT_NE(it, outputs.end()) << name;
  std::vector<double> out;
  for (const auto& y : tr.y) out.push_back(y(it - outputs.begin()));
  return out;
}

TEST(SpeedController, PReachesItsSetPointWithTheClosedLoopTimeConstant) {
  // J omega' = kp (ref - omega) from rest: omega = ref (1 - exp(-t / T)), T = J / kp.
  const double kp = 0.5, ref = 100.0;
  const SpecializedScene m = scene_model(pair_scene(
      "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\" }\n"));
  ASSERT_EQ(state_names(m, m.main), (std::vector<std::string>{"omega_a", "theta_speed"}));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  const double T = J_seen_from_a / kp;
  EXPECT_EQ(system_diagnostics(m, m.main).growing_modes, 0);
  const std::vector<double> omega = column(tr, m, "omega_a"), torque = column(tr, m, "Tc_speed");
  for (std::size_t i = 0; i < tr.t.size(); ++i) {
    // Exact stepping of a 2-state linear system: rounding only, ~1e-15 of the scale per step.
    EXPECT_NEAR(omega[i], ref * (1 - std::exp(-tr.t[i] / T)), 1e-11 * ref) << tr.t[i];
    EXPECT_NEAR(torque[i], kp * ref * std::exp(-tr.t[i] / T), 1e-11 * kp * ref) << tr.t[i];
  }
}

TEST(SpeedController, PIErrorDecaysWithTheClosedLoopPoles) {
  // The error e = ref - omega of J omega' = kp e + ki theta, theta' = e, obeys J e'' + kp e' + ki e = 0
  // with e(0) = ref and e'(0) = -kp ref / J: two real poles for these gains.
  const double kp = 0.5, ki = 0.5, ref = 100.0;
  const SpecializedScene m = scene_model(pair_scene(
      "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\", ki = \"0.5*N*m/rad\" }\n"));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  const double J = J_seen_from_a, disc = std::sqrt(kp * kp - 4 * J * ki);
  ASSERT_GT(kp * kp, 4 * J * ki);
  const double l1 = (-kp + disc) / (2 * J), l2 = (-kp - disc) / (2 * J);
  // A + B = ref, l1 A + l2 B = -kp ref / J
  const double A = (-kp * ref / J - l2 * ref) / (l1 - l2), B = ref - A;
  const std::vector<double> omega = column(tr, m, "omega_a");
  double worst = 0;
  for (std::size_t i = 0; i < tr.t.size(); ++i) {
    const double e = A * std::exp(l1 * tr.t[i]) + B * std::exp(l2 * tr.t[i]);
    worst = std::max(worst, std::abs(ref - omega[i] - e));
  }
  EXPECT_LT(worst, 1e-11 * ref);  // exact stepping: rounding only
}

TEST(SpeedController, StartsAtTheGivenTorqueWithoutABump) {
  // A load of 2 N m held by the controller at 100 rad/s: started at the speed and at the torque that
  // balance the load, the integral takes the load from t = 0 and nothing moves; started at zero
  // torque, the speed dips.
  const std::string tables = "[loads]\na = { constant = \"2*N*m\" }\n[controllers]\n"
                             "speed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\", ki = \"0.5*N*m/rad\" }\n";
  const SpecializedScene bumpless = scene_model(pair_scene(tables, "omega_a = \"100*rad/s\"\nTc_speed = \"2*N*m\""));
  const SpecializedScene from_zero = scene_model(pair_scene(tables, "omega_a = \"100*rad/s\""));
  EXPECT_EQ(bumpless.main.states[1].initial, 4.0);  // theta(0) = (2 - 0.5 * 0) / 0.5
  const Trajectory held = interpret_trajectory(bumpless, bumpless.main, run_settings(bumpless));
  const Trajectory dipped = interpret_trajectory(from_zero, from_zero.main, run_settings(from_zero));
  ASSERT_TRUE(held.status.ok && dipped.status.ok);
  double held_gap = 0, dip = 0;
  for (std::size_t i = 0; i < held.t.size(); ++i) {
    held_gap = std::max(held_gap, std::abs(column(held, bumpless, "omega_a")[i] - 100));
    dip = std::max(dip, std::abs(column(dipped, from_zero, "omega_a")[i] - 100));
  }
  EXPECT_LT(held_gap, 1e-12 * 100);  // an equilibrium, stepped exactly: rounding only
  EXPECT_GT(dip, 0.5);               // 2 N m on 0.068 kg m^2 before the controller answers
}

// The diagnostics see a limited controller within its limits: a stiff P controller (kp / J = 7.4e4/s)
// sets the fastest rate, with limits it never reaches as without limits (whose law is in M itself).
TEST(SpeedController, DiagnosticsSeeALimitedControllersFeedback) {
  const std::string controller = "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"5000*N*m*s/rad\"";
  const SpecializedScene open = scene_model(pair_scene(controller + " }\n"));
  const SpecializedScene limited = scene_model(pair_scene(controller + ", torque_max = \"1e6*N*m\" }\n"));
  ASSERT_EQ(limited.main.limited_controllers.size(), 1u);
  const Diagnostics a = system_diagnostics(open, open.main), b = system_diagnostics(limited, limited.main);
  // -kp / J (no bearing friction in pair.toml) and the integral's 0: the eigenvalues of a 2 x 2, to rounding.
  EXPECT_NEAR(a.fastest_rate, 5000 / J_seen_from_a, 1e-9 * a.fastest_rate);
  EXPECT_NEAR(b.fastest_rate, a.fastest_rate, 1e-12 * a.fastest_rate);
  EXPECT_EQ(b.growing_modes, 0);
}

TEST(SpeedController, MeasuresTheBodyItIsGiven) {
  // Driving a and measuring b, which an external mesh turns the other way (omega_b = -ratio
  // omega_a): J omega_a' = kp (ref - omega_b) = kp (ref + ratio omega_a) feeds back positively, and
  // the run follows it away from the set-point: omega_b = ref (1 - e^(t/T)), T = J / (kp ratio).
  const double kp = 0.5, ref = 10.0;
  const SpecializedScene m = scene_model(pair_scene(
      "[controllers]\nspeed = { body = \"a\", speed_of = \"b\", set_point = \"10*rad/s\", kp = \"0.5*N*m*s/rad\" }\n"));
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  const double T = J_seen_from_a / (kp * ratio);
  // The summary warns of it: one mode growing at 1 / T (an eigenvalue of M, to rounding).
  const Diagnostics d = system_diagnostics(m, m.main);
  EXPECT_EQ(d.growing_modes, 1);
  EXPECT_NEAR(d.fastest_growth_rate, 1 / T, 1e-12 / T);
  const std::vector<double> omega_b = column(tr, m, "omega_b");
  for (std::size_t i = 0; i < tr.t.size(); i += 100) {
    const double expected = ref * (1 - std::exp(tr.t[i] / T));
    EXPECT_NEAR(omega_b[i], expected, 1e-11 * std::max(ref, std::abs(expected))) << tr.t[i];
  }
}

TEST(Loads, ConstantAndLinearLoadsDecelerateAsTheirClosedForm) {
  // From 100 rad/s, a constant load c0 on a and a linear one c1 on b (c1 ratio^2 seen from a):
  // J omega' = -c0 - k omega, k = c1 ratio^2: omega = -c0/k + (omega0 + c0/k) e^(-k t / J).
  const double c0 = 0.2, c1 = 0.5, omega0 = 100.0, k = c1 * ratio * ratio;
  const SpecializedScene m = scene_model(pair_scene("[loads]\na = { constant = \"0.2*N*m\" }\n"
                                                    "b = { linear = \"0.5*N*m*s/rad\" }\n",
                                                    "omega_a = \"100*rad/s\""));
  EXPECT_FALSE(m.main.nonlinear);
  ASSERT_EQ(input_names(m, m.main), std::vector<std::string>{"TL_a"});
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  const std::vector<double> omega = column(tr, m, "omega_a");
  for (std::size_t i = 0; i < tr.t.size(); ++i)
    EXPECT_NEAR(omega[i], -c0 / k + (omega0 + c0 / k) * std::exp(-k * tr.t[i] / J_seen_from_a), 1e-11 * omega0)
        << tr.t[i];
}

TEST(Loads, QuadraticLoadDeceleratesAsItsClosedForm) {
  // A quadratic load c omega_b |omega_b| on b is c ratio^3 omega_a |omega_a| seen from a:
  // J omega' = -q omega^2 for omega > 0, omega = omega0 / (1 + q omega0 t / J).
  const double c = 0.01, omega0 = 100.0, q = c * ratio * ratio * ratio;
  const SpecializedScene m = scene_model(pair_scene("[loads]\nb = { quadratic = \"0.01*N*m*s^2/rad^2\" }\n",
                                                    "omega_a = \"100*rad/s\"", "dopri5"));
  EXPECT_TRUE(m.main.nonlinear);
  for (const rt::Solver solver : {rt::Solver::dopri5, rt::Solver::implicit}) {
    const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m, solver));
    ASSERT_TRUE(tr.status.ok) << tr.status.message;
    const std::vector<double> omega = column(tr, m, "omega_a");
    double worst = 0;
    for (std::size_t i = 0; i < tr.t.size(); ++i)
      worst = std::max(worst, std::abs(omega[i] - omega0 / (1 + q * omega0 * tr.t[i] / J_seen_from_a)));
    // Relative tolerance 1e-11 per step: the global error stays within a few 1e-9 of omega0.
    EXPECT_LT(worst, 1e-8 * omega0) << rt::solver_name(solver);
  }
  const Trajectory refused = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::exact));
  EXPECT_FALSE(refused.status.ok);
}

// E(T) - E(0) = the work of the input torques, the loads and the controller less what bearings and
// mesh dampers dissipate, along both models of the power-split drive. Simpson's rule on samples
// 0.02 ms apart, dopri5 at 1e-11: measured 6e-13 of the change (elastic), 1e-13 (rigid); a 0.6 %
// error in the drag coefficient shows as 2e-3. We assert 1e-9.
TEST(PowerBalance, HoldsWithLoadsAndTheControllersWork) {
  std::string text = with_lines(scene_text("power_split_drive"), {{"horizon = \"8*s\"", "horizon = \"0.4*s\""},
                                                                  {"sample = \"5*ms\"", "sample = \"0.02*ms\""},
                                                                  {"solver = \"implicit\"", "solver = \"dopri5\""},
                                                                  {"tolerance = 1e-6", "tolerance = 1e-11"}});
  // A set-point step within the window, so that the controller works both ways; the car at 85 km/h,
  // where the road load takes 8 kW (3 kW of it the quadratic part).
  text = with_lines(text, {{"at = \"3*s\"", "at = \"0.2*s\""}, {"omega_r = \"0*rpm\"", "omega_r = \"3000*rpm\""}});
  const SpecializedScene m = scene_model(text);
  const Derivation& d = m.derivation;
  const GearMatrices g = gear_matrices(d);
  const Eigen::MatrixXd &J = g.J, &BJ = g.BJ, &K = g.K, &BK = g.BK, &R = g.R, &Q1 = g.Q1;
  const Eigen::Index n = J.rows(), k = K.rows();
  const int c = find_body(d.topology, "c"), s = find_body(d.topology, "s"), r = find_body(d.topology, "r");
  const rt::Signal mg2 = m.scene.inputs[1].signal;  // tau_r, from its table
  const double rpm = M_PI / 30, kp = 1.5, ki = 4;
  for (const SpecializedSystem* sys : {&m.main, &*m.rigid}) {
    const Trajectory tr = interpret_trajectory(m, *sys, run_settings(m, rt::Solver::dopri5));
    ASSERT_TRUE(tr.status.ok) << tr.status.message;
    // The power at sample i with the set-point `ref`: its jump at 0.2 s is met from both sides.
    auto power = [&](std::size_t i, double ref) {
      const Eigen::VectorXd& x = tr.x[i];
      const Eigen::VectorXd omega = sys->kind == SystemKind::elastic ? Eigen::VectorXd(x.head(n))
                                                                     : Eigen::VectorXd(Q1 * x.head(Q1.cols()));
      const Eigen::VectorXd slip = R * omega;  // zero on the rigid model
      const double controller = kp * (ref - omega(c)) + ki * x(x.size() - 1);
      const double road = -(9.56 + 1.67e-4 * omega(r) * std::abs(omega(r)));
      return 120 * omega(c) + rt::value(mg2, tr.t[i]) * omega(r) + controller * omega(s) + road * omega(r) -
             omega.dot(BJ * omega) - slip.dot(BK * slip);
    };
    auto energy = [&](std::size_t i) {
      const Eigen::VectorXd& x = tr.x[i];
      const Eigen::VectorXd omega = sys->kind == SystemKind::elastic ? Eigen::VectorXd(x.head(n))
                                                                     : Eigen::VectorXd(Q1 * x.head(Q1.cols()));
      double e = 0.5 * omega.dot(J * omega);
      if (sys->kind == SystemKind::elastic) e += 0.5 * x.segment(n, k).dot(K.inverse() * x.segment(n, k));
      return e;
    };
    const std::size_t jump = 10000, last = 20000;  // samples at 0.2 s and 0.4 s
    ASSERT_EQ(tr.t.size(), last + 1);
    ASSERT_NEAR(tr.t[jump], 0.2, 1e-12);
    const double h = tr.t[1] - tr.t[0];
    double integral = 0;  // Simpson on [0, 0.2] and [0.2, 0.4]
    for (std::size_t i = 0; i + 2 <= last; i += 2) {
      const double low = i < jump ? 1000 * rpm : 2000 * rpm, high = i + 2 <= jump ? 1000 * rpm : 2000 * rpm;
      integral += h / 3 * (power(i, low) + 4 * power(i + 1, low) + power(i + 2, high));
    }
    const double change = energy(last) - energy(0);
    EXPECT_NEAR(change, integral, 1e-9 * std::abs(change)) << sys->kind;
  }
}

// The scene's main system run interpreted with `solver` (a hybrid run with torque limits).
HybridRun hybrid_run(const SpecializedScene& m, rt::Solver solver, const std::string& tag) {
  rt::SceneRun run = run_settings(m, solver);
  run.out_dir = temp_dir("limits_" + tag).string();
  run.quiet = true;
  EXPECT_EQ(run_interpreted(m, run), 0);
  return read_hybrid_run(run.out_dir, m.scene.name);
}

TEST(TorqueLimits, PControllerAtItsLimitThenTheClosedLoop) {
  // From rest toward 100 rad/s with kp = 0.5 N m s/rad: the law asks 50 N m, the limit gives 5, so
  // J omega' = 5 until kp (100 - omega) = 5, at omega* = 90 and t* = 90 J / 5; then
  // omega = 100 - 10 exp(-(t - t*) / (J / kp)).
  const double ref = 100, kp = 0.5, limit = 5, J = J_seen_from_a;
  const double t_star = (ref - limit / kp) * J / limit;
  const SpecializedScene m = scene_model(pair_scene(
      "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\", torque_max = \"5*N*m\" }\n"));
  for (const rt::Solver solver : {rt::Solver::exact, rt::Solver::dopri5}) {
    const HybridRun r = hybrid_run(m, solver, "p");
    ASSERT_EQ(r.events.size(), 1u) << rt::solver_name(solver);
    const auto& [t_event, element, from, to] = r.events[0];
    EXPECT_EQ(element + " " + from + " " + to, "speed at_limit linear");
    // Exact: the event on the exact trajectory to 4 ulps; dopri5: on its dense output at 1e-11.
    EXPECT_NEAR(t_event, t_star, solver == rt::Solver::exact ? 1e-14 : 1e-9) << rt::solver_name(solver);
    const std::size_t omega = r.csv.column("omega_a [rad/s]"), torque = r.csv.column("Tc_speed [N m]");
    double worst = 0;
    for (const auto& row : r.csv.rows) {
      const double t = row[0];
      worst = std::max(worst, std::abs(row[omega] - (t <= t_star ? limit * t / J : ref - 10 * std::exp(-(t - t_star) * kp / J))));
      if (t < t_star) {
        EXPECT_EQ(row[torque], limit) << t;
      }
    }
    // Exact stepping: rounding only; dopri5 at 1e-11 relative, over 2000 samples.
    EXPECT_LT(worst, (solver == rt::Solver::exact ? 1e-11 : 1e-7) * ref) << rt::solver_name(solver);
  }
}

TEST(TorqueLimits, PControllerAtItsLimitAgainstAFanThenTheClosedLoop) {
  // The same from rest with a fan, c omega^2, c = 2e-4 N m s^2: at the limit J omega' = 5 - c omega^2,
  // omega = V tanh(t / T) (V = sqrt(5 / c), T = J / sqrt(5 c)), until kp (100 - omega) = 5 at
  // omega* = 90, t* = T atanh(omega* / V); then the Riccati equation J omega' = kp (ref - omega) -
  // c omega^2 = -c (omega - w1)(omega - w2), whose (omega - w1) / (omega - w2) decays as
  // exp(-c (w1 - w2) (t - t*) / J).
  const double ref = 100, kp = 0.5, limit = 5, c = 2e-4, J = J_seen_from_a;
  const double V = std::sqrt(limit / c), T = J / std::sqrt(limit * c), w_star = ref - limit / kp;
  const double t_star = T * std::atanh(w_star / V);
  const double root = std::sqrt(kp * kp + 4 * c * kp * ref), w1 = (root - kp) / (2 * c), w2 = (-root - kp) / (2 * c);
  auto omega = [&](double t) {
    if (t <= t_star) return V * std::tanh(t / T);
    const double q = (w_star - w1) / (w_star - w2) * std::exp(-c * (w1 - w2) * (t - t_star) / J);
    return (w1 - w2 * q) / (1 - q);
  };
  ASSERT_LT(t_star, 1.8);  // 1.39 s: within the 2 s horizon
  const SpecializedScene m = scene_model(pair_scene(
      "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\", torque_max = \"5*N*m\" }\n"
      "[loads]\na = { quadratic = \"2e-4*N*m*s^2\" }\n", "omega_a = \"0*rpm\"", "dopri5"));
  // Each method's error at tolerance 1e-11, about ten times what was measured: dopri5 (event 3.7e-12 s,
  // speed 5.4e-10 rad/s), TR-BDF2, second order (event 5.8e-9 s, speed 3.0e-7 rad/s).
  for (const auto& [solver, event, speed] : {std::tuple{rt::Solver::dopri5, 4e-11, 5e-9},
                                             std::tuple{rt::Solver::implicit, 6e-8, 3e-6}}) {
    const HybridRun r = hybrid_run(m, solver, "fan");
    ASSERT_EQ(r.events.size(), 1u) << rt::solver_name(solver);
    const auto& [t_event, element, from, to] = r.events[0];
    EXPECT_EQ(element + " " + from + " " + to, "speed at_limit linear");
    EXPECT_NEAR(t_event, t_star, event) << rt::solver_name(solver);
    const std::size_t w = r.csv.column("omega_a [rad/s]"), torque = r.csv.column("Tc_speed [N m]");
    double worst = 0;
    for (const auto& row : r.csv.rows) {
      worst = std::max(worst, std::abs(row[w] - omega(row[0])));
      if (row[0] < t_star) {
        EXPECT_EQ(row[torque], limit) << row[0];
      }
    }
    EXPECT_LT(worst, speed) << rt::solver_name(solver);
  }
}

TEST(TorqueLimits, IntegralTracksTheLimitThenThePIControllerCloses) {
  // kp = ki = 0.5, limit 5 N m, tracking time kp / ki = 1 s. At the limit, J omega' = 5 and
  // q = ki theta - 5 obeys q' = -q / 1 s from q(0) = -5; the law kp e + ki theta = kp e + q + 5 comes
  // back to the limit when kp (ref - 5 t / J) + q(t) = 0. From there the PI loop:
  // J e'' + kp e' + ki e = 0 with e' = -5 / J (the torque is continuous).
  const double ref = 100, kp = 0.5, ki = 0.5, limit = 5, J = J_seen_from_a;
  auto q = [&](double t) { return -limit * std::exp(-t); };
  auto margin = [&](double t) { return kp * (ref - limit * t / J) + q(t); };
  double lo = 0, hi = 2;  // margin(0) = 45 > 0 > margin(2)
  for (int i = 0; i < 200; ++i) (margin(0.5 * (lo + hi)) > 0 ? lo : hi) = 0.5 * (lo + hi);
  const double t_star = 0.5 * (lo + hi), e_star = ref - limit * t_star / J;
  const double disc = std::sqrt(kp * kp - 4 * J * ki), l1 = (-kp + disc) / (2 * J), l2 = (-kp - disc) / (2 * J);
  const double de = -limit / J, A = (de - l2 * e_star) / (l1 - l2), B = e_star - A;
  const SpecializedScene m = scene_model(pair_scene(
      "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", kp = \"0.5*N*m*s/rad\", ki = \"0.5*N*m/rad\", "
      "torque_max = \"5*N*m\" }\n"));
  const HybridRun r = hybrid_run(m, rt::Solver::exact, "pi");
  ASSERT_EQ(r.events.size(), 1u);
  EXPECT_NEAR(std::get<0>(r.events[0]), t_star, 1e-13);  // the bisection's root to 1e-16, the event to 4 ulps
  const std::size_t omega = r.csv.column("omega_a [rad/s]");
  double worst = 0;
  for (const auto& row : r.csv.rows) {
    const double t = row[0], s = t - t_star;
    worst = std::max(worst, std::abs(row[omega] - (t <= t_star ? limit * t / J : ref - A * std::exp(l1 * s) - B * std::exp(l2 * s))));
  }
  EXPECT_LT(worst, 1e-11 * ref);  // exact stepping: rounding only
}

}  // namespace
}  // namespace pogear::test
