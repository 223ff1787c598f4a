// The systems of brakes and clutches: a linear system with the elements' torques as inputs and
// their slips as outputs, and the matrices of one mode of it (a set of stuck elements).
#pragma once

#include <Eigen/Dense>
#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <optional>
#include <string>
#include <utility>
#include <vector>

#include "pogear/balancing.hpp"
#include "pogear/hybrid_observe.hpp"
#include "pogear/state_torques.hpp"
#include "pogear/run_support.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

// A brake or clutch as a run sees it: torque capacity c (kinetic, at full engagement), the static
// friction ratio mu_s / mu_k, and the engagement command p(t) in [0, 1] (piecewise linear).
// A one-way element (freewheel) carries no torque while its slip is positive and holds against
// negative slip only. Kinetic friction that varies with slip s: slipping, the element carries
// c p(t) f(|s|), f the friction curve over |s| [rad/s] from 0 (held beyond its last point); without
// one, f = 1 and the element is linear.
struct FrictionElementData {
  std::string name;
  double capacity = 0, static_ratio = 1;
  Signal command;
  bool one_way = false;
  Table friction_curve = {};  // "= {}": a brace list that stops before it is complete (-Wmissing-field-initializers)
  // The actuator between command and engagement (actuator.hpp): fill delay and lag [s], 0 without.
  double fill_delay = 0, time_constant = 0;
  // Stuck at t = 0 by a start in a gear, whose state holds it there: a run whose capacities let it
  // slip at the start (other --param values than the generator checked) is refused.
  bool held_at_start = false;
};

inline bool actuated(const FrictionElementData& e) { return e.fill_delay > 0 || e.time_constant > 0; }

inline bool varies_with_slip(const FrictionElementData& e) { return !e.friction_curve.t.empty(); }
// f(|s|) at slip s, and its rate over s (the curve is of |s|: its slope times the sign of s).
inline double friction_ratio(const FrictionElementData& e, double s) {
  return varies_with_slip(e) ? e.friction_curve.value(std::abs(s)) : 1.0;
}
inline double friction_ratio_slope(const FrictionElementData& e, double s) {
  return varies_with_slip(e) ? std::copysign(table_slope(e.friction_curve, std::abs(s)), s) : 0.0;
}
// The largest torque the element carries, over its capacity at full command: stuck or slipping.
inline double largest_friction_ratio(const FrictionElementData& e) {
  double r = e.static_ratio;
  for (const double f : e.friction_curve.v) r = std::max(r, f);
  return r;
}

// A speed controller's torque limits (docs/scene-format.md, "Controllers"). The engine treats the
// controller as an element after the brakes and clutches: "stuck" is its linear regime, where its
// torque is its law T = law_x x + law_w w and lies within [torque_min, torque_max]; "slipping" is
// its saturation, the torque held at the limit it reached until the law comes back within the
// limits. (Its integral's anti-windup is in M and N: a term in T - law, zero within the limits.)
// It has no slip and dissipates nothing.
struct TorqueLimitData {
  std::string name;
  double torque_min = -std::numeric_limits<double>::infinity(), torque_max = std::numeric_limits<double>::infinity();
  Eigen::RowVectorXd law_x, law_w;  // over the states and over w (its entries on the known inputs only)
  // A slip controller (docs/scene-format.md, "Slip control") supplies the torque of friction element
  // `supplies`, its column that element's, from `starts_at` or from the start of triggered signal
  // `started_by` until that element's slip reaches zero; its limits are 0 and the element's capacity
  // in the direction of its target. Before and after, it is off (open, its torque 0) and the element
  // carries its own torque, at command 1 from the controller's start on. Its integral, state
  // `integral`, starts where the law continues the element's command (bumpless).
  int supplies = -1;
  double starts_at = 0;
  int started_by = -1;
  Eigen::Index integral = -1;
};

// A speed or a slip crossing a value, the event a triggered signal may wait for instead of an
// element's change of state: |S_k x| of friction element `slip_of` (value > 0), or the speed
// `speed` x (a row over the states; run_hybrid_system fills it from the system's output `output`),
// crossing `value` [rad/s] upward or downward. It fires at the first crossing after t = 0: a
// quantity beyond the value at the start must come back first.
struct CrossingTrigger {
  int slip_of = -1;
  Eigen::RowVectorXd speed;
  std::string output;
  double value = 0;
  bool upward = false;
};

// A signal of the system that starts on an event (docs/scene-format.md, "Triggered signals"): an
// input's (index into HybridSystem::inputs) or an element's command (into elements). Its times count
// from the instant `element` first enters `state` (slipping or stuck) after the start, or `crossing`
// first happens (then `element` is unused), plus `delay`; until then the signal is `before`, a
// signal of time (without one: the value the signal has before its own times, held_until_start).
struct TriggeredSignal {
  bool command = false;
  int index = -1;
  int element = -1;
  ElementState state = ElementState::stuck;
  double delay = 0;
  std::string name;  // in the events file
  std::optional<Signal> before;
  std::optional<CrossingTrigger> crossing;
};

// The system with its friction elements and torque limits: dx/dt = M x + N w, w = [u; q; T], the
// scene's inputs u (signals of time), the state torques q (functions of the state and time), one torque T_k per
// friction element, acting as -T_k on the element's first body and +T_k on its second, then one per
// torque-limited controller; the friction elements' slips s = S x. A stuck friction element is the
// constraint S_k x = 0 with T_k its multiplier. With quadratic torques the modes are nonlinear:
// dopri5 and TR-BDF2 step them, exact stepping is refused.
struct HybridSystem {
  Eigen::MatrixXd M, N, S;
  std::vector<FrictionElementData> elements;
  std::vector<TorqueLimitData> limits;
  std::vector<Signal> inputs;  // u
  std::vector<StateTorqueData> state_torques;  // q
  std::vector<TriggeredSignal> triggered;
  // The states that are speeds (rad/s): the scale of the zero-slip rule (hybrid_data.hpp). Empty:
  // the states some slip reads.
  std::vector<Eigen::Index> speed_states;
};

// Whether some element's friction varies with slip: its slipping modes are then nonlinear.
inline bool varies_with_slip(const HybridSystem& sys) {
  return std::any_of(sys.elements.begin(), sys.elements.end(), [](const FrictionElementData& e) { return varies_with_slip(e); });
}

// Whether some element's actuator lags its command: the engagement is then exponential between the
// command's breakpoints, not linear.
inline bool lags_its_command(const HybridSystem& sys) {
  return std::any_of(sys.elements.begin(), sys.elements.end(), [](const FrictionElementData& e) { return e.time_constant > 0; });
}

// The triggered signals that wait for a crossing (each runs as a monitor: hybrid_crossings.hpp).
inline int crossing_count(const HybridSystem& sys) {
  int n = 0;
  for (const TriggeredSignal& s : sys.triggered) n += s.crossing.has_value();
  return n;
}

// A system's own input columns N (its signals', the driveline's state torques', then its elements'
// and limits') with the quadratic loads' columns Nq inserted after the first `head`, as HybridSystem::N
// orders them (w = [u; q; T]); and a controller's law over the system's inputs padded to that order
// (a law reads no quadratic torque).
inline Eigen::MatrixXd with_quadratic_columns(const Eigen::MatrixXd& N, Eigen::Index head, const Eigen::MatrixXd& Nq) {
  Eigen::MatrixXd out(N.rows(), N.cols() + Nq.cols());
  out << N.leftCols(head), Nq, N.rightCols(N.cols() - head);
  return out;
}
inline Eigen::RowVectorXd law_with_quadratic_columns(const Eigen::RowVectorXd& law, Eigen::Index head, Eigen::Index nq) {
  Eigen::RowVectorXd out = Eigen::RowVectorXd::Zero(law.size() + nq);
  out.head(head) = law.head(head);
  out.tail(law.size() - head) = law.tail(law.size() - head);
  return out;
}

namespace hybrid_detail {

// The matrices of one mode: dx/dt = A x + B v, v = w with the stuck torques set to zero (they are
// B's zero columns), and the stuck torques T_S = Kx x + Kv v. With H = S_S the stuck rows and N_S
// their torque columns, H dx/dt = 0 gives T_S = -(H N_S)^-1 H (M x + N v): H N_S = -H L^-1 H^T is
// definite when the stuck rows are independent, and the projector I - N_S (H N_S)^-1 H keeps the
// state on the mode's constraints.
struct ModeMatrices {
  std::vector<int> stuck;  // element indices, in order
  Eigen::MatrixXd A, B, Kx, Kv;
  Eigen::MatrixXd projector;  // onto H x = 0
  Eigen::MatrixXd augmented_A, augmented_B;  // with the slip integrals (see ExactStepper::add_energy)
  // augmented_A balanced, D^-1 augmented_A D with D = diag(balance) (powers of 2, so exact), and the
  // largest absolute row sum of it; and D^-1 augmented_B. Forces in N next to speeds in rad/s make
  // augmented_A's norm 1e7 where its spectral radius is 3e4: balanced, a short Taylor series of
  // the flow converges without cancellation (ExactStepper::flow).
  Eigen::VectorXd balance;
  Eigen::MatrixXd balanced_A, balanced_B;
  double balanced_norm = 0;
  double event_step = std::numeric_limits<double>::infinity();  // event_check_step(A), set by mode_of
  ModalForm modal;  // of A and B, set by mode_of (hybrid_mode_cache.hpp)
  // The stuck torques cannot be determined: the stuck rows are dependent (they constrain the gear
  // more than once), or, with `ill_conditioned`, independent but across inertias so disparate that
  // double precision cannot separate them (the torques would carry no correct digit).
  bool singular = false;
  bool ill_conditioned = false;
};

inline ModeMatrices mode_matrices(const HybridSystem& sys, std::uint32_t mask) {
  const Eigen::Index nx = sys.M.rows(), nw = sys.N.cols(), nf = sys.S.rows(),
                     nl = static_cast<Eigen::Index>(sys.limits.size()), ne = nf + nl, nu = nw - ne;
  ModeMatrices m;
  for (Eigen::Index k = 0; k < ne; ++k)
    if (mask & (1u << k)) m.stuck.push_back(static_cast<int>(k));
  // Torque limits first: a controller within its limits is a known feedback, its torque column
  // closed through its law; at a limit its torque is a known input.
  Eigen::MatrixXd M0 = sys.M, N0 = sys.N;
  for (Eigen::Index l = 0; l < nl; ++l) {
    const TorqueLimitData& c = sys.limits[static_cast<std::size_t>(l)];
    const Eigen::Index col = nu + nf + l;
    if (mask & (1u << (nf + l))) {
      M0 += sys.N.col(col) * c.law_x;
      N0 += sys.N.col(col) * c.law_w;
      N0.col(col).setZero();
    }
  }
  std::vector<int> stuck_friction;
  for (const int k : m.stuck)
    if (k < nf) stuck_friction.push_back(k);
  const auto ns = static_cast<Eigen::Index>(stuck_friction.size());
  Eigen::MatrixXd Bv = N0;
  m.projector = Eigen::MatrixXd::Identity(nx, nx);
  Eigen::MatrixXd Kx_f = Eigen::MatrixXd::Zero(ns, nx), Kv_f = Eigen::MatrixXd::Zero(ns, nw);
  Eigen::MatrixXd NS(nx, ns);
  if (ns > 0) {
    Eigen::MatrixXd H(ns, nx);
    for (Eigen::Index j = 0; j < ns; ++j) {
      H.row(j) = sys.S.row(stuck_friction[static_cast<std::size_t>(j)]);
      NS.col(j) = N0.col(nu + stuck_friction[static_cast<std::size_t>(j)]);
      Bv.col(nu + stuck_friction[static_cast<std::size_t>(j)]).setZero();
    }
    // H N_S = -H L^-1 H^T has the rank of the stuck rows H, since L is definite. Dependent rows
    // over-constrain the gear and leave their torques undetermined (the caller reports it). The
    // rank is decided on H itself, each row scaled to a largest entry of 1: H N_S carries the
    // inertias' spread on its diagonal (1/J: 1e9 against 1e-9 for brakes on trains of 1e-9 and
    // 1e9 kg m^2), where a relative pivot threshold would drop the small pivots of independent rows.
    Eigen::MatrixXd Hs = H;
    for (Eigen::Index j = 0; j < ns; ++j)
      if (const double big = Hs.row(j).cwiseAbs().maxCoeff(); big > 0) Hs.row(j) /= big;
    if (Eigen::FullPivLU<Eigen::MatrixXd>(Hs).rank() < ns) {
      m.singular = true;
      return m;
    }
    // Solved as D (D H N_S D)^-1 D, D in powers of 2 (exact) giving a unit diagonal: independent
    // elements on separate trains then solve to the last bit. Rows that couple bodies of disparate
    // inertias stay ill-conditioned after it; past an error of 1e-8 the torques are refused.
    const Eigen::MatrixXd HN = H * NS;
    Eigen::VectorXd d(ns);
    for (Eigen::Index j = 0; j < ns; ++j)
      d(j) = HN(j, j) != 0 && std::isfinite(HN(j, j)) ? std::ldexp(1.0, -std::ilogb(HN(j, j)) / 2) : 1.0;
    const Eigen::PartialPivLU<Eigen::MatrixXd> lu(d.asDiagonal() * HN * d.asDiagonal());
    if (!(lu.rcond() * 1e-8 >= std::numeric_limits<double>::epsilon())) {
      m.singular = m.ill_conditioned = true;
      return m;
    }
    auto solve = [&](const Eigen::MatrixXd& X) -> Eigen::MatrixXd { return d.asDiagonal() * lu.solve(d.asDiagonal() * X); };
    Kx_f = -solve(H * M0);
    Kv_f = -solve(H * Bv);
    m.projector -= NS * solve(H);
  }
  m.A = M0;
  m.B = Bv;
  for (Eigen::Index j = 0; j < ns; ++j) {  // rank-one updates, in the order of the stuck elements
    m.A += NS.col(j) * Kx_f.row(j);
    m.B += NS.col(j) * Kv_f.row(j);
  }
  // The stuck elements' torques T_S = Kx x + Kv v, in the order of m.stuck: a friction element's
  // from its constraint, a controller's from its law.
  const auto nstuck = static_cast<Eigen::Index>(m.stuck.size());
  m.Kx = Eigen::MatrixXd::Zero(nstuck, nx);
  m.Kv = Eigen::MatrixXd::Zero(nstuck, nw);
  for (Eigen::Index j = 0, f = 0; j < nstuck; ++j) {
    const int k = m.stuck[static_cast<std::size_t>(j)];
    if (k < nf) {
      m.Kx.row(j) = Kx_f.row(f);
      m.Kv.row(j) = Kv_f.row(f++);
    } else {
      m.Kx.row(j) = sys.limits[static_cast<std::size_t>(k - nf)].law_x;
      m.Kv.row(j) = sys.limits[static_cast<std::size_t>(k - nf)].law_w;
    }
  }
  // Augmented with sigma' = S x and rho' = sigma: the integrals that make each element's dissipated
  // energy exact over a step (ExactStepper::add_energy).
  const Eigen::Index na = nx + 2 * ne;
  m.augmented_A = Eigen::MatrixXd::Zero(na, na);
  m.augmented_A.topLeftCorner(nx, nx) = m.A;
  m.augmented_A.block(nx, 0, nf, nx) = sys.S;  // a controller's rows stay zero: no slip
  m.augmented_A.block(nx + ne, nx, ne, ne) = Eigen::MatrixXd::Identity(ne, ne);
  m.augmented_B = Eigen::MatrixXd::Zero(na, nw);
  m.augmented_B.topRows(nx) = m.B;
  m.balanced_A = m.augmented_A;
  m.balance = balance(m.balanced_A, 30);
  m.balanced_B = m.balance.cwiseInverse().asDiagonal() * m.augmented_B;
  m.balanced_norm = na ? m.balanced_A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  return m;
}

}  // namespace hybrid_detail

}  // namespace pogear::rt
