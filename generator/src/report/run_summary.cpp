// See run_summary.hpp.
#include "report/run_summary.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <variant>

#include <fmt/format.h>

#include "codegen/codegen_system.hpp"
#include "vibrate/diagnostics.hpp"
#include "specialize/initial_state.hpp"
#include "common/matrix_balancing.hpp"
#include "common/printer.hpp"
#include "specialize/reference_model.hpp"
#include "pogear/stability_limit.hpp"

namespace pogear {

// What the scene's loads and controllers make of the equations, for the summary.
std::string loads_and_controllers_note(const SpecializedScene& model) {
  const Scene& sc = model.scene;
  const Topology& t = model.derivation.topology;
  std::string s;
  for (const LoadSpec& l : sc.loads) {
    std::vector<std::string> parts;
    if (l.varying) parts.push_back("a grade's, varying in time (an input)");
    else if (l.constant != 0) parts.push_back("constant (an input)");
    if (l.linear != 0) parts.push_back("linear in speed (a damping: linear)");
    if (l.quadratic != 0) parts.push_back("quadratic in speed (nonlinear)");
    s += fmt::format("load on {}: {}\n", t.bodies[static_cast<std::size_t>(l.body)].name,
                     parts.empty() ? std::string("zero") : joined(parts));
  }
  for (const ControllerSpec& c : sc.controllers)
    if (c.supplies >= 0)
      s += fmt::format("slip controller {}: {} command of {} for its slip, its integral theta_{} a state; from {} until "
                       "{} locks, its torque from {} to {} N m (the capacity){}\n",
                       c.name, c.kp != 0 && c.ki != 0 ? "PI" : c.kp != 0 ? "P" : "I",
                       t.friction_elements[static_cast<std::size_t>(c.supplies)].name, c.name,
                       c.set_point_start ? std::string("its target's start") : fmt::format("t = {} s", c.start),
                       t.friction_elements[static_cast<std::size_t>(c.supplies)].name, c.torque_min, c.torque_max,
                       c.ki != 0 ? fmt::format(", the integral tracking a limit (time constant {:.6g} s)", c.tracking_time)
                                 : std::string());
    else
      s += fmt::format("controller {}: {} torque on {} for the speed of {}, its integral theta_{} a state{}\n", c.name,
                       c.kp != 0 && c.ki != 0 ? "PI" : c.kp != 0 ? "P" : "I",
                       t.bodies[static_cast<std::size_t>(c.body)].name, t.bodies[static_cast<std::size_t>(c.measured)].name,
                       c.name,
                       c.limited() ? fmt::format("; torque from {} to {} N m, events at the limits, where its integral "
                                                 "tracks the limit (time constant {} s)", c.torque_min, c.torque_max,
                                                 c.tracking_time)
                                   : std::string(" (linear)"));
  if (sc.engine)
    s += fmt::format("engine on its body 'engine': torque from its map ({} speeds x {} throttles, bilinear) at its "
                     "speed and the throttle (nonlinear)\n", sc.engine->map.speeds.size(), sc.engine->map.throttles.size());
  if (sc.converter)
    s += fmt::format("converter from {} to {}: pump torque (omega_p / K(SR))^2, turbine TR(SR) times it, coast as a "
                     "coupling (nonlinear); its loss E_converter [J] in the CSV\n",
                     t.bodies[static_cast<std::size_t>(sc.converter->pump)].name,
                     t.bodies[static_cast<std::size_t>(sc.converter->turbine)].name);
  if (model.main.nonlinear) {
    s += fmt::format("nonlinear ({}): integrated by {}{}; exact stepping needs a linear scene\n",
                     model.main.driveline.empty() ? "quadratic loads" : "engine, converter or quadratic loads",
                     rt::solver_name(sc.solver),
                     sc.solver == rt::Solver::rk4 ? fmt::format(", fixed step {} s", sc.step)
                                                  : fmt::format(", adaptive steps at tolerance {}", sc.tolerance));
    s += nonlinearity_cost_note(model);
  }
  return s;
}

namespace {

// The longest step at which dopri5 is stable on the mode lambda: |R(lambda h)| <= 1, R(z) = 1 + z +
// z^2/2 + z^3/6 + z^4/24 + z^5/120 + z^6/600 (its 5th-order solution's stability function), found by
// doubling h to the first unstable step and bisecting back.
double dopri5_stable_step(std::complex<double> lambda) {
  auto stable = [&](double h) {
    const std::complex<double> z = lambda * h;
    return std::abs(1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6 + z * (1.0 / 24 + z * (1.0 / 120 + z / 600.0)))))) <= 1;
  };
  if (!(std::abs(lambda) > 0)) return std::numeric_limits<double>::infinity();
  double lo = 0, hi = 0.1 / std::abs(lambda);
  while (stable(hi) && hi * std::abs(lambda) < 10) lo = hi, hi *= 2;
  if (stable(hi)) return hi;
  for (int i = 0; i < 60; ++i) (stable(0.5 * (lo + hi)) ? lo : hi) = 0.5 * (lo + hi);
  return lo;
}

}  // namespace

std::string nonlinearity_cost_note(const SpecializedScene& model) {
  const Scene& sc = model.scene;
  if (sc.solver == rt::Solver::rk4 || !(sc.sample > 0)) return {};
  const Eigen::MatrixXd M = state_matrix(model, model.main);
  if (M.rows() == 0) return {};
  const Eigen::MatrixXd B = balanced(M);
  const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(B, false).eigenvalues();
  // Two bounds on the adaptive methods' steps: dopri5's stability, and while a brake, clutch or torque
  // limit has an event function, an eighth of the fastest oscillation's period (hybrid_adaptive.hpp).
  double stable = std::numeric_limits<double>::infinity();
  std::complex<double> stiffest;
  if (sc.solver == rt::Solver::dopri5)
    for (Eigen::Index i = 0; i < lambda.size(); ++i)
      if (const double h = dopri5_stable_step(lambda(i)); h < stable) stable = h, stiffest = lambda(i);
  const bool events = !model.friction.empty() || !model.main.limited_controllers.empty();
  const double watched = events ? rt::event_check_step(B) : std::numeric_limits<double>::infinity();
  const double h = std::min(stable, watched);
  if (!(h * 4 < sc.sample)) return {};
  const std::string bound =
      stable <= watched
          ? fmt::format("dopri5's stability on the stiffest mode, |lambda| = {:.3g} 1/s", std::abs(stiffest))
          : fmt::format("an eighth of the fastest oscillation's period ({:.4g} Hz) while a brake, clutch or torque "
                        "limit may change state", std::numbers::pi / (4 * watched) / (2 * std::numbers::pi));
  return fmt::format("  what it costs: steps of at most {:.2g} s ({}), about {:.3g} over the horizon, where exact "
                     "stepping of a linear scene takes about one per sample period ({:.3g})\n",
                     h, bound, std::ceil(sc.horizon / h), std::ceil(sc.horizon / sc.sample));
}

// What exact stepping makes of the scene's sine inputs: it holds each linear over the scene's step,
// which errs by about (w h)^2 / 12 of the sine's effect (the hold's error, A (w h)^2 / 8 at most
// mid-step, averaged over the step). Above 1e-6 that is a warning: no longer "exact".
std::string sine_inputs_note(const SpecializedScene& model) {
  const Scene& sc = model.scene;
  if (sc.solver != rt::Solver::exact) return {};
  std::string s;
  const double h = std::min(sc.sample, sc.step);
  for (const InputSpec& in : sc.inputs) {
    const auto* sine = std::get_if<rt::Sine>(&in.signal);
    if (!sine || sine->amplitude == 0 || sine->frequency_hz == 0) continue;
    const double wh = 2 * std::numbers::pi * std::abs(sine->frequency_hz) * h;
    const double error = wh * wh / 12;
    const double step_for_1e8 = std::sqrt(12 * 1e-8) / (2 * std::numbers::pi * std::abs(sine->frequency_hz));
    s += fmt::format("{}sine input {} ({} Hz): exact stepping holds it linear over steps of {} s, an error of about "
                     "{:.2g} of its effect; for 1e-8 take step <= {:.2g} s, or use dopri5\n",
                     error > 1e-6 ? "warning: " : "",
                     variable_name(model.derivation.topology, Variable{VariableKind::torque, in.body}),
                     sine->frequency_hz, h, error, step_for_1e8);
  }
  // A grade's load s sin a + c cos a, a linear between the table's rows: its second derivative is at
  // most its size times a'^2, so the hold errs by about (a' h)^2 / 12 of it.
  for (const LoadSpec& l : sc.loads) {
    const auto* grade = l.varying ? std::get_if<rt::GradeLoad>(&*l.varying) : nullptr;
    if (!grade) continue;
    double rate = 0;
    for (std::size_t i = 1; i < grade->angle.t.size(); ++i)
      if (grade->angle.t[i] > grade->angle.t[i - 1])
        rate = std::max(rate, std::abs(grade->angle.v[i] - grade->angle.v[i - 1]) / (grade->angle.t[i] - grade->angle.t[i - 1]));
    if (rate == 0) continue;
    const double error = (rate * h) * (rate * h) / 12;
    s += fmt::format("{}grade (a table, up to {:.3g} rad/s): exact stepping holds the road load linear over steps of "
                     "{} s, an error of about {:.2g} of its size; for 1e-8 take step <= {:.2g} s, or use dopri5\n",
                     error > 1e-6 ? "warning: " : "", rate, h, error, std::sqrt(12 * 1e-8) / rate);
  }
  return s;
}

std::string operation_summary(const SpecializedScene& model) {
  std::string s;
  auto one = [&](const SpecializedSystem& sys) {
    s += fmt::format("{} ({} states, {} inputs, {} outputs): rhs {}; outputs {}\n", kind_name(sys.kind), sys.states.size(),
                     sys.inputs.size(), sys.outputs.size(), operation_text(sys.rhs_ops).str(), operation_text(sys.output_ops).str());
    s += diagnostics_text(system_diagnostics(model, sys), "  ");
    s += rk4_step_note(model, sys);
  };
  one(model.main);
  s += initial_deflection_note(model);
  s += loads_and_controllers_note(model);
  s += sine_inputs_note(model);
  if (model.rigid) one(*model.rigid);
  if (!model.friction.empty()) {
    std::string names;
    for (const FrictionRun& f : model.friction) names += (names.empty() ? "" : ", ") + f.name + (f.one_way ? " (one-way)" : "");
    const Topology& t = model.derivation.topology;
    s += fmt::format("brakes and clutches: {} engaged ({}), {} open throughout; modes (sets of stuck elements): at "
                     "most {}, each formed by the simulator when a run first reaches it\n",
                     model.friction.size(), names, t.friction_elements.size() - model.friction.size(),
                     std::size_t{1} << model.friction.size());
  }
  return s;
}

std::string rk4_step_note(const SpecializedScene& model, const SpecializedSystem& system) {
  const Scene& sc = model.scene;
  if (sc.solver != rt::Solver::rk4 || !(sc.step > 0) || !(sc.sample > 0)) return {};
  // The step the run takes: the sample cut into the fewest equal steps no longer than `step`.
  const double h = sc.sample / std::ceil(sc.sample / std::min(sc.step, sc.sample) * (1 - 1e-12));
  const Eigen::MatrixXd M = state_matrix(model, system);
  if (M.rows() == 0) return {};
  const Eigen::VectorXcd lambda = Eigen::EigenSolver<Eigen::MatrixXd>(balanced(M), false).eigenvalues();
  // A mode e^(lambda t) advances by e^z per step, z = lambda h; rk4 by its polynomial R(z). Their
  // difference is the step's error in that mode, relative to its amplitude at the step's start.
  double worst = 0;
  std::complex<double> worst_lambda;
  for (Eigen::Index i = 0; i < lambda.size(); ++i) {
    const std::complex<double> z = lambda(i) * h;
    const std::complex<double> r = 1.0 + z * (1.0 + z * (0.5 + z * (1.0 / 6 + z / 24.0)));
    const double error = std::abs(r - std::exp(z));
    if (error > worst) worst = error, worst_lambda = lambda(i);
  }
  if (!(worst > 1e-6)) return {};
  // The local error is |z|^5 / 120 for small z: 1e-8 per step at |z| = (1.2e-6)^(1/5).
  const double step_for_1e8 = std::pow(1.2e-6, 0.2) / std::abs(worst_lambda);
  return fmt::format("  warning: rk4 steps of {:.3g} s err by {:.2g} of its amplitude per step on the mode at {:.4g} Hz (|lambda| h = "
                     "{:.3g}), and such errors add up over the run; for 1e-8 per step take step <= {:.2g} s, or use "
                     "exact or dopri5\n",
                     h, worst, std::abs(worst_lambda.imag()) / (2 * std::numbers::pi), std::abs(worst_lambda) * h,
                     step_for_1e8);
}

}  // namespace pogear
