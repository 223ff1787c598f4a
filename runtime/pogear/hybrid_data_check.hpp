// Whether a hybrid workspace and the system it runs fit each other and the engine's limits, checked
// before every run (a run on data sized for another system would read out of bounds).
#pragma once

#include <algorithm>
#include <cmath>

#include "pogear/hybrid_data.hpp"

namespace pogear::rt::hybrid {

// Why data does not fit the system, or nullptr: a run on data sized for another system would read
// out of bounds.
inline const char* data_mismatch(const HybridSystem& sys, const HybridData& d) {
  const Eigen::Index nx = sys.M.rows(), ne = sys.S.rows() + static_cast<Eigen::Index>(sys.limits.size());
  if (sys.M.cols() != nx || sys.N.rows() != nx || sys.S.cols() != nx)
    return "the system's matrices M, N and S do not agree on the number of states";
  if (sys.S.rows() != static_cast<Eigen::Index>(sys.elements.size()))
    return "the system has not one slip row per brake or clutch";
  for (const FrictionElementData& e : sys.elements) {
    const Table& f = e.friction_curve;
    if (f.t.empty()) continue;
    bool fits = f.t.size() >= 2 && f.v.size() == f.t.size() && f.t.front() == 0;
    for (std::size_t i = 0; fits && i < f.t.size(); ++i)
      fits = std::isfinite(f.t[i]) && f.v[i] > 0 && f.v[i] <= 10 && (i == 0 || f.t[i] > f.t[i - 1]);
    if (!fits) return "a friction curve is not slips strictly increasing from 0 with ratios in (0, 10]";
  }
  for (const FrictionElementData& e : sys.elements)
    if (!(e.fill_delay >= 0) || !std::isfinite(e.fill_delay) || !(e.time_constant >= 0) || !std::isfinite(e.time_constant))
      return "an actuator's fill delay or time constant is negative or not finite";
  if (sys.N.cols() != static_cast<Eigen::Index>(sys.inputs.size() + sys.state_torques.size()) + ne)
    return "the system has not one input column per input, state torque, brake or clutch, and torque limit";
  for (const StateTorqueData& q : sys.state_torques) {
    if (q.speed.size() != nx) return "a state torque's speed is not a row over the system's states";
    const bool converter = q.kind == StateTorqueKind::converter_pump || q.kind == StateTorqueKind::converter_turbine;
    if (converter && (q.turbine.size() != nx || q.converter.capacity.x.size() < 1 ||
                      q.converter.capacity.x.size() != q.converter.capacity.y.size() ||
                      q.converter.torque_ratio.x.size() < 1 ||
                      q.converter.torque_ratio.x.size() != q.converter.torque_ratio.y.size()))
      return "a converter's turbine speed or tables do not fit the system";
    if (q.kind == StateTorqueKind::engine &&
        (q.engine.speeds.empty() || q.engine.throttles.empty() || q.engine.torque.size() != q.engine.throttles.size() ||
         std::any_of(q.engine.torque.begin(), q.engine.torque.end(),
                     [&](const std::vector<double>& row) { return row.size() != q.engine.speeds.size(); })))
      return "an engine's map does not fit its speeds and throttles";
  }
  for (std::size_t i = 0; i < sys.limits.size(); ++i) {
    const TorqueLimitData& l = sys.limits[i];
    if (l.law_x.size() != nx || l.law_w.size() != sys.N.cols())
      return "a controller's law is not a row over the system's states and inputs";
    if (l.supplies < 0) continue;
    if (l.supplies >= sys.S.rows() || l.integral >= nx || l.started_by >= static_cast<int>(sys.triggered.size()) ||
        !std::isfinite(l.starts_at) ||
        !((l.torque_min == 0 && l.torque_max > 0) || (l.torque_max == 0 && l.torque_min < 0)))
      return "a slip controller names no brake or clutch, state or trigger of the system, or its limits are not 0 "
             "and a capacity";
    for (std::size_t j = 0; j < i; ++j)
      if (sys.limits[j].supplies == l.supplies) return "two slip controllers supply the same brake or clutch";
    if (actuated(sys.elements[static_cast<std::size_t>(l.supplies)]))
      return "a slip controller supplies a brake or clutch with an actuator (its command would need the actuator's state)";
  }
  if (ne > 32) return "more than 32 brakes, clutches and torque limits (a mode is a 32-bit set)";
  for (const TriggeredSignal& s : sys.triggered) {
    const std::size_t n = s.command ? sys.elements.size() : sys.inputs.size();
    // A crossing's trigger is its monitor, one of the last d.nm elements (with_crossing_monitors).
    const bool trigger_fits = s.crossing ? s.element >= ne - d.nm && s.element < ne
                                         : s.element >= 0 && static_cast<std::size_t>(s.element) < sys.elements.size();
    if (s.index < 0 || static_cast<std::size_t>(s.index) >= n || !trigger_fits)
      return "a triggered signal names no signal or no brake or clutch of the system";
    if (s.state == ElementState::open || !(s.delay >= 0) || !std::isfinite(s.delay))
      return "a triggered signal waits for an element to open, or for a negative or infinite delay";
    if (!startable(s.command ? sys.elements[static_cast<std::size_t>(s.index)].command
                             : sys.inputs[static_cast<std::size_t>(s.index)]))
      return "a triggered signal is a sine, which has no value to hold before it starts";
    if (s.before && !startable(*s.before) && s.command)
      return "a triggered command is a sine before it starts (a command is piecewise linear)";
    for (const TriggeredSignal& o : sys.triggered)
      if (&o != &s && o.command == s.command && o.index == s.index) return "a signal is triggered twice";
  }
  for (const Eigen::Index j : sys.speed_states)
    if (j < 0 || j >= nx) return "a speed state of the system is not one of its states";
  if (d.nx != nx || d.ne != ne || d.nf != sys.S.rows() || d.nw != sys.N.cols() || d.S.rows() != ne ||
      d.S.cols() != nx || d.x.size() != nx || d.energy.size() != ne + static_cast<Eigen::Index>(sys.state_torques.size()) || d.state.size() != static_cast<std::size_t>(ne) ||
      d.dir.size() != d.state.size() || d.g0.size() != ne || d.v.size() != d.nw || d.dx.size() != nx ||
      d.nu != d.ns + static_cast<Eigen::Index>(sys.state_torques.size()) ||
      d.inputs.size() != sys.inputs.size() || d.commands.size() != sys.elements.size() || d.actuators.size() != sys.elements.size() ||
      d.start.size() != sys.triggered.size() || d.before.size() != sys.triggered.size() ||
      d.nm != crossing_count(sys) || d.supplier.size() != d.state.size() || d.phase.size() != d.state.size() ||
      d.shown_w.size() != d.nw - d.nm || d.shown_slip.size() != ne - d.nm)
    return "the hybrid workspace was sized for another system";
  return nullptr;
}

}  // namespace pogear::rt::hybrid
