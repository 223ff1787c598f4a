// The hybrid engine's workspace (HybridData): a run's element states, mode and energy, the cache of
// the modes met, and every scratch vector, sized once from a HybridSystem; and the elements' laws.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <optional>
#include <utility>
#include <vector>

#include "pogear/actuator.hpp"
#include "pogear/event_proof.hpp"
#include "pogear/hybrid_modes.hpp"
#include "pogear/hybrid_observe.hpp"
#include "pogear/solver.hpp"

namespace pogear::rt::hybrid {

using hybrid_detail::ModeMatrices;

// What the run has computed per mode and per step length, kept from run to run.
struct ModeCache {
  std::map<std::uint32_t, ModeMatrices> modes;
  std::map<std::pair<std::uint32_t, double>, ExactMatrices> discretizations;
  std::map<std::pair<std::uint32_t, double>, StepProof> proofs;  // clear_of_events' maps
  // How often each step length was taken by the Taylor series: sorted by (mode, length) as the maps,
  // in a vector whose capacity is reserved, so that a new length costs no allocation.
  std::vector<std::pair<std::pair<std::uint32_t, double>, int>> taylor_uses;
};

// The bound on the step lengths each cache keeps (uneven steps after events): beyond it, it starts anew.
inline constexpr std::size_t kStepLengthsKept = 256;

// A point of a step's trajectory: the state x, the stepper's own state z there (the exact method's
// state augmented with the slip integrals; unused by the others), the known inputs v and the event
// functions g.
struct EventPoint {
  Eigen::VectorXd x, z, v, g;
};

// Elements 0..nf-1 are the brakes and clutches, nf..ne-1 the controllers' torque limits, the last nm
// of them the monitors of crossings (hybrid_crossings.hpp), which no event, sample or mode reports.
struct HybridData {
  int ne = 0, nf = 0, nm = 0;
  // States; the scene's signals u; the known inputs [u; q], q the state torques (of the state);
  // all inputs w = [u; q; T].
  Eigen::Index nx = 0, ns = 0, nu = 0, nw = 0;
  double horizon = 0;
  Eigen::MatrixXd S;  // the slips of all elements (a controller's row zero: it has no slip)
  Eigen::VectorXd slip_norm;  // ||S_k||_1, the zero-slip rule's scale (slip_is_zero); a monitor's ||law_x||_1
  std::vector<Eigen::Index> speed_states;  // the system's speeds, or the states some slip reads
  std::vector<double> breaks;  // of the inputs and commands
  // The signals as the run reads them: the system's, a triggered one's times moved to its start;
  // for each input and command the triggered signal it is (-1: none); for each triggered signal what
  // it is until it starts, its start (infinite until its trigger) and whether that was reported.
  // `triggers_live`: off while the initial mode resolves (no event); `started_now`: a signal started
  // at the instant being resolved, which must be resolved again with it.
  std::vector<Signal> inputs, commands, before;
  // Per brake or clutch with an actuator, its engagement's knots (the command as the run reads it:
  // `before`, then from a trigger's start the triggered one); empty for the others.
  std::vector<ActuatorKnots> actuators;
  std::vector<int> input_trigger, command_trigger;
  std::vector<double> start;
  std::vector<char> reported;
  bool triggers_live = false, started_now = false;
  // The shortest period of a sine among the inputs and commands (infinity without one), and the
  // longest step over which the exact method may hold the inputs linear: the scene's step when a
  // sine or a grade's load is present (its error is what the summary states), else unbounded.
  double sine_period = std::numeric_limits<double>::infinity();
  double hold_step = std::numeric_limits<double>::infinity();

  Eigen::VectorXd x, energy;
  std::vector<ElementState> state;
  std::vector<int> dir;  // the direction of a slipping element's slip (of a controller: of its limit)
  // Slip control (TorqueLimitData::supplies): for each friction element the slip controller that
  // supplies it (-1: none); for each slip controller its phase, waiting, controlling or done.
  std::vector<int> supplier;
  std::vector<signed char> phase;
  std::uint32_t mask = 0;  // bit k set when element k is stuck
  std::vector<char> watched;  // the elements with an event function over the current step
  std::vector<int> events_in_sample;  // the chattering guard (max_events_per_sample)
  int locations_in_sample = 0;
  long steps = 0;
  std::optional<std::pair<double, double>> inaccurate;  // the step and error of an untrusted exponential
  ModeCache cache;

  // Scratch, sized here: the driver's step start (inputs v0, event functions g0, g_a at a bracket's
  // start), its step end and points within the step; the event functions' rates; the samples' state,
  // energy, w and slips; mode resolution's working copies; T the stuck torques (its head).
  Eigen::VectorXd v0, g0, g_a, T, dT, dx, p0, p1, dp, dv, r0, r1, v, sample_x, sample_energy, sample_w, sample_slip,
      slip, projected;
  EventPoint end, mid, side;
  std::vector<ElementState> old_state;
  // A sample's w, slips and energy without the monitors' entries (observe_sample).
  Eigen::VectorXd shown_w, shown_slip, shown_energy;
};

inline EventPoint make_event_point(const HybridData& d) {
  EventPoint p;
  p.x.resize(d.nx);
  p.z.resize(d.nx + 2 * d.ne);  // the exact method's augmented state
  p.v.resize(d.nw);
  p.g.resize(d.ne);
  return p;
}

inline HybridData make_hybrid_data(const HybridSystem& sys, double horizon) {
  HybridData d;
  d.nf = static_cast<int>(sys.S.rows());
  d.ne = d.nf + static_cast<int>(sys.limits.size());
  d.nm = std::min(crossing_count(sys), static_cast<int>(sys.limits.size()));  // data_mismatch refuses a difference
  d.nx = sys.M.rows();
  d.ns = static_cast<Eigen::Index>(sys.inputs.size());
  d.nu = d.ns + static_cast<Eigen::Index>(sys.state_torques.size());
  d.nw = d.nu + d.ne;
  d.horizon = horizon;
  d.cache.taylor_uses.reserve(kStepLengthsKept + 1);
  d.S = Eigen::MatrixXd::Zero(d.ne, d.nx);
  d.S.topRows(d.nf) = sys.S;
  d.slip_norm = d.S.cwiseAbs().rowwise().sum();
  for (int k = d.ne - d.nm; k < d.ne; ++k)  // a monitor's quantity, for its band (monitor_band)
    d.slip_norm(k) = sys.limits[static_cast<std::size_t>(k - d.nf)].law_x.lpNorm<1>();
  d.speed_states = sys.speed_states;
  if (d.speed_states.empty())
    for (Eigen::Index j = 0; j < d.nx; ++j)
      if (d.S.col(j).cwiseAbs().maxCoeff() > 0) d.speed_states.push_back(j);
  const auto ne = static_cast<std::size_t>(d.ne);
  d.x.resize(d.nx);
  d.energy.setZero(d.ne + d.nu - d.ns);  // the elements' heat, then the state torques' work
  d.state.assign(ne, ElementState::open);
  d.old_state.assign(ne, ElementState::open);
  d.dir.assign(ne, 0);
  d.supplier.assign(ne, -1);
  d.phase.assign(ne, 0);
  for (std::size_t l = 0; l < sys.limits.size(); ++l)
    if (const int k = sys.limits[l].supplies; k >= 0 && k < d.nf) d.supplier[static_cast<std::size_t>(k)] = d.nf + static_cast<int>(l);
  d.watched.assign(ne, 0);
  d.events_in_sample.assign(ne, 0);
  for (Eigen::VectorXd* e : {&d.g0, &d.g_a, &d.p0, &d.p1, &d.dp, &d.r0, &d.r1, &d.T, &d.dT, &d.sample_slip, &d.slip})
    e->resize(d.ne);
  d.sample_energy.resize(d.energy.size());
  for (Eigen::VectorXd* w : {&d.v0, &d.dv, &d.v, &d.sample_w}) w->resize(d.nw);
  for (Eigen::VectorXd* x : {&d.dx, &d.sample_x, &d.projected}) x->resize(d.nx);
  d.end = d.mid = d.side = make_event_point(d);
  d.shown_w.resize(d.nw - d.nm);
  d.shown_slip.resize(d.ne - d.nm);
  d.shown_energy.resize(d.energy.size() - d.nm);
  d.inputs = sys.inputs;  // each run copies them again: the system may change between runs
  for (const FrictionElementData& e : sys.elements) d.commands.push_back(e.command);
  d.actuators.resize(sys.elements.size());
  d.input_trigger.assign(sys.inputs.size(), -1);
  d.command_trigger.assign(sys.elements.size(), -1);
  d.before.resize(sys.triggered.size());
  d.start.assign(sys.triggered.size(), std::numeric_limits<double>::infinity());
  d.reported.assign(sys.triggered.size(), 0);
  return d;
}

// The elements' laws: a controller's limits and law, a friction element's command and torque.
inline bool is_limit(const HybridData& d, int k) { return k >= d.nf; }
inline const TorqueLimitData& limit(const HybridSystem& sys, const HybridData& d, int k) {
  return sys.limits[static_cast<std::size_t>(k - d.nf)];
}
inline const std::string& element_name(const HybridSystem& sys, const HybridData& d, int k) {
  return is_limit(d, k) ? limit(sys, d, k).name : sys.elements[static_cast<std::size_t>(k)].name;
}
// Slip control: whether element k is a slip controller; whether friction element k's torque is its
// slip controller's now (it is controlling); whether slip controller k is off (waiting or done: open,
// its torque 0); when it starts (infinite until its trigger).
enum : signed char { kWaiting = 0, kControlling = 1, kDone = 2 };
inline bool is_slip_controller(const HybridSystem& sys, const HybridData& d, int k) {
  return is_limit(d, k) && limit(sys, d, k).supplies >= 0;
}
inline bool controlled(const HybridData& d, int k) {
  const int l = d.supplier[static_cast<std::size_t>(k)];
  return l >= 0 && d.phase[static_cast<std::size_t>(l)] == kControlling;
}
inline bool off(const HybridSystem& sys, const HybridData& d, int k) {
  return is_slip_controller(sys, d, k) && d.phase[static_cast<std::size_t>(k)] != kControlling;
}
inline double control_start(const HybridSystem& sys, const HybridData& d, int k) {
  const TorqueLimitData& c = limit(sys, d, k);
  return c.started_by >= 0 ? d.start[static_cast<std::size_t>(c.started_by)] : c.starts_at;
}
// A controller's torque at the limit it reached in direction dir.
inline double held_torque(const HybridSystem& sys, const HybridData& d, int k) {
  return d.dir[static_cast<std::size_t>(k)] > 0 ? limit(sys, d, k).torque_max : limit(sys, d, k).torque_min;
}
// A controller's torque Tk within its limits: the margins to its upper and lower limit, each widened
// by `band` (a monitor's, monitor_band), negative beyond. The event functions and mode resolution
// both judge a limit by these, so that what one finds beyond the other does too.
inline std::pair<double, double> limit_margins(const HybridSystem& sys, const HybridData& d, int k, double Tk, double band) {
  return {limit(sys, d, k).torque_max + band - Tk, Tk - limit(sys, d, k).torque_min + band};
}
// A controller's law at state x and known inputs v.
template <class X, class V>
double law(const HybridSystem& sys, const HybridData& d, int k, const X& x, const V& v) {
  return limit(sys, d, k).law_x.dot(x) + limit(sys, d, k).law_w.dot(v);
}
// Input j's and element k's signal at time t: a triggered one's `before` until it starts.
inline const Signal& input_signal(const HybridData& d, std::size_t j, double t) {
  const int i = d.input_trigger[j];
  return i >= 0 && t < d.start[static_cast<std::size_t>(i)] ? d.before[static_cast<std::size_t>(i)] : d.inputs[j];
}
inline const Signal& command_signal(const HybridData& d, std::size_t k, double t) {
  const int i = d.command_trigger[k];
  return i >= 0 && t < d.start[static_cast<std::size_t>(i)] ? d.before[static_cast<std::size_t>(i)] : d.commands[k];
}

// An element's command as it engages the element: a controller's is 1 throughout (it is never open,
// a slip controller's phase aside), a slip-controlled element's from its controller's start on (its
// capacity at lock-up), an actuated element's the engagement its actuator gives.
inline double command(const HybridSystem& sys, const HybridData& d, int k, double t) {
  if (is_limit(d, k)) return 1.0;
  const auto K = static_cast<std::size_t>(k);
  if (const int l = d.supplier[K]; l >= 0 && d.phase[static_cast<std::size_t>(l)] != kWaiting) return 1.0;
  if (const FrictionElementData& e = sys.elements[K]; actuated(e)) return engagement(d.actuators[K], e.time_constant, t);
  return value(command_signal(d, K, t), t);
}
// Its rate (right derivative), where command() follows the element's own signal.
inline double command_slope(const HybridSystem& sys, const HybridData& d, int k, double t) {
  const auto K = static_cast<std::size_t>(k);
  if (const FrictionElementData& e = sys.elements[K]; actuated(e)) return engagement_slope(d.actuators[K], e.time_constant, t);
  return slope(command_signal(d, K, t), t);
}
// The torque per unit command of element k while it slips: its capacity, or zero for a one-way
// element overrunning in its free direction.
inline double torque_scale(const HybridSystem& sys, const HybridData& d, int k) {
  const auto K = static_cast<std::size_t>(k);
  return sys.elements[K].one_way && d.dir[K] > 0 ? 0.0 : sys.elements[K].capacity;
}
// Whether element k's command is zero from t until the next breakpoint (it is linear there).
inline bool open_after(const HybridSystem& sys, const HybridData& d, int k, double t) {
  if (is_limit(d, k)) return false;
  const auto next = std::upper_bound(d.breaks.begin(), d.breaks.end(), t);
  const double t_next = next == d.breaks.end() ? std::max(d.horizon, t) : *next;
  return command(sys, d, k, t) == 0 && command(sys, d, k, t + 0.5 * (t_next - t)) == 0;
}

// The zero-slip rule: a slip is zero when it lies within the rounding of the speeds it is computed
// from, |S_k x| <= 256 eps ||S_k||_1 max |x_j| over the gear's speeds (HybridSystem::speed_states).
// A start or a projection computed in
// floating point leaves slips of a few ulps of the speeds where the exact slip is zero (1.6e-13 rad/s
// on a locked pair turning at a few hundred rad/s): an exact test would let such noise choose a
// direction and apply the full kinetic torque in it. `speed` is max |x_j| (speed_scale).
inline double speed_scale(const HybridData& d, const Eigen::VectorXd& x) {
  double big = 0;
  for (const Eigen::Index j : d.speed_states) big = std::max(big, std::abs(x(j)));
  return big;
}
inline constexpr double kZeroSlipUlps = 256;
inline bool slip_is_zero(const HybridData& d, int k, double slip, double speed) {
  return std::abs(slip) <= kZeroSlipUlps * std::numeric_limits<double>::epsilon() * d.slip_norm(k) * speed;
}
// The same rule for a crossing's monitor (hybrid_crossings.hpp): its quantity leaves the range of
// its regime only by more than the rounding of the speeds it is computed from, so a speed held at
// its threshold (a brake holding a carrier at the 0 of "omega_c2 > 0") never crosses it by noise.
// Zero for every other element.
inline double monitor_band(const HybridData& d, int k, const Eigen::VectorXd& x) {
  if (k < d.ne - d.nm) return 0.0;
  return kZeroSlipUlps * std::numeric_limits<double>::epsilon() * d.slip_norm(k) * speed_scale(d, x);
}

}  // namespace pogear::rt::hybrid
