// The systems of brakes and clutches: a linear system with the elements' torques as inputs and
// their slips as outputs, and the matrices of one mode of it (a set of stuck elements).
#pragma once

#include <Eigen/Dense>
#include <cmath>
#include <cstdint>
#include <limits>
#include <string>
#include <vector>

#include "pogear/run_support.hpp"
#include "pogear/signals.hpp"

namespace pogear::rt {

// A brake or clutch as a run sees it: torque capacity c (kinetic, at full engagement), the static
// friction ratio mu_s / mu_k, and the engagement command p(t) in [0, 1] (piecewise linear).
// A one-way element (freewheel) carries no torque while its slip is positive and holds against
// negative slip only.
struct FrictionElementData {
  std::string name;
  double capacity = 0, static_ratio = 1;
  Signal command;
  bool one_way = false;
};

// The system with its friction elements: dx/dt = M x + N w, w = [u; T], the scene's nu inputs u and
// one torque T_k per element, acting as -T_k on the element's first body and +T_k on its second; its
// slips s = S x. A stuck element is the constraint S_k x = 0 with T_k its multiplier.
struct HybridSystem {
  Eigen::MatrixXd M, N, S;
  std::vector<FrictionElementData> elements;
  std::vector<Signal> inputs;  // u
};

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
  Eigen::MatrixXd augmented_A, augmented_B;  // with the slip integrals (see Engine::energy_step)
  // augmented_A balanced, D^-1 augmented_A D with D = diag(balance) (powers of 2, so exact), and the
  // largest absolute row sum of it; and D^-1 augmented_B. Forces in N next to speeds in rad/s make
  // augmented_A's norm 1e7 where its spectral radius is 3e4: balanced, a short Taylor series of
  // the flow converges without cancellation (Engine::flow).
  Eigen::VectorXd balance;
  Eigen::MatrixXd balanced_A, balanced_B;
  double balanced_norm = 0;
  double event_step = std::numeric_limits<double>::infinity();  // event_check_step(A), set by the engine
  ModalForm modal;  // of A and B, set by the engine (HybridEngine::mode_of)
  bool singular = false;
};

inline ModeMatrices mode_matrices(const HybridSystem& sys, std::uint32_t mask) {
  const Eigen::Index nx = sys.M.rows(), nw = sys.N.cols(), ne = sys.S.rows(), nu = nw - ne;
  ModeMatrices m;
  for (Eigen::Index k = 0; k < ne; ++k)
    if (mask & (1u << k)) m.stuck.push_back(static_cast<int>(k));
  const auto ns = static_cast<Eigen::Index>(m.stuck.size());
  Eigen::MatrixXd Bv = sys.N;
  m.projector = Eigen::MatrixXd::Identity(nx, nx);
  m.Kx = Eigen::MatrixXd::Zero(ns, nx);
  m.Kv = Eigen::MatrixXd::Zero(ns, nw);
  if (ns > 0) {
    Eigen::MatrixXd H(ns, nx), NS(nx, ns);
    for (Eigen::Index j = 0; j < ns; ++j) {
      H.row(j) = sys.S.row(m.stuck[j]);
      NS.col(j) = sys.N.col(nu + m.stuck[j]);
      Bv.col(nu + m.stuck[j]).setZero();
    }
    const Eigen::MatrixXd HN = H * NS;
    const Eigen::FullPivLU<Eigen::MatrixXd> lu(HN);
    // H N_S = -H L^-1 H^T: its rank is that of the stuck rows. Dependent rows over-constrain the
    // gear and leave their torques undetermined (the caller reports it).
    if (lu.rank() < ns) {
      m.singular = true;
      return m;
    }
    m.Kx = -lu.solve(H * sys.M);
    m.Kv = -lu.solve(H * Bv);
    m.projector -= NS * lu.solve(H);
  }
  m.A = sys.M;
  m.B = Bv;
  for (Eigen::Index j = 0; j < ns; ++j) {
    m.A += sys.N.col(nu + m.stuck[j]) * m.Kx.row(j);
    m.B += sys.N.col(nu + m.stuck[j]) * m.Kv.row(j);
  }
  // Augmented with sigma' = S x and rho' = sigma: the integrals that make each element's dissipated
  // energy exact over a step (Engine::energy_step).
  const Eigen::Index na = nx + 2 * ne;
  m.augmented_A = Eigen::MatrixXd::Zero(na, na);
  m.augmented_A.topLeftCorner(nx, nx) = m.A;
  m.augmented_A.block(nx, 0, ne, nx) = sys.S;
  m.augmented_A.block(nx + ne, nx, ne, ne) = Eigen::MatrixXd::Identity(ne, ne);
  m.augmented_B = Eigen::MatrixXd::Zero(na, nw);
  m.augmented_B.topRows(nx) = m.B;
  // Osborne's iteration with powers of 2, as LAPACK's gebal: column i times f, row i over f, until
  // each row and column have about the same absolute sum.
  m.balance = Eigen::VectorXd::Ones(na);
  m.balanced_A = m.augmented_A;
  for (int sweep = 0; sweep < 30; ++sweep) {
    bool done = true;
    for (Eigen::Index i = 0; i < na; ++i) {
      const double diag = std::abs(m.balanced_A(i, i));
      double c = m.balanced_A.col(i).cwiseAbs().sum() - diag, r = m.balanced_A.row(i).cwiseAbs().sum() - diag;
      if (!(c > 0 && r > 0)) continue;
      const double s = c + r;
      double f = 1;
      while (c < r / 2) {
        c *= 2;
        r /= 2;
        f *= 2;
      }
      while (c >= 2 * r) {
        c /= 2;
        r *= 2;
        f /= 2;
      }
      if (c + r < 0.95 * s) {
        done = false;
        m.balance(i) *= f;
        m.balanced_A.col(i) *= f;
        m.balanced_A.row(i) /= f;
      }
    }
    if (done) break;
  }
  m.balanced_B = m.balance.cwiseInverse().asDiagonal() * m.augmented_B;
  m.balanced_norm = na ? m.balanced_A.cwiseAbs().rowwise().sum().maxCoeff() : 0.0;
  return m;
}

}  // namespace hybrid_detail

}  // namespace pogear::rt
