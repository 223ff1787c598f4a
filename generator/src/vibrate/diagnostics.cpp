// Eigenvalues of M give the time scales; a mode whose decay rate is below rounding of the
// fastest one counts as not decaying (a free rotation without friction, an undamped mesh).
#include "vibrate/diagnostics.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <numbers>

#include <fmt/format.h>

#include "common/exact_algebra.hpp"
#include "common/matrix_balancing.hpp"
#include "derive/engagement.hpp"
#include "read/slip_control.hpp"
#include "specialize/parameter_folding.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"
#include "vibrate/vibration_modes.hpp"
#include "pogear/stability_limit.hpp"

namespace pogear {
namespace {

double condition(const Eigen::MatrixXd& A) {
  if (A.size() == 0) return 1;
  Eigen::JacobiSVD<Eigen::MatrixXd> svd(A);
  const auto& s = svd.singularValues();
  return s(s.size() - 1) > 0 ? s(0) / s(s.size() - 1) : std::numeric_limits<double>::infinity();
}

std::string number(double v) { return std::isfinite(v) ? fmt::format("{:.4g}", v) : "inf"; }

}  // namespace

Diagnostics diagnose(const Eigen::MatrixXd& M, const Eigen::MatrixXd& L1, const Eigen::MatrixXd& R, double sample,
                     const InputExcitation& excitation) {
  Diagnostics d;
  // Balanced first (exact, the same eigenvalues): unbalanced, the mesh-force rows of a very stiff
  // gear ruled the rounding, and modes of a passive gear came out growing.
  const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(balanced(M), false).eigenvalues();
  d.fastest_rate = lambda.cwiseAbs().maxCoeff();
  d.fastest_time_constant = d.fastest_rate > 0 ? 1 / d.fastest_rate : std::numeric_limits<double>::infinity();
  double slowest_decay = std::numeric_limits<double>::infinity();
  // Rounding in the eigenvalues of M is ~1e-13 of its largest one; below that a decay rate is noise.
  const double floor = 1e-11 * d.fastest_rate;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    const double decay = -lambda(i).real();
    if (std::abs(decay) <= floor) {
      ++d.undecaying_modes;
      continue;
    }
    if (decay < 0) {
      ++d.growing_modes;
      d.fastest_growth_rate = std::max(d.fastest_growth_rate, -decay);
      continue;
    }
    slowest_decay = std::min(slowest_decay, decay);
  }
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    if (!(std::abs(lambda(i).imag()) > floor)) continue;
    const double hz = std::abs(lambda(i).imag()) / (2 * std::numbers::pi);
    d.fastest_oscillation_hz = std::max(d.fastest_oscillation_hz, hz);
    // Below 1 % of the inputs' own effect, an oscillation cannot make a sampled peak read 1 % low.
    if (excitation.of(std::abs(lambda(i))) >= 0.01) d.excited_oscillation_hz = std::max(d.excited_oscillation_hz, hz);
  }
  d.sample = sample;
  if (sample > 0 && d.excited_oscillation_hz > 0) {
    const double cycles = d.excited_oscillation_hz * sample;  // per sample
    d.sampled_peak_shortfall = cycles >= 0.5 ? 1.0 : 1 - std::cos(std::numbers::pi * cycles);
  }
  if (std::isfinite(slowest_decay) && slowest_decay > 0) {
    d.slowest_time_constant = 1 / slowest_decay;
    // The fastest time scale over the slowest time constant, |lambda|max / min|Re lambda|: mesh
    // modes are lightly damped oscillations, and it is their frequency, not their decay rate,
    // that bounds an explicit method's step against the time the scene must cover.
    d.stiffness_ratio = d.fastest_rate / slowest_decay;
  }
  d.cond_L1 = condition(L1);
  const Eigen::MatrixXd RRt = R * R.transpose();
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(RRt);
  qr.setThreshold(1e-9);
  if (qr.rank() == RRt.rows()) d.cond_RRt = condition(RRt);
  d.rk4_max_step = rt::rk4_stability_limit(M);
  d.suggested_solver = "exact";
  // An explicit method's step is bounded by the fastest mode, |lambda| h < ~3, whether that mode
  // decays or not; the stiffness ratio only sees decaying modes, so an undamped gear with 1e-29 s
  // mesh modes had ratio 1 and was called not stiff. Stability alone then costs sample |lambda|max
  // steps per sample: above 1e3, the steps are set by a mode the output does not resolve.
  const double steps_per_sample = sample * d.fastest_rate;
  std::string why;
  if (d.stiffness_ratio > 1e3) {
    why = fmt::format("stiffness ratio {}", number(d.stiffness_ratio));
  } else if (steps_per_sample > 1e3) {
    why = fmt::format("the fastest time scale {} s is {} times below the sample period and bounds an explicit "
                      "method's step, damped or not", number(d.fastest_time_constant), number(steps_per_sample));
  }
  d.adaptive_solver = why.empty() ? "dopri5" : "implicit";
  d.reason = fmt::format("the scene is linear: exact stepping is exact up to rounding for piecewise-linear inputs, or "
                         "refuses the step; among "
                         "adaptive methods use {}",
                         why.empty() ? "dopri5 (not stiff)" : fmt::format("implicit ({})", why));
  return d;
}

std::string diagnostics_text(const Diagnostics& d, const std::string& in) {
  std::string s;
  s += fmt::format("{}stiffness ratio {}; fastest time scale {} s; slowest time constant {} s{}\n", in,
                   number(d.stiffness_ratio), number(d.fastest_time_constant), number(d.slowest_time_constant),
                   d.undecaying_modes ? fmt::format("; {} mode(s) do not decay", d.undecaying_modes) : "");
  if (d.growing_modes)
    s += fmt::format("{}warning: {} mode(s) grow, the fastest by e in {} s: the scene is unstable (a speed controller "
                     "whose torque slows the speed it measures feeds back positively: check its body and speed_of)\n",
                     in, d.growing_modes, number(1 / d.fastest_growth_rate));
  s += fmt::format("{}cond(L1) = {}; cond(R R^T) = {}\n", in, number(d.cond_L1),
                   d.cond_RRt ? number(*d.cond_RRt) : "singular (redundant meshes)");
  s += fmt::format("{}largest stable rk4 step {} s; suggested solver: {} ({})\n", in, number(d.rk4_max_step),
                   d.suggested_solver, d.reason);
  // Above 1 %: the output would show the scene's fastest vibration visibly lower than it is.
  if (d.sampled_peak_shortfall > 0.01) {
    const double f = d.excited_oscillation_hz;
    s += fmt::format("{}warning: sample period {} s is {} of a period of the fastest oscillation{} ({} Hz): ", in,
                     number(d.sample), number(d.sample * f),
                     f < d.fastest_oscillation_hz ? " the inputs excite" : "", number(f));
    s += d.sampled_peak_shortfall >= 1
             ? "the samples do not resolve it (fewer than 2 per period), and its peaks can be missed entirely"
             : fmt::format("its sampled peaks can read up to {:.3g} % low", 100 * d.sampled_peak_shortfall);
    s += fmt::format("; for 1 % take sample <= {} s\n", number(std::acos(0.99) / (std::numbers::pi * f)));
  }
  if (d.lowest_natural_frequency_hz)
    s += fmt::format("{}lowest natural frequency {} Hz (undamped elastic model{}): the rigid model holds for inputs "
                     "well below it\n", in, fmt::format("{:.6g}", *d.lowest_natural_frequency_hz),
                     d.natural_frequency_of.empty() ? "" : ", " + d.natural_frequency_of);
  else if (!d.natural_frequency_note.empty())
    s += fmt::format("{}lowest natural frequency not computed: {}\n", in, d.natural_frequency_note);
  return s;
}

std::string diagnostics_json(const Diagnostics& d, const std::string& in) {
  auto num = [](double v) { return std::isfinite(v) ? fmt::format("{}", v) : std::string("null"); };
  std::string s = "{\n";
  s += fmt::format("{}  \"stiffness_ratio\": {},\n", in, num(d.stiffness_ratio));
  s += fmt::format("{}  \"fastest_time_scale\": {},\n", in, num(d.fastest_time_constant));
  s += fmt::format("{}  \"slowest_time_constant\": {},\n", in, num(d.slowest_time_constant));
  s += fmt::format("{}  \"undecaying_modes\": {},\n", in, d.undecaying_modes);
  s += fmt::format("{}  \"growing_modes\": {},\n", in, d.growing_modes);
  s += fmt::format("{}  \"cond_L1\": {},\n", in, num(d.cond_L1));
  s += fmt::format("{}  \"cond_RRt\": {},\n", in, d.cond_RRt ? num(*d.cond_RRt) : "null");
  s += fmt::format("{}  \"rk4_max_step\": {},\n", in, num(d.rk4_max_step));
  s += fmt::format("{}  \"fastest_oscillation_hz\": {},\n", in, num(d.fastest_oscillation_hz));
  s += fmt::format("{}  \"excited_oscillation_hz\": {},\n", in, num(d.excited_oscillation_hz));
  s += fmt::format("{}  \"suggested_solver\": \"{}\",\n", in, d.suggested_solver);
  s += fmt::format("{}  \"lowest_natural_frequency_hz\": {}\n", in,
                   d.lowest_natural_frequency_hz ? num(*d.lowest_natural_frequency_hz) : "null");
  return s + in + "}";
}

namespace {

// Sets the diagnostics' lowest natural frequency, or the reason it has none, and says of which gear:
// the derivation's engaged elements stuck, or, when a scene's brakes and clutches switch
// (`elements_switch`), all of them open.
void add_natural_frequency(Diagnostics& diagnostics, const Derivation& d, const GiNaC::exmap& values,
                           bool elements_switch) {
  try {
    diagnostics.lowest_natural_frequency_hz = lowest_natural_frequency(d, values);
  } catch (const std::domain_error& e) {
    diagnostics.natural_frequency_note = e.what();
  }
  if (!d.engaged.empty())
    diagnostics.natural_frequency_of = engaged_names(d.topology, d.engaged, ", ") + " engaged";
  else if (elements_switch)
    diagnostics.natural_frequency_of = "every brake and clutch open; each gear's with pogear modes --engaged";
}

}  // namespace

InputExcitation input_excitation(const SpecializedScene& model, const SpecializedSystem& sys) {
  const Scene& sc = model.scene;
  InputExcitation e{.jumps = !model.friction.empty() || !sys.limited_controllers.empty()};
  // A start as given is in equilibrium only at rest with no input acting: the mesh forces start at
  // the values given (zero by default), whatever the torques.
  bool acting = std::any_of(sys.states.begin(), sys.states.end(), [](const StatePort& x) { return x.initial != 0; });
  for (const rt::Signal& u : input_signals(sys)) {
    acting = acting || rt::value(u, 0.0) != 0;
    // Its jumps in (0, horizon], the slope changes at its corners, and its size U, max |u| over the run.
    double size = std::abs(rt::value(u, 0.0));
    std::vector<double> corners;
    if (const auto* step = std::get_if<rt::Step>(&u)) {
      size = std::max({size, std::abs(step->before), std::abs(step->after)});
      e.jumps = e.jumps || (step->time > 0 && step->time <= sc.horizon && step->before != step->after);
    } else if (const auto* ramp = std::get_if<rt::Ramp>(&u)) {
      size = std::max({size, std::abs(rt::value(u, sc.horizon))});
      if (ramp->start_time <= sc.horizon) corners.push_back(std::abs(ramp->slope));
    } else if (const auto* sine = std::get_if<rt::Sine>(&u)) {
      size = std::max(size, std::abs(sine->offset) + std::abs(sine->amplitude));
      if (sine->amplitude != 0) e.sine_rate = std::max(e.sine_rate, 2 * std::numbers::pi * std::abs(sine->frequency_hz));
    } else if (const auto* table = std::get_if<rt::Table>(&u)) {
      for (double v : table->v) size = std::max(size, std::abs(v));
      for (std::size_t i = 0; i < table->t.size() && table->t[i] <= sc.horizon; ++i) {
        if (i + 1 < table->t.size() && table->t[i + 1] == table->t[i] && table->v[i + 1] != table->v[i] &&
            table->t[i] > 0)
          e.jumps = true;
        const double before = table->t[i] > 0 ? rt::slope(u, std::nextafter(table->t[i], -1.0)) : 0.0;
        corners.push_back(std::abs(rt::slope(u, table->t[i]) - before));
      }
    } else if (const auto* grade = std::get_if<rt::GradeLoad>(&u)) {
      // At most hypot(sine, cosine); its rate turns at the angle's corners by that times theirs.
      size = std::hypot(grade->sine, grade->cosine);
      const rt::Table& angle = grade->angle;
      for (std::size_t i = 0; i < angle.t.size() && angle.t[i] <= sc.horizon; ++i) {
        const double before = angle.t[i] > 0 ? rt::table_slope(angle, std::nextafter(angle.t[i], -1.0)) : 0.0;
        corners.push_back(size * std::abs(rt::table_slope(angle, angle.t[i]) - before));
      }
    }
    if (size > 0)
      for (double c : corners) e.corner_rate = std::max(e.corner_rate, c / size);
  }
  e.jumps = e.jumps || (sc.start == Start::given && acting);
  return e;
}

Diagnostics derivation_diagnostics(const Derivation& d) {
  const GiNaC::exmap& at = d.values;
  const Eigen::MatrixXd L = evaluate_matrix(d.elastic.L, at);
  const Eigen::MatrixXd M = L.diagonal().cwiseInverse().asDiagonal() * evaluate_matrix(d.elastic.A, at);
  Diagnostics out = diagnose(M, evaluate_matrix(d.rigid_values.L1, {}), evaluate_matrix(d.elastic.R, at));
  add_natural_frequency(out, d, at, false);
  return out;
}

Diagnostics system_diagnostics(const SpecializedScene& model, const SpecializedSystem& sys) {
  const Derivation& d = model.derivation;
  const GiNaC::exmap& values = model.values.numbers;
  // The specialized system's own M, exact in the tunable parameters, at their values: the numbers
  // numeric_system computes by another formula (the tests compare them), without solving again.
  // L1 holds inertias and radii only, which the folding leaves at the model's values. Limited
  // controllers within their limits: a stiff controller's feedback is there, not in the open M.
  Diagnostics out = diagnose(state_matrix_within_limits(model, sys), evaluate_matrix(d.rigid_values.L1, {}),
                             evaluate_matrix(d.elastic.R, values), model.scene.sample, input_excitation(model, sys));
  // At the derivation's values (the scene's overrides), not the folded ones: a rigid scene folds
  // the stiffnesses away, yet the frequency below which it holds is that of its gear.
  add_natural_frequency(out, d, d.values, !model.friction.empty());
  // With brakes and clutches every adaptive step is held to the mode's event-check step (an eighth
  // of its fastest period) while an element is watched, which a stuck element with a command always
  // is: that step resolves the fastest mode already, so stiffness gains TR-BDF2 nothing, and its
  // order 2 costs accuracy. Measured on every shipped shift and a held-back one (bench/shift_solvers.py):
// for state errors of 1e-7 and below dopri5 is the faster on each.
  if (!model.friction.empty() && out.adaptive_solver != "dopri5") {
    out.adaptive_solver = "dopri5";
    const auto at = out.reason.find("among adaptive methods use ");
    if (at != std::string::npos)
      out.reason = out.reason.substr(0, at) +
                   "among adaptive methods use dopri5 (brakes and clutches hold its steps to the event-check step, "
                   "which resolves the fastest mode: on every shipped shift it reaches a state error of 1e-7 or "
                   "less sooner than implicit, docs/accuracy-vs-time.md)";
  }
  if (const auto refusal = rt::solver_refusal(rt::Solver::exact, {.nonlinear = sys.nonlinear})) {
    out.suggested_solver = out.adaptive_solver;
    out.reason = model.friction.empty()
                     ? fmt::format("the scene is nonlinear (a quadratic load, an engine or a converter), {}; its linear "
                                   "part is {}", refusal->reason, out.adaptive_solver == "implicit" ? "stiff" : "not stiff")
                     : fmt::format("the scene is nonlinear (a quadratic load, an engine or a converter), {}; with brakes "
                                   "and clutches dopri5, whose steps the event-check step holds (on every shipped shift "
                                   "it reaches a state error of 1e-7 or less sooner than implicit, "
                                   "docs/accuracy-vs-time.md)",
                                   refusal->reason);
  } else if (const auto curve = rt::solver_refusal(rt::Solver::exact, {.friction_curve = solver_traits(model).friction_curve})) {
    out.suggested_solver = "dopri5";
    out.reason = fmt::format("{}, {}; dopri5 integrates it, its steps held to the event-check step as on every shift",
                             curve->cause, curve->reason);
  } else if (const auto lag = rt::solver_refusal(rt::Solver::exact, {.actuator_lag = solver_traits(model).actuator_lag})) {
    out.suggested_solver = "dopri5";
    out.reason = fmt::format("{}, {}; dopri5 integrates it, its steps held to the event-check step as on every shift",
                             lag->cause, lag->reason);
  } else if (const auto slip = rt::solver_refusal(rt::Solver::exact, {.slip_control = has_slip_control(model.scene)})) {
    out.suggested_solver = "dopri5";
    out.reason = fmt::format("{}, {}; dopri5 integrates it on its dense output, its steps held to the event-check "
                             "step as on every shift", slip->cause, slip->reason);
  }
  return out;
}

}  // namespace pogear
