// Without any damping the elastic model conserves energy: exact stepping keeps it to rounding
// over 1e4 periods of the fastest mode, and TR-BDF2 loses it at the rate its theory gives.
#include <fmt/format.h>

#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

// The one-stage gear, no friction, no mesh damping, no input, spinning and twisted at t = 0.
SpecializedScene undamped(double horizon, double sample, double tolerance) {
  std::string text = with_effects(scene_text("paper_one_stage"), "\"mesh_compliance\", \"mesh_forces\"");
  text = with_line(text, "compare_rigid = true", "compare_rigid = false");
  text = with_line(text, "tau_c = { constant = \"100*Nm\" }", "");
  text = with_line(text, "omega_c = \"0*rpm\"", "omega_c = \"100*rpm\"\nomega_s = \"-50*rpm\"\nF_ps = \"200*N\"");
  text = with_line(text, "horizon = ", "horizon = " + fmt::format("{}", horizon) + " #");
  text = with_line(text, "sample = ", "sample = " + fmt::format("{}", sample) + " #");
  text = with_line(text, "tolerance = 1e-9", "tolerance = " + fmt::format("{}", tolerance) + "\nmax_steps = 100000000");
  return scene_model(text);
}

std::vector<double> energies(const SpecializedScene& m, const Trajectory& tr) {
  const Derivation& d = m.derivation;
  const GiNaC::exmap v = d.values;
  const Eigen::MatrixXd J = evaluate_matrix(d.elastic.J, v), K = evaluate_matrix(d.elastic.K, v);
  const Eigen::Index n = J.rows();
  std::vector<double> e;
  for (const auto& x : tr.x)
    e.push_back(0.5 * x.head(n).dot(J * x.head(n)) + 0.5 * x.tail(K.rows()).dot(K.inverse() * x.tail(K.rows())));
  return e;
}

double fastest_period(const SpecializedScene& m) { return 2 * 3.141592653589793 / system_diagnostics(m, m.main).fastest_rate; }

TEST(Undamped, ExactSteppingConservesEnergyOver1e4Periods) {
  const double period = fastest_period(undamped(1, 1e-3, 1e-8));
  const SpecializedScene m = undamped(1e4 * period, period / 8, 1e-8);
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::exact));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  ASSERT_GE(tr.t.back(), 1e4 * period * (1 - 1e-12));
  const auto e = energies(m, tr);
  double drift = 0;
  for (double x : e) drift = std::max(drift, std::abs(x - e.front()) / e.front());
  // exp(M h) preserves energy exactly; each of the 8e4 steps (a 10x10 matrix-vector product)
  // adds rounding of ~n eps = 1e-15 relative, and such errors add up at most linearly:
  // 8e4 * 1e-15 = 8e-11. Measured 7e-14 (5.2e-11 before exp.hpp squared e^A - I instead of e^A).
  RecordProperty("energy_drift", fmt::format("{}", drift));
  EXPECT_LT(drift, 2e-10);
}

TEST(Undamped, TrBdf2LosesEnergyAtItsTheoreticalRate) {
  const double period = fastest_period(undamped(1, 1e-3, 1e-8));
  const double tol = 1e-4;
  const SpecializedScene m = undamped(1e4 * period, period / 8, tol);
  const Trajectory tr = interpret_trajectory(m, m.main, run_settings(m, rt::Solver::implicit));
  ASSERT_TRUE(tr.status.ok) << tr.status.message;
  const auto e = energies(m, tr);
  const double loss = (e.front() - e.back()) / e.front();
  // L-stable methods dissipate: per step TR-BDF2 damps a mode with w h = y by ~c y^4, and
  // its controller keeps the local error c3 y^3 ~ tol, so per period (2 pi / y steps) the
  // energy falls by ~tol, independent of the step. Over 1e4 periods: 1e4 * tol = 1 at most;
  // it must lose energy (never gain it) and at most that. Measured 0.124, i.e. 0.12 tol per
  // period; more than 1e-3 shows the dissipation is there, as an L-stable method must have.
  EXPECT_GT(loss, 1e-3);
  EXPECT_LT(loss, 1e4 * tol);
  for (std::size_t i = 1; i < e.size(); ++i) ASSERT_LE(e[i], e[i - 1] * (1 + 1e-9)) << "energy grew at sample " << i;
  RecordProperty("energy_loss", std::to_string(loss));
}

}  // namespace
}  // namespace pogear::test
