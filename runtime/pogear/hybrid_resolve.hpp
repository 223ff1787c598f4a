// Mode resolution: which elements stick at an instant (stick–slip resolution, the state projected onto
// the stuck elements' constraints), and which have an event function over a step (watch).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <string>

#include "pogear/hybrid_inputs.hpp"
#include "pogear/hybrid_mode_cache.hpp"

namespace pogear::rt::hybrid {

// A triggered signal's start moved to t0: its times, and its breakpoints (t0 itself among them)
// added to d.breaks, whose capacity run() reserved for them (no allocation within a run). Its
// `before` still holds until t0.
inline void start_signal(const HybridSystem& sys, HybridData& d, std::size_t i, double t0) {
  const TriggeredSignal& s = sys.triggered[i];
  const auto j = static_cast<std::size_t>(s.index);
  d.start[i] = t0;
  if (s.command) move_times(d.commands[j], sys.elements[j].command, t0);
  else move_times(d.inputs[j], sys.inputs[j], t0);
  auto add = [&](double b) {
    if (!(b >= t0) || !(b <= d.horizon)) return;
    const auto at = std::lower_bound(d.breaks.begin(), d.breaks.end(), b);
    if ((at == d.breaks.end() || *at != b) && d.breaks.size() < d.breaks.capacity()) d.breaks.insert(at, b);
  };
  add(t0);
  if (s.command && actuated(sys.elements[j])) {
    // The actuator engages by `before` until t0 + its delay, then lags the triggered command.
    const FrictionElementData& e = sys.elements[j];
    ActuatorKnots& knots = d.actuators[j];
    const double from = t0 + e.fill_delay;
    drop_knots_from(knots, from);
    const std::size_t kept = knots.t.size();
    add_knots(knots, d.commands[j], t0, e.fill_delay, e.time_constant);
    for (std::size_t n = kept; n < knots.t.size(); ++n) add(knots.t[n]);
    return;
  }
  for_each_break(s.command ? d.commands[j] : d.inputs[j], add);
}

// A change of element k's state at t, reported; the signals it triggers start (after their delay).
inline void record(const HybridSystem& sys, HybridData& d, double t, int k, ElementState from, ElementState to,
                   const EventObserver& on_event) {
  if (from == to) return;
  if (k < d.ne - d.nm) on_event(HybridEvent{t, k, from, to, -1});  // a monitor's change is no event of the gear
  if (!d.triggers_live) return;
  for (std::size_t i = 0; i < sys.triggered.size(); ++i) {
    const TriggeredSignal& s = sys.triggered[i];
    if (s.element != k || s.state != to || std::isfinite(d.start[i])) continue;
    start_signal(sys, d, i, t + s.delay);
    if (d.start[i] <= t) d.started_now = true;  // its value may jump at this very instant (a delay below an ulp of t too)
  }
}

// The triggered signals that start at or before t, reported once (in time order: at the
// breakpoint of their start, or at their trigger's instant without a delay).
inline void report_starts(const HybridSystem& sys, HybridData& d, double t, const EventObserver& on_event) {
  for (std::size_t i = 0; i < sys.triggered.size(); ++i)
    if (!d.reported[i] && d.start[i] <= t) {
      d.reported[i] = 1;
      on_event(HybridEvent{d.start[i], sys.triggered[i].crossing ? -1 : sys.triggered[i].element, ElementState::open,
                           ElementState::open, static_cast<int>(i)});
    }
}

// The least ratio of a torque beyond what it can hold: an excess of an ulp, whose quotient rounds
// to 1, still counts (else the event function that found it stays negative, and the event recurs).
inline constexpr double kJustBeyond = 1 + std::numeric_limits<double>::epsilon();

// How far element k's torque Tk lies beyond what it can hold, as a ratio above 1 (at most 1 when it
// holds): a friction element's |T| over its static capacity at its command (infinite for a one-way
// element pulled forward), a controller's excess over its range.
inline double overload(const HybridSystem& sys, const HybridData& d, int k, double Tk, double t, double band = 0) {
  if (is_limit(d, k)) {
    const double lo = limit(sys, d, k).torque_min - band, hi = limit(sys, d, k).torque_max + band;
    const double range = std::isfinite(hi - lo) ? hi - lo : std::max({1.0, std::abs(std::isfinite(hi) ? hi : lo)});
    // Beyond as the event function sees it (limit_margins): lo and hi rounded would differ by an ulp.
    const auto [above, below] = limit_margins(sys, d, k, Tk, band);
    return above < 0 ? std::max(kJustBeyond, 1 - above / range) : below < 0 ? std::max(kJustBeyond, 1 - below / range) : 0.0;
  }
  const auto& e = sys.elements[static_cast<std::size_t>(k)];
  const double capacity = e.static_ratio * e.capacity * command(sys, d, k, t);
  const double Tj = std::abs(Tk);
  if (e.one_way && Tk > 0) return std::numeric_limits<double>::infinity();
  if (!(capacity > 0)) return Tj > 0 ? std::numeric_limits<double>::infinity() : 0.0;
  return Tj > capacity ? std::max(kJustBeyond, Tj / capacity) : Tj / capacity;
}

// The slip controllers that start at or before t (control_start) begin controlling, bumpless: their
// integral starts where their law gives the command the element had (zero without an integral term);
// false (with `error`) when the element one supplies does not slip, or slips against its target's sign.
inline bool start_slip_control(const HybridSystem& sys, HybridData& d, double t, std::string& error) {
  for (int l = d.nf; l < d.ne; ++l) {
    const auto L = static_cast<std::size_t>(l);
    if (!is_slip_controller(sys, d, l) || d.phase[L] != kWaiting || !(control_start(sys, d, l) <= t)) continue;
    const TorqueLimitData& c = limit(sys, d, l);
    const double p = command(sys, d, c.supplies, t), capacity = c.torque_max > 0 ? c.torque_max : c.torque_min;
    d.phase[L] = kControlling;
    if (c.integral >= 0 && c.integral < d.nx) {
      d.x(c.integral) = 0;
      known_inputs(sys, d, t, false, d.x, d.v);
      if (const double gain = c.law_x(c.integral); gain != 0) d.x(c.integral) = (p * capacity - law(sys, d, l, d.x, d.v)) / gain;
    }
    const double s = d.S.row(c.supplies).dot(d.x);
    const std::string& element = sys.elements[static_cast<std::size_t>(c.supplies)].name;
    if (d.state[static_cast<std::size_t>(c.supplies)] == ElementState::stuck || slip_is_zero(d, c.supplies, s, speed_scale(d, d.x))) {
      error = c.name + " starts at t = " + detail::num(t) + " s while " + element + " does not slip; a slip controller "
              "takes over an element that slips (an on-coming one once it engages): start it then";
      return false;
    }
    if ((s > 0) != (c.torque_max > 0)) {
      error = c.name + " starts at t = " + detail::num(t) + " s while " + element + " slips at " + detail::num(s) +
              " rad/s, against its target's sign; give the target the sign of the slip";
      return false;
    }
  }
  return true;
}

// How far below its static capacity a brake or clutch released at this instant must find its torque
// to stick again within it, relative: when a signal it triggered starts (a slip controller's, bumpless,
// say), the mode is resolved again from the same state, and the stuck torques recomputed there differ
// from those that released it by the rounding of another order of operations (a few ulps of the
// largest torque, times the mode's condition), not by a change of the gear's state.
inline constexpr double kReleasedMargin = 1e-12;

// The consistent mode at time t, from d.x and the element states: every element that is stuck, or
// whose slip is zero (or just reached zero: `trigger`), is tried stuck; the one whose torque exceeds
// what it holds by the largest factor is released (slipping in its torque's direction) and the rest
// solved again, until every stuck torque is held. Elements released at an instant stay released
// within it, so the loop ends after at most one pass per element; `released`, those a resolution at
// the same instant released before a triggered signal started, stick again only below their
// capacity by more than kReleasedMargin. Sets d.mask and d.state, projects d.x onto the mode's
// constraints and reports each change of state; false (with `error`) when the stuck elements
// over-constrain the gear or an element chatters.
inline bool resolve_mode(const HybridSystem& sys, HybridData& d, double t, int trigger, const EventObserver& on_event,
                         std::string& error, std::uint32_t released = 0) {
  report_starts(sys, d, t, on_event);
  if (!start_slip_control(sys, d, t, error)) return false;
  d.old_state = d.state;
  std::uint32_t mask = 0;
  d.slip.noalias() = d.S * d.x;
  const double speed = speed_scale(d, d.x);
  // An element without command until the next breakpoint holds nothing: it is no candidate (at rest
  // every slip is zero, and open elements tried stuck could over-constrain the gear). A controller
  // is always tried within its limits: it leaves saturation whenever its law allows. A slip is zero
  // by the zero-slip rule (slip_is_zero), never by its rounding's sign.
  // A slip-controlled element whose slip is zero ends its control (kDone): it is tried stuck at full
  // command, and its controller is off, held at its limit 0.
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    if (is_slip_controller(sys, d, k) && d.phase[K] != kControlling) {
      d.dir[K] = limit(sys, d, k).torque_max == 0 ? 1 : -1;
      continue;
    }
    const bool zero = is_limit(d, k) || slip_is_zero(d, k, d.slip(k), speed);
    if (is_limit(d, k) || (!open_after(sys, d, k, t) && (d.state[K] == ElementState::stuck || zero || k == trigger))) {
      mask |= 1u << k;
      if (controlled(d, k)) d.phase[static_cast<std::size_t>(d.supplier[K])] = kDone;
    } else if (!zero) {
      d.dir[K] = d.slip(k) > 0 ? 1 : -1;
    }
  }
  for (int round = 0; round <= d.ne; ++round) {
    const auto& m = mode_of(sys, d.cache, mask);
    if (m.singular) {
      std::string names;
      for (int k : m.stuck) names += (names.empty() ? "" : ", ") + element_name(sys, d, k);
      error = m.ill_conditioned
                  ? "the stuck elements " + names + " join bodies of inertias too disparate for double precision " +
                        "to determine their torques at t = " + detail::num(t) +
                        " s; check the inertias (a tiny one beside a huge one)"
                  : "the stuck elements " + names + " constrain the gear more than once at t = " + detail::num(t) +
                        " s (their torques are undetermined); engage fewer elements at a time";
      return false;
    }
    for (int k = 0; k < d.ne; ++k)
      d.state[static_cast<std::size_t>(k)] = (mask >> k) & 1u ? ElementState::stuck : ElementState::slipping;
    const Eigen::VectorXd* x = &d.x;
    if (!m.stuck.empty()) {
      d.projected.noalias() = m.projector * d.x;
      x = &d.projected;
    }
    known_inputs(sys, d, t, false, *x, d.v);
    d.T.noalias() = m.Kx * *x;
    d.T.noalias() += m.Kv * d.v;
    int worst = -1;
    double worst_ratio = 1;
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      double ratio = overload(sys, d, m.stuck[j], d.T(static_cast<Eigen::Index>(j)), t, monitor_band(d, m.stuck[j], *x));
      if ((released >> m.stuck[j]) & 1u && !is_limit(d, m.stuck[j]) && ratio > 1 - kReleasedMargin) ratio = std::max(ratio, kJustBeyond);
      if (ratio > worst_ratio) {
        worst_ratio = ratio;
        worst = m.stuck[j];
      }
    }
    if (worst < 0) {
      d.mask = mask;
      if (!m.stuck.empty()) d.x.swap(d.projected);
      break;
    }
    const auto W = static_cast<std::size_t>(worst);
    for (std::size_t j = 0; j < m.stuck.size(); ++j)
      if (m.stuck[j] == worst) {
        const double Tw = d.T(static_cast<Eigen::Index>(j));
        d.dir[W] = is_limit(d, worst) ? (Tw > limit(sys, d, worst).torque_max ? 1 : -1) : (Tw > 0 ? 1 : -1);
      }
    mask &= ~(1u << worst);
  }
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    if (d.state[K] != ElementState::stuck && (open_after(sys, d, k, t) || off(sys, d, k))) d.state[K] = ElementState::open;
    if (d.old_state[K] != d.state[K]) {
      record(sys, d, t, k, d.old_state[K], d.state[K], on_event);
      if (++d.events_in_sample[K] > max_events_per_sample) {
        error = "chattering: " + element_name(sys, d, k) + " changed state more than " +
                std::to_string(max_events_per_sample) + " times within one sample period, at t = " + detail::num(t) +
                " s; shorten the sample period if the changes are real, or check the engagement commands";
        return false;
      }
    }
  }
  if (d.started_now) {  // each signal starts once, so this ends
    d.started_now = false;
    for (int k = 0; k < d.ne; ++k)
      if (const auto K = static_cast<std::size_t>(k); d.old_state[K] == ElementState::stuck && d.state[K] != ElementState::stuck)
        released |= 1u << k;
    return resolve_mode(sys, d, t, -1, on_event, error, released);
  }
  return true;
}

// Marks the elements with an event function over [t, t_end] (no breakpoint inside): those whose
// command is not zero throughout. The others are open from t on (a change of state reported), their
// direction that of their slip.
inline void watch(const HybridSystem& sys, HybridData& d, double t, double t_end, const EventObserver& on_event) {
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    const bool open = off(sys, d, k) || (command(sys, d, k, t) == 0 && command(sys, d, k, std::nextafter(t_end, t)) == 0);
    if (open && d.state[K] != ElementState::stuck) {
      const double s = d.S.row(k).dot(d.x);
      d.dir[K] = s > 0 ? 1 : s < 0 ? -1 : d.dir[K];
      if (d.state[K] != ElementState::open) {
        record(sys, d, t, k, d.state[K], ElementState::open, on_event);
        d.state[K] = ElementState::open;
      }
    }
    d.watched[K] = !open;
  }
}

inline bool any_watched(const HybridData& d) {
  return std::find(d.watched.begin(), d.watched.end(), 1) != d.watched.end();
}

}  // namespace pogear::rt::hybrid
