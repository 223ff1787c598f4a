// The laws of a torque converter and an engine (docs/scene-format.md, "Converter and engine"): the
// torques they put on their bodies as functions of the speeds and the throttle, with their slopes.
#pragma once

#include <Eigen/Core>
#include <algorithm>
#include <cstddef>
#include <optional>
#include <vector>

#include "pogear/signals.hpp"

namespace pogear::rt {

// y(x), linear between the points (x strictly increasing) and held at the end values beyond them.
struct Curve {
  std::vector<double> x, y;
};

// The segment of the curve that holds a (its first index), or -1 below the first point and n-1 above
// the last: the curve is flat there.
inline std::ptrdiff_t curve_segment(const std::vector<double>& x, double a) {
  const auto n = static_cast<std::ptrdiff_t>(x.size());
  if (n < 2 || !(a >= x.front())) return -1;
  if (a >= x.back()) return n - 1;
  return std::upper_bound(x.begin(), x.end(), a) - x.begin() - 1;
}

// The curve's value at a, and its slope there (the right-hand one at a point; zero where it is flat).
inline double curve_value(const Curve& c, double a, double& slope) {
  const std::ptrdiff_t i = curve_segment(c.x, a);
  slope = 0;
  if (i < 0) return c.y.front();
  const auto I = static_cast<std::size_t>(i);
  if (I + 1 >= c.x.size()) return c.y.back();
  slope = (c.y[I + 1] - c.y[I]) / (c.x[I + 1] - c.x[I]);
  return c.y[I] + slope * (a - c.x[I]);
}

// A converter's tables over the speed ratio sigma = omega_t / omega_p from 0 to below 1: capacity
// factor K [(rad/s)/sqrt(N m)] and torque ratio TR. From the last point to sigma = 1, 1/K^2 falls
// linearly to 0 and TR goes linearly to 1: a fluid coupling passes no torque at equal speeds.
struct ConverterData {
  Curve capacity, torque_ratio;
};

// 1/K(sigma)^2 [N m s^2/rad^2], the pump torque per pump speed squared, and its slope in sigma.
inline double pump_coefficient(const ConverterData& c, double sigma, double& slope) {
  const double last = c.capacity.x.back();
  if (sigma > last) {
    const double k = c.capacity.y.back(), at_last = 1 / (k * k);
    slope = -at_last / (1 - last);
    return sigma >= 1 ? (slope = 0, 0.0) : at_last * (1 - sigma) / (1 - last);
  }
  double dk = 0;
  const double k = curve_value(c.capacity, sigma, dk);
  slope = -2 * dk / (k * k * k);
  return 1 / (k * k);
}
inline double converter_torque_ratio(const ConverterData& c, double sigma, double& slope) {
  const double last = c.torque_ratio.x.back();
  if (sigma > last) {
    const double tr = c.torque_ratio.y.back();
    slope = (1 - tr) / (1 - last);
    return sigma >= 1 ? (slope = 0, 1.0) : tr + slope * (sigma - last);
  }
  return curve_value(c.torque_ratio, sigma, slope);
}

// The converter's torques on the pump and on the turbine, and their partial derivatives in the two
// speeds. Drive (omega_t <= omega_p): the pump absorbs T_p = omega_p^2 / K(sigma)^2 and the turbine
// receives TR(sigma) T_p (sigma held at 0 while the turbine turns backwards). Coast (omega_t >
// omega_p): the turbine drives the pump as a coupling, T = omega_t^2 / K(omega_p / omega_t)^2 with
// torque ratio 1. A pump turning backwards mirrors both speeds and torques.
struct ConverterTorques {
  double pump = 0, turbine = 0;
  double pump_dp = 0, pump_dt = 0, turbine_dp = 0, turbine_dt = 0;  // d(torque)/d(omega_p), d/d(omega_t)
};

inline ConverterTorques converter_torques(const ConverterData& c, double wp, double wt) {
  ConverterTorques r;
  if (wp < 0 || (wp == 0 && wt < 0)) {
    r = converter_torques(c, -wp, -wt);  // odd in the two speeds: the torques flip, their slopes stay
    r.pump = -r.pump;
    r.turbine = -r.turbine;
    return r;
  }
  if (wt <= wp) {
    if (wp == 0) return r;
    const double ratio = wt / wp, sigma = std::max(ratio, 0.0);
    double dc = 0, dtr = 0;
    const double coefficient = pump_coefficient(c, sigma, dc), tr = converter_torque_ratio(c, sigma, dtr);
    if (ratio < 0) dc = dtr = 0;
    const double tp = coefficient * wp * wp;
    // d sigma / d omega_p = -omega_t / omega_p^2, d sigma / d omega_t = 1 / omega_p
    const double tp_dp = 2 * coefficient * wp - dc * wt, tp_dt = dc * wp;
    r.pump = -tp;
    r.pump_dp = -tp_dp;
    r.pump_dt = -tp_dt;
    r.turbine = tr * tp;
    r.turbine_dp = tr * tp_dp - dtr * (wt / (wp * wp)) * tp;
    r.turbine_dt = tr * tp_dt + dtr / wp * tp;
    return r;
  }
  const double sigma = wp / wt;  // coast: wt > wp >= 0
  double dc = 0;
  const double coefficient = pump_coefficient(c, sigma, dc);
  const double t = coefficient * wt * wt, t_dp = dc * wt, t_dt = 2 * coefficient * wt - dc * wp;
  r.pump = t;
  r.pump_dp = t_dp;
  r.pump_dt = t_dt;
  r.turbine = -t;
  r.turbine_dp = -t_dp;
  r.turbine_dt = -t_dt;
  return r;
}

// An engine's full-load and part-load map: torque [N m] at speeds [rad/s] (strictly increasing) and
// throttles in [0, 1] (strictly increasing), torque[throttle][speed]; bilinear between the points,
// held at the map's edges beyond them.
struct EngineData {
  std::vector<double> speeds, throttles;
  std::vector<std::vector<double>> torque;
};

struct EngineTorque {
  double torque = 0, d_speed = 0, d_throttle = 0;
};

inline EngineTorque engine_torque(const EngineData& e, double speed, double throttle) {
  // Per axis: the lower point's index and the weight of the upper one (0 where the map is flat).
  struct Axis {
    std::size_t i = 0;
    double w = 0, per = 0;  // per: d w / d value
  };
  auto axis = [](const std::vector<double>& x, double a) {
    Axis r;
    const std::ptrdiff_t i = curve_segment(x, a);
    if (i < 0) return r;
    r.i = static_cast<std::size_t>(i);
    if (r.i + 1 >= x.size()) return r;
    r.per = 1 / (x[r.i + 1] - x[r.i]);
    r.w = (a - x[r.i]) * r.per;
    return r;
  };
  const Axis s = axis(e.speeds, speed), p = axis(e.throttles, throttle);
  auto at = [&](std::size_t ip, std::size_t is) {
    return e.torque[std::min(ip, e.throttles.size() - 1)][std::min(is, e.speeds.size() - 1)];
  };
  const double t00 = at(p.i, s.i), t01 = at(p.i, s.i + 1), t10 = at(p.i + 1, s.i), t11 = at(p.i + 1, s.i + 1);
  const double low = t00 + s.w * (t01 - t00), high = t10 + s.w * (t11 - t10);
  EngineTorque r;
  r.torque = low + p.w * (high - low);
  r.d_speed = s.per * ((1 - p.w) * (t01 - t00) + p.w * (t11 - t10));
  r.d_throttle = p.per * (high - low);
  return r;
}

// A scene's engine and converter as a system gives them to the hybrid runs: their data, and the
// speeds of their bodies over the system's states.
struct DrivelineData {
  std::optional<EngineData> engine;
  Signal throttle = Constant{0.0};
  Eigen::RowVectorXd engine_speed;
  std::optional<ConverterData> converter;
  Eigen::RowVectorXd pump_speed, turbine_speed;
};

}  // namespace pogear::rt
