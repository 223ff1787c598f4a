// The known inputs v of a hybrid run (w with the stuck torques left out) at an instant and their
// rates: the signals, the state torques, the slipping and held torques.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <limits>

#include "pogear/hybrid_data.hpp"

namespace pogear::rt::hybrid {

// The torque of slipping friction element k at time `at` and state x: c p(t) dir, times f(|S_k x|)
// where its friction varies with slip.
inline double slipping_torque(const HybridSystem& sys, const HybridData& d, int k, double at, const Eigen::VectorXd& x) {
  const auto K = static_cast<std::size_t>(k);
  const double T = torque_scale(sys, d, k) * command(sys, d, k, at) * d.dir[K];
  return varies_with_slip(sys.elements[K]) ? T * friction_ratio(sys.elements[K], d.S.row(k).dot(x)) : T;
}

// v = w at time t and state x: the inputs, the state torques, slipping torques c p(t) f dir, held
// controller torques, stuck torques left at zero. `before` asks for the left limit (a step that ends
// on a breakpoint).
inline void known_inputs(const HybridSystem& sys, const HybridData& d, double t, bool before, const Eigen::VectorXd& x,
                         Eigen::VectorXd& v) {
  const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
  v.resize(d.nw);
  for (Eigen::Index i = 0; i < d.ns; ++i) v(i) = value(input_signal(d, static_cast<std::size_t>(i), at), at);
  for (Eigen::Index i = d.ns; i < d.nu; ++i) v(i) = state_torque(sys.state_torques[static_cast<std::size_t>(i - d.ns)], x, at).torque;
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    // + 0.0: an open element's torque is 0, not -0, in the CSV.
    v(d.nu + k) = d.state[K] == ElementState::stuck || (k < d.nf && controlled(d, k)) ? 0.0
                  : is_limit(d, k) ? held_torque(sys, d, k)
                                   : slipping_torque(sys, d, k, at, x) + 0.0;
  }
}

// dv/dt at time t (its left limit when `before`): the inputs' slopes, the slipping torques' c p'(t)
// dir; stuck torques and held controller torques 0; the state torques' and the torques of friction
// that varies with slip by state_torque_slopes, which needs dx/dt.
inline void known_input_slopes(const HybridSystem& sys, const HybridData& d, double t, bool before,
                               Eigen::VectorXd& dv) {
  const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
  for (Eigen::Index i = 0; i < d.ns; ++i) dv(i) = slope(input_signal(d, static_cast<std::size_t>(i), at), at);
  for (int k = 0; k < d.ne; ++k) {
    const auto K = static_cast<std::size_t>(k);
    dv(d.nu + k) = d.state[K] == ElementState::stuck || is_limit(d, k) || controlled(d, k)
                       ? 0.0
                       : torque_scale(sys, d, k) * command_slope(sys, d, k, at) * d.dir[K];
  }
}

// The torque friction element k carries at state x and known inputs v: its own, or while its slip
// controller controls it the controller's (its law within the limits, else the limit it holds).
template <class X>
double carried_torque(const HybridSystem& sys, const HybridData& d, int k, const X& x, const Eigen::VectorXd& v) {
  if (!controlled(d, k)) return v(d.nu + k);
  const int l = d.supplier[static_cast<std::size_t>(k)];
  return d.state[static_cast<std::size_t>(l)] == ElementState::stuck ? law(sys, d, l, x, v) : v(d.nu + l);
}

// Whether friction element k slips with a torque of its own that varies with its slip.
inline bool slips_along_curve(const HybridSystem& sys, const HybridData& d, int k) {
  const auto K = static_cast<std::size_t>(k);
  return varies_with_slip(sys.elements[K]) && d.state[K] != ElementState::stuck && !controlled(d, k);
}

// The state torques' rates at state x moving at dx/dt, at time t (its left limit when `before`), and
// those of the slipping torques whose friction varies with slip: c dir (p' f + p f' ds/dt).
inline void state_torque_slopes(const HybridSystem& sys, const HybridData& d, double t, bool before,
                                const Eigen::VectorXd& x, const Eigen::VectorXd& dx, Eigen::VectorXd& dv) {
  const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
  for (Eigen::Index i = d.ns; i < d.nu; ++i) {
    const StateTorqueData& q = sys.state_torques[static_cast<std::size_t>(i - d.ns)];
    const StateTorqueValue v = state_torque(q, x, at);
    dv(i) = v.d_speed * q.speed.dot(dx) + v.d_time;
    if (v.d_turbine != 0) dv(i) += v.d_turbine * q.turbine.dot(dx);
  }
  for (int k = 0; k < d.nf; ++k) {
    if (!slips_along_curve(sys, d, k)) continue;
    const auto K = static_cast<std::size_t>(k);
    const FrictionElementData& e = sys.elements[K];
    const double s = d.S.row(k).dot(x);
    dv(d.nu + k) = torque_scale(sys, d, k) * d.dir[K] *
                   (command_slope(sys, d, k, at) * friction_ratio(e, s) +
                    command(sys, d, k, at) * friction_ratio_slope(e, s) * d.S.row(k).dot(dx));
  }
}

// The Jacobian of the slipping torques whose friction varies with slip, added to J: B's column of
// element k times c p(t) dir f'(s) S_k.
inline void add_friction_curve_jacobian(const HybridSystem& sys, const HybridData& d, const Eigen::MatrixXd& B, double t,
                                        const Eigen::VectorXd& x, Eigen::MatrixXd& J) {
  for (int k = 0; k < d.nf; ++k) {
    if (!slips_along_curve(sys, d, k)) continue;
    const auto K = static_cast<std::size_t>(k);
    const double g = torque_scale(sys, d, k) * command(sys, d, k, t) * d.dir[K] *
                     friction_ratio_slope(sys.elements[K], d.S.row(k).dot(x));
    if (g == 0) continue;
    for (Eigen::Index c = 0; c < J.cols(); ++c)  // the outer product by hand: no temporary
      if (d.S(k, c) != 0) J.col(c) += g * d.S(k, c) * B.col(d.nu + k);
  }
}

// The Jacobian of the state torques' contribution to dx/dt, B_q dq/dx, added to J: a mode's B column
// times the torque's gradient over the states.
inline void add_state_torque_jacobian(const HybridSystem& sys, const HybridData& d, const Eigen::MatrixXd& B, double t,
                                      const Eigen::VectorXd& x, Eigen::MatrixXd& J) {
  for (Eigen::Index i = d.ns; i < d.nu; ++i) {
    const StateTorqueData& q = sys.state_torques[static_cast<std::size_t>(i - d.ns)];
    const StateTorqueValue v = state_torque(q, x, t);
    for (Eigen::Index c = 0; c < J.cols(); ++c) {  // the outer product by hand: no temporary
      const double g = v.d_speed * q.speed(c) + (v.d_turbine != 0 ? v.d_turbine * q.turbine(c) : 0.0);
      if (g != 0) J.col(c) += g * B.col(i);
    }
  }
}

}  // namespace pogear::rt::hybrid
