// Reduction to the rigid model. Ranks and row choices are taken numerically at the model's
// parameter values (which satisfy the geometry relations); the algebra itself is symbolic.
#include "rigid_model.hpp"

#include <algorithm>
#include <numeric>

#include <fmt/format.h>

#include "printer.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// Relative threshold for numeric rank: R's entries are radii of one scale, and a genuine
// dependency cancels to rounding (~1e-16 relative), far below 1e-9.
int numeric_rank(const Eigen::MatrixXd& m) {
  if (m.size() == 0) return 0;
  Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(m);
  qr.setThreshold(1e-9);
  return static_cast<int>(qr.rank());
}

Eigen::MatrixXd columns(const Eigen::MatrixXd& m, const std::vector<int>& cols) {
  Eigen::MatrixXd out(m.rows(), cols.size());
  for (std::size_t j = 0; j < cols.size(); ++j) out.col(j) = m.col(cols[j]);
  return out;
}

// Rows of R that are independent on the eliminated columns, as many as there are eliminated.
std::vector<int> independent_rows(const Eigen::MatrixXd& Rn, const std::vector<int>& elim) {
  const Eigen::MatrixXd sub = columns(Rn, elim);
  std::vector<int> rows;
  Eigen::MatrixXd picked(0, sub.cols());
  for (int i = 0; i < sub.rows() && rows.size() < elim.size(); ++i) {
    Eigen::MatrixXd trial(picked.rows() + 1, sub.cols());
    trial << picked, sub.row(i);
    if (numeric_rank(trial) == trial.rows()) {
      picked = trial;
      rows.push_back(i);
    }
  }
  return rows;
}

// Q with R Q = 0 and identity rows at the kept velocities.
GiNaC::matrix kernel_basis(const GiNaC::matrix& R, const Eigen::MatrixXd& Rn, const std::vector<int>& kept,
                           const std::vector<int>& elim) {
  const unsigned n = R.cols();
  const unsigned k = kept.size();
  GiNaC::matrix Q(n, k);
  for (unsigned j = 0; j < k; ++j) Q(kept[j], j) = 1;
  if (elim.empty()) return Q;
  const std::vector<int> rows = independent_rows(Rn, elim);
  const unsigned e = elim.size();
  GiNaC::matrix A(e, e), B(e, k), vars(e, k);
  for (unsigned i = 0; i < e; ++i) {
    for (unsigned j = 0; j < e; ++j) A(i, j) = R(rows[i], elim[j]);
    for (unsigned j = 0; j < k; ++j) {
      B(i, j) = -R(rows[i], kept[j]);
      vars(i, j) = GiNaC::symbol(fmt::format("__q{}_{}", i, j));
    }
  }
  const GiNaC::matrix X = A.solve(vars, B);
  for (unsigned i = 0; i < e; ++i)
    for (unsigned j = 0; j < k; ++j) Q(elim[i], j) = X(i, j).normal();
  return Q;
}

// No sum anywhere in e: a product of powers of symbols, whose products GiNaC keeps in lowest
// terms by itself.
bool is_monomial(const ex& e) {
  if (GiNaC::is_a<GiNaC::numeric>(e) || GiNaC::is_a<GiNaC::symbol>(e)) return true;
  if (GiNaC::is_exactly_a<GiNaC::power>(e))
    return GiNaC::is_a<GiNaC::symbol>(e.op(0)) && GiNaC::is_a<GiNaC::numeric>(e.op(1)) &&
           GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer();
  if (!GiNaC::is_exactly_a<GiNaC::mul>(e)) return false;
  for (const ex& f : e)
    if (!is_monomial(f)) return false;
  return true;
}

// normal(a b), without normal's polynomial gcds when both are monomials (every entry of Q1 for
// a chain of stages is one): their product is already in lowest terms.
ex normal_product(const ex& a, const ex& b) {
  if (a.is_zero() || b.is_zero()) return 0;
  if (is_monomial(a) && is_monomial(b)) return a * b;
  return (a * b).normal();
}

std::string names_of(const Topology& t, const std::vector<int>& bodies, const char* sep = ",") {
  std::string s;
  for (int b : bodies) s += (s.empty() ? "" : sep) + t.bodies[b].name;
  return s;
}

[[noreturn]] void fail_tied(const Topology& t, const GiNaC::matrix& R, const Eigen::MatrixXd& Rn,
                            const std::vector<int>& kept, const std::vector<std::vector<int>>& valid,
                            const SourceLocation& where, const GiNaC::exmap& values, Symbols& s) {
  std::string valid_list;
  for (const auto& v : valid) valid_list += (valid_list.empty() ? "" : "; ") + names_of(t, v);
  std::string tie = names_of(t, kept, ", ") + " are tied together";
  if (!valid.empty()) {
    // Name the smallest group of kept velocities that every rigid motion ties together.
    std::vector<int> other;
    for (int b = 0; b < static_cast<int>(t.bodies.size()); ++b)
      if (std::find(valid[0].begin(), valid[0].end(), b) == valid[0].end()) other.push_back(b);
    const GiNaC::matrix Q = kernel_basis(R, Rn, valid[0], other);
    const Eigen::MatrixXd Qn = evaluate_matrix(Q, values);
    bool found = false;
    for (std::size_t a = 0; a < kept.size() && !found; ++a)
      for (std::size_t b = a + 1; b < kept.size() && !found; ++b) {
        Eigen::MatrixXd pair(2, Qn.cols());
        pair << Qn.row(kept[a]), Qn.row(kept[b]);
        if (numeric_rank(pair) == 2) continue;
        found = true;
        int j = 0;
        while (j < Qn.cols() && Qn(kept[a], j) == 0.0) ++j;
        const std::string na = t.bodies[kept[a]].name, nb = t.bodies[kept[b]].name;
        if (j == Qn.cols()) {
          tie = fmt::format("omega_{} is 0 in every rigid motion", na);
        } else {
          const ex ratio = (Q(kept[b], j) / Q(kept[a], j)).normal();
          tie = fmt::format("{} and {} are tied: {} in every rigid motion", na, nb,
                            print_expression(symbol(s, "omega_" + nb) == ratio * symbol(s, "omega_" + na),
                                             Notation::text));
        }
      }
  }
  throw InputError(where, fmt::format("the kept velocities {} do not parametrize the rigid motions: {}; valid "
                                      "choices are {}",
                                      names_of(t, kept), tie, valid_list));
}

}  // namespace

std::vector<int> force_recovery_bodies(const Eigen::MatrixXd& Rn) {
  std::vector<int> order(Rn.cols());
  std::iota(order.begin(), order.end(), 0);
  auto nonzeros = [&](int j) { return (Rn.col(j).array() != 0.0).count(); };
  std::stable_sort(order.begin(), order.end(), [&](int a, int b) { return nonzeros(a) < nonzeros(b); });
  std::vector<int> picked;
  for (int j : order) {
    picked.push_back(j);
    if (numeric_rank(columns(Rn, picked)) < static_cast<int>(picked.size())) picked.pop_back();
    if (picked.size() == static_cast<std::size_t>(Rn.rows())) break;
  }
  std::sort(picked.begin(), picked.end());
  return picked;
}

std::vector<std::vector<int>> valid_keep_sets(const Eigen::MatrixXd& Rn, std::size_t limit) {
  const int n = static_cast<int>(Rn.cols());
  const int rank = numeric_rank(Rn);
  const int k = n - rank;
  if (k == 0) return {{}};
  // Depth first over the bodies in order, keeping before eliminating, yields the sets in
  // lexicographic order. A branch is entered only if it can still be completed: its eliminated
  // columns independent and, with the undecided ones, spanning R's columns (then they extend to
  // a basis). So each set costs O(n) ranks; walking all C(n, k) subsets instead took minutes for
  // gears of 25 bodies whose valid sets are rare.
  std::vector<std::vector<int>> out;
  std::vector<int> kept, elim;
  auto completable = [&](int next) {
    if (numeric_rank(columns(Rn, elim)) != static_cast<int>(elim.size())) return false;
    std::vector<int> reach = elim;
    for (int b = next; b < n; ++b) reach.push_back(b);
    return numeric_rank(columns(Rn, reach)) == rank;
  };
  auto visit = [&](auto& self, int b) -> void {
    if (out.size() >= limit) return;
    if (b == n) {
      out.push_back(kept);
      return;
    }
    kept.push_back(b);
    if (static_cast<int>(kept.size()) <= k && completable(b + 1)) self(self, b + 1);
    kept.pop_back();
    elim.push_back(b);
    if (static_cast<int>(elim.size()) <= rank && completable(b + 1)) self(self, b + 1);
    elim.pop_back();
  };
  visit(visit, 0);
  return out;
}

RigidModel reduce_to_rigid(const Topology& t, const RadiusMatrix& rm, const ElasticModel& e,
                           const std::vector<std::string>& keep, const SourceLocation& where, Symbols& s) {
  const int n = static_cast<int>(t.bodies.size());
  const GiNaC::exmap values = numeric_substitutions(s, rm.values);
  const Eigen::MatrixXd Rn = evaluate_matrix(e.R, values);
  RigidModel r;
  r.rank = numeric_rank(Rn);
  const int dof = n - r.rank;

  for (const auto& name : keep) {
    const int b = find_body(t, name);
    if (b < 0) throw InputError(where, fmt::format("cannot keep '{}': there is no such body", name));
    if (std::find(r.kept.begin(), r.kept.end(), b) != r.kept.end())
      throw InputError(where, fmt::format("'{}' is kept twice", name));
    r.kept.push_back(b);
  }
  const auto valid = valid_keep_sets(Rn, 12);
  if (static_cast<int>(r.kept.size()) != dof) {
    throw InputError(where, fmt::format("{} {} kept, but this gear has {} degrees of freedom ({} bodies, "
                                        "rank of R {}); keep {}, e.g. {}",
                                        r.kept.size(), r.kept.size() == 1 ? "velocity" : "velocities", dof, n,
                                        r.rank, dof,
                                        valid.empty() ? "" : names_of(t, valid[0])));
  }
  for (int b = 0; b < n; ++b)
    if (std::find(r.kept.begin(), r.kept.end(), b) == r.kept.end()) r.eliminated.push_back(b);
  if (numeric_rank(columns(Rn, r.eliminated)) != static_cast<int>(r.eliminated.size()))
    fail_tied(t, e.R, Rn, r.kept, valid, where, values, s);

  r.Q1 = kernel_basis(e.R, Rn, r.kept, r.eliminated);
  const unsigned k = r.kept.size();
  r.L1 = GiNaC::matrix(k, k);
  r.A1 = GiNaC::matrix(k, k);
  // L1 and A1 are symmetric; each sum is built at once (adding term by term re-sorts it each time).
  for (unsigned i = 0; i < k; ++i)
    for (unsigned j = i; j < k; ++j) {
      GiNaC::exvector l, a;
      for (int b = 0; b < n; ++b) {
        const ex q = normal_product(r.Q1(b, i), r.Q1(b, j));
        if (q.is_zero()) continue;
        l.push_back(e.J(b, b) * q);
        a.push_back(-e.B_J(b, b) * q);
      }
      r.L1(i, j) = r.L1(j, i) = GiNaC::add(l);
      r.A1(i, j) = r.A1(j, i) = GiNaC::add(a);
    }
  r.B1 = r.Q1.transpose();

  // Eq. (8) needs R R^T invertible; with redundant meshes it is not (DESIGN.md §4).
  const int m = static_cast<int>(t.meshes.size());
  r.redundant_meshes = r.rank < m;
  if (r.redundant_meshes) {
    // DESIGN.md §4: the elastic model's limit splits the load as F = K R (R^T K R)^+ g. On the
    // rigid model g is orthogonal to ker R = span Q1, and on that subspace (R^T K R)^+ equals
    // (R^T K R + Q1 Q1^T)^-1, an ordinary inverse. The split depends on stiffness ratios, so
    // its weights are numbers at the model's values, computed exactly and then rounded.
    const GiNaC::matrix Kx = exact_matrix(e.K, values);
    const GiNaC::matrix Rx = exact_matrix(e.R, values);
    const GiNaC::matrix Qx = exact_matrix(r.Q1, values);
    const GiNaC::matrix S = Rx.transpose().mul(Kx).mul(Rx).add(Qx.mul(Qx.transpose()));
    const GiNaC::matrix W = Kx.mul(Rx).mul(S.inverse());  // m x n
    for (int i = 0; i < m; ++i) {
      ex f = 0;
      for (int b = 0; b < n; ++b) {
        const ex w = GiNaC::ex_to<GiNaC::numeric>(W(i, b)).evalf();
        if (W(i, b).is_zero()) continue;
        ex g = symbol(s, e.torques[b]);
        for (unsigned j = 0; j < k; ++j) {
          const std::string& kept_name = t.bodies[r.kept[j]].name;
          g -= e.J(b, b) * r.Q1(b, j) * symbol(s, "domega_" + kept_name) +
               e.B_J(b, b) * r.Q1(b, j) * symbol(s, "omega_" + kept_name);
        }
        f += w * g;
      }
      r.force_recovery.push_back(f);
    }
  } else {
    r.force_bodies = force_recovery_bodies(Rn);
    // On the rigid model g = tau - J Q1 x1' - B_J Q1 x1 lies in range(R^T), so eq. (8)'s
    // (R R^T)^-1 R g equals (R_S^T)^-1 g_S for any m bodies S with independent columns of R.
    // The sparsest S gives the shortest expressions, e.g. F_sg = -g_g/r_g.
    GiNaC::matrix RSt(m, m), vars(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) {
        RSt(i, j) = e.R(j, r.force_bodies[i]);
        vars(i, j) = GiNaC::symbol(fmt::format("__p{}_{}", i, j));
      }
    const GiNaC::matrix P = RSt.solve(vars, GiNaC::ex_to<GiNaC::matrix>(GiNaC::unit_matrix(m)));  // (R_S^T)^-1
    for (int i = 0; i < m; ++i) {
      ex f = 0;
      std::vector<ex> inertial(k, 0), friction(k, 0);
      for (int a = 0; a < m; ++a) {
        const int b = r.force_bodies[a];
        const ex p = P(i, a).normal();
        if (p.is_zero()) continue;
        f += p * symbol(s, e.torques[b]);
        for (unsigned j = 0; j < k; ++j) {
          inertial[j] += p * e.J(b, b) * r.Q1(b, j);
          friction[j] += p * e.B_J(b, b) * r.Q1(b, j);
        }
      }
      for (unsigned j = 0; j < k; ++j) {
        const std::string& kept_name = t.bodies[r.kept[j]].name;
        f -= inertial[j].normal() * symbol(s, "domega_" + kept_name);
        f -= friction[j].normal() * symbol(s, "omega_" + kept_name);
      }
      r.force_recovery.push_back(f);
    }
  }
  return r;
}

RigidValues exact_rigid_values(const RigidModel& r, const ElasticModel& e, const GiNaC::exmap& values) {
  RigidValues v;
  v.Q1 = exact_matrix(r.Q1, values);
  const unsigned n = v.Q1.rows(), k = v.Q1.cols();
  v.L1 = GiNaC::matrix(k, k);
  v.A1 = GiNaC::matrix(k, k);
  std::vector<GiNaC::numeric> J(n), BJ(n);
  for (unsigned b = 0; b < n; ++b) {
    J[b] = as_number(exact_value(e.J(b, b), values));
    BJ[b] = as_number(exact_value(e.B_J(b, b), values));
  }
  for (unsigned i = 0; i < k; ++i)
    for (unsigned j = i; j < k; ++j) {
      GiNaC::numeric l = 0, a = 0;
      for (unsigned b = 0; b < n; ++b) {
        if (v.Q1(b, i).is_zero() || v.Q1(b, j).is_zero()) continue;
        const GiNaC::numeric q = as_number(v.Q1(b, i)).mul(as_number(v.Q1(b, j)));
        l = l.add(J[b].mul(q));
        a = a.sub(BJ[b].mul(q));
      }
      v.L1(i, j) = v.L1(j, i) = l;
      v.A1(i, j) = v.A1(j, i) = a;
    }
  return v;
}

}  // namespace pogear
