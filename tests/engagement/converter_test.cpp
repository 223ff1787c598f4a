// A torque converter and an engine against closed forms: the law's torques, slopes and coupling, a
// pump run up against a held turbine (stall), a locked-up converter against a plain clutch, a
// constant-torque engine against the same torque as an input, and the energy balance of the shipped
// 6HP26 launch (engine work = stored + converter loss + clutch heat + bearings + road).
#include <algorithm>
#include <cmath>
#include <string>

#include <fmt/format.h>
#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "pogear/driveline.hpp"
#include "pogear/hybrid.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

constexpr double per_rpm = 0.10471975511965977;  // rad/s per rpm

// K in rpm/sqrt(N m) at SR 0, 0.5, 0.8, 0.85; TR 2.0, 1.4, 1.04, 1.0 (coupling point 0.85).
rt::ConverterData curves() {
  return {{{0, 0.5, 0.8, 0.85}, {140 * per_rpm, 160 * per_rpm, 200 * per_rpm, 230 * per_rpm}},
          {{0, 0.5, 0.8, 0.85}, {2.0, 1.4, 1.04, 1.0}}};
}

TEST(Converter, LawIsTheTablesTorqueAndItsSlopes) {
  const rt::ConverterData c = curves();
  // Stall: T_p = (omega_p / K(0))^2, the turbine TR(0) times it.
  const double wp = 2000 * per_rpm;
  rt::ConverterTorques s = rt::converter_torques(c, wp, 0);
  const double K0 = 140 * per_rpm;
  EXPECT_NEAR(-s.pump, wp * wp / (K0 * K0), 1e-12 * wp * wp / (K0 * K0));
  EXPECT_NEAR(s.turbine, 2.0 * wp * wp / (K0 * K0), 1e-12 * wp * wp / (K0 * K0));
  // Above the coupling point the turbine receives what the pump absorbs (TR = 1), less at SR = 1: none.
  const rt::ConverterTorques coupled = rt::converter_torques(c, wp, 0.9 * wp);
  EXPECT_NEAR(coupled.turbine, -coupled.pump, 1e-13 * coupled.turbine);
  EXPECT_GT(coupled.turbine, 0);
  const rt::ConverterTorques locked = rt::converter_torques(c, wp, wp);
  EXPECT_EQ(locked.pump, 0);
  EXPECT_EQ(locked.turbine, 0);
  // Coast: the turbine drives the pump, the flow's loss (omega_t - omega_p) T is positive.
  const rt::ConverterTorques coast = rt::converter_torques(c, wp, 1.2 * wp);
  EXPECT_GT(coast.pump, 0);
  EXPECT_EQ(coast.turbine, -coast.pump);
  // Every regime dissipates: -(T_pump omega_p + T_turbine omega_t) >= 0.
  for (double sr = -0.5; sr <= 3; sr += 0.01) {
    const rt::ConverterTorques r = rt::converter_torques(c, wp, sr * wp);
    EXPECT_GE(-(r.pump * wp + r.turbine * sr * wp), -1e-9) << "SR " << sr;
  }
  // Slopes against central differences inside segments (h^2 error of a smooth piece: 1e-7 relative).
  for (const double sr : {0.2, 0.65, 0.83, 0.95, 1.3, 4.0}) {
    const double wt = sr * wp, h = 1e-4 * wp;
    const rt::ConverterTorques r = rt::converter_torques(c, wp, wt);
    const rt::ConverterTorques p1 = rt::converter_torques(c, wp + h, wt), p0 = rt::converter_torques(c, wp - h, wt);
    const rt::ConverterTorques t1 = rt::converter_torques(c, wp, wt + h), t0 = rt::converter_torques(c, wp, wt - h);
    const double scale = std::abs(r.turbine) / wp + std::abs(r.pump) / wp;
    EXPECT_NEAR(r.pump_dp, (p1.pump - p0.pump) / (2 * h), 1e-6 * scale) << "SR " << sr;
    EXPECT_NEAR(r.pump_dt, (t1.pump - t0.pump) / (2 * h), 1e-6 * scale) << "SR " << sr;
    EXPECT_NEAR(r.turbine_dp, (p1.turbine - p0.turbine) / (2 * h), 1e-6 * scale) << "SR " << sr;
    EXPECT_NEAR(r.turbine_dt, (t1.turbine - t0.turbine) / (2 * h), 1e-6 * scale) << "SR " << sr;
  }
}

TEST(Engine, MapIsBilinearAndHeldAtItsEdges) {
  const rt::EngineData e{{100, 300}, {0, 1}, {{-20, -40}, {200, 160}}};
  EXPECT_NEAR(rt::engine_torque(e, 200, 0.5).torque, 0.25 * (-20 - 40 + 200 + 160), 1e-12);
  EXPECT_EQ(rt::engine_torque(e, 50, 1).torque, 200);    // below the first speed: held
  EXPECT_EQ(rt::engine_torque(e, 400, 0).torque, -40);   // above the last: held
  const rt::EngineTorque t = rt::engine_torque(e, 150, 0.25);
  EXPECT_NEAR(t.d_speed, 0.75 * (-20.0 / 200) + 0.25 * (-40.0 / 200), 1e-15);
  EXPECT_NEAR(t.d_throttle, (200 + 0.25 * -40) - (-20 + 0.25 * -20), 1e-12);
}

// Two bodies p and t (a brake H on t), driven by tau_p; the scene's [converter] and [inputs].
SpecializedScene pair_scene(const std::string& name, const std::string& scene_tail) {
  const auto dir = temp_dir("converter_" + name);
  write_text(dir / "pair.toml", R"(name = "pair"
[[body]]
name = "p"
[[body]]
name = "t"
[[body]]
name = "l"
[[shaft]]
name = "s"
bodies = ["t", "l"]
[[brake]]
name = "H"
body = "t"
[[clutch]]
name = "L"
bodies = ["p", "t"]
[parameters]
J_p = "0.2*kg*m^2"
J_t = "0.05*kg*m^2"
J_l = "0.05*kg*m^2"
b_p = "0"
b_t = "0"
b_l = "0"
K_s = "1e4*N*m/rad"
b_s = "0"
Tcap_H = "5000*N*m"
Tcap_L = "800*N*m"
)");
  write_text(dir / (name + ".toml"), "name = \"" + name + "\"\nmodel = \"pair.toml\"\n" + scene_tail);
  return specialize(parse_scene((dir / (name + ".toml")).string()));
}

const char* converter_table = R"(
[converter]
pump = "p"
turbine = "t"
speed_ratio = [0, 0.5, 0.8, 0.85]
capacity_factor = [140, 160, 200, 230]
torque_ratio = [2.0, 1.4, 1.04, 1.0]
)";

struct DrivelineRun {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, w, energy;
  rt::RunStatus status;
};

DrivelineRun run_driveline(const SpecializedScene& model, const SpecializedSystem& sys, double tolerance, double sample) {
  const NumericSystem ns = numeric_system(model, sys);
  const rt::HybridSystem hs = hybrid_system(model, sys, ns);
  rt::HybridMethod method{rt::Solver::dopri5, {}};
  rt::set_tolerance(method.options, tolerance);
  rt::HybridEngine engine(hs, model.scene.horizon, method);
  DrivelineRun r;
  r.status = engine.run(ns.x0, sample, [&](double t, const rt::HybridSample& s) {
    r.t.push_back(t);
    r.x.push_back(s.x);
    r.w.push_back(s.w);
    r.energy.push_back(s.energy);
    return true;
  }, [](const rt::HybridEvent&) {});
  return r;
}

// The largest gap between the states of two runs sampled alike (both must have run to the end).
double largest_state_gap(const DrivelineRun& a, const DrivelineRun& b) {
  EXPECT_TRUE(a.status.ok) << a.status.message;
  EXPECT_TRUE(b.status.ok) << b.status.message;
  EXPECT_EQ(a.t.size(), b.t.size());
  double gap = 0;
  for (std::size_t i = 0; i < std::min(a.t.size(), b.t.size()); ++i)
    gap = std::max(gap, (a.x[i] - b.x[i]).cwiseAbs().maxCoeff());
  return a.status.ok && b.status.ok ? gap : INFINITY;
}

// Stall: the turbine held, J_p omega' = tau - omega^2 / K0^2 runs up as
// omega = K0 sqrt(tau) tanh(t sqrt(tau) / (K0 J_p)) to the stall speed K0 sqrt(tau); the brake holds
// TR(0) omega^2 / K0^2.
TEST(Converter, StallRunsUpAsTheClosedForm) {
  const SpecializedScene model = pair_scene("stall", std::string(converter_table) + R"(
[inputs]
tau_p = "300*N*m"
[engagement]
H = "1"
[initial]
omega_p = "0*rad/s"
omega_t = "0*rad/s"
[simulation]
horizon = "1.5*s"
sample = "5*ms"
solver = "dopri5"
)");
  const DrivelineRun r = run_driveline(model, model.main, 1e-12, 5e-3);
  ASSERT_TRUE(r.status.ok) << r.status.message;
  const double K0 = 140 * per_rpm, tau = 300, J = 0.2;
  const std::vector<Variable> states = state_variables(model.main);
  // The rigid model keeps omega_p and omega_t (t and l turn as one): w = [tau_p; Tpump, Tturbine; T_H].
  ASSERT_EQ(states.size(), 2u);
  double worst = 0, worst_torque = 0;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    const double expected = K0 * std::sqrt(tau) * std::tanh(r.t[i] * std::sqrt(tau) / (K0 * J));
    worst = std::max(worst, std::abs(r.x[i](0) - expected));
    // The held turbine's torque is the brake's: its stuck torque on t balances TR(0) T_p.
    const double turbine = 2.0 * r.x[i](0) * r.x[i](0) / (K0 * K0);
    worst_torque = std::max(worst_torque, std::abs(r.w[i](3) - turbine));
  }
  ::testing::Test::RecordProperty("speed_error", fmt::format("{:.3g}", worst));
  ::testing::Test::RecordProperty("held_torque_error", fmt::format("{:.3g}", worst_torque));
  // dopri5 at 1e-12 on a smooth run-up: 1e-9 of the stall speed (2425 rpm = 254 rad/s).
  EXPECT_LT(worst, 2.5e-7);
  EXPECT_LT(worst_torque, 1e-8 * 600);
  EXPECT_NEAR(r.x.back()(0), K0 * std::sqrt(tau), 1e-3);  // 1.5 s is 7 time constants: tanh = 1 - 2e-6
}

// A locked-up converter passes no torque of its own (SR = 1): the run is the run of a plain clutch.
TEST(Converter, LockedUpIsAClutch) {
  const std::string common = R"(
[inputs]
tau_p = { ramp = "200*N*m/s" }
[loads]
l = { linear = "0.5*N*m*s/rad" }
[initial]
omega_p = "0*rad/s"
omega_t = "0*rad/s"
[simulation]
horizon = "1*s"
sample = "10*ms"
solver = "dopri5"
)";
  const SpecializedScene locked = pair_scene("locked", std::string(converter_table) +
                                                           "lockup = { capacity = \"800*N*m\" }\n[engagement]\nlockup = \"1\"\n" + common);
  const SpecializedScene clutch = pair_scene("clutch", "[engagement]\nL = \"1\"\n" + common);
  const DrivelineRun a = run_driveline(locked, locked.main, 1e-11, 1e-2), b = run_driveline(clutch, clutch.main, 1e-11, 1e-2);
  // The stuck pair's slip is rounding (a few ulps of the speed), so is the converter's torque: speeds
  // agree to 1e-12 of the largest (100 rad/s at 1 s).
  const double gap = largest_state_gap(a, b);
  ::testing::Test::RecordProperty("state_gap", fmt::format("{:.3g}", gap));
  EXPECT_LT(gap, 1e-10);
  EXPECT_GT(a.x.back()(0), 50);
}

// An engine whose map is one constant torque is that torque as an input.
TEST(Engine, ConstantMapIsAnInputTorque) {
  auto scene = [&](const std::string& name, const std::string& torque, const std::string& input) {
    return pair_scene(name, "[engine]\ninertia = \"0.2*kg*m^2\"\nthrottle = 1\nmap_speeds = [1000]\nmap_throttles = [1]\n"
                            "map_torques = [[" + torque + "]]\n" +
                            "[converter]\nturbine = \"p\"\nspeed_ratio = [0, 0.5]\ncapacity_factor = [140, 160]\n"
                            "torque_ratio = [2.0, 1.4]\n" + input + R"(
[loads]
t = { linear = "0.5*N*m*s/rad" }
[engagement]
L = "1"
[initial]
omega_engine = "800*rpm"
omega_p = "0*rad/s"
omega_t = "0*rad/s"
[simulation]
horizon = "1*s"
sample = "10*ms"
solver = "dopri5"
)");
  };
  const SpecializedScene mapped = scene("mapped", "120", ""), input = scene("input", "0", "[inputs]\ntau_engine = \"120*N*m\"\n");
  const DrivelineRun a = run_driveline(mapped, mapped.main, 1e-11, 1e-2), b = run_driveline(input, input.main, 1e-11, 1e-2);
  // The same equations by two paths: the adaptive steps may differ in rounding only (1e-11 of 300 rad/s).
  const double gap = largest_state_gap(a, b);
  ::testing::Test::RecordProperty("state_gap", fmt::format("{:.3g}", gap));
  EXPECT_LT(gap, 1e-8);
}

// The shipped launch: the engine's work (integrated by the run) equals the change of the stored
// energy plus the converter's loss, the clutches' heat, the drag's work (the run's), and the road's
// constant part and the bearings' damping (Simpson here, on a sample of 0.1 ms).
TEST(Converter, LaunchEnergyBalanceCloses) {
  const SpecializedScene model = specialize(parse_scene(source_path("models/scenes/zf6hp26_launch.toml")));
  const SpecializedSystem& sys = model.main;
  const NumericSystem ns = numeric_system(model, sys);
  const rt::HybridSystem hs = hybrid_system(model, sys, ns);
  const double h = 1e-4;
  const DrivelineRun r = run_driveline(model, sys, 1e-12, h);
  ASSERT_TRUE(r.status.ok) << r.status.message;
  const auto nu = static_cast<Eigen::Index>(hs.inputs.size());
  const auto ne = static_cast<Eigen::Index>(hs.elements.size());
  const Eigen::MatrixXd A = ns.L * ns.M;
  std::vector<double> p_in, p_damp;
  for (std::size_t i = 0; i < r.t.size(); ++i) {
    p_in.push_back((ns.L * r.x[i]).dot(hs.N.leftCols(nu) * r.w[i].head(nu)));
    p_damp.push_back(-r.x[i].dot(A * r.x[i]));
  }
  ASSERT_EQ((r.t.size() - 1) % 2, 0u);
  double road = 0, damping = 0;
  for (std::size_t i = 0; i + 2 < r.t.size(); i += 2) {
    road += h / 3 * (p_in[i] + 4 * p_in[i + 1] + p_in[i + 2]);
    damping += h / 3 * (p_damp[i] + 4 * p_damp[i + 1] + p_damp[i + 2]);
  }
  const Eigen::VectorXd& e = r.energy.back();
  ASSERT_EQ(e.size(), ne + static_cast<Eigen::Index>(hs.state_torques.size()));
  const double heat = e.head(ne).sum();
  double engine = 0, converter = 0, drag = 0;
  for (std::size_t q = 0; q < hs.state_torques.size(); ++q) {
    const double work = e(ne + static_cast<Eigen::Index>(q));
    switch (hs.state_torques[q].kind) {
      case rt::StateTorqueKind::engine: engine += work; break;
      case rt::StateTorqueKind::quadratic: drag -= work; break;
      default: converter -= work;
    }
  }
  const double stored0 = 0.5 * r.x.front().dot(ns.L * r.x.front()), stored = 0.5 * r.x.back().dot(ns.L * r.x.back());
  const double residual = engine + road - (stored - stored0 + converter + heat + damping + drag);
  ::testing::Test::RecordProperty("relative_residual", fmt::format("{:.3g}", residual / engine));
  ::testing::Test::RecordProperty("engine_work_J", fmt::format("{:.6g}", engine));
  ::testing::Test::RecordProperty("converter_loss_J", fmt::format("{:.6g}", converter));
  ::testing::Test::RecordProperty("clutch_heat_J", fmt::format("{:.6g}", heat));
  EXPECT_GT(engine, 1e5);
  EXPECT_GT(converter, 1e3);
  EXPECT_GT(heat, 100);
  EXPECT_GT(drag, 0);
  // The run's quadratures are of its dense output at 1e-12; Simpson's on the road's and bearings'
  // power (a few kJ, smooth between events) errs by O(h^2) at the events' kinks: 1e-9 of the engine's work.
  EXPECT_NEAR(engine + road, stored - stored0 + converter + heat + damping + drag, 1e-9 * engine)
      << "engine " << engine << ", road " << road << ", stored " << stored - stored0 << ", converter " << converter
      << ", heat " << heat << ", bearings " << damping << ", drag " << drag;
}

// The launch's converter follows its tables through the coupling point: at every sample before the
// lock-up, the pump torque is omega_p^2 / K(SR)^2 and the turbine's TR(SR) times it, K and TR
// interpolated here from the scene file's numbers, and the run crosses SR = 0.85, where TR is 1.
TEST(Converter, LaunchFollowsItsTablesThroughTheCouplingPoint) {
  const SpecializedScene model = specialize(parse_scene(source_path("models/scenes/zf6hp26_launch.toml")));
  const NumericSystem ns = numeric_system(model, model.main);
  const DrivelineRun r = run_driveline(model, model.main, 1e-10, 2e-3);
  ASSERT_TRUE(r.status.ok) << r.status.message;
  const std::vector<double> sr{0, 0.1, 0.2, 0.3, 0.4, 0.5, 0.6, 0.7, 0.8, 0.85, 0.9};
  const std::vector<double> K{140, 141, 142, 144, 147, 151, 158, 170, 194, 218, 270};
  const std::vector<double> TR{2.0, 1.88, 1.76, 1.64, 1.52, 1.40, 1.28, 1.16, 1.04, 1.0, 1.0};
  auto at = [&](const std::vector<double>& y, double x) {
    std::size_t i = 0;
    while (i + 2 < sr.size() && x > sr[i + 1]) ++i;
    return y[i] + (y[i + 1] - y[i]) * (x - sr[i]) / (sr[i + 1] - sr[i]);
  };
  // Inputs w = [TL_vehicle; Tengine, Tpump, Tturbine; ...]; speeds of the engine, pump and turbine.
  const Eigen::Index pump = 2, turbine = 3;
  double highest = 0;
  int checked = 0;
  for (std::size_t i = 0; i < r.t.size() && r.t[i] < 3.0; ++i) {
    const double wp = ns.driveline_speeds.row(1).dot(r.x[i]), wt = ns.driveline_speeds.row(2).dot(r.x[i]);
    const double s = wt / wp;
    if (!(s >= 0 && s <= 0.9)) continue;
    highest = std::max(highest, s);
    const double k = at(K, s) * per_rpm, tp = wp * wp / (k * k);
    // The run's interpolation and this one's differ in rounding only.
    EXPECT_NEAR(-r.w[i](pump), tp, 1e-12 * tp) << "t " << r.t[i] << ", SR " << s;
    EXPECT_NEAR(r.w[i](turbine), at(TR, s) * tp, 1e-12 * tp) << "t " << r.t[i] << ", SR " << s;
    ++checked;
  }
  EXPECT_GT(highest, 0.85);  // past the coupling point before the 1-2 shift
  EXPECT_GT(checked, 1000);
}

}  // namespace
}  // namespace pogear::test
