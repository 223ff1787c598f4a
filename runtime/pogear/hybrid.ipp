// The definitions of hybrid.hpp's HybridEngine: compiled into libpogear_runtime
// (runtime/src/hybrid.cpp), or included inline by hybrid.hpp under POGEAR_RT_HEADER_ONLY. The engine
// does not depend on a model's size, so no simulator compiles it again.
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <map>
#include <numbers>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pogear/driver_loops.hpp"
#include "pogear/event_proof.hpp"
#include "pogear/hybrid.hpp"
#include "pogear/steppers.hpp"

namespace pogear::rt {

POGEAR_RT_ABI_BEGIN

// The engine behind HybridEngine: owns the modes it has met and their discretizations; steps,
// locates events and resolves modes.
class HybridEngineCore {
 public:
  HybridEngineCore(const HybridSystem& sys, double horizon, HybridMethod method)
      : sys_(sys), horizon_(horizon), method_(std::move(method)) {
    nf_ = static_cast<int>(sys.S.rows());
    ne_ = nf_ + static_cast<int>(sys.limits.size());
    nx_ = sys.M.rows();
    // The slips of every element: a torque-limited controller's row is zero (it has no slip).
    S_ = Eigen::MatrixXd::Zero(ne_, nx_);
    S_.topRows(nf_) = sys.S;
    nu_ = static_cast<Eigen::Index>(sys.inputs.size());
    nw_ = nu_ + ne_;
  }
  HybridEngineCore(const HybridEngineCore&) = delete;  // the steppers hold references to its right-hand side
  HybridEngineCore& operator=(const HybridEngineCore&) = delete;

  // Integrates from x0 at t = 0 to the horizon, landing on every sample time (obs is called there,
  // t = 0 included, and may return false to stop) and every breakpoint of the inputs and commands.
  // on_event is called for every change of an element's state. Fails the run on a non-finite state,
  // an over-constrained set of stuck elements, or chattering.
  RunStatus run(const Eigen::VectorXd& x0, double sample, const SampleObserver& obs, const EventObserver& on_event) {
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
    const EventObserver no_event = [](const HybridEvent&) {};
    if (!resolve(t, -1, no_event, error)) return fail(error, t);
    if (!observe(t, obs)) return RunStatus{false, "stopped", t};
    if (method_.solver == Solver::dopri5) return run_stepped<Dopri5<Eigen::VectorXd, ModeRhs>>(grid, obs, on_event);
    if (method_.solver == Solver::implicit)
      return run_stepped<TrBdf2<Eigen::VectorXd, ModeRhs, ModeJacobian>>(grid, obs, on_event);
    if (method_.solver != Solver::exact)
      return fail(std::string("brakes and clutches are not simulated with ") + std::string(solver_name(method_.solver)) +
                      " (fixed steps cannot locate their events); use exact, dopri5 or implicit", t);
    for (long k = 1; k < grid.count; ++k) {
      const double t_sample = grid.at(k);
      events_in_sample_.assign(static_cast<std::size_t>(ne_), 0);
      locations_in_sample_ = 0;
      while (t < t_sample) {
        while (next_break < breaks_.size() && breaks_[next_break] <= t) ++next_break;
        const double t_end = next_break < breaks_.size() ? std::min(t_sample, breaks_[next_break]) : t_sample;
        if (!step_to(t, t_end, on_event, error)) return fail(error, t);
        if (inaccurate_) return fail(detail::inaccurate_exact_step(inaccurate_->first, inaccurate_->second), t);
        if (!x_.allFinite()) return fail("the state is not finite", t);
      }
      if (!observe(t, obs)) return RunStatus{false, "stopped", t};
    }
    return RunStatus{true, "", t};
  }

  int modes_met() const { return static_cast<int>(modes_.size()); }
  long steps() const { return steps_; }
  long rhs_evals() const { return rhs_.evaluations; }

 private:
  using Modes = std::map<std::uint32_t, hybrid_detail::ModeMatrices>;

  static RunStatus fail(const std::string& why, double t) { return RunStatus{false, why, t}; }

  const hybrid_detail::ModeMatrices& mode_of(std::uint32_t mask) {
    auto it = modes_.find(mask);
    if (it == modes_.end()) {
      it = modes_.emplace(mask, hybrid_detail::mode_matrices(sys_, mask)).first;
      if (!it->second.singular) {
        auto& md = it->second;
        md.modal = modal_form(md.A, md.B);
        // event_check_step from the modal form's eigenvalues (the same solver on the same matrix)
        // rather than a second eigenvalue solve.
        if (md.A.rows() > 0 && md.modal.lambda.size() == md.A.rows()) {
          const double omega = md.modal.lambda.imag().cwiseAbs().maxCoeff();
          md.event_step = !(omega >= 0) ? 0.0
                          : omega > 0   ? std::numbers::pi / (4 * omega)
                                        : std::numeric_limits<double>::infinity();
        } else {
          md.event_step = event_step_limit(md.A);
        }
      }
    }
    return it->second;
  }

  // The entry of `cache` for mode `mask` and a step within 1e-9 h of h, or its end: steps between
  // grid times differ by the rounding of those times only, far below the rounding of t itself.
  template <class Map>
  static auto near_step(Map& cache, std::uint32_t mask, double h) {
    auto it = cache.lower_bound(std::make_pair(mask, h * (1 - 1e-9)));
    return it != cache.end() && it->first.first == mask && it->first.second <= h * (1 + 1e-9) ? it : cache.end();
  }

  // The mode's exact step of h (or of a length within 1e-9 h of it).
  const ExactMatrices& discretization(std::uint32_t mask, double h) {
    const auto key = std::make_pair(mask, h);
    auto it = near_step(discretizations_, mask, h);
    if (it == discretizations_.end()) {
      // Uneven steps after events: keep the cache bounded.
      if (discretizations_.size() > 256) discretizations_.clear();
      const auto& m = mode_of(mask);
      it = discretizations_.emplace(key, exact_matrices(m.augmented_A, m.augmented_B, h, nx_)).first;
      note_accuracy(it->second, h);
    }
    return it->second;
  }

  // An exponential that cannot be trusted (its rounding estimate, exact.hpp): the run stops after
  // the step that used it, before its state is observed.
  void note_accuracy(const ExactMatrices& d, double h) {
    if (!(d.rounding <= kExactMaxRounding) && !inaccurate_) inaccurate_ = std::make_pair(h, d.rounding);
  }

  // Elements k >= nf_ are the controllers' torque limits (TorqueLimitData), after the brakes and clutches.
  bool is_limit(int k) const { return k >= nf_; }
  const TorqueLimitData& limit(int k) const { return sys_.limits[static_cast<std::size_t>(k - nf_)]; }
  const std::string& element_name(int k) const {
    return is_limit(k) ? limit(k).name : sys_.elements[static_cast<std::size_t>(k)].name;
  }
  // A controller's torque at the limit it reached in direction dir.
  double held_torque(int k) const { return dir_[static_cast<std::size_t>(k)] > 0 ? limit(k).torque_max : limit(k).torque_min; }
  // A controller's law at state x and known inputs v.
  double law(int k, const Eigen::VectorXd& x, const Eigen::VectorXd& v) const {
    return limit(k).law_x.dot(x) + limit(k).law_w.dot(v);
  }

  // An element's command: a controller's is 1 throughout (it is never open).
  double command(int k, double t) const {
    return is_limit(k) ? 1.0 : value(sys_.elements[static_cast<std::size_t>(k)].command, t);
  }

  // The torque per unit command of element k while it slips: its capacity, or zero for a one-way
  // element overrunning in its free direction.
  double torque_scale(int k) const {
    const auto K = static_cast<std::size_t>(k);
    return sys_.elements[K].one_way && dir_[K] > 0 ? 0.0 : sys_.elements[K].capacity;
  }

  // Whether element k's command is zero from t until the next breakpoint (it is linear there).
  bool open_after(int k, double t) const {
    if (is_limit(k)) return false;
    const auto next = std::upper_bound(breaks_.begin(), breaks_.end(), t);
    const double t_next = next == breaks_.end() ? std::max(horizon_, t) : *next;
    return command(k, t) == 0 && command(k, t + 0.5 * (t_next - t)) == 0;
  }

  // w at time t: the inputs, slipping torques c p(t) dir, stuck torques left at zero. `before` asks
  // for the left limit (a step that ends on a breakpoint).
  void known_inputs(double t, bool before, Eigen::VectorXd& v) const {
    const double at = before ? std::nextafter(t, -std::numeric_limits<double>::infinity()) : t;
    v.resize(nw_);
    for (Eigen::Index i = 0; i < nu_; ++i) v(i) = value(sys_.inputs[static_cast<std::size_t>(i)], at);
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      // + 0.0: an open element's torque is 0, not -0, in the CSV.
      v(nu_ + k) = state_[K] == ElementState::stuck ? 0.0
                   : is_limit(k)                     ? held_torque(k)
                                                     : torque_scale(k) * command(k, at) * dir_[K] + 0.0;
    }
  }
  Eigen::VectorXd known_inputs(double t, bool before) const {
    Eigen::VectorXd v;
    known_inputs(t, before, v);
    return v;
  }

  bool observe(double t, const SampleObserver& obs) {
    return observe(t, x_, energy_, obs);
  }
  // The sample at t: w with the stuck torques recovered for the state x, and the slips.
  bool observe(double t, const Eigen::VectorXd& x, const Eigen::VectorXd& energy, const SampleObserver& obs) {
    const auto& m = mode_of(mask_);
    known_inputs(t, false, sample_w_);
    if (!m.stuck.empty()) {
      sample_T_.setZero(m.Kx.rows());
      detail::small_matvec_add(m.Kx, nx_, x.data(), sample_T_.data());
      detail::small_matvec_add(m.Kv, nw_, sample_w_.data(), sample_T_.data());
      for (std::size_t j = 0; j < m.stuck.size(); ++j)
        sample_w_(nu_ + m.stuck[j]) = sample_T_(static_cast<Eigen::Index>(j));
    }
    sample_slip_.setZero(ne_);
    detail::small_matvec_add(S_, nx_, x.data(), sample_slip_.data());
    return obs(t, HybridSample{x, sample_w_, sample_slip_, energy, mask_});
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
      const double Tk = T(static_cast<Eigen::Index>(j));
      if (is_limit(k)) {  // a controller within its limits: the margin to the nearer one
        g(k) = std::min(limit(k).torque_max - Tk, Tk - limit(k).torque_min);
        continue;
      }
      const auto& e = sys_.elements[static_cast<std::size_t>(k)];
      g(k) = e.static_ratio * e.capacity * command(k, at) - std::abs(Tk);
      if (e.one_way) g(k) = std::min(g(k), -Tk);  // a one-way element lets go when T turns positive
    }
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (!watched[K] || state_[K] == ElementState::stuck) continue;
      // A saturated controller: how far its law lies beyond the limit it holds.
      g(k) = is_limit(k) ? dir_[K] * (law(k, x, v) - held_torque(k)) : dir_[K] * S_.row(k).dot(x);
    }
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
        const auto J = static_cast<Eigen::Index>(j);
        if (is_limit(k)) {
          r(k) = limit(k).torque_max - T(J) < T(J) - limit(k).torque_min ? -dT(J) : dT(J);
          continue;
        }
        const auto& e = sys_.elements[static_cast<std::size_t>(k)];
        const double margin = e.static_ratio * e.capacity * p(k) - std::abs(T(J));
        r(k) = e.one_way && -T(J) < margin ? -dT(J) : e.static_ratio * e.capacity * dp(k) - (T(J) < 0 ? -dT(J) : dT(J));
      }
    }
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (!watched[K] || state_[K] == ElementState::stuck) continue;
      r(k) = is_limit(k) ? dir_[K] * (limit(k).law_x.dot(dx) + limit(k).law_w.dot(dv)) : dir_[K] * S_.row(k).dot(dx);
    }
    return r;
  }

  // One step of the current mode from t0 over h: the augmented state [x; sigma; rho] at t0 + h.
  // (The integrals sigma and rho start at zero: only x's columns of Phi count.)
  void advance(const ExactMatrices& d, const Eigen::VectorXd& v0, const Eigen::VectorXd& v1, Eigen::VectorXd& z) {
    advance_dv_ = v1 - v0;
    z.setZero(d.Phi.rows());
    detail::small_matvec_add(d.Phi, nx_, x_.data(), z.data());
    detail::small_matvec_add(d.Gamma0, nw_, v0.data(), z.data());
    detail::small_matvec_add(d.Gamma1, nw_, advance_dv_.data(), z.data());
  }
  Eigen::VectorXd advance(const ExactMatrices& d, const Eigen::VectorXd& v0, const Eigen::VectorXd& v1) {
    Eigen::VectorXd z;
    advance(d, v0, v1, z);
    return z;
  }

  // One step of h in mode m: by the cached discretization of h; a length met fewer than 64 times
  // (sub-steps after an event, each event's own remainder) by the Taylor series of flow() when it
  // converges, a few dozen matrix-vector products instead of an exponential. On the 11-state Simpson
  // upshift an exponential (with its rounding estimate) costs about 1.3 million instructions, a
  // Taylor step about 22 thousand (callgrind).
  Eigen::VectorXd step(const hybrid_detail::ModeMatrices& m, double h, const Eigen::VectorXd& v0,
                       const Eigen::VectorXd& v1) {
    if (h * m.balanced_norm <= 2 && near_step(discretizations_, mask_, h) == discretizations_.end()) {
      auto it = near_step(taylor_uses_, mask_, h);
      if (it == taylor_uses_.end()) {
        if (taylor_uses_.size() > 256) taylor_uses_.clear();  // bounded, as the discretizations
        it = taylor_uses_.emplace(std::make_pair(mask_, h), 0).first;
      }
      if (++it->second < 64) return flow(m, h, v0, v1);
    }
    return advance(discretization(mask_, h), v0, v1);
  }

  // The augmented state [x; sigma; rho] at theta from the current state, the inputs linear from v0 to
  // v1 (as advance() with the exponential at theta). For theta |balanced_A| <= 2 by the Taylor series
  // of the flow of [z; w; w'] (w the inputs) in balanced coordinates, summed until its terms are
  // below rounding: no term exceeds 2^k / k! <= 2 times the (balanced) state, so the sum is exact up
  // to a few rounding errors, at the cost of a few dozen products with the matrix instead of an
  // exponential (event location calls it a dozen times per event). Longer theta: the exponential.
  Eigen::VectorXd flow(const hybrid_detail::ModeMatrices& m, double theta, const Eigen::VectorXd& v0,
                       const Eigen::VectorXd& v1) {
    if (!(theta * m.balanced_norm <= 2)) {
      const ExactMatrices d = exact_matrices(m.augmented_A, m.augmented_B, theta, nx_);
      note_accuracy(d, theta);
      return advance(d, v0, v1);
    }
    Eigen::VectorXd z = Eigen::VectorXd::Zero(m.augmented_A.rows());
    z.head(nx_) = x_.cwiseQuotient(m.balance.head(nx_));
    Eigen::VectorXd term = z, w = v0, dw = (v1 - v0) / theta, next;
    for (int k = 1; k < 80; ++k) {
      next.setZero(z.size());
      detail::small_matvec_add(m.balanced_A, z.size(), term.data(), next.data());
      // The inputs' series: v0, theta v', then nothing.
      if (k <= 2) detail::small_matvec_add(m.balanced_B, nw_, w.data(), next.data());
      term = (theta / k) * next;
      w = (theta / k) * dw;
      dw.setZero();
      z += term;
      if (k > 2 && term.cwiseAbs().maxCoeff() <= 1e-18 * z.cwiseAbs().maxCoeff()) break;
    }
    return z.cwiseProduct(m.balance);
  }

  // Adds each slipping element's dissipated energy over [t0, t0 + h]: with p(t0 + s) = p0 + (p1 - p0)
  // s / h, int c p dir s dt = c dir (p1 sigma(h) - (p1 - p0) rho(h) / h), sigma and rho the augmented
  // integrals of the slip (zero at t0). Exact when p is linear over the step.
  void energy_step(const Eigen::VectorXd& z, double t0, double h, bool before) {
    const double t1 = t0 + h;
    const double at1 = before ? std::nextafter(t1, -std::numeric_limits<double>::infinity()) : t1;
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (state_[K] == ElementState::stuck || is_limit(k)) continue;
      const double p0 = command(k, t0), p1 = command(k, at1);
      const double sigma = z(nx_ + k), rho = z(nx_ + ne_ + k);
      energy_(k) += torque_scale(k) * dir_[K] * (p1 * sigma - (p1 - p0) * rho / h);
    }
  }

  // The elements with an event function over [t, t_end] (no breakpoint inside): those whose command
  // is not zero throughout. The others are open from t on.
  const std::vector<char>& watch(double t, double t_end, const EventObserver& on_event) {
    std::vector<char>& watched = watched_;
    watched.assign(static_cast<std::size_t>(ne_), 0);
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      const bool open = command(k, t) == 0 && command(k, std::nextafter(t_end, t)) == 0;
      if (open && state_[K] != ElementState::stuck) {
        const double s = S_.row(k).dot(x_);
        dir_[K] = s > 0 ? 1 : s < 0 ? -1 : dir_[K];
        if (state_[K] != ElementState::open) {
          record(t, k, state_[K], ElementState::open, on_event);
          state_[K] = ElementState::open;
        }
      }
      watched[K] = !open;
    }
    return watched;
  }

  // The element whose event function crossed over a step (g0 at its start, g1 at its end), or -1: a
  // stuck element's margin turned negative, a slip reached zero or changed sign.
  int crossing(const Eigen::VectorXd& g0, const Eigen::VectorXd& g1) const {
    int hit = -1;
    for (int k = 0; k < ne_; ++k) {
      const bool stuck = state_[static_cast<std::size_t>(k)] == ElementState::stuck;
      if (stuck ? g1(k) < 0 : g1(k) < 0 || (g1(k) == 0 && g0(k) > 0)) hit = k;
    }
    return hit;
  }

  // Whether an event function, positive at both ends of the step [t, t + h] (x0, v0 and x1, v1 there),
  // may dip to zero in between: its cubic through the ends' values and rates does.
  bool may_dip(const hybrid_detail::ModeMatrices& m, double t, double h, bool before, const Eigen::VectorXd& x0,
               const Eigen::VectorXd& v0, const Eigen::VectorXd& g0, const Eigen::VectorXd& x1,
               const Eigen::VectorXd& v1, const Eigen::VectorXd& g1, const std::vector<char>& watched) const {
    const double t1 = t + h;
    const Eigen::VectorXd dv = (v1 - v0) / h;
    Eigen::VectorXd p0(ne_), p1(ne_);
    for (int k = 0; k < ne_; ++k) {
      p0(k) = command(k, t);
      p1(k) = command(k, before ? std::nextafter(t1, t) : t1);
    }
    const Eigen::VectorXd dp = (p1 - p0) / h;
    const Eigen::VectorXd r0 = event_rates(m, x0, v0, dv, p0, dp, watched);
    const Eigen::VectorXd r1 = event_rates(m, x1, v1, dv, p1, dp, watched);
    for (int k = 0; k < ne_; ++k)
      if (cubic_dips(g0(k), g1(k), r0(k), r1(k), h)) return true;
    return false;
  }

  // Whether no event function can reach zero within the step [t, t + h] from x0 (v0) to x1 (v1): the
  // modal bound of event_proof.hpp, for every watched function (a stuck element's |T| as both signs of
  // T). False when the mode has no trustworthy modal form.
  bool clear_of_events(const hybrid_detail::ModeMatrices& m, double t, double h, bool before,
                       const Eigen::VectorXd& x0, const Eigen::VectorXd& v0, const Eigen::VectorXd& x1,
                       const Eigen::VectorXd& v1, const std::vector<char>& watched) {
    if (!m.modal.ok) return false;
    const StepProof& p = step_proof_of(m, h);
    slow_motion(p, x0, x1, v0, v1, slow_);
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      // A saturated controller's function is dir (law - held torque).
      const double offset = is_limit(k) ? -dir_[K] * held_torque(k) : 0.0;
      if (watched[K] && state_[K] != ElementState::stuck && !stays_positive(p, slow_, k, dir_[K], offset, offset, h))
        return false;
    }
    const double t1 = t + h, at1 = before ? std::nextafter(t1, t) : t1;
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      const int k = m.stuck[j];
      if (is_limit(k)) {  // torque_max - T and T - torque_min
        const double hi = limit(k).torque_max, lo = limit(k).torque_min;
        if (!stays_positive(p, slow_, k, -1, hi, hi, h) || !stays_positive(p, slow_, k, 1, -lo, -lo, h)) return false;
        continue;
      }
      const auto& el = sys_.elements[static_cast<std::size_t>(k)];
      const double mu_c = el.static_ratio * el.capacity, L0 = mu_c * command(k, t), L1 = mu_c * command(k, at1);
      // mu c p - T and mu c p + T: the margin for each sign of T; a one-way element also -T.
      if (!stays_positive(p, slow_, k, -1, L0, L1, h) || !stays_positive(p, slow_, k, 1, L0, L1, h)) return false;
      if (el.one_way && !stays_positive(p, slow_, k, -1, 0, 0, h)) return false;
    }
    return true;
  }

  // The mode's proof maps for steps of h (or of a length within 1e-9 h of it, as the discretizations).
  const StepProof& step_proof_of(const hybrid_detail::ModeMatrices& m, double h) {
    auto it = near_step(proofs_, mask_, h);
    if (it == proofs_.end()) {
      if (proofs_.size() > 256) proofs_.clear();  // bounded, as the discretizations
      // One function per element: its slip S_k x, or while it is stuck its torque Kx_j x + Kv_j w; a
      // controller's law in either regime.
      Eigen::MatrixXd C = S_, D = Eigen::MatrixXd::Zero(ne_, nw_);
      for (std::size_t j = 0; j < m.stuck.size(); ++j) {
        C.row(m.stuck[j]) = m.Kx.row(static_cast<Eigen::Index>(j));
        D.row(m.stuck[j]) = m.Kv.row(static_cast<Eigen::Index>(j));
      }
      for (int k = nf_; k < ne_; ++k) {
        C.row(k) = limit(k).law_x;
        D.row(k) = limit(k).law_w;
      }
      it = proofs_.emplace(std::make_pair(mask_, h), step_proof(m.modal, m.A, m.B, C, D, h)).first;
    }
    return it->second;
  }

  // Steps from t to t_end (t_end a sample time or a breakpoint), stopping at the first event within
  // it. On return t is t_end, or the event's time with the new mode resolved.
  bool step_to(double& t, double t_end, const EventObserver& on_event, std::string& error) {
    const bool lands_on_break = std::binary_search(breaks_.begin(), breaks_.end(), t_end);
    const std::vector<char>& watched = watch(t, t_end, on_event);
    double h = t_end - t;
    // While an element is watched, a step longer than the mode's event_step is taken only when
    // clear_of_events proves that no event function reaches zero within it; otherwise steps of at
    // most event_step, equal ones, so that they share one discretization. After a failed proof the
    // rest of the sample period is not tried again.
    const double check = mode_of(mask_).event_step;
    if (h > check && std::find(watched.begin(), watched.end(), 1) != watched.end()) {
      if (t_end != unproven_until_) {
        const auto& m = mode_of(mask_);
        Eigen::VectorXd &v0 = step_v0_, &v1 = step_v1_, &z = step_z_, &x1 = step_x1_;
        known_inputs(t, false, v0);
        known_inputs(t_end, lands_on_break, v1);
        advance(discretization(mask_, h), v0, v1, z);
        ++steps_;
        x1 = z.head(nx_);
        if (clear_of_events(m, t, h, lands_on_break, x_, v0, x1, v1, watched)) {
          energy_step(z, t, h, lands_on_break);
          x_.swap(x1);
          t = t_end;
          return lands_on_break ? resolve(t, -1, on_event, error) : true;
        }
        unproven_until_ = t_end;
      }
      h /= std::ceil(h / check - 1e-9);
    }
    for (int depth = 0;; ++depth) {
      const auto& m = mode_of(mask_);
      const double t1 = t + h;
      const bool before = lands_on_break && t1 == t_end;
      const Eigen::VectorXd v0 = known_inputs(t, false), v1 = known_inputs(t1, before);
      const Eigen::VectorXd z = step(m, h, v0, v1);
      ++steps_;
      const Eigen::VectorXd x1 = z.head(nx_);
      const Eigen::VectorXd g0 = event_values(m, x_, v0, t, false, watched);
      const Eigen::VectorXd g1 = event_values(m, x1, v1, t1, before, watched);
      const int hit = crossing(g0, g1);
      // A possible dip halves the step: the exact trajectory is cheap to recompute.
      if (hit < 0 && depth < 30 && may_dip(m, t, h, before, x_, v0, g0, x1, v1, g1, watched)) {
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
      if (!count_location(t, error)) return false;
      // Each value of the iteration from the mode's exact flow at theta: exact up to rounding.
      auto at = [&](double theta, bool before_theta) {
        EventPoint p;
        p.v = known_inputs(t + theta, before_theta);
        p.z = flow(m, theta, v0, p.v);
        p.g = event_values(m, p.z.head(nx_), p.v, t + theta, before_theta, watched);
        return p;
      };
      double a = 0, b = h;
      EventPoint pb{z, g1, v1};
      const int k = locate(t, a, b, g0, pb, at);
      energy_step(pb.z, t, b, false);
      x_ = pb.z.head(nx_);
      t = t + b;
      // The new mode starts ringing: no whole-period proof for the rest of this sample period.
      unproven_until_ = t_end;
      return resolve(t, k, on_event, error);
    }
  }

  // The chattering guard on located events (see max_events_per_sample).
  bool count_location(double t, std::string& error) {
    if (++locations_in_sample_ <= max_events_per_sample * (ne_ + 1)) return true;
    error = "chattering: more than " + std::to_string(max_events_per_sample * (ne_ + 1)) +
            " events within one sample period, at t = " + detail::num(t) +
            " s; shorten the sample period if the changes are real, or check the engagement commands";
    return false;
  }

  // A point of the trajectory in an event's bracket: state (the exact method's augmented one), event
  // functions and known inputs.
  struct EventPoint {
    Eigen::VectorXd z, g, v;
  };

  // The earliest event in (t + a, t + b], g_a the event functions at t + a and pb the point at t + b,
  // where some function has crossed: Illinois iteration on the earliest function that changes sign,
  // at(theta, before) giving the trajectory at t + theta. Returns the element; b and pb become the
  // first representable time where its function has crossed (to 4 ulps) and the point there.
  template <class At>
  int locate(double t, double& a, double& b, const Eigen::VectorXd& g_a, EventPoint& pb, At& at) const {
    auto crossed = [&](const Eigen::VectorXd& g, int k) {
      return state_[static_cast<std::size_t>(k)] == ElementState::stuck ? g(k) < 0 : g(k) <= 0;
    };
    // The earliest crossing among several: shrink the bracket to the first function that crosses.
    const double a0 = a;
    int k = -1;
    for (int i = 0; i < ne_; ++i)
      if (crossed(pb.g, i) && (k < 0 || pb.g(i) / (pb.g(i) - g_a(i)) > pb.g(k) / (pb.g(k) - g_a(k)))) k = i;
    double ga = g_a(k), gb = pb.g(k);
    int side = 0;
    for (int iter = 0; iter < 200; ++iter) {
      const double tol = 4 * std::numeric_limits<double>::epsilon() * std::max(1.0, std::abs(t + b));
      if (b - a <= tol) break;
      double c = ga > 0 && std::isfinite(ga) && gb < ga ? b - gb * (b - a) / (gb - ga) : 0.5 * (a + b);
      if (!(c > a + 0.01 * tol && c < b - 0.01 * tol)) c = 0.5 * (a + b);
      if (ga == 0) c = 0.5 * (a + b);  // a just-released element: no secant from a zero
      EventPoint pc = at(c, false);
      // Another element crossing before k's root: it is the earliest one now.
      int first = -1;
      for (int i = 0; i < ne_; ++i)
        if (crossed(pc.g, i)) first = (first < 0 || i == k) ? i : first;
      if (first >= 0) {
        if (first != k && !crossed(pc.g, k)) {  // keeps the bracket: nothing had crossed at a
          k = first;
          ga = a > a0 ? at(a, false).g(k) : g_a(k);
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
    return k;
  }

  // The right-hand side of the current mode for dopri5 and TR-BDF2: dx/dt = A x + B v(t).
  struct ModeRhs {
    const HybridEngineCore* engine = nullptr;
    const hybrid_detail::ModeMatrices* mode = nullptr;
    Eigen::VectorXd v;
    long evaluations = 0;
    void operator()(double t, const Eigen::VectorXd& x, Eigen::VectorXd& dx) {
      ++evaluations;
      engine->known_inputs(t, false, v);
      dx.noalias() = mode->A * x;
      dx.noalias() += mode->B * v;
    }
  };
  struct ModeJacobian {
    const hybrid_detail::ModeMatrices* mode = nullptr;
    void operator()(double, const Eigen::VectorXd&, Eigen::MatrixXd& J) const { J = mode->A; }
  };

  template <class Stepper>
  Stepper make_stepper() {
    if constexpr (requires { Stepper(rhs_, jacobian_, true, x_, 1.0, 1.0); })
      return Stepper(rhs_, jacobian_, true, x_, method_.options.rtol, method_.options.atol);
    else
      return Stepper(rhs_, x_, method_.options.rtol, method_.options.atol);
  }

  // The energy each slipping element dissipates over [ta, tb] of the stepper's last step: its power
  // T_k s_k, a polynomial of degree 5 at most on the dense output (degree 4 for dopri5, 3 for
  // TR-BDF2, times a command linear between breakpoints), by 3-point Gauss-Legendre, exact for it.
  template <class Stepper>
  void add_dissipation(Stepper& s, double ta, double tb, Eigen::VectorXd& energy) {
    if (!(tb > ta)) return;
    static constexpr double node = 0.7745966692414834, weight[3] = {5.0 / 9, 8.0 / 9, 5.0 / 9};
    const double mid = 0.5 * (ta + tb), half = 0.5 * (tb - ta);
    for (int i = 0; i < 3; ++i) {
      const double ti = mid + (i - 1) * node * half;
      s.dense(ti, dense_x_);
      known_inputs(ti, false, dense_v_);
      for (int k = 0; k < nf_; ++k)
        if (state_[static_cast<std::size_t>(k)] != ElementState::stuck)
          energy(k) += weight[i] * half * dense_v_(nu_ + k) * S_.row(k).dot(dense_x_);
    }
  }

  // The run with dopri5 or TR-BDF2 (after the initial mode and sample): adaptive steps within a mode,
  // ending on breakpoints; after each accepted step the event functions are checked at its end (and,
  // when the cubic through the ends' values and rates dips, at 8 points inside); an event is located
  // on the step's dense output, the samples before it come from there, and the stepper restarts in
  // the new mode.
  template <class Stepper>
  RunStatus run_stepped(const detail::Grid& grid, const SampleObserver& obs, const EventObserver& on_event) {
    const SolverOptions& opt = method_.options;
    const char* name = method_.solver == Solver::dopri5 ? "dopri5" : "implicit";
    double t = 0, h = std::min(opt.h, opt.h_max), h_max = opt.h_max;
    if (!(h > 0)) return fail("invalid step size h = " + detail::num(opt.h), t);
    long k = 1, attempts = 0;
    std::size_t next_break = 0;
    std::string error;
    std::optional<Stepper> s;
    std::uint32_t stepper_mask = 0;
    bool restart = true;
    std::vector<char> watched;
    Eigen::VectorXd g0, v0 = known_inputs(0.0, false), v1, g1, x0, energy = energy_;
    rhs_.engine = this;
    // Samples up to t_new (or before it, when `before`) from the last step's dense output.
    auto emit = [&](double t_new, bool before) {
      while (k < grid.count && (before ? grid.at(k) < t_new : grid.at(k) <= t_new)) {
        const double ts = grid.at(k);
        energy = energy_;
        add_dissipation(*s, t, ts, energy);
        s->dense(ts, dense_x_);
        if (!observe(ts, ts == t_new ? x_ : dense_x_, energy, obs)) return false;
        ++k;
        events_in_sample_.assign(static_cast<std::size_t>(ne_), 0);
        locations_in_sample_ = 0;
      }
      return true;
    };
    // A sample at the instant of an event sees the new mode, as with the exact method.
    auto observe_event_instant = [&](double t_event) {
      if (k >= grid.count || grid.at(k) != t_event) return true;
      if (!observe(t_event, obs)) return false;
      ++k;
      events_in_sample_.assign(static_cast<std::size_t>(ne_), 0);
      locations_in_sample_ = 0;
      return true;
    };
    while (k < grid.count) {
      while (next_break < breaks_.size() && breaks_[next_break] <= t) ++next_break;
      const bool before_break = next_break < breaks_.size();
      const double t_stop = before_break ? breaks_[next_break] : horizon_;
      if (restart) {
        const auto& m = mode_of(mask_);
        rhs_.mode = jacobian_.mode = &m;
        if (!s || stepper_mask != mask_) {
          s.emplace(make_stepper<Stepper>());
          stepper_mask = mask_;
        }
        s->start(t, x_);
        watched = watch(t, t_stop, on_event);
        // As for the exact method, no step longer than the mode's event_step while an element is
        // watched (TR-BDF2 would otherwise step over oscillations it damps numerically).
        h_max = std::find(watched.begin(), watched.end(), 1) != watched.end() ? std::min(opt.h_max, m.event_step)
                                                                               : opt.h_max;
        h = std::min(h, h_max);
        known_inputs(t, false, v0);
        g0 = event_values(m, x_, v0, t, false, watched);
        restart = false;
      }
      const auto& m = *rhs_.mode;
      // A step that would leave a sliver (< 10% of h) before the stop is stretched to end on it.
      const bool clipped = t_stop - t <= std::min(1.1 * h, h_max);
      const double hs = clipped ? t_stop - t : h;
      const bool brk = clipped && before_break;
      if (++attempts > opt.max_steps)
        return fail(std::string(name) + " stopped at t = " + detail::num(t) + ": max_steps = " +
                        std::to_string(opt.max_steps) + " reached",
                    t);
      ++steps_;
      const double err = s->attempt(t, x_, hs, brk);
      const double hmin =
          std::max(16 * std::numeric_limits<double>::epsilon() * std::abs(t), std::numeric_limits<double>::min());
      if (!(err <= 1)) {
        h = std::min(s->next_h(err, hs), h_max);
        if (h < hmin)
          return fail(std::isnan(err) ? "the state is not finite"
                                      : std::string(name) + " stalled at t = " + detail::num(t) + ": step size h = " +
                                            detail::num(h) + " below the minimum",
                      t);
        continue;
      }
      const double t1 = clipped ? t_stop : t + hs;
      x0 = x_;
      s->accept(t, x_, hs);
      known_inputs(t1, brk, v1);
      g1 = event_values(m, x_, v1, t1, brk, watched);
      int hit = crossing(g0, g1);
      double a = 0, b = t1 - t;
      EventPoint pb{x_, g1, v1};
      Eigen::VectorXd g_a = g0;
      auto at = [&](double theta, bool before) {
        EventPoint p;
        s->dense(t + theta, p.z);
        if (theta == t1 - t) p.z = x_;
        p.v = known_inputs(t + theta, before);
        p.g = event_values(m, p.z, p.v, t + theta, before, watched);
        return p;
      };
      if (hit < 0 && may_dip(m, t, b, brk, x0, v0, g0, x_, v1, g1, watched)) {
        // The dense output at 8 points: the first that has crossed closes the bracket.
        for (int i = 1; i < 8 && hit < 0; ++i) {
          EventPoint p = at(b * i / 8, false);
          hit = crossing(g_a, p.g);
          if (hit >= 0) {
            a = b * (i - 1) / 8;
            b = b * i / 8;
            pb = std::move(p);
          } else {
            g_a = p.g;
          }
        }
      }
      if (hit < 0) {
        // A sample on a breakpoint waits for the mode the breakpoint's commands resolve to.
        if (!emit(t1, brk)) return RunStatus{false, "stopped", t1};
        add_dissipation(*s, t, t1, energy_);
        const double h_next = s->next_h(err, hs);
        // A step shortened to end on a stop says nothing against the step size before it.
        h = std::min(clipped ? std::max(h, h_next) : h_next, h_max);
        t = t1;
        std::swap(v0, v1);
        std::swap(g0, g1);
        if (!x_.allFinite()) return fail("the state is not finite", t);
        if (brk) {
          if (!resolve(t, -1, on_event, error)) return fail(error, t);
          restart = true;
          if (!observe_event_instant(t)) return RunStatus{false, "stopped", t};
        }
        continue;
      }
      if (!count_location(t, error)) return fail(error, t);
      const int element = locate(t, a, b, g_a, pb, at);
      const double te = t + b;
      x_ = pb.z;
      if (!emit(te, true)) return RunStatus{false, "stopped", te};
      add_dissipation(*s, t, te, energy_);
      t = te;
      if (!resolve(t, element, on_event, error)) return fail(error, t);
      restart = true;
      if (!observe_event_instant(t)) return RunStatus{false, "stopped", t};
    }
    return RunStatus{true, "", t};
  }

  void record(double t, int k, ElementState from, ElementState to, const EventObserver& on_event) {
    if (from == to) return;
    on_event(HybridEvent{t, k, from, to});
  }

  // The consistent mode at time t: every element that is stuck, or whose slip is zero (or just
  // reached zero: `trigger`), is tried stuck; the one whose torque exceeds its static capacity by
  // the largest factor is released (slipping in its torque's direction) and the rest solved again,
  // until every stuck torque is within capacity. Elements released at an instant stay released
  // within it, so the loop ends after at most one pass per element.
  bool resolve(double t, int trigger, const EventObserver& on_event, std::string& error) {
    const std::vector<ElementState> old = state_;
    std::uint32_t mask = 0;
    const Eigen::VectorXd slip = S_ * x_;
    // An element without command until the next breakpoint holds nothing: it is no candidate (at
    // rest every slip is zero, and open elements tried stuck could over-constrain the gear). A
    // controller is always tried within its limits: it leaves saturation whenever its law allows.
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (is_limit(k) || (!open_after(k, t) && (state_[K] == ElementState::stuck || slip(k) == 0 || k == trigger)))
        mask |= 1u << k;
      else if (slip(k) != 0) dir_[K] = slip(k) > 0 ? 1 : -1;
    }
    for (int round = 0; round <= ne_; ++round) {
      const auto& m = mode_of(mask);
      if (m.singular) {
        std::string names;
        for (int k : m.stuck) names += (names.empty() ? "" : ", ") + element_name(k);
        error = m.ill_conditioned
                    ? "the stuck elements " + names + " join bodies of inertias too disparate for double precision " +
                          "to determine their torques at t = " + detail::num(t) +
                          " s; check the inertias (a tiny one beside a huge one)"
                    : "the stuck elements " + names + " constrain the gear more than once at t = " + detail::num(t) +
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
        if (is_limit(k)) {  // beyond a limit: by how much, relative to the range
          const double Tk = T(static_cast<Eigen::Index>(j)), lo = limit(k).torque_min, hi = limit(k).torque_max;
          const double range = std::isfinite(hi - lo) ? hi - lo : std::max({1.0, std::abs(std::isfinite(hi) ? hi : lo)});
          const double ratio = Tk > hi ? 1 + (Tk - hi) / range : Tk < lo ? 1 + (lo - Tk) / range : 0.0;
          if (ratio > worst_ratio) {
            worst_ratio = ratio;
            worst = k;
          }
          continue;
        }
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
        if (m.stuck[j] == worst) {
          const double Tw = T(static_cast<Eigen::Index>(j));
          dir_[W] = is_limit(worst) ? (Tw > limit(worst).torque_max ? 1 : -1) : (Tw > 0 ? 1 : -1);
        }
      mask &= ~(1u << worst);
    }
    for (int k = 0; k < ne_; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (state_[K] != ElementState::stuck && open_after(k, t)) state_[K] = ElementState::open;
      if (old[K] != state_[K]) {
        record(t, k, old[K], state_[K], on_event);
        if (++events_in_sample_[K] > max_events_per_sample) {
          error = "chattering: " + element_name(k) + " changed state more than " +
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
  int ne_ = 0, nf_ = 0;  // elements, and of them brakes and clutches (the rest: torque limits)
  Eigen::MatrixXd S_;    // the slips of all elements (the limits' rows zero)
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
  HybridMethod method_;
  ModeRhs rhs_;
  ModeJacobian jacobian_;
  Eigen::VectorXd dense_x_, dense_v_;  // scratch of add_dissipation and the samples
  double unproven_until_ = -1;         // the end of the sample period whose long step was not clear
  std::map<std::pair<std::uint32_t, double>, StepProof> proofs_;  // clear_of_events' maps per mode and step
  SlowMotion slow_;
  std::optional<std::pair<double, double>> inaccurate_;  // the step and error of an untrusted exponential
  // Scratch of the steps and samples, kept from step to step to stay off the heap.
  std::vector<char> watched_;
  Eigen::VectorXd step_v0_, step_v1_, step_z_, step_x1_, advance_dv_, sample_w_, sample_T_, sample_slip_;
  std::map<std::pair<std::uint32_t, double>, int> taylor_uses_;  // step lengths taken by Taylor series
};


POGEAR_RT_API HybridEngine::HybridEngine(const HybridSystem& sys, double horizon, HybridMethod method)
    : core_(std::make_unique<HybridEngineCore>(sys, horizon, std::move(method))) {}

POGEAR_RT_API HybridEngine::~HybridEngine() = default;

POGEAR_RT_API RunStatus HybridEngine::run(const Eigen::VectorXd& x0, double sample, const SampleObserver& obs,
                                          const EventObserver& on_event) {
  return core_->run(x0, sample, obs, on_event);
}

POGEAR_RT_API int HybridEngine::modes_met() const { return core_->modes_met(); }

POGEAR_RT_API long HybridEngine::steps() const { return core_->steps(); }

POGEAR_RT_API long HybridEngine::rhs_evals() const { return core_->rhs_evals(); }

POGEAR_RT_ABI_END

}  // namespace pogear::rt
