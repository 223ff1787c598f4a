// Brakes and clutches in a run: stick–slip friction as modes of a linear system (the set of stuck
// elements), exact stepping within a mode, and events located on the exact trajectory.
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <string>
#include <utility>
#include <vector>

#include "pogear/driver_loops.hpp"
#include "pogear/hybrid_modes.hpp"
#include "pogear/run_support.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

enum class ElementState { open, slipping, stuck };
inline const char* state_name(ElementState s) {
  return s == ElementState::open ? "open" : s == ElementState::slipping ? "slipping" : "stuck";
}

struct HybridEvent {
  double t = 0;
  int element = 0;
  ElementState from = ElementState::open, to = ElementState::open;
};

// What the run knows at a sample: state, the full input w (stuck torques recovered), slips, the
// energy each element has dissipated, and the mode (bit k set when element k is stuck).
struct HybridSample {
  const Eigen::VectorXd& x;
  const Eigen::VectorXd& w;
  const Eigen::VectorXd& slip;
  const Eigen::VectorXd& energy;
  std::uint32_t mode;
};

// Chattering guard: a run stops when one element changes state more often than this within one
// sample period, or more than this many times (elements + 1) events are located within one.
// Physical shifts change each element a few times in a whole run; a Zeno sequence exceeds any bound.
inline constexpr int max_events_per_sample = 100;

// The hybrid run: owns the modes it has met and their discretizations; steps, locates events and
// resolves modes. One object per run (not shared between threads).
class HybridEngine {
 public:
  HybridEngine(const HybridSystem& sys, double horizon) : sys_(sys), horizon_(horizon) {
    ne_ = static_cast<int>(sys.S.rows());
    nx_ = sys.M.rows();
    nu_ = static_cast<Eigen::Index>(sys.inputs.size());
    nw_ = nu_ + ne_;
  }

  // Integrates from x0 at t = 0 to the horizon, landing on every sample time (obs is called there,
  // t = 0 included, and may return false to stop) and every breakpoint of the inputs and commands.
  // on_event is called for every change of an element's state. Fails the run on a non-finite state,
  // an over-constrained set of stuck elements, or chattering.
  template <class Obs, class OnEvent>
  RunStatus run(const Eigen::VectorXd& x0, double sample, Obs&& obs, OnEvent&& on_event) {
    std::vector<Signal> all = sys_.inputs;
    for (const auto& e : sys_.elements) all.push_back(e.command);
    breaks_ = breakpoints(all, 0.0, horizon_);
    x_ = x0;
    energy_ = Eigen::VectorXd::Zero(ne_);
    dir_.assign(static_cast<std::size_t>(ne_), 0);
    state_.assign(static_cast<std::size_t>(ne_), ElementState::open);
    mask_ = 0;
    double t = 0;
    if (!(sample > 0) || !(horizon_ / sample < 0x1p62)) return fail("invalid sample period", t);
    // The sample times of every other driver, so that the CSV rows of all runs of a scene align.
    const detail::Grid grid = detail::sample_grid(0.0, horizon_, sample);
    std::size_t next_break = 0;
    std::string error;
    events_in_sample_.assign(static_cast<std::size_t>(ne_), 0);
    locations_in_sample_ = 0;
    // The initial mode is where the run starts, not an event.
    auto no_event = [](const HybridEvent&) {};
    if (!resolve(t, -1, no_event, error)) return fail(error, t);
    if (!observe(t, obs)) return RunStatus{false, "stopped", t};
    for (long k = 1; k < grid.count; ++k) {
      const double t_sample = grid.at(k);
      events_in_sample_.assign(static_cast<std::size_t>(ne_), 0);
      locations_in_sample_ = 0;
      while (t < t_sample) {
        while (next_break < breaks_.size() && breaks_[next_break] <= t) ++next_break;
        const double t_end = next_break < breaks_.size() ? std::min(t_sample, breaks_[next_break]) : t_sample;
        if (!step_to(t, t_end, on_event, error)) return fail(error, t);
        if (!x_.allFinite()) return fail("the state is not finite", t);
      }
      if (!observe(t, obs)) return RunStatus{false, "stopped", t};
    }
    return RunStatus{true, "", t};
  }

  int modes_met() const { return static_cast<int>(modes_.size()); }
  long steps() const { return steps_; }

 private:
  using Modes = std::map<std::uint32_t, hybrid_detail::ModeMatrices>;

  static RunStatus fail(const std::string& why, double t) { return RunStatus{false, why, t}; }

  const hybrid_detail::ModeMatrices& mode_of(std::uint32_t mask) {
    auto it = modes_.find(mask);
    if (it == modes_.end()) it = modes_.emplace(mask, hybrid_detail::mode_matrices(sys_, mask)).first;
    return it->second;
  }

  const ExactMatrices& discretization(std::uint32_t mask, double h) {
    const auto key = std::make_pair(mask, h);
    auto it = discretizations_.find(key);
    if (it == discretizations_.end()) {
      // Uneven steps after events: keep the cache bounded.
      if (discretizations_.size() > 64) discretizations_.clear();
      const auto& m = mode_of(mask);
      it = discretizations_.emplace(key, exact_matrices(m.augmented_A, m.augmented_B, h)).first;
    }
    return it->second;
  }

  double command(int k, double t) const { return value(sys_.elements[static_cast<std::size_t>(k)].command, t); }

  // The torque per unit command of element k while it slips: its capacity, or zero for a one-way
  // element overrunning in its free direction.
  double torque_scale(int k) const {
    const auto K = static_cast<std::size_t>(k);
    return sys_.elements[K].one_way && dir_[K] > 0 ? 0.0 : sys_.elements[K].capacity;
  }

  // Whether element k's command is zero from t until the next breakpoint (it is linear there).
  bool open_after(int k, double t) const {
    const auto next = std::upper_bound(breaks_.begin(), breaks_.end(), t);
    const double t_next = next == breaks_.end() ? std::max(horizon_, t) : *next;
    return command(k, t) == 0 && command(k, t + 0.5 * (t_next - t)) == 0;
  }

  // w at time t: the inputs, slipping torques c p(t) dir, stuck torques left at zero. `before` asks
  // for the left limit (a step that ends on a breakpoint).
  Eigen::VectorXd known_inputs(double t, bool before) const {
    const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
    Eigen::VectorXd v(nw_);
    for (Eigen::Index i = 0; i < nu_; ++i) v(i) = value(sys_.inputs[static_cast<std::size_t>(i)], at);
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      // + 0.0: an open element's torque is 0, not -0, in the CSV.
      v(nu_ + k) = state_[K] == ElementState::stuck ? 0.0 : torque_scale(k) * command(k, at) * dir_[K] + 0.0;
    }
    return v;
  }

  // w with the stuck torques recovered, for the state x.
  Eigen::VectorXd full_inputs(const hybrid_detail::ModeMatrices& m, const Eigen::VectorXd& x, Eigen::VectorXd v) const {
    if (!m.stuck.empty()) {
      const Eigen::VectorXd T = m.Kx * x + m.Kv * v;
      for (std::size_t j = 0; j < m.stuck.size(); ++j) v(nu_ + m.stuck[j]) = T(static_cast<Eigen::Index>(j));
    }
    return v;
  }

  template <class Obs>
  bool observe(double t, Obs& obs) {
    const auto& m = mode_of(mask_);
    const Eigen::VectorXd w = full_inputs(m, x_, known_inputs(t, false));
    const Eigen::VectorXd slip = sys_.S * x_;
    return obs(t, HybridSample{x_, w, slip, energy_, mask_});
  }

  // Event functions of the current mode at state x and known inputs v, time t: slipping elements
  // dir * slip (an event when it reaches zero), stuck elements the static capacity less |T| (an event
  // when it goes negative). Elements without a function (open over the step) give +inf.
  Eigen::VectorXd event_values(const hybrid_detail::ModeMatrices& m, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                               double t, bool before, const std::vector<char>& watched) const {
    const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
    Eigen::VectorXd g = Eigen::VectorXd::Constant(ne_, std::numeric_limits<double>::infinity());
    Eigen::VectorXd T;
    if (!m.stuck.empty()) T = m.Kx * x + m.Kv * v;
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      const int k = m.stuck[j];
      const auto& e = sys_.elements[static_cast<std::size_t>(k)];
      const double Tk = T(static_cast<Eigen::Index>(j));
      g(k) = e.static_ratio * e.capacity * command(k, at) - std::abs(Tk);
      if (e.one_way) g(k) = std::min(g(k), -Tk);  // a one-way element lets go when T turns positive
    }
    for (int k = 0; k < ne_; ++k)
      if (watched[static_cast<std::size_t>(k)] && state_[static_cast<std::size_t>(k)] != ElementState::stuck)
        g(k) = dir_[static_cast<std::size_t>(k)] * sys_.S.row(k).dot(x);
    return g;
  }

  // Time derivatives of the event functions (for the check between the ends of a step).
  // dv: the known inputs' slope over the step; p, dp: the commands there and their slopes.
  Eigen::VectorXd event_rates(const hybrid_detail::ModeMatrices& m, const Eigen::VectorXd& x, const Eigen::VectorXd& v,
                              const Eigen::VectorXd& dv, const Eigen::VectorXd& p, const Eigen::VectorXd& dp,
                              const std::vector<char>& watched) const {
    const Eigen::VectorXd dx = m.A * x + m.B * v;
    Eigen::VectorXd r = Eigen::VectorXd::Zero(ne_);
    if (!m.stuck.empty()) {
      const Eigen::VectorXd T = m.Kx * x + m.Kv * v, dT = m.Kx * dx + m.Kv * dv;
      for (std::size_t j = 0; j < m.stuck.size(); ++j) {
        const int k = m.stuck[j];
        const auto& e = sys_.elements[static_cast<std::size_t>(k)];
        const auto J = static_cast<Eigen::Index>(j);
        const double margin = e.static_ratio * e.capacity * p(k) - std::abs(T(J));
        r(k) = e.one_way && -T(J) < margin ? -dT(J) : e.static_ratio * e.capacity * dp(k) - (T(J) < 0 ? -dT(J) : dT(J));
      }
    }
    for (int k = 0; k < ne_; ++k)
      if (watched[static_cast<std::size_t>(k)] && state_[static_cast<std::size_t>(k)] != ElementState::stuck)
        r(k) = dir_[static_cast<std::size_t>(k)] * sys_.S.row(k).dot(dx);
    return r;
  }

  // One step of the current mode from t0 over h: the augmented state [x; sigma; rho] at t0 + h.
  Eigen::VectorXd advance(const ExactMatrices& d, const Eigen::VectorXd& v0, const Eigen::VectorXd& v1) const {
    Eigen::VectorXd z = Eigen::VectorXd::Zero(d.Phi.rows());
    z.head(nx_) = x_;
    return d.Phi * z + d.Gamma0 * v0 + d.Gamma1 * (v1 - v0);
  }

  // Adds each slipping element's dissipated energy over [t0, t0 + h]: with p(t0 + s) = p0 + (p1 - p0)
  // s / h, int c p dir s dt = c dir (p1 sigma(h) - (p1 - p0) rho(h) / h), sigma and rho the augmented
  // integrals of the slip (zero at t0). Exact when p is linear over the step.
  void energy_step(const Eigen::VectorXd& z, double t0, double h, bool before) {
    const double t1 = t0 + h;
    const double at1 = before ? std::nextafter(t1, -std::numeric_limits<double>::infinity()) : t1;
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (state_[K] == ElementState::stuck) continue;
      const double p0 = command(k, t0), p1 = command(k, at1);
      const double sigma = z(nx_ + k), rho = z(nx_ + ne_ + k);
      energy_(k) += torque_scale(k) * dir_[K] * (p1 * sigma - (p1 - p0) * rho / h);
    }
  }

  // Whether the cubic through g0, g1 with slopes r0, r1 (over a step h) dips to zero or below
  // between its ends: then the step is split, as the function may cross zero twice within it.
  static bool dips_between(double g0, double g1, double r0, double r1, double h) {
    if (!(g0 > 0 && g1 > 0) || !std::isfinite(g0) || !std::isfinite(g1)) return false;
    if (r0 >= 0 && r1 <= 0) return false;  // rises then falls: no interior minimum
    // Hermite form on s in [0, 1]: q(s) = h00 g0 + h10 h r0 + h01 g1 + h11 h r1.
    const double d0 = h * r0, d1 = h * r1;
    // q'(s) = a s^2 + b s + c
    const double a = 6 * g0 + 3 * d0 - 6 * g1 + 3 * d1, b = -6 * g0 - 4 * d0 + 6 * g1 - 2 * d1, c = d0;
    auto q = [&](double s) {
      const double s2 = s * s, s3 = s2 * s;
      return (2 * s3 - 3 * s2 + 1) * g0 + (s3 - 2 * s2 + s) * d0 + (-2 * s3 + 3 * s2) * g1 + (s3 - s2) * d1;
    };
    double roots[2];
    int n = 0;
    if (std::abs(a) < 1e-300) {
      if (b != 0) roots[n++] = -c / b;
    } else {
      const double disc = b * b - 4 * a * c;
      if (disc >= 0) {
        const double sq = std::sqrt(disc);
        roots[n++] = (-b - sq) / (2 * a);
        roots[n++] = (-b + sq) / (2 * a);
      }
    }
    for (int i = 0; i < n; ++i)
      if (roots[i] > 0 && roots[i] < 1 && q(roots[i]) <= 0) return true;
    return false;
  }

  // Steps from t to t_end (t_end a sample time or a breakpoint), stopping at the first event within
  // it. On return t is t_end, or the event's time with the new mode resolved.
  template <class OnEvent>
  bool step_to(double& t, double t_end, OnEvent& on_event, std::string& error) {
    const bool lands_on_break = std::binary_search(breaks_.begin(), breaks_.end(), t_end);
    // Elements whose command is zero over the whole step are open: no event function.
    std::vector<char> watched(static_cast<std::size_t>(ne_), 0);
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      const bool open = command(k, t) == 0 && command(k, std::nextafter(t_end, t)) == 0;
      if (open && state_[K] != ElementState::stuck) {
        const double s = sys_.S.row(k).dot(x_);
        dir_[K] = s > 0 ? 1 : s < 0 ? -1 : dir_[K];
        if (state_[K] != ElementState::open) {
          record(t, k, state_[K], ElementState::open, on_event);
          state_[K] = ElementState::open;
        }
      }
      watched[K] = !open;
    }
    double h = t_end - t;
    for (int depth = 0;; ++depth) {
      const auto& m = mode_of(mask_);
      const ExactMatrices& d = discretization(mask_, h);
      const double t1 = t + h;
      const bool before = lands_on_break && t1 == t_end;
      const Eigen::VectorXd v0 = known_inputs(t, false), v1 = known_inputs(t1, before);
      const Eigen::VectorXd z = advance(d, v0, v1);
      ++steps_;
      const Eigen::VectorXd x1 = z.head(nx_);
      const Eigen::VectorXd g0 = event_values(m, x_, v0, t, false, watched);
      const Eigen::VectorXd g1 = event_values(m, x1, v1, t1, before, watched);
      int hit = -1;
      for (int k = 0; k < ne_; ++k) {
        const bool stuck = state_[static_cast<std::size_t>(k)] == ElementState::stuck;
        if (stuck ? g1(k) < 0 : g1(k) < 0 || (g1(k) == 0 && g0(k) > 0)) hit = k;
      }
      bool split = false;
      if (hit < 0 && depth < 30) {
        const Eigen::VectorXd dv = (v1 - v0) / h;
        Eigen::VectorXd p0(ne_), p1(ne_);
        for (int k = 0; k < ne_; ++k) {
          p0(k) = command(k, t);
          p1(k) = command(k, before ? std::nextafter(t1, t) : t1);
        }
        const Eigen::VectorXd dp = (p1 - p0) / h;
        const Eigen::VectorXd r0 = event_rates(m, x_, v0, dv, p0, dp, watched);
        const Eigen::VectorXd r1 = event_rates(m, x1, v1, dv, p1, dp, watched);
        for (int k = 0; k < ne_ && !split; ++k) split = dips_between(g0(k), g1(k), r0(k), r1(k), h);
      }
      if (split) {
        h *= 0.5;
        continue;
      }
      if (hit < 0) {
        energy_step(z, t, h, before);
        x_ = x1;
        t = t1 == t_end ? t_end : t1;
        if (t == t_end && lands_on_break) return resolve(t, -1, on_event, error);
        return true;
      }
      return locate_and_switch(t, h, before, watched, on_event, error);
    }
  }

  // The earliest event in (t, t + h]: Illinois iteration on the earliest event function that
  // changes sign, each value from the mode's exponential at theta (exact up to rounding). The event
  // is placed at the first representable time where the function has crossed; the state there
  // becomes the current state and the mode is resolved.
  template <class OnEvent>
  bool locate_and_switch(double& t, double h, bool before_end, const std::vector<char>& watched, OnEvent& on_event,
                         std::string& error) {
    if (++locations_in_sample_ > max_events_per_sample * (ne_ + 1)) {
      error = "chattering: more than " + std::to_string(max_events_per_sample * (ne_ + 1)) +
              " events within one sample period, at t = " + detail::num(t) +
              " s; shorten the sample period if the changes are real, or check the engagement commands";
      return false;
    }
    const auto& m = mode_of(mask_);
    const Eigen::VectorXd v0 = known_inputs(t, false);
    struct Point {
      Eigen::VectorXd z, g;
      Eigen::VectorXd v;
    };
    auto at = [&](double theta, bool before) {
      const ExactMatrices d = exact_matrices(m.augmented_A, m.augmented_B, theta);
      Point p;
      p.v = known_inputs(t + theta, before);
      p.z = advance(d, v0, p.v);
      p.g = event_values(m, p.z.head(nx_), p.v, t + theta, before, watched);
      return p;
    };
    auto crossed = [&](const Eigen::VectorXd& g, int k) {
      return state_[static_cast<std::size_t>(k)] == ElementState::stuck ? g(k) < 0 : g(k) <= 0;
    };
    // The earliest crossing among several: shrink the bracket to the first function that crosses.
    double a = 0, b = h;
    Point pb = at(b, before_end);
    const Eigen::VectorXd g0 = event_values(m, x_, v0, t, false, watched);
    int k = -1;
    for (int i = 0; i < ne_; ++i)
      if (crossed(pb.g, i) && (k < 0 || pb.g(i) / (pb.g(i) - g0(i)) > pb.g(k) / (pb.g(k) - g0(k)))) k = i;
    double ga = g0(k), gb = pb.g(k);
    int side = 0;
    for (int iter = 0; iter < 200; ++iter) {
      const double tol = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t + b));
      if (b - a <= tol) break;
      double c = ga > 0 && std::isfinite(ga) && gb < ga ? b - gb * (b - a) / (gb - ga) : 0.5 * (a + b);
      if (!(c > a + 0.01 * tol && c < b - 0.01 * tol)) c = 0.5 * (a + b);
      if (ga == 0) c = 0.5 * (a + b);  // a just-released element: no secant from a zero
      Point pc = at(c, false);
      // Another element crossing before k's root: it is the earliest one now.
      int first = -1;
      for (int i = 0; i < ne_; ++i)
        if (crossed(pc.g, i)) first = (first < 0 || i == k) ? i : first;
      if (first >= 0) {
        if (first != k && !crossed(pc.g, k)) {  // keeps the bracket: nothing had crossed at a
          k = first;
          ga = a > 0 ? at(a, false).g(k) : g0(k);
          side = 0;
        }
        b = c;
        gb = pc.g(k);
        pb = std::move(pc);
        if (side == -1) ga *= 0.5;  // Illinois: the retained end's value halved
        side = -1;
      } else {
        a = c;
        ga = pc.g(k);
        if (side == 1) gb *= 0.5;
        side = 1;
      }
    }
    energy_step(pb.z, t, b, false);
    x_ = pb.z.head(nx_);
    t = t + b;
    return resolve(t, k, on_event, error);
  }

  template <class OnEvent>
  void record(double t, int k, ElementState from, ElementState to, OnEvent& on_event) {
    if (from == to) return;
    on_event(HybridEvent{t, k, from, to});
  }

  // The consistent mode at time t: every element that is stuck, or whose slip is zero (or just
  // reached zero: `trigger`), is tried stuck; the one whose torque exceeds its static capacity by
  // the largest factor is released (slipping in its torque's direction) and the rest solved again,
  // until every stuck torque is within capacity. Elements released at an instant stay released
  // within it, so the loop ends after at most one pass per element.
  template <class OnEvent>
  bool resolve(double t, int trigger, OnEvent& on_event, std::string& error) {
    const std::vector<ElementState> old = state_;
    std::uint32_t mask = 0;
    const Eigen::VectorXd slip = sys_.S * x_;
    // An element without command until the next breakpoint holds nothing: it is no candidate (at
    // rest every slip is zero, and open elements tried stuck could over-constrain the gear).
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (!open_after(k, t) && (state_[K] == ElementState::stuck || slip(k) == 0 || k == trigger)) mask |= 1u << k;
      else if (slip(k) != 0) dir_[K] = slip(k) > 0 ? 1 : -1;
    }
    for (int round = 0; round <= ne_; ++round) {
      const auto& m = mode_of(mask);
      if (m.singular) {
        std::string names;
        for (int k : m.stuck) names += (names.empty() ? "" : ", ") + sys_.elements[static_cast<std::size_t>(k)].name;
        error = "the stuck elements " + names + " constrain the gear more than once at t = " + detail::num(t) +
                " s (their torques are undetermined); engage fewer elements at a time";
        return false;
      }
      for (int k = 0; k < ne_; ++k)
        state_[static_cast<std::size_t>(k)] = (mask >> k) & 1u ? ElementState::stuck : ElementState::slipping;
      Eigen::VectorXd v = known_inputs(t, false);
      const Eigen::VectorXd T = m.Kx * project(m, x_) + m.Kv * v;
      int worst = -1;
      double worst_ratio = 1;
      for (std::size_t j = 0; j < m.stuck.size(); ++j) {
        const int k = m.stuck[j];
        const auto& e = sys_.elements[static_cast<std::size_t>(k)];
        const double limit = e.static_ratio * e.capacity * command(k, t);
        const double Tj = std::abs(T(static_cast<Eigen::Index>(j)));
        double ratio = limit > 0 ? Tj / limit : (Tj > 0 ? std::numeric_limits<double>::infinity() : 0.0);
        if (e.one_way && T(static_cast<Eigen::Index>(j)) > 0) ratio = std::numeric_limits<double>::infinity();
        if (ratio > worst_ratio) {
          worst_ratio = ratio;
          worst = k;
        }
      }
      if (worst < 0) {
        mask_ = mask;
        x_ = project(m, x_);
        break;
      }
      const auto W = static_cast<std::size_t>(worst);
      for (std::size_t j = 0; j < m.stuck.size(); ++j)
        if (m.stuck[j] == worst) dir_[W] = T(static_cast<Eigen::Index>(j)) > 0 ? 1 : -1;
      mask &= ~(1u << worst);
    }
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (state_[K] != ElementState::stuck && open_after(k, t)) state_[K] = ElementState::open;
      if (old[K] != state_[K]) {
        record(t, k, old[K], state_[K], on_event);
        if (++events_in_sample_[K] > max_events_per_sample) {
          error = "chattering: " + sys_.elements[K].name + " changed state more than " +
                  std::to_string(max_events_per_sample) + " times within one sample period, at t = " + detail::num(t) +
                  " s; shorten the sample period if the changes are real, or check the engagement commands";
          return false;
        }
      }
    }
    return true;
  }

  Eigen::VectorXd project(const hybrid_detail::ModeMatrices& m, const Eigen::VectorXd& x) const {
    return m.stuck.empty() ? x : Eigen::VectorXd(m.projector * x);
  }

  const HybridSystem& sys_;
  double horizon_;
  int ne_ = 0;
  Eigen::Index nx_ = 0, nu_ = 0, nw_ = 0;
  std::vector<double> breaks_;
  Eigen::VectorXd x_, energy_;
  std::vector<int> dir_;
  std::vector<ElementState> state_;
  std::uint32_t mask_ = 0;
  std::vector<int> events_in_sample_;
  int locations_in_sample_ = 0;
  long steps_ = 0;
  Modes modes_;
  std::map<std::pair<std::uint32_t, double>, ExactMatrices> discretizations_;
};

}  // namespace pogear::rt
