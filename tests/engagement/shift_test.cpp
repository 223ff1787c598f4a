// The shipped shift scenes simulated with brakes and clutches: the power balance along every shift,
// the elastic and rigid models agreeing once a mode's transient has decayed, and a clutch-to-clutch
// shift's sequence of events. `pogear simulate` of a shift, compiled against interpreted and in rpm:
// tests/commands/shift_test.cpp.
#include <algorithm>
#include <cmath>
#include <tuple>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "pogear/hybrid.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

SpecializedScene shipped(const std::string& name) {
  return specialize(parse_scene(source_path("models/scenes/" + name + ".toml")));
}

struct Recorded {
  std::vector<double> t;
  std::vector<Eigen::VectorXd> x, w, energy;
  std::vector<std::uint32_t> mode;
  std::vector<rt::HybridEvent> events;
  rt::RunStatus status;
  long rhs_evals = 0;
};

Recorded run(const rt::HybridSystem& hs, const Eigen::VectorXd& x0, double horizon, double sample,
             rt::HybridMethod method = {}) {
  Recorded r;
  rt::HybridEngine engine(hs, horizon, method);
  r.status = engine.run(
      x0, sample,
      [&](double t, const rt::HybridSample& s) {
        r.t.push_back(t);
        r.x.push_back(s.x);
        r.w.push_back(s.w);
        r.energy.push_back(s.energy);
        r.mode.push_back(s.mode);
        return true;
      },
      [&](const rt::HybridEvent& e) { r.events.push_back(e); });
  r.rhs_evals = engine.rhs_evals();
  return r;
}

// The power balance of L x' = A x + B w (A = L M, B = L N): the stored energy x^T L x / 2 changes
// by the inputs' work x^T L N_u u, less the damping losses -x^T A x, less the friction losses
// T_k s_k, which the engine integrates exactly as E_k. The first two are integrated here by
// Simpson's rule on a sample of 20 us. Every shipped scene with brakes or clutches, with the exact
// method (E_k from the slip integrals) and dopri5 (E_k by quadrature on its dense output).
TEST(Shift, EnergyBalanceHoldsAlongEveryShippedShift) {
  rt::HybridMethod dopri5{rt::Solver::dopri5, {}};
  rt::set_tolerance(dopri5.options, 1e-10);
  for (const std::string name : {"gearshift_planetary", "simpson_1_2_upshift", "power_split_ev_launch"})
  for (const rt::HybridMethod& method : {rt::HybridMethod{}, dopri5}) {
    const SpecializedScene model = shipped(name);
    for (const SpecializedSystem* sys : {&model.main, &*model.rigid}) {
      SCOPED_TRACE(name + " " + std::string(kind_name(sys->kind)) + " " + std::string(rt::solver_name(method.solver)));
      const NumericSystem ns = numeric_system(model, *sys);
      const rt::HybridSystem hs = hybrid_system(model, *sys, ns);
      const double h = 2e-5;
      const Recorded r = run(hs, ns.x0, model.scene.horizon, h, method);
      ASSERT_TRUE(r.status.ok) << r.status.message;
      ASSERT_FALSE(r.events.empty());
      const auto nu = static_cast<Eigen::Index>(hs.inputs.size());
      const Eigen::MatrixXd A = ns.L * ns.M;
      std::vector<double> p_in, p_damp;
      for (std::size_t i = 0; i < r.t.size(); ++i) {
        const Eigen::VectorXd Lx = ns.L * r.x[i];
        p_in.push_back(Lx.dot(ns.N.leftCols(nu) * r.w[i].head(nu)));
        p_damp.push_back(-r.x[i].dot(A * r.x[i]));
      }
      // Simpson's rule over pairs of samples (the sample count is even: horizon / h).
      ASSERT_EQ((r.t.size() - 1) % 2, 0u);
      double work = 0, damping = 0, largest = 0;
      for (std::size_t i = 0; i + 2 < r.t.size(); i += 2) {
        work += h / 3 * (p_in[i] + 4 * p_in[i + 1] + p_in[i + 2]);
        damping += h / 3 * (p_damp[i] + 4 * p_damp[i + 1] + p_damp[i + 2]);
        largest = std::max(largest, std::abs(work));
      }
      const double stored0 = 0.5 * r.x.front().dot(ns.L * r.x.front());
      const double stored = 0.5 * r.x.back().dot(ns.L * r.x.back());
      const double friction = r.energy.back().sum();
      // The one-way brake of the power split holds, then freewheels: it dissipates nothing.
      if (name == "power_split_ev_launch") EXPECT_EQ(friction, 0);
      else EXPECT_GT(friction, 0);
      EXPECT_GE(damping, 0);
      // Simpson's error is (h w)^4 / 180 of the power's oscillation at w, 4e-8 at the elastic
      // models' highest mesh mode (about 3000 rad/s), plus O(h^2) at the kinks events put in the
      // power (its slope jumps when a friction torque does); 1e-6 of the input work covers both,
      // while one lost friction or damping term would break the balance by percents.
      EXPECT_NEAR(stored - stored0, work - damping - friction, 1e-6 * largest)
          << "work " << work << ", damping " << damping << ", friction " << friction << ", stored " << stored;
    }
  }
}

// The three methods that run brakes and clutches find the same events along every shipped scene:
// the same sequence, at times that agree to their accuracy, and the same end state. Elastic
// meshes ring when an element lets go, and the ringing can bring a slip back to zero several times
// within a millisecond (the Simpson upshift's B2 sticks and slips twice more as it releases): an
// engine that only looked at the ends of its sample steps would miss those events, which the
// adaptive methods, stepping through the ringing, find.
// Every sample agrees too, in mode and torques. A sample at the instant of an event reports the state
// after it with every method, as a signal's value at its step is the one after it: the shipped
// shifts command their elements on the sample grid (gearshift_planetary at 2 s), so the events their
// commands cause fall on samples exactly.
TEST(Shift, EveryMethodLocatesTheSameEvents) {
  rt::HybridMethod dopri5{rt::Solver::dopri5, {}}, implicit{rt::Solver::implicit, {}};
  rt::set_tolerance(dopri5.options, 1e-11);
  rt::set_tolerance(implicit.options, 1e-9);
  for (const std::string name : {"gearshift_planetary", "simpson_1_2_upshift", "power_split_ev_launch"}) {
    const SpecializedScene model = shipped(name);
    for (const SpecializedSystem* sys : {&model.main, &*model.rigid}) {
      const NumericSystem ns = numeric_system(model, *sys);
      const rt::HybridSystem hs = hybrid_system(model, *sys, ns);
      const Recorded exact = run(hs, ns.x0, model.scene.horizon, 1e-3);
      ASSERT_TRUE(exact.status.ok) << exact.status.message;
      int on_sample = 0;
      for (const rt::HybridEvent& e : exact.events) on_sample += std::count(exact.t.begin(), exact.t.end(), e.t) > 0;
      if (name == "gearshift_planetary") {
        EXPECT_GE(on_sample, 2);  // the brake's release, the clutch's apply
      }
      // Event times: dopri5 at 1e-11 locates them within about 1e-11 s of the exact trajectory's
      // (measured: 2.5e-11 s at 1e-8, the elastic gear shift's lock); TR-BDF2, of order 2, within about 1e-7 s at 1e-9. The end
      // states within the same orders, relative to the largest state. The torques at every sample
      // (inputs, slipping elements', stuck ones' recovered from the state) within torque_tol of
      // their largest value: measured, dopri5 within 1e-9; TR-BDF2 within 5.4e-5 on the elastic
      // models (order 2: its global error is far above its local tolerance while it steps through
      // the meshes' ringing) and 7e-11 on the rigid ones. A sample in the wrong mode is off by the
      // whole torque of an element.
      for (const auto& [method, time_tol, state_tol, torque_tol] :
           {std::tuple{dopri5, 1e-9, 1e-8, 1e-8}, std::tuple{implicit, 2e-6, 1e-5, 2e-4}}) {
        SCOPED_TRACE(name + " " + std::string(kind_name(sys->kind)) + " " + std::string(rt::solver_name(method.solver)));
        const Recorded r = run(hs, ns.x0, model.scene.horizon, 1e-3, method);
        ASSERT_TRUE(r.status.ok) << r.status.message;
        ASSERT_EQ(r.events.size(), exact.events.size());
        for (std::size_t i = 0; i < r.events.size(); ++i) {
          EXPECT_EQ(r.events[i].element, exact.events[i].element) << i;
          EXPECT_EQ(r.events[i].from, exact.events[i].from) << i;
          EXPECT_EQ(r.events[i].to, exact.events[i].to) << i;
          EXPECT_NEAR(r.events[i].t, exact.events[i].t, time_tol) << i;
        }
        const double scale = exact.x.back().cwiseAbs().maxCoeff();
        EXPECT_LE((r.x.back() - exact.x.back()).cwiseAbs().maxCoeff(), state_tol * scale);
        EXPECT_EQ(r.mode.back(), exact.mode.back());
        // Exact stepping evaluates no right-hand side; the adaptive methods count theirs.
        EXPECT_EQ(exact.rhs_evals, 0);
        EXPECT_GT(r.rhs_evals, static_cast<long>(r.events.size()));
        ASSERT_EQ(r.t.size(), exact.t.size());
        double torque_scale = 0;
        for (const Eigen::VectorXd& w : exact.w) torque_scale = std::max(torque_scale, w.cwiseAbs().maxCoeff());
        for (std::size_t i = 0; i < r.t.size(); ++i) {
          // A sample within the accuracy of a located event may fall on either side of it.
          bool near_located = false;
          for (const rt::HybridEvent& e : exact.events)
            near_located |= e.t != r.t[i] && std::abs(e.t - r.t[i]) <= 10 * time_tol;
          if (near_located) continue;
          ASSERT_EQ(r.mode[i], exact.mode[i]) << "t = " << r.t[i];
          EXPECT_LE((r.w[i] - exact.w[i]).cwiseAbs().maxCoeff(), torque_tol * torque_scale) << "t = " << r.t[i];
        }
      }
    }
  }
}

// After each transient the elastic gear moves as the rigid one: the same events in the same order,
// and in the last mode (clutch locked, direct drive) the same speeds and clutch torque.
TEST(Shift, ElasticAndRigidModelsAgreeAfterTheTransient) {
  const SpecializedScene model = shipped("gearshift_planetary");
  const NumericSystem elastic = numeric_system(model, model.main), rigid = numeric_system(model, *model.rigid);
  const Recorded e = run(hybrid_system(model, model.main, elastic), elastic.x0, model.scene.horizon, 1e-3);
  const Recorded r = run(hybrid_system(model, *model.rigid, rigid), rigid.x0, model.scene.horizon, 1e-3);
  ASSERT_TRUE(e.status.ok) << e.status.message;
  ASSERT_TRUE(r.status.ok) << r.status.message;
  ASSERT_EQ(e.events.size(), r.events.size());
  for (std::size_t i = 0; i < e.events.size(); ++i) {
    EXPECT_EQ(e.events[i].element, r.events[i].element) << i;
    EXPECT_EQ(e.events[i].to, r.events[i].to) << i;
    // The meshes' compliance delays the elastic gear by its transient: a few milliseconds.
    EXPECT_NEAR(e.events[i].t, r.events[i].t, 5e-3) << i;
  }
  // Rigid states are the kept velocities (s, c); the elastic ones every body's velocity, then the
  // mesh forces: omega_s and omega_c are the first two of both (bodies in file order: s, c, p, r).
  const std::size_t last = e.t.size() - 1;
  ASSERT_EQ(e.mode[last], 2u);  // the clutch (element 1) stuck, the brake open
  ASSERT_EQ(r.mode[last], 2u);
  // After the lock both models turn with the same acceleration. The speeds keep the small offset
  // the meshes' compliance made during the 48 ms of slip (measured: 3.6e-5 rad/s, 5e-6 of the
  // speeds), and the elastic clutch torque converges to the rigid one as the set's vibration decays
  // (6e-6 N m apart at 4 s). A wrong mode (a sign, a lost torque) would be off by its whole size.
  for (int j = 0; j < 2; ++j) EXPECT_NEAR(e.x[last](j), r.x[last](j), 1e-4 * std::abs(r.x[last](j))) << j;
  const Eigen::Index clutch = e.w[last].size() - 1;
  EXPECT_NEAR(e.w[last](clutch), r.w[last](r.w[last].size() - 1), 1e-4 * std::abs(r.w[last](clutch)));
  // The same acceleration: the offset changes by less than the vibration left over the last 0.5 s.
  const std::size_t half = last - 500;
  for (int j = 0; j < 2; ++j)
    EXPECT_NEAR(e.x[last](j) - r.x[last](j), e.x[half](j) - r.x[half](j), 1e-6 * std::abs(r.x[last](j))) << j;
}

// The Simpson 1-2 upshift hands the load from B2 to B1 with C1 applied throughout: B2 releases
// first (breaking away as its command falls), B1 slips and then locks, and the gear ends in 2nd,
// whose ratio the output and input speeds then keep.
TEST(Shift, SimpsonUpshiftIsAClutchToClutchShift) {
  const SpecializedScene model = shipped("simpson_1_2_upshift");
  const NumericSystem ns = numeric_system(model, *model.rigid);
  const Recorded r = run(hybrid_system(model, *model.rigid, ns), ns.x0, model.scene.horizon, 1e-3);
  ASSERT_TRUE(r.status.ok) << r.status.message;
  // Elements in the model's order: C1 (0), B1 (2), B2 (3); the scene engages all three.
  ASSERT_EQ(model.friction.size(), 3u);
  EXPECT_EQ(model.friction[0].name, "C1");
  EXPECT_EQ(model.friction[1].name, "B1");
  EXPECT_EQ(model.friction[2].name, "B2");
  EXPECT_EQ(r.mode.front(), 0b101u);  // 1st gear: C1 and B2 stuck
  EXPECT_EQ(r.mode.back(), 0b011u);   // 2nd gear: C1 and B1 stuck
  double b2_released = -1, b1_locked = -1;
  for (const rt::HybridEvent& ev : r.events) {
    if (ev.element == 2 && ev.from == rt::ElementState::stuck && b2_released < 0) b2_released = ev.t;
    if (ev.element == 1 && ev.to == rt::ElementState::stuck) b1_locked = ev.t;
    EXPECT_FALSE(ev.element == 0) << "C1 changed state at " << ev.t;
  }
  EXPECT_GT(b2_released, 1.0);
  EXPECT_GT(b1_locked, b2_released);
  EXPECT_LT(b1_locked, 2.0);
  // Rigid states: the kept velocities i, o, s. In 2nd gear (sun held) omega_o / omega_i is the
  // ratio pogear ratios prints for C1+B1: 12/17 with 30/21/72 teeth.
  const Eigen::VectorXd& x = r.x.back();
  EXPECT_NEAR(x(1) / x(0), 12.0 / 17.0, 1e-12);
  EXPECT_NEAR(x(2), 0, 1e-12 * std::abs(x(0)));
}

// A carrier of 1e-30 kg m^2 makes the gear-shift scene's stuck torques change within femtoseconds:
// exact stepping then checks for events every few 1e-7 s, millions of steps a second of the run.
// max_steps bounds them (the run took minutes, with no bound): it stops with the reason, up front
// where the rest of a sample period alone needs more steps than are left.
TEST(Shift, ExactSteppingOfAStiffModeStopsAtMaxSteps) {
  std::string text = read_text(source_path("models/scenes/gearshift_planetary.toml"));
  text.replace(text.find("[inputs]"), 8, "[parameters]\nJ_c = \"1e-30*kg*m^2\"\n\n[inputs]");
  const SpecializedScene model = specialize(parse_scene_text(text, source_path("models/scenes/gearshift_planetary.toml")));
  const NumericSystem ns = numeric_system(model, model.main);
  for (const long max_steps : {1000L, 20L}) {
    SCOPED_TRACE(max_steps);
    rt::HybridMethod method;
    method.options.max_steps = max_steps;
    const Recorded r = run(hybrid_system(model, model.main, ns), ns.x0, 0.1, 1e-3, method);
    ASSERT_FALSE(r.status.ok);
    EXPECT_NE(r.status.message.find("max_steps = " + std::to_string(max_steps)), std::string::npos) << r.status.message;
    EXPECT_LT(r.t.back(), 0.1);
  }
  // Samples 50 ms apart: the first period alone needs thousands of event-check steps.
  rt::HybridMethod method;
  method.options.max_steps = 1000;
  const Recorded r = run(hybrid_system(model, model.main, ns), ns.x0, 0.1, 0.05, method);
  ASSERT_FALSE(r.status.ok);
  EXPECT_NE(r.status.message.find("event-check step"), std::string::npos) << r.status.message;
  EXPECT_NE(r.status.message.find("beyond max_steps = 1000"), std::string::npos) << r.status.message;
}

}  // namespace
}  // namespace pogear::test
