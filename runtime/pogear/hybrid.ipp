// The definitions of hybrid.hpp's HybridEngine: compiled into libpogear_runtime
// (runtime/src/hybrid.cpp), or included inline by hybrid.hpp under POGEAR_RT_HEADER_ONLY. The engine
// does not depend on a model's size, so no simulator compiles it again.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <utility>
#include <vector>

#include "pogear/hybrid.hpp"
#include "pogear/hybrid_adaptive.hpp"
#include "pogear/hybrid_crossings.hpp"
#include "pogear/hybrid_data_check.hpp"
#include "pogear/hybrid_driver.hpp"
#include "pogear/hybrid_exact.hpp"

namespace pogear::rt {

POGEAR_RT_ABI_BEGIN

// What a HybridEngine holds: the model, the workspace (kept from run to run with its mode cache),
// the method. A model with crossings runs as its copy with their monitors (hybrid_crossings.hpp),
// made again at every run: the engine reads the user's system at every run.
class HybridEngineCore {
 public:
  HybridEngineCore(const HybridSystem& user, double horizon, HybridMethod method)
      : user(user), monitored(hybrid::with_crossing_monitors(user)),
        sys(crossing_count(user) ? monitored : user), data(hybrid::make_hybrid_data(sys, horizon)),
        method(std::move(method)) {}

  const HybridSystem& user;
  HybridSystem monitored;
  const HybridSystem& sys;
  hybrid::HybridData data;
  HybridMethod method;
  long rhs_evals = 0;
};

POGEAR_RT_ABI_END

namespace hybrid {

template <class Stepper>
RunStatus run_adaptive_modes(HybridEngineCore& c, const char* name, const detail::Grid& grid,
                             const SampleObserver& obs, const EventObserver& on_event) {
  AdaptiveStepper<Stepper> s(c.sys, c.data, c.method.options, name);
  std::string error;
  if (!s.valid_step(error)) return RunStatus{false, error, 0.0};
  const RunStatus st = run_modes(c.sys, c.data, s, grid, obs, on_event);
  c.rhs_evals += s.rhs_evals();
  return st;
}

// The run: the workspace reset to x0 at t = 0, the initial mode resolved and observed, then the
// driver loop with the method's stepper.
inline RunStatus run(HybridEngineCore& c, const Eigen::VectorXd& x0, double sample, const SampleObserver& obs,
                     const EventObserver& on_event) {
  if (const char* why = crossing_mismatch(c.user)) return RunStatus{false, why, 0.0};
  if (&c.sys == &c.monitored) c.monitored = with_crossing_monitors(c.user);
  const HybridSystem& sys = c.sys;
  HybridData& d = c.data;
  if (const char* why = data_mismatch(sys, d)) return RunStatus{false, why, 0.0};
  if (x0.size() != d.nx) return RunStatus{false, "the initial state does not fit the system", 0.0};
  // solver_refusal's rule, kept by the engine itself: the exact flow is of a linear mode.
  if (c.method.solver == Solver::exact && !sys.state_torques.empty())
    return RunStatus{false, "a quadratic load, a converter or an engine makes the modes nonlinear, which exact "
                            "stepping does not integrate", 0.0};
  const bool slip_control = std::any_of(sys.limits.begin(), sys.limits.end(), [](const TorqueLimitData& l) { return l.supplies >= 0; });
  if (c.method.solver == Solver::exact && slip_control)
    return RunStatus{false, "a slip controller makes its element's heat quadratic in the state, which exact stepping "
                            "does not integrate", 0.0};
  if (c.method.solver == Solver::exact && lags_its_command(sys))
    return RunStatus{false, "an actuator's lag makes its element's engagement exponential between the command's "
                            "breakpoints, which exact stepping does not integrate", 0.0};
  // The signals as the run reads them: a triggered one is its `before` until it starts.
  d.inputs = sys.inputs;
  for (std::size_t k = 0; k < sys.elements.size(); ++k) d.commands[k] = sys.elements[k].command;
  std::fill(d.input_trigger.begin(), d.input_trigger.end(), -1);
  std::fill(d.command_trigger.begin(), d.command_trigger.end(), -1);
  std::size_t start_breaks = 0;
  std::vector<Signal> all;
  for (std::size_t i = 0; i < sys.triggered.size(); ++i) {
    const TriggeredSignal& s = sys.triggered[i];
    const auto j = static_cast<std::size_t>(s.index);
    (s.command ? d.command_trigger[j] : d.input_trigger[j]) = static_cast<int>(i);
    const Signal& after = s.command ? d.commands[j] : d.inputs[j];
    d.before[i] = held_until_start(after, s.before);
    if (!s.command || !actuated(sys.elements[j])) all.push_back(d.before[i]);  // an actuator's knots are its breakpoints
    for_each_break(after, [&](double) { ++start_breaks; });
    start_breaks += s.command ? 2 : 1;  // the start itself, and an actuator's knot at the start plus its delay
  }
  std::fill(d.start.begin(), d.start.end(), std::numeric_limits<double>::infinity());
  std::fill(d.reported.begin(), d.reported.end(), 0);
  d.triggers_live = d.started_now = false;
  for (std::size_t j = 0; j < d.inputs.size(); ++j)
    if (d.input_trigger[j] < 0) all.push_back(d.inputs[j]);
  for (std::size_t k = 0; k < d.commands.size(); ++k)
    if (d.command_trigger[k] < 0 && !actuated(sys.elements[k])) all.push_back(d.commands[k]);
  for (const auto& q : sys.state_torques)  // an engine's throttle steps end steps as an input's do
    if (q.kind == StateTorqueKind::engine) all.push_back(q.throttle);
  // The horizon itself may be one: the last step then ends on the inputs' values before it.
  d.breaks = breakpoints(all, 0.0, std::nextafter(d.horizon, std::numeric_limits<double>::infinity()));
  for (const TorqueLimitData& l : sys.limits)  // a slip controller's start in time: its mode is resolved there
    if (l.supplies >= 0 && l.started_by < 0 && l.starts_at > 0 && l.starts_at <= d.horizon)
      d.breaks.insert(std::lower_bound(d.breaks.begin(), d.breaks.end(), l.starts_at), l.starts_at);
  // An actuated element's engagement (actuator.hpp), from the command as the run starts reading it;
  // its knots are breakpoints in place of the command's own (room kept for a triggered command's).
  for (std::size_t k = 0; k < sys.elements.size(); ++k) {
    const FrictionElementData& e = sys.elements[k];
    ActuatorKnots& knots = d.actuators[k];
    for (std::vector<double>* v : {&knots.t, &knots.e, &knots.p, &knots.slope}) v->clear();
    if (!actuated(e)) continue;
    const int i = d.command_trigger[k];
    const Signal& now = i >= 0 ? d.before[static_cast<std::size_t>(i)] : d.commands[k];
    const std::size_t n = knot_count(now) + (i >= 0 ? knot_count(d.commands[k]) + 1 : 0);
    for (std::vector<double>* v : {&knots.t, &knots.e, &knots.p, &knots.slope}) v->reserve(n);
    add_knots(knots, now, -std::numeric_limits<double>::infinity(), e.fill_delay, e.time_constant);
    for (const double t : knots.t)
      if (t > 0 && t <= d.horizon) d.breaks.insert(std::lower_bound(d.breaks.begin(), d.breaks.end(), t), t);
  }
  d.breaks.erase(std::unique(d.breaks.begin(), d.breaks.end()), d.breaks.end());
  d.breaks.reserve(d.breaks.size() + start_breaks);
  d.sine_period = shortest_sine_period(all);
  d.hold_step = std::numeric_limits<double>::infinity();
  if (c.method.solver == Solver::exact && (std::isfinite(d.sine_period) || curved(all))) {
    if (!(c.method.options.h > 0)) return RunStatus{false, "invalid step size h = " + detail::num(c.method.options.h), 0.0};
    d.hold_step = c.method.options.h;
  }
  d.x = x0;
  d.energy.setZero();
  std::fill(d.dir.begin(), d.dir.end(), 0);
  std::fill(d.phase.begin(), d.phase.end(), hybrid::kWaiting);
  std::fill(d.state.begin(), d.state.end(), ElementState::open);
  d.mask = 0;
  if (!(sample > 0) || !(d.horizon / sample < 0x1p62)) return RunStatus{false, "invalid sample period", 0.0};
  // The sample times of every other driver, so that the CSV rows of all runs of a scene align.
  const detail::Grid grid = detail::sample_grid(0.0, d.horizon, sample);
  std::fill(d.events_in_sample.begin(), d.events_in_sample.end(), 0);
  d.locations_in_sample = 0;
  std::string error;
  // The initial mode is where the run starts, not an event.
  const EventObserver no_event = [](const HybridEvent&) {};
  if (!resolve_mode(sys, d, 0.0, -1, no_event, error)) return RunStatus{false, error, 0.0};
  for (std::size_t k = 0; k < sys.elements.size(); ++k)
    if (const FrictionElementData& e = sys.elements[k]; e.held_at_start && !((d.mask >> k) & 1u)) {
      const double engaged = command(sys, d, static_cast<int>(k), 0.0);
      return RunStatus{false,
                       e.name + " slips at t = 0, where the start in a gear holds it: its torque exceeds its static "
                           "capacity there, " + detail::num(e.static_ratio * e.capacity * engaged) + " N m (" +
                           detail::num(e.capacity) + " N m x static ratio " + detail::num(e.static_ratio) +
                           " x command " + detail::num(engaged) + "); raise its capacity (--param), or start with "
                           "smaller torques",
                       0.0};
    }
  if (!observe_sample(sys, d, 0.0, d.x, d.energy, obs)) return RunStatus{false, "stopped", 0.0};
  d.triggers_live = true;
  switch (c.method.solver) {
    case Solver::exact: {
      ExactStepper s(sys, d, c.method.options.max_steps);
      return run_modes(sys, d, s, grid, obs, on_event);
    }
    case Solver::dopri5:
      return run_adaptive_modes<Dopri5<Eigen::VectorXd, ModeRhs>>(c, "dopri5", grid, obs, on_event);
    case Solver::implicit:
      return run_adaptive_modes<TrBdf2<Eigen::VectorXd, ModeRhs, ModeJacobian>>(c, "implicit", grid, obs, on_event);
    default:
      return RunStatus{false,
                       std::string("brakes and clutches are not simulated with ") +
                           std::string(solver_name(c.method.solver)) +
                           " (fixed steps cannot locate their events); use exact, dopri5 or implicit",
                       0.0};
  }
}

}  // namespace hybrid

POGEAR_RT_ABI_BEGIN

POGEAR_RT_API HybridEngine::HybridEngine(const HybridSystem& sys, double horizon, HybridMethod method)
    : core_(std::make_unique<HybridEngineCore>(sys, horizon, std::move(method))) {}

POGEAR_RT_API HybridEngine::~HybridEngine() = default;

POGEAR_RT_API RunStatus HybridEngine::run(const Eigen::VectorXd& x0, double sample, const SampleObserver& obs,
                                          const EventObserver& on_event) {
  return hybrid::run(*core_, x0, sample, obs, on_event);
}

// The sets of stuck elements met, the crossings' monitors left out (their regimes are no modes of the gear).
POGEAR_RT_API int HybridEngine::modes_met() const {
  const hybrid::HybridData& d = core_->data;
  if (d.nm == 0) return static_cast<int>(d.cache.modes.size());
  const std::uint32_t shown = (1u << (d.ne - d.nm)) - 1u;
  std::vector<std::uint32_t> masks;
  for (const auto& [mask, m] : d.cache.modes) masks.push_back(mask & shown);
  std::sort(masks.begin(), masks.end());
  return static_cast<int>(std::unique(masks.begin(), masks.end()) - masks.begin());
}

POGEAR_RT_API long HybridEngine::steps() const { return core_->data.steps; }

POGEAR_RT_API long HybridEngine::rhs_evals() const { return core_->rhs_evals; }

POGEAR_RT_ABI_END

}  // namespace pogear::rt
