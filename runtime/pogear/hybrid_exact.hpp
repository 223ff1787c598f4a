// The exact method within a mode: steps by the mode's cached discretization or its Taylor flow, a
// whole sample period at once where the proof of event_proof.hpp shows no event can fall in it,
// events located on the exact trajectory and each element's dissipated energy from the slip
// integrals. A stepper of the driver loop (hybrid_driver.hpp). Its modes are linear (the engine
// refuses it a system with quadratic torques), so the known inputs never read the state it passes.
#pragma once

#include <cmath>
#include <string>

#include "pogear/hybrid_events.hpp"
#include "pogear/hybrid_mode_cache.hpp"
#include "pogear/hybrid_resolve.hpp"

namespace pogear::rt::hybrid {

class ExactStepper {
 public:
  static constexpr bool lands_on_samples = true;    // its steps end on every sample time
  static constexpr bool restarts_each_step = true;  // each step starts from the state as resolved
  static constexpr bool scans_for_dips = false;     // it halves a step instead

  // max_steps bounds the run's steps: a mode whose event-check step is tiny (inertias far apart make
  // its stuck torques stiff) would otherwise step for ever.
  ExactStepper(const HybridSystem& sys, HybridData& d, long max_steps = 10000000)
      : sys_(sys), d_(d), max_steps_(max_steps), steps_before_(d.steps) {
    const Eigen::Index na = d.nx + 2 * d.ne;
    for (Eigen::VectorXd* v : {&z_, &term_, &next_}) v->resize(na);
    for (Eigen::VectorXd* v : {&v0_, &w_, &dw_, &dv_}) v->resize(d.nw);
    slow_.parts.resize(2 * d.nx);
    slow_.amplitude.resize(d.nx);
    side_ = make_event_point(d);
  }

  // A step from t toward t_stop (a sample time or a breakpoint), in equal steps of at most the hold
  // step (a sine's linear hold: the scene's step) that share one discretization: the whole of one when
  // the mode's event_step allows or its proof is tried (once per stop: after a failed proof the rest
  // of the period is not tried again), else equal steps of at most event_step.
  void start(double t, double t_stop, bool stop_is_break) {
    t_stop_ = t_stop;
    stop_is_break_ = stop_is_break;
    h_ = t_stop - t;
    if (h_ > d_.hold_step) h_ /= std::ceil(h_ / d_.hold_step - 1e-9);
    depth_ = 0;
    needed_ = 0;
    try_whole_ = false;
    check_ = mode_of(sys_, d_.cache, d_.mask).event_step;
    if (h_ > check_ && any_watched(d_)) {
      if (t_stop != unproven_until_)
        try_whole_ = true;
      else
        divide_into_checks(t);
    }
  }

  bool step(double t, const Eigen::VectorXd& v0, EventPoint& end, StepEnd& e, std::string& error) {
    const auto& m = mode_of(sys_, d_.cache, d_.mask);
    if (needed_ > 0) {
      error = "exact stepping cannot reach t = " + detail::num(t_stop_) + " from t = " + detail::num(t) +
              ": the mode's event-check step of " + detail::num(check_) + " s needs " + detail::num(needed_) +
              " steps, beyond max_steps = " + std::to_string(max_steps_) +
              " (its stuck torques change that fast: check for inertias far apart); raise max_steps, or use "
              "--solver implicit";
      return false;
    }
    if (d_.steps - steps_before_ >= max_steps_) {
      error = "exact stepping stopped at t = " + detail::num(t) + ": max_steps = " + std::to_string(max_steps_) + " reached";
      return false;
    }
    v0_ = v0;
    if (try_whole_) {
      try_whole_ = false;
      // The stop itself, or a hold step short of it.
      const bool whole = h_ == t_stop_ - t;
      const double t1 = whole ? t_stop_ : t + h_;
      const bool before = whole && stop_is_break_;
      known_inputs(sys_, d_, t1, before, d_.x, end.v);
      advance(discretization(sys_, d_, d_.mask, h_), v0, end.v, end.z);
      ++d_.steps;
      end.x = end.z.head(d_.nx);
      if (clear_of_events(m, t, h_, before, d_.x, v0, end.x, end.v)) {
        e = StepEnd{t1, h_, before, true};
        return true;
      }
      unproven_until_ = t_stop_;
      divide_into_checks(t);
      if (needed_ > 0) return step(t, v0, end, e, error);
    }
    const double t1 = t + h_;
    const bool before = stop_is_break_ && t1 == t_stop_;
    known_inputs(sys_, d_, t1, before, d_.x, end.v);
    // A length met fewer than 64 times (sub-steps after an event, each event's own remainder) by the
    // Taylor series of flow() when it converges: a few dozen matrix-vector products instead of an
    // exponential.
    if (h_ * m.balanced_norm <= 2 && near_step(d_.cache.discretizations, d_.mask, h_) == d_.cache.discretizations.end() &&
        count_taylor_use(d_.cache, d_.mask, h_) < 64)
      flow(m, h_, v0, end.v, end.z);
    else
      advance(discretization(sys_, d_, d_.mask, h_), v0, end.v, end.z);
    ++d_.steps;
    end.x = end.z.head(d_.nx);
    e = StepEnd{t1, h_, before, false};
    return true;
  }

  // A possible dip of an event function halves the step: the exact trajectory is cheap to recompute.
  bool can_shorten() const { return depth_ < 30; }
  void shorten() {
    h_ *= 0.5;
    ++depth_;
  }

  // The point at t + theta within the step from t, from the mode's exact flow: exact up to rounding.
  void point(double t, double theta, EventPoint& p) {
    known_inputs(sys_, d_, t + theta, false, d_.x, p.v);
    flow(mode_of(sys_, d_.cache, d_.mask), theta, v0_, p.v, p.z);
    p.x = p.z.head(d_.nx);
  }
  // The state at the sample time ts within the step from t, and the energy dissipated since t.
  void sample_at(double t, double ts, Eigen::VectorXd& x, Eigen::VectorXd& energy) {
    point(t, ts - t, side_);
    add_energy(side_.z, t, ts - t, false, energy);
    x = side_.x;
  }
  void add_step_dissipation(double t, const StepEnd& e, const EventPoint& end, Eigen::VectorXd& energy) const {
    add_energy(end.z, t, e.theta, e.before, energy);
  }
  void add_dissipation_to(double t, double theta, const EventPoint& p, Eigen::VectorXd& energy) const {
    add_energy(p.z, t, theta, false, energy);
  }
  void step_accepted() {}
  // The new mode starts ringing: no whole-period proof for the rest of this sample period.
  void event_located() { unproven_until_ = t_stop_; }
  long rhs_evals() const { return 0; }

 private:
  // The augmented state [x; sigma; rho] at t0 + h from d.x (sigma and rho start at zero: only x's
  // columns of Phi count), inputs linear from v0 to v1.
  void advance(const ExactMatrices& e, const Eigen::VectorXd& v0, const Eigen::VectorXd& v1, Eigen::VectorXd& z) {
    dv_ = v1 - v0;
    z.setZero(e.Phi.rows());
    detail::small_matvec_add(e.Phi, d_.nx, d_.x.data(), z.data());
    detail::small_matvec_add(e.Gamma0, d_.nw, v0.data(), z.data());
    detail::small_matvec_add(e.Gamma1, d_.nw, dv_.data(), z.data());
  }

  // The augmented state at theta from d.x, the inputs linear from v0 to v1 (as advance() with the
  // exponential at theta). For theta |balanced_A| <= 2 by the Taylor series of the flow of [z; w; w']
  // (w the inputs) in balanced coordinates, summed until its terms are below rounding: no term
  // exceeds 2^k / k! <= 2 times the (balanced) state, so the sum is exact up to a few rounding
  // errors. Longer theta: the exponential.
  void flow(const ModeMatrices& m, double theta, const Eigen::VectorXd& v0, const Eigen::VectorXd& v1,
            Eigen::VectorXd& out) {
    if (!(theta * m.balanced_norm <= 2)) {
      const ExactMatrices e = exact_matrices(m.augmented_A, m.augmented_B, theta, d_.nx);
      note_accuracy(d_, e, theta);
      return advance(e, v0, v1, out);
    }
    z_.setZero(m.augmented_A.rows());
    z_.head(d_.nx) = d_.x.cwiseQuotient(m.balance.head(d_.nx));
    term_ = z_;
    w_ = v0;
    dw_ = (v1 - v0) / theta;
    for (int k = 1; k < 80; ++k) {
      next_.setZero(z_.size());
      detail::small_matvec_add(m.balanced_A, z_.size(), term_.data(), next_.data());
      // The inputs' series: v0, theta v', then nothing.
      if (k <= 2) detail::small_matvec_add(m.balanced_B, d_.nw, w_.data(), next_.data());
      term_ = (theta / k) * next_;
      w_ = (theta / k) * dw_;
      dw_.setZero();
      z_ += term_;
      if (k > 2 && term_.cwiseAbs().maxCoeff() <= 1e-18 * z_.cwiseAbs().maxCoeff()) break;
    }
    out = z_.cwiseProduct(m.balance);
  }

  // Adds each slipping element's dissipated energy over [t0, t0 + h]: with p(t0 + s) = p0 + (p1 -
  // p0) s / h, int c p dir s dt = c dir (p1 sigma(h) - (p1 - p0) rho(h) / h), sigma and rho the
  // augmented integrals of the slip. Exact when p is linear over the step.
  void add_energy(const Eigen::VectorXd& z, double t0, double h, bool before, Eigen::VectorXd& energy) const {
    const double t1 = t0 + h;
    const double at1 = before ? std::nextafter(t1, -std::numeric_limits<double>::infinity()) : t1;
    for (int k = 0; k < d_.ne; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (d_.state[K] == ElementState::stuck || is_limit(d_, k)) continue;
      const double p0 = command(sys_, d_, k, t0), p1 = command(sys_, d_, k, at1);
      const double sigma = z(d_.nx + k), rho = z(d_.nx + d_.ne + k);
      energy(k) += torque_scale(sys_, d_, k) * d_.dir[K] * (p1 * sigma - (p1 - p0) * rho / h);
    }
  }

  // Whether no event function can reach zero within the step [t, t + h] from x0 (v0) to x1 (v1): the
  // modal bound of event_proof.hpp, for every watched function (a stuck element's |T| as both signs
  // of T). False when the mode has no trustworthy modal form.
  bool clear_of_events(const ModeMatrices& m, double t, double h, bool before, const Eigen::VectorXd& x0,
                       const Eigen::VectorXd& v0, const Eigen::VectorXd& x1, const Eigen::VectorXd& v1) {
    if (!m.modal.ok) return false;
    const StepProof& p = step_proof_of(sys_, d_, d_.mask, h);
    slow_motion(p, x0, x1, v0, v1, slow_);
    for (int k = 0; k < d_.ne; ++k) {
      const auto K = static_cast<std::size_t>(k);
      // A saturated controller's function is dir (law - held torque).
      const double offset = is_limit(d_, k) ? -d_.dir[K] * held_torque(sys_, d_, k) : 0.0;
      if (d_.watched[K] && d_.state[K] != ElementState::stuck &&
          !stays_positive(p, slow_, k, d_.dir[K], offset, offset, h))
        return false;
    }
    const double t1 = t + h, at1 = before ? std::nextafter(t1, t) : t1;
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      const int k = m.stuck[j];
      if (is_limit(d_, k)) {  // torque_max - T and T - torque_min (a monitor's widened by its band)
        const double band = monitor_band(d_, k, x0);
        const double hi = limit(sys_, d_, k).torque_max + band, lo = limit(sys_, d_, k).torque_min - band;
        if (!stays_positive(p, slow_, k, -1, hi, hi, h) || !stays_positive(p, slow_, k, 1, -lo, -lo, h)) return false;
        continue;
      }
      const auto& el = sys_.elements[static_cast<std::size_t>(k)];
      const double mu_c = el.static_ratio * el.capacity, L0 = mu_c * command(sys_, d_, k, t),
                   L1 = mu_c * command(sys_, d_, k, at1);
      // mu c p - T and mu c p + T: the margin for each sign of T; a one-way element also -T.
      if (!stays_positive(p, slow_, k, -1, L0, L1, h) || !stays_positive(p, slow_, k, 1, L0, L1, h)) return false;
      if (el.one_way && !stays_positive(p, slow_, k, -1, 0, 0, h)) return false;
    }
    return true;
  }

  const HybridSystem& sys_;
  HybridData& d_;
  // Equal steps of at most check_ to t_stop_, unless they exceed what is left of max_steps
  // (needed_ is then their count, and the next step refuses).
  void divide_into_checks(double t) {
    const double n = std::ceil((t_stop_ - t) / check_ - 1e-9);
    needed_ = static_cast<double>(d_.steps - steps_before_) + n > static_cast<double>(max_steps_) ? n : 0.0;
    if (needed_ == 0) h_ /= std::ceil(h_ / check_ - 1e-9);
  }

  long max_steps_, steps_before_;  // the bound on this run's steps, and the workspace's count before it
  double needed_ = 0;
  double t_stop_ = 0, h_ = 0, check_ = 0;
  double unproven_until_ = -1;  // the end of the sample period whose whole step was not clear
  bool stop_is_break_ = false, try_whole_ = false;
  int depth_ = 0;
  SlowMotion slow_;
  EventPoint side_;  // a sample within a step
  Eigen::VectorXd v0_, z_, term_, next_, w_, dw_, dv_;
};

}  // namespace pogear::rt::hybrid
