// Torques that are functions of the state (and of time through a throttle): a quadratic load, a
// torque converter's torques on its pump and turbine, an engine's map; their data and their law.
#pragma once

#include <Eigen/Core>
#include <cmath>
#include <utility>
#include <vector>

#include "pogear/driveline.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

// A torque that is a function of the state: a quadratic load -c s |s| on the speed s = speed x (a
// fan, a vehicle's air drag), a torque converter's torque on its pump or on its turbine (speed x the
// pump's speed, turbine x the turbine's), or an engine's map at speed x and its throttle signal. It
// enters dx/dt through its column of N as an input does, so that a mode's projection and its stuck
// torques take it as they take the scene's torques.
enum class StateTorqueKind { quadratic, converter_pump, converter_turbine, engine };
struct StateTorqueData {
  Eigen::RowVectorXd speed;
  double coefficient = 0;  // a quadratic torque's c
  StateTorqueKind kind = StateTorqueKind::quadratic;
  Eigen::RowVectorXd turbine;  // a converter's
  ConverterData converter;
  EngineData engine;
  Signal throttle = Constant{0.0};  // an engine's, in [0, 1]
};
// The engine's torque, the converter's on its pump and on its turbine, those the data has, in that
// order: the order of a system's driveline inputs (Tengine, Tpump, Tturbine).
inline std::vector<StateTorqueData> driveline_state_torques(const DrivelineData& data) {
  std::vector<StateTorqueData> out;
  if (data.engine) {
    StateTorqueData q;
    q.kind = StateTorqueKind::engine;
    q.speed = data.engine_speed;
    q.engine = *data.engine;
    q.throttle = data.throttle;
    out.push_back(std::move(q));
  }
  if (data.converter)
    for (const StateTorqueKind kind : {StateTorqueKind::converter_pump, StateTorqueKind::converter_turbine}) {
      StateTorqueData q;
      q.kind = kind;
      q.speed = data.pump_speed;
      q.turbine = data.turbine_speed;
      q.converter = *data.converter;
      out.push_back(std::move(q));
    }
  return out;
}

inline StateTorqueData quadratic_torque_data(Eigen::RowVectorXd speed, double coefficient) {
  StateTorqueData q;
  q.speed = std::move(speed);
  q.coefficient = coefficient;
  return q;
}

// A state torque at the state x and time t (the throttle's), with its partial derivatives in the
// speed speed x, in the turbine's speed turbine x (a converter's) and in time (an engine's throttle).
struct StateTorqueValue {
  double torque = 0, d_speed = 0, d_turbine = 0, d_time = 0;
};
template <class X>
StateTorqueValue state_torque(const StateTorqueData& q, const X& x, double t) {
  const double s = q.speed.dot(x);
  switch (q.kind) {
    case StateTorqueKind::quadratic:
      return {-q.coefficient * s * std::abs(s), -2 * q.coefficient * std::abs(s), 0, 0};
    case StateTorqueKind::converter_pump: {
      const ConverterTorques c = converter_torques(q.converter, s, q.turbine.dot(x));
      return {c.pump, c.pump_dp, c.pump_dt, 0};
    }
    case StateTorqueKind::converter_turbine: {
      const ConverterTorques c = converter_torques(q.converter, s, q.turbine.dot(x));
      return {c.turbine, c.turbine_dp, c.turbine_dt, 0};
    }
    case StateTorqueKind::engine: {
      const EngineTorque e = engine_torque(q.engine, s, value(q.throttle, t));
      return {e.torque, e.d_speed, 0, e.d_throttle * slope(q.throttle, t)};
    }
  }
  return {};
}

// The speed of the body a state torque acts on (its power is the torque times it): a converter's
// turbine torque's is the turbine's, every other's its speed.
inline const Eigen::RowVectorXd& acted_speed(const StateTorqueData& q) {
  return q.kind == StateTorqueKind::converter_turbine ? q.turbine : q.speed;
}

}  // namespace pogear::rt
