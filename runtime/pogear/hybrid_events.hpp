// The event functions of a mode (one per element: a slipping element's slip reaching zero, a stuck
// element's torque reaching its static capacity, a controller reaching or leaving a limit), their
// rates, and the location of the earliest event on any dense output (an Illinois iteration).
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "pogear/hybrid_inputs.hpp"

namespace pogear::rt::hybrid {

// The event functions g of mode m at state x and known inputs v, time t: slipping elements dir *
// slip (an event when it reaches zero), stuck elements the static capacity less |T| (an event when it
// goes negative), a controller within its limits the margin to the nearer one, a saturated one how
// far its law lies beyond the limit it holds. Elements without a function (open over the step) +inf.
inline void event_values(const HybridSystem& sys, HybridData& d, const ModeMatrices& m, const Eigen::VectorXd& x,
                         const Eigen::VectorXd& v, double t, bool before, Eigen::VectorXd& g) {
  const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
  g.setConstant(d.ne, std::numeric_limits<double>::infinity());
  if (!m.stuck.empty()) {
    d.T.noalias() = m.Kx * x;
    d.T.noalias() += m.Kv * v;
  }
  for (std::size_t j = 0; j < m.stuck.size(); ++j) {
    const int k = m.stuck[j];
    const double Tk = d.T(static_cast<Eigen::Index>(j));
    if (is_limit(d, k)) {
      const auto [above, below] = limit_margins(sys, d, k, Tk, monitor_band(d, k, x));
      g(k) = std::min(above, below);
      continue;
    }
    const auto& e = sys.elements[static_cast<std::size_t>(k)];
    g(k) = e.static_ratio * e.capacity * command(sys, d, k, at) - std::abs(Tk);
    if (e.one_way) g(k) = std::min(g(k), -Tk);  // a one-way element lets go when T turns positive
  }
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    if (!d.watched[K] || d.state[K] == ElementState::stuck) continue;
    g(k) = is_limit(d, k) ? d.dir[K] * (law(sys, d, k, x, v) - held_torque(sys, d, k)) : d.dir[K] * d.S.row(k).dot(x);
  }
}

// The event functions' time derivatives r at x and v, the known inputs' slope dv, the commands p and
// their slopes dp.
inline void event_rates(const HybridSystem& sys, HybridData& d, const ModeMatrices& m, double t, bool before,
                        const Eigen::VectorXd& x, const Eigen::VectorXd& v, const Eigen::VectorXd& p, Eigen::VectorXd& r) {
  d.dx.noalias() = m.A * x;
  d.dx.noalias() += m.B * v;
  state_torque_slopes(sys, d, t, before, x, d.dx, d.dv);
  r.setZero(d.ne);
  if (!m.stuck.empty()) {
    d.T.noalias() = m.Kx * x;
    d.T.noalias() += m.Kv * v;
    d.dT.noalias() = m.Kx * d.dx;
    d.dT.noalias() += m.Kv * d.dv;
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      const int k = m.stuck[j];
      const auto J = static_cast<Eigen::Index>(j);
      if (is_limit(d, k)) {
        r(k) = limit(sys, d, k).torque_max - d.T(J) < d.T(J) - limit(sys, d, k).torque_min ? -d.dT(J) : d.dT(J);
        continue;
      }
      const auto& e = sys.elements[static_cast<std::size_t>(k)];
      const double margin = e.static_ratio * e.capacity * p(k) - std::abs(d.T(J));
      r(k) = e.one_way && -d.T(J) < margin ? -d.dT(J)
                                           : e.static_ratio * e.capacity * d.dp(k) - (d.T(J) < 0 ? -d.dT(J) : d.dT(J));
    }
  }
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    if (!d.watched[K] || d.state[K] == ElementState::stuck) continue;
    r(k) = is_limit(d, k) ? d.dir[K] * (limit(sys, d, k).law_x.dot(d.dx) + limit(sys, d, k).law_w.dot(d.dv))
                          : d.dir[K] * d.S.row(k).dot(d.dx);
  }
}

// Whether element k's function has crossed at g: a stuck element's margin is negative, a slip has
// reached zero or changed sign.
inline bool crossed(const HybridData& d, const Eigen::VectorXd& g, int k) {
  return d.state[static_cast<std::size_t>(k)] == ElementState::stuck ? g(k) < 0 : g(k) <= 0;
}

// The element whose event function crossed over a step (g0 at its start, g1 at its end), or -1.
inline int crossing(const HybridData& d, const Eigen::VectorXd& g0, const Eigen::VectorXd& g1) {
  int hit = -1;
  for (int k = 0; k < d.ne; ++k) {
    const bool stuck = d.state[static_cast<std::size_t>(k)] == ElementState::stuck;
    if (stuck ? g1(k) < 0 : g1(k) < 0 || (g1(k) == 0 && g0(k) > 0)) hit = k;
  }
  return hit;
}

// Whether an event function, positive at both ends of the step [t, t + h] (x0, v0, g0 and x1, v1,
// g1 there), may dip to zero in between: its cubic through the ends' values and rates does. The rates
// take the inputs' own slopes at each end: a sine's secant over the step would flatten the very
// swing that drives a stuck element's torque across its capacity.
inline bool may_dip(const HybridSystem& sys, HybridData& d, const ModeMatrices& m, double t, double h, bool before,
                    const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, const Eigen::VectorXd& g0,
                    const Eigen::VectorXd& x1, const Eigen::VectorXd& v1, const Eigen::VectorXd& g1) {
  const double t1 = t + h;
  for (int k = 0; k < d.ne; ++k) {
    d.p0(k) = command(sys, d, k, t);
    d.p1(k) = command(sys, d, k, before ? std::nextafter(t1, t) : t1);
  }
  d.dp = (d.p1 - d.p0) / h;
  known_input_slopes(sys, d, t, false, d.dv);
  event_rates(sys, d, m, t, false, x0, v0, d.p0, d.r0);
  known_input_slopes(sys, d, t1, before, d.dv);
  event_rates(sys, d, m, t1, before, x1, v1, d.p1, d.r1);
  for (int k = 0; k < d.ne; ++k)
    if (cubic_dips(g0(k), g1(k), d.r0(k), d.r1(k), h)) return true;
  return false;
}

// The chattering guard on located events (see max_events_per_sample).
inline bool count_location(HybridData& d, double t, std::string& error) {
  if (++d.locations_in_sample <= max_events_per_sample * (d.ne + 1)) return true;
  error = "chattering: more than " + std::to_string(max_events_per_sample * (d.ne + 1)) +
          " events within one sample period, at t = " + detail::num(t) +
          " s; shorten the sample period if the changes are real, or check the engagement commands";
  return false;
}

// Where a step ended: at t1 = t + theta (or on the stop itself), the left limit of a breakpoint
// (`before`), and whether its stepper proved it free of events (the exact method's whole-period
// proof: nothing to detect).
struct StepEnd {
  double t1 = 0, theta = 0;
  bool before = false, clear = false;
};

// The earliest event in (t + a, t + b], g_a the event functions at t + a and pb the point at t + b,
// where some function has crossed: an Illinois iteration on the earliest function that changes
// sign (SciPy's solve_event_equation, on several functions at once), at(theta, p) filling the point
// at t + theta from any dense output. Returns the element; b and pb become the first representable
// time where its function has crossed (to 4 ulps) and the point there. pc and pa are scratch.
template <class At>
int locate_event(const HybridData& d, double t, double& a, double& b, const Eigen::VectorXd& g_a, EventPoint& pb,
                 EventPoint& pc, EventPoint& pa, At&& at) {
  // The earliest crossing among several: shrink the bracket to the first function that crosses.
  const double a0 = a;
  int k = -1;
  for (int i = 0; i < d.ne; ++i)
    if (crossed(d, pb.g, i) && (k < 0 || pb.g(i) / (pb.g(i) - g_a(i)) > pb.g(k) / (pb.g(k) - g_a(k)))) k = i;
  double ga = g_a(k), gb = pb.g(k);
  int side = 0;
  for (int iter = 0; iter < 200; ++iter) {
    const double tol = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t + b));
    if (b - a <= tol) break;
    double c = ga > 0 && std::isfinite(ga) && gb < ga ? b - gb * (b - a) / (gb - ga) : 0.5 * (a + b);
    if (!(c > a + 0.01 * tol && c < b - 0.01 * tol)) c = 0.5 * (a + b);
    if (ga == 0) c = 0.5 * (a + b);  // a just-released element: no secant from a zero
    at(c, pc);
    // Another element crossing before k's root: it is the earliest one now.
    int first = -1;
    for (int i = 0; i < d.ne; ++i)
      if (crossed(d, pc.g, i)) first = (first < 0 || i == k) ? i : first;
    if (first >= 0) {
      if (first != k && !crossed(d, pc.g, k)) {  // keeps the bracket: nothing had crossed at a
        k = first;
        if (a > a0) {
          at(a, pa);
          ga = pa.g(k);
        } else {
          ga = g_a(k);
        }
        side = 0;
      }
      b = c;
      gb = pc.g(k);
      std::swap(pb, pc);
      if (side == -1) ga *= 0.5;  // Illinois: the retained end's value halved
      side = -1;
    } else {
      a = c;
      ga = pc.g(k);
      if (side == 1) gb *= 0.5;
      side = 1;
    }
  }
  return k;
}

}  // namespace pogear::rt::hybrid
