// Input signals (torques, forces) of pogear simulators: plain value types evaluated at time t, and
// the times where they jump or kink, so that steppers can land on them instead of stepping across.
#pragma once

#include <algorithm>
#include <cmath>
#include <functional>
#include <limits>
#include <numbers>
#include <optional>
#include <string>
#include <variant>
#include <vector>

namespace pogear::rt {

// All signals are right-continuous: at a switching time the new value already holds. Steppers rely on
// this: a step starting on a breakpoint sees the new value, a step ending on one asks just before it.
struct Constant {
  double v = 0;
  double value(double) const { return v; }
};

struct Step {
  double before = 0, after = 0, time = 0;
  double value(double t) const { return t < time ? before : after; }
};

struct Ramp {
  double start_time = 0, slope = 0, initial = 0;
  double value(double t) const { return t < start_time ? initial : initial + slope * (t - start_time); }
};

struct Sine {
  double amplitude = 0, frequency_hz = 0, phase_rad = 0, offset = 0;
  double value(double t) const {
    return offset + amplitude * std::sin(2 * std::numbers::pi * frequency_hz * t + phase_rad);
  }
};

// Piecewise linear through (t[i], v[i]) (t and v of the same size), held constant outside. t must be
// non-decreasing; a repeated time is a jump (the later point wins: the signal stays right-continuous).
struct Table {
  std::vector<double> t, v;
  double value(double x) const {
    if (t.empty()) return 0;
    if (!(x >= t.front())) return v.front();  // also a NaN time: never index out of range
    if (x >= t.back()) return v.back();
    const auto i = static_cast<std::size_t>(std::upper_bound(t.begin(), t.end(), x) - t.begin());
    const double w = (x - t[i - 1]) / (t[i] - t[i - 1]);  // t[i-1] <= x < t[i], so no 0/0
    return v[i - 1] + w * (v[i] - v[i - 1]);
  }
};

// A road's load through its grade, sine sin(a(t)) + cosine cos(a(t)), the angle a [rad] a table of
// time (a car's weight along the road and its rolling resistance on it). Smooth between the
// angle's breakpoints, but not linear: exact stepping holds it linear over the scene's step.
struct GradeLoad {
  Table angle;
  double sine = 0, cosine = 0;
  double value(double t) const {
    const double a = angle.value(t);
    return sine * std::sin(a) + cosine * std::cos(a);
  }
};

using Signal = std::variant<Constant, Step, Ramp, Sine, Table, GradeLoad>;

inline double value(const Signal& s, double t) {
  return std::visit([t](const auto& sig) { return sig.value(t); }, s);
}

// A table's slope at t (its right derivative at a row), 0 outside it.
inline double table_slope(const Table& tab, double t) {
  if (tab.t.empty() || !(t >= tab.t.front()) || t >= tab.t.back()) return 0.0;
  const auto i = static_cast<std::size_t>(std::upper_bound(tab.t.begin(), tab.t.end(), t) - tab.t.begin());
  return (tab.v[i] - tab.v[i - 1]) / (tab.t[i] - tab.t[i - 1]);
}

// The signal's slope at t (its right derivative where it kinks).
inline double slope(const Signal& s, double t) {
  if (const auto* r = std::get_if<Ramp>(&s)) return t < r->start_time ? 0.0 : r->slope;
  if (const auto* sine = std::get_if<Sine>(&s)) {
    const double w = 2 * std::numbers::pi * sine->frequency_hz;
    return sine->amplitude * w * std::cos(w * t + sine->phase_rad);
  }
  if (const auto* tab = std::get_if<Table>(&s)) return table_slope(*tab, t);
  if (const auto* g = std::get_if<GradeLoad>(&s)) {
    const double a = g->angle.value(t);
    return (g->sine * std::cos(a) - g->cosine * std::sin(a)) * table_slope(g->angle, t);
  }
  return 0.0;  // Constant, Step
}

// Whether some signal is not linear between its breakpoints (a sine that moves, a grade's load):
// exact stepping then holds the inputs linear over the scene's step.
inline bool curved(const std::vector<Signal>& signals) {
  return std::any_of(signals.begin(), signals.end(), [](const Signal& s) {
    const auto* sine = std::get_if<Sine>(&s);
    const auto* grade = std::get_if<GradeLoad>(&s);
    return (sine && sine->amplitude != 0 && sine->frequency_hz != 0) ||
           (grade && std::adjacent_find(grade->angle.v.begin(), grade->angle.v.end(), std::not_equal_to<>()) !=
                         grade->angle.v.end());
  });
}

// The shortest period of the signals' sines (of those that move), or infinity: a sine's value is
// not linear between breakpoints, and crosses its mean twice a period.
inline double shortest_sine_period(const std::vector<Signal>& signals) {
  double period = std::numeric_limits<double>::infinity();
  for (const Signal& s : signals)
    if (const auto* sine = std::get_if<Sine>(&s); sine && sine->amplitude != 0 && sine->frequency_hz != 0)
      period = std::min(period, 1 / std::abs(sine->frequency_hz));
  return period;
}

// Signals that start on an event (a triggered command, HybridSystem::triggered): the times of
// `original` moved by t0 into `live`, in place (no allocation: live is a copy of original). Until it
// starts such a signal is its `before`, or the value it has before its own times (a table's first
// row, a ramp's initial value, a step's `before`: its value at -infinity). A sine has no such value
// (it is refused as a triggered signal: startable).
inline bool startable(const Signal& s) { return !std::holds_alternative<Sine>(s); }
inline void move_times(Signal& live, const Signal& original, double t0) {
  if (auto* st = std::get_if<Step>(&live)) st->time = t0 + std::get<Step>(original).time;
  if (auto* r = std::get_if<Ramp>(&live)) r->start_time = t0 + std::get<Ramp>(original).start_time;
  auto move_table = [t0](Table& to, const Table& from) {
    for (std::size_t i = 0; i < to.t.size() && i < from.t.size(); ++i) to.t[i] = t0 + from.t[i];
  };
  if (auto* tab = std::get_if<Table>(&live)) move_table(*tab, std::get<Table>(original));
  if (auto* g = std::get_if<GradeLoad>(&live)) move_table(g->angle, std::get<GradeLoad>(original).angle);
}
// What a signal that starts on an event is until then.
inline Signal held_until_start(const Signal& s, const std::optional<Signal>& before) {
  return before ? *before : Signal{Constant{value(s, -std::numeric_limits<double>::infinity())}};
}
// Calls f(t) for every time of the signal where it or its slope may jump, unsorted (breakpoints
// without their vector).
template <class F>
void for_each_break(const Signal& s, F&& f) {
  if (const auto* st = std::get_if<Step>(&s)) f(st->time);
  if (const auto* r = std::get_if<Ramp>(&s)) f(r->start_time);
  if (const auto* tab = std::get_if<Table>(&s))
    for (double t : tab->t) f(t);
  if (const auto* g = std::get_if<GradeLoad>(&s))
    for (double t : g->angle.t) f(t);
}

// Times in the open interval (t0, t1) where the signal or its slope jumps, sorted, without duplicates.
inline std::vector<double> breakpoints(const Signal& s, double t0, double t1) {
  std::vector<double> out;
  auto add = [&](double t) {
    if (t > t0 && t < t1) out.push_back(t);
  };
  for_each_break(s, add);
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

// Breakpoints of all inputs of a model, merged.
inline std::vector<double> breakpoints(const std::vector<Signal>& signals, double t0, double t1) {
  std::vector<double> out;
  for (const Signal& s : signals) {
    const std::vector<double> b = breakpoints(s, t0, t1);
    out.insert(out.end(), b.begin(), b.end());
  }
  std::sort(out.begin(), out.end());
  out.erase(std::unique(out.begin(), out.end()), out.end());
  return out;
}

}  // namespace pogear::rt
