// dopri5 or TR-BDF2 within a mode: adaptive steps on dx/dt = A x + B v(t, x), ending on breakpoints,
// events located on their dense output and each element's dissipated energy by quadrature on it.
// A stepper of the driver loop (hybrid_driver.hpp).
#pragma once

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <string>

#include "pogear/hybrid_events.hpp"
#include "pogear/hybrid_mode_cache.hpp"
#include "pogear/hybrid_resolve.hpp"
#include "pogear/steppers.hpp"

namespace pogear::rt::hybrid {

// The right-hand side of the current mode: dx/dt = A x + B v(t, x), v of x through the state
// torques only, and its Jacobian A + B dv/dx.
struct ModeRhs {
  const HybridSystem* sys = nullptr;
  const HybridData* d = nullptr;
  const ModeMatrices* mode = nullptr;
  Eigen::VectorXd v;
  long evaluations = 0;
  void operator()(double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
    ++evaluations;
    known_inputs(*sys, *d, t, false, x, v);
    dx.noalias() = mode->A * x;
    dx.noalias() += mode->B * v;
  }
};
struct ModeJacobian {
  const HybridSystem* sys = nullptr;
  const HybridData* d = nullptr;
  const ModeMatrices* mode = nullptr;
  void operator()(double t, const Eigen::VectorXd& x, Eigen::MatrixXd& J) const {
    J = mode->A;
    add_state_torque_jacobian(*sys, *d, mode->B, t, x, J);
    add_friction_curve_jacobian(*sys, *d, mode->B, t, x, J);
  }
};

template <class Stepper>
class AdaptiveStepper {
 public:
  static constexpr bool lands_on_samples = false;    // samples come from the dense output
  static constexpr bool restarts_each_step = false;  // only after an event or a breakpoint
  static constexpr bool scans_for_dips = true;       // a possible dip: the dense output at 8 points

  AdaptiveStepper(const HybridSystem& sys, HybridData& d, const SolverOptions& opt, const char* name)
      : sys_(sys), d_(d), opt_(opt), name_(name), h_(std::min(opt.h, opt.h_max)), h_max_(opt.h_max) {
    rhs_.sys = &sys;
    rhs_.d = &d;
    rhs_.v.resize(d.nw);
    jacobian_.sys = &sys;
    jacobian_.d = &d;
    x1_.resize(d.nx);
    dense_x_.resize(d.nx);
    dense_v_.resize(d.nw);
    corner_dx_.resize(d.nx);
  }
  bool valid_step(std::string& error) const {
    if (h_ > 0) return true;
    error = "invalid step size h = " + detail::num(opt_.h);
    return false;
  }

  // Restarts in the current mode at t (its stepper made anew when the mode changed). As for the
  // exact method, no step longer than the mode's event_step while an element is watched (TR-BDF2
  // would otherwise step over oscillations it damps numerically), nor than a sixteenth of the
  // shortest sine's period: a sine can drive a stuck element's torque while the state stays at rest,
  // and the error control, which sees only the state, would step over its every crossing.
  void start(double t, double t_stop, bool stop_is_break) {
    const auto& m = mode_of(sys_, d_.cache, d_.mask);
    rhs_.mode = jacobian_.mode = &m;
    if (!s_ || stepper_mask_ != d_.mask) {
      // A linear mode's Jacobian is A throughout: one Newton iteration solves each stage exactly.
      if constexpr (requires { Stepper(rhs_, jacobian_, true, d_.x, 1.0, 1.0); })
        s_.emplace(rhs_, jacobian_, sys_.state_torques.empty() && !varies_with_slip(sys_), d_.x, opt_.rtol, opt_.atol);
      else
        s_.emplace(rhs_, d_.x, opt_.rtol, opt_.atol);
      stepper_mask_ = d_.mask;
    }
    s_->start(t, d_.x);
    h_max_ = any_watched(d_) ? std::min({opt_.h_max, m.event_step, d_.sine_period / 16}) : opt_.h_max;
    h_ = std::min(h_, h_max_);
    t_stop_ = t_stop;
    stop_is_break_ = stop_is_break;
  }

  // One accepted step from t (rejected attempts retried with a smaller step). A step that would
  // leave a sliver (< 10% of h) before the stop is stretched to end on it.
  bool step(double t, const Eigen::VectorXd&, EventPoint& end, StepEnd& e, std::string& error) {
    const double corner = time_to_corner(t);
    for (;;) {
      clipped_ = t_stop_ - t <= std::min(1.1 * h_, h_max_);
      hs_ = clipped_ ? t_stop_ - t : h_;
      // A step ends just past a friction curve's corner ahead (1e-3 of the way beyond, so that a
      // prediction a little short leaves the next step a sliver to cross, which it takes whole).
      cornered_ = corner < hs_ && corner > 1e-3 * hs_;
      if (cornered_) {
        hs_ = corner * (1 + 1e-3);
        clipped_ = false;
      }
      const bool brk = clipped_ && stop_is_break_;
      if (++attempts_ > opt_.max_steps) {
        error = std::string(name_) + " stopped at t = " + detail::num(t) + ": max_steps = " +
                std::to_string(opt_.max_steps) + " reached";
        return false;
      }
      ++d_.steps;
      err_ = s_->attempt(t, d_.x, hs_, brk);
      const double hmin =
          std::max(16 * std::numeric_limits<double>::epsilon() * std::abs(t), std::numeric_limits<double>::min());
      if (!(err_ <= 1)) {
        h_ = std::min(s_->next_h(err_, hs_), h_max_);
        if (h_ < hmin) {
          error = std::isnan(err_) ? "the state is not finite"
                                   : std::string(name_) + " stalled at t = " + detail::num(t) + ": step size h = " +
                                         detail::num(h_) + " below the minimum";
          return false;
        }
        continue;
      }
      t1_ = clipped_ ? t_stop_ : t + hs_;
      x1_ = d_.x;
      s_->accept(t, x1_, hs_);
      end.x = x1_;
      known_inputs(sys_, d_, t1_, brk, end.x, end.v);
      e = StepEnd{t1_, t1_ - t, brk, false};
      return true;
    }
  }

  // The time until a slipping element's |slip| reaches the next corner of its friction curve (a row
  // past the first) at the slip's present rate; infinity when none is ahead. Across a corner the
  // slip's second derivative jumps inside the step, which the error estimate misjudges: at a
  // tolerance of 1e-10 such a step left 1.6e-7 rad/s where the tolerance asks for 1e-9.
  double time_to_corner(double t) {
    if (!varies_with_slip(sys_)) return std::numeric_limits<double>::infinity();
    rhs_(t, d_.x, corner_dx_);
    double best = std::numeric_limits<double>::infinity();
    for (int k = 0; k < d_.nf; ++k) {
      if (!slips_along_curve(sys_, d_, k)) continue;
      const std::vector<double>& at = sys_.elements[static_cast<std::size_t>(k)].friction_curve.t;
      const double s = d_.S.row(k).dot(d_.x), a = std::abs(s), rate = std::copysign(1.0, s) * d_.S.row(k).dot(corner_dx_);
      if (rate > 0) {
        const auto next = std::upper_bound(at.begin() + 1, at.end(), a);
        if (next != at.end()) best = std::min(best, (*next - a) / rate);
      } else if (rate < 0) {
        const auto next = std::lower_bound(at.begin() + 1, at.end(), a);
        if (next != at.begin() + 1) best = std::min(best, (*(next - 1) - a) / rate);
      }
    }
    return best;
  }

  bool can_shorten() const { return false; }
  void shorten() {}

  // The point at t + theta within the step from t, from the dense output (its end: the step's own).
  void point(double t, double theta, EventPoint& p) {
    s_->dense(t + theta, p.x);
    if (theta == t1_ - t) p.x = x1_;
    known_inputs(sys_, d_, t + theta, false, p.x, p.v);
  }
  void sample_at(double t, double ts, Eigen::VectorXd& x, Eigen::VectorXd& energy) {
    add_dissipation(t, ts, energy);
    s_->dense(ts, x);
  }
  void add_step_dissipation(double t, const StepEnd& e, const EventPoint&, Eigen::VectorXd& energy) {
    add_dissipation(t, e.t1, energy);
  }
  void add_dissipation_to(double t, double theta, const EventPoint&, Eigen::VectorXd& energy) {
    add_dissipation(t, t + theta, energy);
  }
  // A step shortened to end on a stop or a corner says nothing against the step size before it.
  void step_accepted() {
    const double h_next = s_->next_h(err_, hs_);
    h_ = std::min(clipped_ || cornered_ ? std::max(h_, h_next) : h_next, h_max_);
  }
  void event_located() {}
  long rhs_evals() const { return rhs_.evaluations; }

 private:
  // The energy each slipping element dissipates over [ta, tb] of the last step: its power T_k s_k, a
  // polynomial of degree 5 at most on the dense output (degree 4 for dopri5, 3 for TR-BDF2, times a
  // command linear between breakpoints), by 3-point Gauss-Legendre, exact for it (a slip controller's
  // law times the slip, of degree 8, to the order 6 of the rule). With it the work
  // each state torque does on its body, q_i times that body's speed (exact for a quadratic load's
  // power only where it keeps its sign; a converter's and an engine's to the order 6 of the rule).
  void add_dissipation(double ta, double tb, Eigen::VectorXd& energy) {
    if (!(tb > ta)) return;
    static constexpr double node = 0.7745966692414834, weight[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    const double mid = 0.5 * (ta + tb), half = 0.5 * (tb - ta);
    for (int i = 0; i < 3; ++i) {
      const double ti = mid + (i - 1) * node * half;
      s_->dense(ti, dense_x_);
      known_inputs(sys_, d_, ti, false, dense_x_, dense_v_);
      for (int k = 0; k < d_.nf; ++k)
        if (d_.state[static_cast<std::size_t>(k)] != ElementState::stuck)
          energy(k) += weight[i] * half * carried_torque(sys_, d_, k, dense_x_, dense_v_) * d_.S.row(k).dot(dense_x_);
      for (Eigen::Index q = d_.ns; q < d_.nu; ++q)
        energy(d_.ne + q - d_.ns) +=
            weight[i] * half * dense_v_(q) * acted_speed(sys_.state_torques[static_cast<std::size_t>(q - d_.ns)]).dot(dense_x_);
    }
  }

  const HybridSystem& sys_;
  HybridData& d_;
  const SolverOptions& opt_;
  const char* name_;
  ModeRhs rhs_;
  ModeJacobian jacobian_;
  std::optional<Stepper> s_;
  std::uint32_t stepper_mask_ = 0;
  double h_, h_max_, t_stop_ = 0, t1_ = 0, hs_ = 0, err_ = 0;
  bool stop_is_break_ = false, clipped_ = false, cornered_ = false;
  long attempts_ = 0;
  Eigen::VectorXd x1_, dense_x_, dense_v_, corner_dx_;
};

}  // namespace pogear::rt::hybrid
