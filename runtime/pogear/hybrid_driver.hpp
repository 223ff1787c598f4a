// The hybrid engine's one driver loop, over any stepper within a mode (hybrid_exact.hpp,
// hybrid_adaptive.hpp): stop at the next breakpoint (or sample), step, detect, locate on the dense
// output, account energy, sample, resolve, restart.
#pragma once

#include <string>
#include <utility>

#include "pogear/hybrid_events.hpp"
#include "pogear/hybrid_mode_cache.hpp"
#include "pogear/hybrid_resolve.hpp"

namespace pogear::rt::hybrid {

// The sample at t: w with the stuck torques recovered for the state x, and the slips.
inline bool observe_sample(const HybridSystem& sys, HybridData& d, double t, const Eigen::VectorXd& x,
                           const Eigen::VectorXd& energy, const SampleObserver& obs) {
  const auto& m = mode_of(sys, d.cache, d.mask);
  known_inputs(sys, d, t, false, x, d.sample_w);
  if (!m.stuck.empty()) {
    d.T.head(m.Kx.rows()).setZero();
    detail::small_matvec_add(m.Kx, d.nx, x.data(), d.T.data());
    detail::small_matvec_add(m.Kv, d.nw, d.sample_w.data(), d.T.data());
    for (std::size_t j = 0; j < m.stuck.size(); ++j) d.sample_w(d.nu + m.stuck[j]) = d.T(static_cast<Eigen::Index>(j));
  }
  for (int k = 0; k < d.nf; ++k)  // a slip-controlled element carries its controller's torque
    if (controlled(d, k)) d.sample_w(d.nu + k) = d.sample_w(d.nu + d.supplier[static_cast<std::size_t>(k)]);
  d.sample_slip.setZero();
  detail::small_matvec_add(d.S, d.nx, x.data(), d.sample_slip.data());
  if (d.nm == 0) return obs(t, HybridSample{x, d.sample_w, d.sample_slip, energy, d.mask});
  // The monitors of crossings are the last elements: their torques end w, their heat (none) ends
  // the elements' part of the energy.
  const Eigen::Index shown = d.ne - d.nm, rest = energy.size() - d.ne;
  d.shown_w = d.sample_w.head(d.nw - d.nm);
  d.shown_slip = d.sample_slip.head(shown);
  d.shown_energy.head(shown) = energy.head(shown);
  d.shown_energy.tail(rest) = energy.tail(rest);
  return obs(t, HybridSample{x, d.shown_w, d.shown_slip, d.shown_energy, d.mask & ((1u << shown) - 1u)});
}

// Why the run cannot go on from state x (an untrusted exponential, a state not finite), or false.
inline bool unfit(const HybridData& d, const Eigen::VectorXd& x, std::string& error) {
  if (d.inaccurate) error = detail::inaccurate_exact_step(d.inaccurate->first, d.inaccurate->second);
  else if (!x.allFinite()) error = "the state is not finite";
  else return false;
  return true;
}

// Runs from the resolved mode at t = 0 (its sample observed) to the end of the grid, stepping with s.
template <class Stepper>
RunStatus run_modes(const HybridSystem& sys, HybridData& d, Stepper& s, const detail::Grid& grid,
                    const SampleObserver& obs, const EventObserver& on_event) {
  double t = 0;
  long k = 1;
  std::size_t next_break = 0;
  bool restart = true;
  std::string error;
  StepEnd e;
  auto fail = [&](double at) { return RunStatus{false, std::move(error), at}; };
  auto stopped = [](double at) { return RunStatus{false, "stopped", at}; };
  auto sampled = [&] {
    ++k;
    std::fill(d.events_in_sample.begin(), d.events_in_sample.end(), 0);
    d.locations_in_sample = 0;
  };
  // The samples in (t, t_new] of the step from t, or in (t, t_new) when `before` (a sample on a
  // breakpoint waits for the mode the breakpoint's commands resolve to). `end`: the step ends at t_new
  // (a stepper that lands on the samples has its sample there).
  auto emit = [&](double t_new, bool before, const StepEnd* end) {
    while (k < grid.count && (before ? grid.at(k) < t_new : grid.at(k) <= t_new)) {
      const double ts = grid.at(k);
      d.sample_energy = d.energy;
      bool go_on;
      if (end && (ts == t_new || Stepper::lands_on_samples)) {
        s.add_step_dissipation(t, *end, d.end, d.sample_energy);
        go_on = observe_sample(sys, d, t_new, d.end.x, d.sample_energy, obs);
      } else {
        s.sample_at(t, ts, d.sample_x, d.sample_energy);
        go_on = observe_sample(sys, d, ts, d.sample_x, d.sample_energy, obs);
      }
      if (!go_on) return false;
      sampled();
    }
    return true;
  };
  // A sample at the instant of an event or breakpoint sees the new mode.
  auto observe_instant = [&] {
    if (k >= grid.count || grid.at(k) != t) return true;
    if (!observe_sample(sys, d, t, d.x, d.energy, obs)) return false;
    sampled();
    return true;
  };
  while (k < grid.count) {
    while (next_break < d.breaks.size() && d.breaks[next_break] <= t) ++next_break;
    const bool before_break = next_break < d.breaks.size();
    double t_stop = before_break ? d.breaks[next_break] : d.horizon;
    if (Stepper::lands_on_samples) t_stop = before_break ? std::min(grid.at(k), t_stop) : grid.at(k);
    const bool stop_is_break = before_break && t_stop == d.breaks[next_break];
    const auto& m = mode_of(sys, d.cache, d.mask);
    if (restart || Stepper::restarts_each_step) {
      watch(sys, d, t, t_stop, on_event);
      s.start(t, t_stop, stop_is_break);
      known_inputs(sys, d, t, false, d.x, d.v0);
      event_values(sys, d, m, d.x, d.v0, t, false, d.g0);
      restart = false;
    }
    int hit = -1;
    for (;;) {  // a step, shortened while an event function may dip within it
      if (!s.step(t, d.v0, d.end, e, error)) return fail(t);
      if (e.clear) break;
      event_values(sys, d, m, d.end.x, d.end.v, e.t1, e.before, d.end.g);
      hit = crossing(d, d.g0, d.end.g);
      if (hit < 0 && s.can_shorten() &&
          may_dip(sys, d, m, t, e.theta, e.before, d.x, d.v0, d.g0, d.end.x, d.end.v, d.end.g)) {
        s.shorten();
        continue;
      }
      break;
    }
    auto at = [&](double theta, EventPoint& p) {
      s.point(t, theta, p);
      event_values(sys, d, m, p.x, p.v, t + theta, false, p.g);
    };
    double a = 0, b = e.theta;
    // Points of the dense output in increasing time, each against the last one seen clear (prev,
    // its functions *g_a): the first that has crossed closes the bracket [prev, theta].
    double prev = 0;
    const Eigen::VectorXd* g_a = &d.g0;
    auto probe = [&](double theta) {
      at(theta, d.mid);
      hit = crossing(d, *g_a, d.mid.g);
      if (hit >= 0) {
        a = prev;
        b = theta;
        std::swap(d.end, d.mid);
        return;
      }
      d.g_a = d.mid.g;
      g_a = &d.g_a;
      prev = theta;
    };
    if (hit < 0 && !e.clear && Stepper::scans_for_dips &&
        may_dip(sys, d, m, t, e.theta, e.before, d.x, d.v0, d.g0, d.end.x, d.end.v, d.end.g))
      for (int i = 1; i < 8 && hit < 0; ++i) probe(e.theta * i / 8);  // the dense output at 8 points
    if (hit < 0 && !e.clear && !Stepper::lands_on_samples && any_watched(d)) {
      // The samples within the step, from its start: no sample may show a mode past its event (a
      // stuck torque beyond its capacity), even where the ends and the scan saw none.
      prev = 0;
      g_a = &d.g0;
      for (long j = k; hit < 0 && j < grid.count && grid.at(j) < e.t1; ++j) probe(grid.at(j) - t);
    }
    if (hit < 0) {
      if (!e.before && unfit(d, d.end.x, error)) return fail(e.t1);
      if (!emit(e.t1, e.before, &e)) return stopped(e.t1);
      s.add_step_dissipation(t, e, d.end, d.energy);
      s.step_accepted();
      d.x.swap(d.end.x);
      t = e.t1;
      std::swap(d.v0, d.end.v);
      std::swap(d.g0, d.end.g);
      if (e.before) {
        if (!resolve_mode(sys, d, t, -1, on_event, error) || unfit(d, d.x, error)) return fail(t);
        restart = true;
        if (!observe_instant()) return stopped(t);
      }
      continue;
    }
    if (!count_location(d, t, error)) return fail(t);
    const int element = locate_event(d, t, a, b, *g_a, d.end, d.mid, d.side, at);
    const double te = t + b;
    if (!emit(te, true, nullptr)) return stopped(te);
    s.add_dissipation_to(t, b, d.end, d.energy);
    d.x = d.end.x;
    t = te;
    s.event_located();
    if (!resolve_mode(sys, d, t, element, on_event, error) || unfit(d, d.x, error)) return fail(t);
    restart = true;
    if (!observe_instant()) return stopped(t);
  }
  return RunStatus{true, "", t};
}

}  // namespace pogear::rt::hybrid
