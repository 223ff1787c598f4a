// See vibration_modes.hpp. J is diagonal and positive, so the generalized problem is the ordinary
// symmetric one of J^-1/2 R^T K R J^-1/2: orthogonal eigenvectors, real eigenvalues, no pairing
// of complex conjugates, and rounding of order eps * lambda_max.
#include "vibrate/vibration_modes.hpp"

#include <algorithm>
#include <cmath>
#include <complex>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"

namespace pogear {
namespace {

// The gear as it vibrates with brakes and clutches stuck: body velocities omega = P q, one q per
// group of bodies the stuck elements tie together (a clutch keeps a_i omega_i = a_j omega_j, a
// brake a_i omega_i = 0, a the bodies' arrows), the groups a brake holds left out. The stuck
// elements' torques lie in the range of E^T, which P^T annihilates, so the model of q is
// J_q = P^T J P (diagonal, the groups being disjoint), R_q = R P, and L, A alike; with nothing
// engaged P = I and this is the gear's elastic model.
struct ModalModel {
  GiNaC::matrix J, K, R, B_J, B_K, L, A;
  Eigen::MatrixXd P;  // bodies x groups, entries 0 and +-1
  int rank = 0;       // of R_q
};

// Where each row or column of a gear matrix goes in the grouped one: (index, sign), index -1 when
// it is dropped (a held body).
using IndexMap = std::vector<std::pair<int, int>>;

// S_rows^T X S_cols for such maps: entry (u, v) sums s_i s_j X(i, j) over the i and j sent to u
// and v. Sums only, no symbolic matrix products: the (n + m)-square L and A of a long chain stay cheap.
GiNaC::matrix grouped(const GiNaC::matrix& X, const IndexMap& rows, unsigned out_rows, const IndexMap& cols,
                      unsigned out_cols) {
  GiNaC::matrix Y(out_rows, out_cols);
  for (unsigned i = 0; i < X.rows(); ++i) {
    if (rows[i].first < 0) continue;
    for (unsigned j = 0; j < X.cols(); ++j)
      if (cols[j].first >= 0 && !X(i, j).is_zero())
        Y(rows[i].first, cols[j].first) += rows[i].second * cols[j].second * X(i, j);
  }
  for (unsigned i = 0; i < out_rows; ++i)
    for (unsigned j = 0; j < out_cols; ++j) Y(i, j) = Y(i, j).expand();
  return Y;
}

ModalModel modal_model(const Derivation& d, const std::vector<int>& engaged, const std::vector<int>& held) {
  const Topology& t = d.topology;
  const ElasticModel& e = d.elastic;
  const int n = static_cast<int>(t.bodies.size()), m = static_cast<int>(t.meshes.size());
  ModalModel mm{e.J, e.K, e.R, e.B_J, e.B_K, e.L, e.A, Eigen::MatrixXd::Identity(n, n), 0};
  if (engaged.empty() && held.empty()) {
    // The gear's rank: the rigid model's when that is the gear's own, else numeric at the model's
    // values, as every rank decision of the reduction is.
    mm.rank = d.engaged.empty() ? d.rigid.rank : numeric_rank(evaluate_matrix(e.R, d.values));
    return mm;
  }
  std::vector<int> parent(n + 1);  // union-find over the bodies and the housing (index n)
  for (int i = 0; i <= n; ++i) parent[i] = i;
  auto root = [&](int i) {
    while (parent[i] != i) i = parent[i] = parent[parent[i]];
    return i;
  };
  for (int k : engaged) {
    const FrictionElement& f = t.friction_elements.at(k);
    const int a = root(f.first), b = root(f.is_brake() ? n : f.second);
    parent[std::min(a, b)] = parent[std::max(a, b)];  // the housing stays a root
  }
  for (int h : held) parent[root(h)] = root(n);  // a held body is tied to the housing, as by a brake
  std::vector<int> group_of_root(n + 1, -1);
  int groups = 0;
  for (int i = 0; i < n; ++i)
    if (root(i) != root(n) && group_of_root[root(i)] < 0) group_of_root[root(i)] = groups++;
  if (groups == 0)
    throw std::domain_error(held.empty() ? "the engaged brakes hold every body, so nothing can vibrate; engage fewer elements"
                                         : "the held bodies and engaged brakes hold every body, so nothing can vibrate; "
                                           "hold fewer bodies");
  // omega_i = a_i a_r q for the group's root r, which turns at q itself.
  IndexMap body(n), mesh(m), state(n + m);
  mm.P = Eigen::MatrixXd::Zero(n, groups);
  for (int i = 0; i < n; ++i) {
    const int g = group_of_root[root(i)];
    body[i] = {g, g < 0 ? 0 : t.bodies[i].arrow * t.bodies[root(i)].arrow};
    if (g >= 0) mm.P(i, g) = body[i].second;
    state[i] = body[i];
  }
  for (int i = 0; i < m; ++i) mesh[i] = {i, 1}, state[n + i] = {groups + i, 1};
  const unsigned q = static_cast<unsigned>(groups), states = static_cast<unsigned>(groups + m);
  mm.J = grouped(e.J, body, q, body, q);
  mm.B_J = grouped(e.B_J, body, q, body, q);
  mm.R = grouped(e.R, mesh, static_cast<unsigned>(m), body, q);
  mm.L = grouped(e.L, state, states, state, states);
  mm.A = grouped(e.A, state, states, state, states);
  mm.rank = numeric_rank(evaluate_matrix(mm.R, d.values));
  return mm;
}

struct Eigenproblem {
  Eigen::VectorXd J, K;  // diagonals
  Eigen::MatrixXd R;
  Eigen::VectorXd lambda;  // ascending; the first n - rank R are the rigid modes, set to 0
  Eigen::MatrixXd phi;     // columns, J-orthonormal
  int rigid = 0;
};

Eigenproblem solve_eigenproblem(const ModalModel& e, const GiNaC::exmap& values) {
  if (e.R.rows() == 0) throw std::domain_error("the model has no mesh, so it has no vibration modes");
  Eigenproblem p;
  p.J = evaluate_matrix(e.J, values).diagonal();
  p.K = evaluate_matrix(e.K, values).diagonal();
  p.R = evaluate_matrix(e.R, values);
  const Eigen::VectorXd s = p.J.cwiseSqrt().cwiseInverse();  // J^-1/2
  const Eigen::MatrixXd RS = p.R * s.asDiagonal();
  const Eigen::MatrixXd S = RS.transpose() * p.K.asDiagonal() * RS;
  const Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> es(S);
  if (es.info() != Eigen::Success) throw std::domain_error("the symmetric eigenvalue solver did not converge");
  p.lambda = es.eigenvalues();
  p.phi = s.asDiagonal() * es.eigenvectors();
  const int n = static_cast<int>(p.J.size());
  p.rigid = n - e.rank;
  const double lambda_max = p.lambda(n - 1);
  if (p.rigid < n) {
    const double spread = lambda_max / p.lambda(p.rigid);
    if (!(p.lambda(p.rigid) > 0) || spread > max_eigenvalue_spread)
      throw std::domain_error(fmt::format(
          "the natural frequencies span a ratio of {:.3g} (lambda from {:.3g} to {:.3g} 1/s^2), above {:.0g}, the "
          "widest span whose lowest frequency double precision gives to 8 digits; make the stiffnesses and inertias "
          "less disparate",
          std::sqrt(spread), p.lambda(p.rigid), lambda_max, std::sqrt(max_eigenvalue_spread)));
  }
  p.lambda.head(p.rigid).setZero();
  return p;
}

double frequency_hz(double lambda) { return std::sqrt(lambda) / (2 * std::numbers::pi); }

// Clusters of modes (index ranges of p.lambda) whose frequencies lie within degenerate_tolerance of
// the cluster's first: the rigid modes are one, each degenerate frequency another.
std::vector<std::pair<int, int>> frequency_clusters(const Eigenproblem& p) {
  const int n = static_cast<int>(p.lambda.size());
  std::vector<std::pair<int, int>> clusters;
  if (p.rigid > 0) clusters.push_back({0, p.rigid});
  for (int i = p.rigid; i < n;) {
    int j = i + 1;
    while (j < n && std::sqrt(p.lambda(j)) - std::sqrt(p.lambda(i)) <= degenerate_tolerance * std::sqrt(p.lambda(j))) ++j;
    clusters.push_back({i, j});
    i = j;
  }
  return clusters;
}

// Damping ratios of the elastic modes, indexed as p.lambda, from the eigenvalues s of M = L^-1 A:
// zeta = -Re s / |s|. Each oscillatory eigenvector (Im s > 0) belongs to the cluster of undamped
// shapes that holds at least 90 % of its kinetic energy (J-projection of its velocities); each
// cluster must receive as many as it has modes, else damping couples the modes and no ratio is
// given. A ratio whose Re s is within 1e6 rounding errors of M's eigenvalues (eps n |M|) is not
// resolved to 6 digits and is left out.
std::vector<std::optional<double>> damping_ratios(const ModalModel& e, const GiNaC::exmap& values, const Eigenproblem& p,
                                                  const std::vector<std::pair<int, int>>& clusters, std::string& note,
                                                  std::vector<DampedMode>& damped) {
  const int n = static_cast<int>(p.lambda.size());
  std::vector<std::optional<double>> zeta(n);
  const Eigen::MatrixXd L = evaluate_matrix(e.L, values);
  const Eigen::MatrixXd M = L.diagonal().cwiseInverse().asDiagonal() * evaluate_matrix(e.A, values);
  const Eigen::EigenSolver<Eigen::MatrixXd> es(M);
  const Eigen::VectorXcd s = es.eigenvalues();
  const double rounding = std::numeric_limits<double>::epsilon() * static_cast<double>(M.rows()) * M.norm();
  std::vector<std::vector<std::complex<double>>> assigned(clusters.size());
  int oscillatory = 0;
  bool coupled = false;
  const double scale = s.cwiseAbs().maxCoeff();
  for (Eigen::Index k = 0; k < s.size(); ++k) {
    if (!(s(k).imag() > 1e-12 * scale)) continue;  // real ones keep |Im| ~1e-16 of the largest |s|
    ++oscillatory;
    damped.push_back(DampedMode{std::abs(s(k)) / (2 * std::numbers::pi), -s(k).real() / std::abs(s(k))});
    const Eigen::VectorXcd v = es.eigenvectors().col(k).head(n);
    const double total = (v.adjoint() * p.J.asDiagonal() * v)(0).real();
    std::size_t best = 0;
    double best_share = -1;
    for (std::size_t c = 0; c < clusters.size(); ++c) {
      double share = 0;
      for (int m = clusters[c].first; m < clusters[c].second; ++m)
        share += std::norm((p.phi.col(m).cwiseProduct(p.J).transpose() * v)(0));
      if (share / total > best_share) best_share = share / total, best = c;
    }
    if (best_share < 0.9 || clusters[best].first < p.rigid) {
      note = "damping couples the modes: an oscillating eigenvector of M is less than 90 % one undamped mode, so "
             "damping ratios are not paired with modes (the damped modes are listed instead)";
      coupled = true;
    }
    assigned[best].push_back(s(k));
  }
  std::sort(damped.begin(), damped.end(), [](auto a, auto b) { return a.frequency_hz < b.frequency_hz; });
  if (coupled) return std::vector<std::optional<double>>(n);
  bool unresolved = false;
  for (std::size_t c = 0; c < clusters.size(); ++c) {
    const auto [first, last] = clusters[c];
    if (first < p.rigid) continue;
    std::vector<std::complex<double>>& pairs = assigned[c];
    if (static_cast<int>(pairs.size()) != last - first) {
      note = fmt::format("M has {} oscillating eigenvalue pair{} for {} elastic mode{}: some are overdamped, so "
                         "damping ratios are not paired with modes (the damped modes are listed instead)", oscillatory, oscillatory == 1 ? "" : "s", n - p.rigid,
                         n - p.rigid == 1 ? "" : "s");
      return std::vector<std::optional<double>>(n);
    }
    std::sort(pairs.begin(), pairs.end(), [](auto x, auto y) { return std::abs(x) < std::abs(y); });
    for (int m = first; m < last; ++m) {
      const std::complex<double> e = pairs[m - first];
      if (std::abs(e.real()) < 1e6 * rounding) {
        unresolved = true;
        continue;
      }
      zeta[m] = -e.real() / std::abs(e);
    }
  }
  if (unresolved)
    note = fmt::format("damping ratios whose decay rate is below {:.2g} 1/s are not resolved to 6 digits in double "
                       "precision and are left out", 1e6 * rounding);
  return zeta;
}

bool has_damping(const ModalModel& e, const GiNaC::exmap& values) {
  return !evaluate_matrix(e.B_J, values).isZero(0) || !evaluate_matrix(e.B_K, values).isZero(0);
}

// det(R^T K R - lambda J) = lambda^(n-r) p(lambda); the coefficients of p, symbolic.
std::vector<GiNaC::ex> characteristic_polynomial(const ModalModel& e, const GiNaC::symbol& lambda) {
  const GiNaC::matrix Kt = e.R.transpose().mul(e.K).mul(e.R);
  const GiNaC::matrix P = Kt.sub(e.J.mul_scalar(lambda));
  const GiNaC::ex det = P.determinant().expand();
  const int n = static_cast<int>(e.J.rows()), r = e.rank;
  std::vector<GiNaC::ex> c;
  for (int k = n - r; k <= n; ++k) c.push_back(det.coeff(lambda, k));
  return c;
}

// The roots of sum_k a[k] lambda^k of degree 1 or 2 in closed form, ascending at `values`. (The
// cubic's trigonometric form is beyond what GiNaC normalizes in reasonable time, so a gear of
// three elastic modes gets its characteristic polynomial only.)
std::vector<GiNaC::ex> characteristic_roots(const std::vector<GiNaC::ex>& a, const GiNaC::exmap& values) {
  using GiNaC::ex;
  if (a.size() == 2) return {GiNaC::normal(-a[0] / a[1])};
  if (a.size() != 3) return {};
  const ex disc = GiNaC::factor(GiNaC::normal(a[1] * a[1] - 4 * a[2] * a[0]));
  const ex sq = GiNaC::sqrt(disc);
  const ex lo = (-a[1] - sq) / (2 * a[2]), hi = (-a[1] + sq) / (2 * a[2]);
  // The sign of a[2] decides which is the smaller.
  return to_double(exact_value(a[2], values)) > 0 ? std::vector<ex>{lo, hi} : std::vector<ex>{hi, lo};
}

}  // namespace

std::string_view mode_kind_name(ModeKind kind) {
  switch (kind) {
    case ModeKind::rigid: return "rigid";
    case ModeKind::planet: return "planet";
    case ModeKind::elastic: break;
  }
  return "elastic";
}

double lowest_natural_frequency(const Derivation& d, const GiNaC::exmap& values) {
  const Eigenproblem p = solve_eigenproblem(modal_model(d, d.engaged, {}), values);
  if (p.rigid >= p.lambda.size()) throw std::domain_error("the model has no elastic mode");
  return frequency_hz(p.lambda(p.rigid));
}

VibrationModes vibration_modes(const Derivation& d, const GiNaC::exmap& values, std::string damping,
                               const std::vector<int>& engaged, const std::vector<int>& held) {
  const ModalModel mm = modal_model(d, engaged, held);
  const Eigenproblem p = solve_eigenproblem(mm, values);
  const Topology& t = d.topology;
  VibrationModes out;
  out.model = t.name;
  for (int k : engaged) out.engaged.push_back(t.friction_elements.at(k).name);
  for (int b : held) out.held.push_back(t.bodies.at(b).name);
  for (const Body& b : t.bodies) out.bodies.push_back(b.name);
  for (const Mesh& m : t.meshes) out.meshes.push_back(m.name);
  out.damping = std::move(damping);
  const int n = static_cast<int>(p.lambda.size());

  const std::vector<std::pair<int, int>> clusters = frequency_clusters(p);
  std::vector<std::optional<double>> zeta(n, 0.0);
  if (has_damping(mm, values)) zeta = damping_ratios(mm, values, p, clusters, out.damping_note, out.damped);

  const Eigen::VectorXd J_body = evaluate_matrix(d.elastic.J, values).diagonal();
  const Eigen::MatrixXd R_body = evaluate_matrix(d.elastic.R, values);
  for (int i = 0; i < n; ++i) {
    VibrationMode m;
    m.frequency_hz = frequency_hz(p.lambda(i));
    m.kind = i < p.rigid ? ModeKind::rigid : ModeKind::elastic;
    Eigen::VectorXd phi = mm.P * p.phi.col(i);  // per body
    Eigen::Index big = 0;
    phi.cwiseAbs().maxCoeff(&big);
    phi /= phi(big);
    phi(big) = 1;  // not 0.9999999999999997
    // Entries at rounding level of the largest (a body the mode leaves at rest) are 0, not noise.
    for (Eigen::Index b = 0; b < phi.size(); ++b)
      if (std::abs(phi(b)) < 1e-12) phi(b) = 0;
    m.shape = phi;
    const Eigen::VectorXd kinetic = J_body.cwiseProduct(phi.cwiseAbs2());
    m.kinetic_energy = kinetic / kinetic.sum();
    if (m.kind != ModeKind::rigid) {
      const Eigen::VectorXd strain = p.K.cwiseProduct((R_body * phi).cwiseAbs2());
      m.strain_energy = strain / strain.sum();
      m.damping_ratio = zeta[i];
      // The shape is exact to ~eps lambda_max / gap; 1e-6 of the largest entry is far above that
      // for the symmetric planet modes (exactly 0 for the central members) and far below a motion.
      bool central_at_rest = true, planet_moves = false;
      for (std::size_t b = 0; b < t.bodies.size(); ++b) {
        const bool moves = std::abs(phi(b)) > 1e-6;
        if (t.bodies[b].axis == AxisKind::central && moves) central_at_rest = false;
        if (t.bodies[b].axis == AxisKind::carried && moves) planet_moves = true;
      }
      if (central_at_rest && planet_moves) m.kind = ModeKind::planet;
    }
    out.modes.push_back(std::move(m));
  }
  for (const auto& [first, last] : clusters)
    for (int k = first; k < last; ++k) out.modes[k].multiplicity = last - first;
  // Closed forms for small gears: GiNaC's determinant of an n x n symbolic matrix grows fast.
  if (mm.rank <= 3 && n <= 8) {
    out.characteristic = characteristic_polynomial(mm, out.lambda);
    const std::vector<GiNaC::ex>& a = out.characteristic;
    out.closed_form = characteristic_roots(a, d.values);
  }
  return out;
}

}  // namespace pogear
