// A brake's or clutch's actuator: the engagement e(t) its command p(t) gives through a fill delay d
// and a first-order lag tau (docs/scene-format.md, "Actuators"), in closed form.
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <vector>

#include "pogear/signals.hpp"

namespace pogear::rt {

// tau de/dt = p(t - d) - e, e at rest on the command's value before its first breakpoint. A command
// is piecewise linear, so on each of its pieces e is the piece's line lagged by tau plus a decaying
// exponential. The knots hold e where each piece starts (the command's breakpoint plus d), the
// delayed command's value there (its right limit) and its slope over the piece; the first knot is
// at -infinity, where the actuator rests. e(t) then costs a binary search and one exponential.
struct ActuatorKnots {
  std::vector<double> t, e, p, slope;
};

// e at u >= 0 after a knot (e0, p0, slope s). Without a lag it is the delayed command itself.
inline double lagged(double e0, double p0, double s, double tau, double u) {
  if (tau == 0) return s == 0 ? p0 : p0 + s * u;
  const double line = s == 0 ? p0 : p0 + s * (u - tau);  // s == 0: no 0 * infinity from the rest knot
  const double a = e0 - p0 + s * tau;
  return a == 0 ? line : line + a * std::exp(-u / tau);
}

inline double engagement(const ActuatorKnots& k, double tau, double t) {
  // Right-continuous as every signal: at a knot's time its piece holds. A NaN time takes the last.
  const auto at = std::upper_bound(k.t.begin(), k.t.end(), t);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(at - k.t.begin() - 1, 0));
  return lagged(k.e[i], k.p[i], k.slope[i], tau, t - k.t[i]);
}

// de/dt at t (its right derivative at a knot).
inline double engagement_slope(const ActuatorKnots& k, double tau, double t) {
  const auto at = std::upper_bound(k.t.begin(), k.t.end(), t);
  const auto i = static_cast<std::size_t>(std::max<std::ptrdiff_t>(at - k.t.begin() - 1, 0));
  if (tau == 0) return k.slope[i];
  const double a = k.e[i] - k.p[i] + k.slope[i] * tau;
  return a == 0 ? k.slope[i] : k.slope[i] - a / tau * std::exp(-(t - k.t[i]) / tau);
}

// Drops the knots at or after `t`: the command that made them no longer holds from there.
inline void drop_knots_from(ActuatorKnots& k, double t) {
  const auto n = static_cast<std::size_t>(std::lower_bound(k.t.begin(), k.t.end(), t) - k.t.begin());
  for (std::vector<double>* v : {&k.t, &k.e, &k.p, &k.slope}) v->resize(n);
}

// Adds a knot where `command` holds from raw time r on (engagement time r + delay), e carried on
// from the last knot; the first knot is the actuator at rest at -infinity.
inline void add_knot(ActuatorKnots& k, const Signal& command, double r, double delay, double tau) {
  const double t = r + delay;
  if (!k.t.empty() && !(t > k.t.back())) return;  // a repeated breakpoint (a table's jump): one knot
  const double p = value(command, r), s = std::isfinite(r) ? slope(command, r) : 0.0;
  const double e = k.t.empty() ? p : lagged(k.e.back(), k.p.back(), k.slope.back(), tau, t - k.t.back());
  k.t.push_back(t);
  k.e.push_back(e);
  k.p.push_back(p);
  k.slope.push_back(s);
}

// The knots of `command` from raw time `from` on: a knot there and at each of its breakpoints after
// it (a command's breakpoints come sorted: a table's rows are, a step or a ramp has one).
inline void add_knots(ActuatorKnots& k, const Signal& command, double from, double delay, double tau) {
  add_knot(k, command, from, delay, tau);
  for_each_break(command, [&](double b) {
    if (b > from) add_knot(k, command, b, delay, tau);
  });
}

// How many knots add_knots may add for `command` (capacity to reserve: no allocation within a run).
inline std::size_t knot_count(const Signal& command) {
  std::size_t n = 1;
  for_each_break(command, [&](double) { ++n; });
  return n;
}

}  // namespace pogear::rt
