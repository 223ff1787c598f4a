// The benchmark's own statement of stick–slip modes (docs/friction-elements.md), written apart from
// the runtime's engine and over any scalar: in long double it is the reference the events benchmark
// measures every method against, in double the mode logic of the CVODE peer.
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <variant>
#include <vector>

#include <pogear/signals.hpp>

namespace bench {

namespace rt = pogear::rt;

enum class Phase { open, slipping, stuck };
inline const char* phase_name(Phase p) { return p == Phase::open ? "open" : p == Phase::slipping ? "slipping" : "stuck"; }

struct RefEvent {
  long double t = 0;
  int element = 0;
  Phase from = Phase::open, to = Phase::open;
};

// A piecewise linear signal's value in the scalar T (constants and tables: what the events scene
// uses), so that a long-double run does not round its times through double.
template <class T>
T signal_value(const rt::Signal& s, T t) {
  if (const auto* c = std::get_if<rt::Constant>(&s)) return T(c->v);
  const auto& tab = std::get<rt::Table>(s);  // the caller checks the forms (hybrid_forms_supported)
  if (!(t >= T(tab.t.front()))) return T(tab.v.front());
  if (t >= T(tab.t.back())) return T(tab.v.back());
  std::size_t i = 1;
  while (!(t < T(tab.t[i]))) ++i;
  const T w = (t - T(tab.t[i - 1])) / (T(tab.t[i]) - T(tab.t[i - 1]));
  return T(tab.v[i - 1]) + w * (T(tab.v[i]) - T(tab.v[i - 1]));
}

inline bool hybrid_forms_supported(const std::vector<rt::Signal>& signals) {
  for (const auto& s : signals)
    if (!std::holds_alternative<rt::Constant>(s) && !std::holds_alternative<rt::Table>(s)) return false;
  return true;
}

struct ElementSpec {
  double capacity = 0, static_ratio = 1;
  rt::Signal command;
  bool one_way = false;
};

// dx/dt = M x + N w, w = [u; T]; slips S x. The mode with stuck set `stuck`: dx/dt = A x + B v with
// the stuck torques Kx x + Kv v.
template <class T>
struct ModeOf {
  using Mat = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  std::vector<int> stuck;
  Mat A, B, Kx, Kv, P;  // P: projector onto the stuck constraints
  bool singular = false;
};

template <class T>
struct HybridProblem {
  using Mat = Eigen::Matrix<T, Eigen::Dynamic, Eigen::Dynamic>;
  using Vec = Eigen::Matrix<T, Eigen::Dynamic, 1>;
  Mat M, N, S;
  std::vector<rt::Signal> inputs;
  std::vector<ElementSpec> elements;
  int nx = 0, nu = 0, ne = 0;

  ModeOf<T> mode(std::uint32_t mask) const {
    ModeOf<T> m;
    for (int k = 0; k < ne; ++k)
      if (mask >> k & 1u) m.stuck.push_back(k);
    const auto ns = static_cast<Eigen::Index>(m.stuck.size());
    Mat Bv = N;
    m.P = Mat::Identity(nx, nx);
    m.Kx = Mat::Zero(ns, nx);
    m.Kv = Mat::Zero(ns, nu + ne);
    if (ns) {
      Mat H(ns, nx), NS(nx, ns);
      for (Eigen::Index j = 0; j < ns; ++j) {
        H.row(j) = S.row(m.stuck[j]);
        NS.col(j) = N.col(nu + m.stuck[j]);
        Bv.col(nu + m.stuck[j]).setZero();
      }
      const Eigen::FullPivLU<Mat> lu(H * NS);
      if (lu.rank() < ns) {
        m.singular = true;
        return m;
      }
      m.Kx = -lu.solve(H * M);
      m.Kv = -lu.solve(H * Bv);
      m.P -= NS * lu.solve(H);
    }
    m.A = M;
    m.B = Bv;
    for (Eigen::Index j = 0; j < ns; ++j) {
      m.A += N.col(nu + m.stuck[j]) * m.Kx.row(j);
      m.B += N.col(nu + m.stuck[j]) * m.Kv.row(j);
    }
    return m;
  }
};

// The elements' phases and slip directions, and the rules: known inputs, event functions, and the
// mode at an instant (stuck where the slip is zero unless the static capacity cannot hold, the
// element most over it released first).
template <class T>
struct Phases {
  using Vec = Eigen::Matrix<T, Eigen::Dynamic, 1>;
  const HybridProblem<T>* pb = nullptr;
  std::vector<Phase> phase;
  std::vector<int> dir;
  std::uint32_t mask = 0;

  T command(int k, T t) const { return signal_value(pb->elements[static_cast<std::size_t>(k)].command, t); }
  // Open from t until `t_next` (the next breakpoint): the command is zero at both ends (linear between).
  bool open_over(int k, T t, T t_next) const { return command(k, t) == 0 && command(k, (t + t_next) / 2) == 0; }

  Vec known(T t) const {
    Vec v(pb->nu + pb->ne);
    for (int i = 0; i < pb->nu; ++i) v(i) = signal_value(pb->inputs[static_cast<std::size_t>(i)], t);
    for (int k = 0; k < pb->ne; ++k) {
      const auto& e = pb->elements[static_cast<std::size_t>(k)];
      const auto K = static_cast<std::size_t>(k);
      const T scale = e.one_way && dir[K] > 0 ? T(0) : T(e.capacity);
      v(pb->nu + k) = phase[K] == Phase::stuck ? T(0) : scale * command(k, t) * T(dir[K]);
    }
    return v;
  }

  // Event functions: slipping elements dir * slip, stuck ones mu c p - |T| (and -T for a one-way
  // element); +inf for open ones.
  Vec events(const ModeOf<T>& m, const Vec& x, T t) const {
    Vec g = Vec::Constant(pb->ne, std::numeric_limits<T>::infinity());
    const Vec v = known(t);
    Vec Ts;
    if (!m.stuck.empty()) Ts = m.Kx * x + m.Kv * v;
    for (int k = 0; k < pb->ne; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (phase[K] == Phase::slipping) g(k) = T(dir[K]) * pb->S.row(k).dot(x);
    }
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      const int k = m.stuck[j];
      const auto& e = pb->elements[static_cast<std::size_t>(k)];
      const T Tk = Ts(static_cast<Eigen::Index>(j));
      g(k) = T(e.static_ratio) * T(e.capacity) * command(k, t) - std::abs(Tk);
      if (e.one_way) g(k) = std::min(g(k), -Tk);
    }
    return g;
  }

  bool crossed(const Vec& g, int k) const {
    return phase[static_cast<std::size_t>(k)] == Phase::stuck ? g(k) < 0 : g(k) <= 0;
  }

  // The mode at time t for state x (projected onto it), `trigger` the element whose event this is.
  // Appends the changes to `log`. False when the stuck elements over-constrain the gear.
  bool resolve(T t, T t_next, int trigger, Vec& x, std::vector<RefEvent>& log) {
    const std::vector<Phase> old = phase;
    const Vec slip = pb->S * x;
    std::uint32_t m = 0;
    for (int k = 0; k < pb->ne; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (!open_over(k, t, t_next) && (phase[K] == Phase::stuck || slip(k) == 0 || k == trigger)) m |= 1u << k;
      else if (slip(k) != 0) dir[K] = slip(k) > 0 ? 1 : -1;
    }
    for (int round = 0; round <= pb->ne; ++round) {
      const ModeOf<T> md = pb->mode(m);
      if (md.singular) return false;
      for (int k = 0; k < pb->ne; ++k) phase[static_cast<std::size_t>(k)] = m >> k & 1u ? Phase::stuck : Phase::slipping;
      const Vec Ts = md.Kx * (md.P * x) + md.Kv * known(t);
      int worst = -1;
      T worst_ratio = 1;
      for (std::size_t j = 0; j < md.stuck.size(); ++j) {
        const int k = md.stuck[j];
        const auto& e = pb->elements[static_cast<std::size_t>(k)];
        const T limit = T(e.static_ratio) * T(e.capacity) * command(k, t), Tj = Ts(static_cast<Eigen::Index>(j));
        T ratio = limit > 0 ? std::abs(Tj) / limit : (Tj != 0 ? std::numeric_limits<T>::infinity() : T(0));
        if (e.one_way && Tj > 0) ratio = std::numeric_limits<T>::infinity();
        if (ratio > worst_ratio) {
          worst_ratio = ratio;
          worst = k;
          dir[static_cast<std::size_t>(k)] = Tj > 0 ? 1 : -1;
        }
      }
      if (worst < 0) {
        mask = m;
        x = md.P * x;
        break;
      }
      m &= ~(1u << worst);
    }
    for (int k = 0; k < pb->ne; ++k) {
      const auto K = static_cast<std::size_t>(k);
      if (phase[K] != Phase::stuck && open_over(k, t, t_next)) phase[K] = Phase::open;
      if (phase[K] != old[K]) log.push_back(RefEvent{static_cast<long double>(t), k, old[K], phase[K]});
    }
    return true;
  }
};

}  // namespace bench
