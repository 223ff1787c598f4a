// Reduction to the rigid model. Ranks and row choices are taken numerically at the model's
// parameter values (which satisfy the geometry relations); the algebra itself is symbolic.
#include "rigid_model.hpp"

#include <algorithm>
#include <numeric>
#include <stdexcept>

#include <cln/integer.h>
#include <cln/rational.h>
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

// A X = B for a nonsingular symbolic A, block by block in A's block triangular form: equations
// matched to unknowns along A's nonzeros, and the strongly connected components of "equation
// uses the unknown another one is matched to" (Tarjan), which come out dependencies first. Each
// diagonal block is nonsingular (their determinants multiply to det A) and small: 2 x 2 for a
// chain of stages, where solving all of A at once worked on e x e rational functions.
GiNaC::matrix block_triangular_solve(const GiNaC::matrix& A, const GiNaC::matrix& B) {
  const int e = static_cast<int>(A.rows()), k = static_cast<int>(B.cols());
  std::vector<std::vector<int>> uses(e);
  for (int i = 0; i < e; ++i)
    for (int j = 0; j < e; ++j)
      if (!A(i, j).is_zero()) uses[i].push_back(j);
  // Maximum matching by augmenting paths; nonsingular A has a perfect one.
  std::vector<int> row_of(e, -1), col_of(e, -1);
  std::vector<char> seen;
  auto augment = [&](auto& self, int i) -> bool {
    for (int j : uses[i]) {
      if (seen[j]) continue;
      seen[j] = 1;
      if (row_of[j] < 0 || self(self, row_of[j])) {
        row_of[j] = i;
        col_of[i] = j;
        return true;
      }
    }
    return false;
  };
  for (int i = 0; i < e; ++i) {
    seen.assign(e, 0);
    if (!augment(augment, i)) throw std::domain_error("block_triangular_solve: singular matrix");
  }
  // Tarjan's strongly connected components over the equations.
  std::vector<int> index(e, -1), low(e, 0), stack;
  std::vector<char> on_stack(e, 0);
  std::vector<std::vector<int>> blocks;
  int counter = 0;
  auto connect = [&](auto& self, int i) -> void {
    index[i] = low[i] = counter++;
    stack.push_back(i);
    on_stack[i] = 1;
    for (int j : uses[i]) {
      const int next = row_of[j];
      if (next == i) continue;
      if (index[next] < 0) {
        self(self, next);
        low[i] = std::min(low[i], low[next]);
      } else if (on_stack[next]) {
        low[i] = std::min(low[i], index[next]);
      }
    }
    if (low[i] != index[i]) return;
    blocks.emplace_back();
    int top;
    do {
      top = stack.back();
      stack.pop_back();
      on_stack[top] = 0;
      blocks.back().push_back(top);
    } while (top != i);
    std::sort(blocks.back().begin(), blocks.back().end());
  };
  for (int i = 0; i < e; ++i)
    if (index[i] < 0) connect(connect, i);

  // Each block's inverse once (its entries are radii), then one normal() per entry of X: solving
  // for all k columns at once normalized every intermediate rational function.
  GiNaC::matrix X(e, k);
  std::vector<char> solved(e, 0);
  for (const auto& rows : blocks) {
    const unsigned size = rows.size();
    GiNaC::matrix Ab(size, size);
    for (unsigned a = 0; a < size; ++a)
      for (unsigned b = 0; b < size; ++b) Ab(a, b) = A(rows[a], col_of[rows[b]]);
    GiNaC::matrix inverse = Ab.inverse();
    for (unsigned a = 0; a < size; ++a)
      for (unsigned b = 0; b < size; ++b) inverse(a, b) = inverse(a, b).normal();
    for (int c = 0; c < k; ++c) {
      std::vector<ex> rhs(size);
      for (unsigned a = 0; a < size; ++a) {
        const int i = rows[a];
        GiNaC::exvector terms{B(i, c)};
        for (int j : uses[i])
          if (solved[j] && !X(j, c).is_zero()) terms.push_back(-A(i, j) * X(j, c));
        rhs[a] = GiNaC::add(terms);
      }
      for (unsigned a = 0; a < size; ++a) {
        GiNaC::exvector terms;
        for (unsigned b = 0; b < size; ++b)
          if (!inverse(a, b).is_zero() && !rhs[b].is_zero()) terms.push_back(inverse(a, b) * rhs[b]);
        X(col_of[rows[a]], c) = ex(GiNaC::add(terms)).normal();
      }
    }
    for (int i : rows) solved[col_of[i]] = 1;
  }
  return X;
}

// Q with R_rows Q = 0 and identity rows at the kept velocities; `rows` are independent on the
// eliminated columns (independent_rows), so this is ker R.
GiNaC::matrix kernel_basis(const GiNaC::matrix& R, const std::vector<int>& rows, const std::vector<int>& kept,
                           const std::vector<int>& elim) {
  const unsigned n = R.cols();
  const unsigned k = kept.size();
  GiNaC::matrix Q(n, k);
  for (unsigned j = 0; j < k; ++j) Q(kept[j], j) = 1;
  if (elim.empty()) return Q;
  const unsigned e = elim.size();
  GiNaC::matrix A(e, e), B(e, k);
  for (unsigned i = 0; i < e; ++i) {
    for (unsigned j = 0; j < e; ++j) A(i, j) = R(rows[i], elim[j]);
    for (unsigned j = 0; j < k; ++j) B(i, j) = -R(rows[i], kept[j]);
  }
  const GiNaC::matrix X = block_triangular_solve(A, B);
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

cln::cl_RA rational_value(const ex& x) {
  const GiNaC::numeric v = as_number(x);
  if (!v.is_rational()) throw std::domain_error("a parameter value is not a rational number");
  return cln::the<cln::cl_RA>(v.to_cl_N());
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
    const GiNaC::matrix Q = kernel_basis(R, independent_rows(Rn, other), valid[0], other);
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
                           const std::vector<std::string>& keep, const SourceLocation& where, Symbols& s,
                           bool closed_forms) {
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

  r.constraint_rows = independent_rows(Rn, r.eliminated);
  r.Q1 = kernel_basis(e.R, r.constraint_rows, r.kept, r.eliminated);
  const unsigned k = r.kept.size();
  if (closed_forms) {
    r.L1 = GiNaC::matrix(k, k);
    r.A1 = GiNaC::matrix(k, k);
    r.B1 = r.Q1.transpose();
  } else {
    r.L1 = r.A1 = r.B1 = GiNaC::matrix(0, 0);
  }
  // L1 and A1 are symmetric; each sum is built at once (adding term by term re-sorts it each time).
  for (unsigned i = 0; i < k && closed_forms; ++i)
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
    GiNaC::matrix RSt(m, m);
    for (int i = 0; i < m; ++i)
      for (int j = 0; j < m; ++j) RSt(i, j) = e.R(j, r.force_bodies[i]);
    // (R_S^T)^-1; R_S^T is as sparse as R (block triangular along a chain).
    const GiNaC::matrix P = block_triangular_solve(RSt, GiNaC::ex_to<GiNaC::matrix>(GiNaC::unit_matrix(m)));
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
  // Integers over common denominators: Q1(b, i) = q[b][i] / qden[i], J_b = jn[b] / jden and
  // B_J(b) = bn[b] / bden, so that each entry of L1 = Q1^T J Q1 and A1 = -Q1^T B_J Q1 is an integer
  // sum reduced once. Summing the rationals term by term took a gcd of numbers of thousands of
  // bits per term for a long chain.
  std::vector<cln::cl_RA> J(n), BJ(n);
  cln::cl_I jden = 1, bden = 1;
  for (unsigned b = 0; b < n; ++b) {
    J[b] = rational_value(exact_value(e.J(b, b), values));
    BJ[b] = rational_value(exact_value(e.B_J(b, b), values));
    jden = cln::lcm(jden, cln::denominator(J[b]));
    bden = cln::lcm(bden, cln::denominator(BJ[b]));
  }
  std::vector<cln::cl_I> jn(n), bn(n), qden(k, cln::cl_I(1));
  for (unsigned b = 0; b < n; ++b) {
    jn[b] = cln::numerator(J[b]) * cln::exquo(jden, cln::denominator(J[b]));
    bn[b] = cln::numerator(BJ[b]) * cln::exquo(bden, cln::denominator(BJ[b]));
  }
  std::vector<std::vector<cln::cl_I>> q(n, std::vector<cln::cl_I>(k, cln::cl_I(0)));
  for (unsigned i = 0; i < k; ++i) {
    for (unsigned b = 0; b < n; ++b)
      if (!v.Q1(b, i).is_zero()) qden[i] = cln::lcm(qden[i], cln::denominator(rational_value(v.Q1(b, i))));
    for (unsigned b = 0; b < n; ++b)
      if (!v.Q1(b, i).is_zero()) {
        const cln::cl_RA x = rational_value(v.Q1(b, i));
        q[b][i] = cln::numerator(x) * cln::exquo(qden[i], cln::denominator(x));
      }
  }
  for (unsigned i = 0; i < k; ++i)
    for (unsigned j = i; j < k; ++j) {
      cln::cl_I l = 0, a = 0;
      for (unsigned b = 0; b < n; ++b) {
        if (cln::zerop(q[b][i]) || cln::zerop(q[b][j])) continue;
        const cln::cl_I qq = q[b][i] * q[b][j];
        l = l + jn[b] * qq;
        a = a - bn[b] * qq;
      }
      const cln::cl_I d = qden[i] * qden[j];
      v.L1(i, j) = v.L1(j, i) = GiNaC::numeric(cln::cl_N(l / (jden * d)));
      v.A1(i, j) = v.A1(j, i) = GiNaC::numeric(cln::cl_N(a / (bden * d)));
    }
  return v;
}

GiNaC::matrix exact_rigid_response(const RigidModel& r, const ElasticModel& e, const GiNaC::exmap& values,
                                   const GiNaC::matrix& torques) {
  // With omega' = Q1 y (the constraint rows force it, their kernel being exactly span Q1) the
  // first block row J Q1 y + R_c^T lambda = T, multiplied by Q1^T (R_c Q1 = 0), is L1 y = Q1^T T;
  // and y = omega' at the kept bodies, where Q1 is the identity. So this is L1^-1 Q1^T T without
  // L1: the saddle-point matrix has the sparsity of R (a few entries per row, banded along a
  // chain) and entries of a few machine words, where L1 is dense with entries of thousands of
  // bits for a long chain, and exact elimination of it cost seconds to minutes.
  const unsigned n = e.J.rows(), c = r.constraint_rows.size(), s = n + c, cols = torques.cols();
  GiNaC::matrix S(s, s), rhs(s, cols);
  for (unsigned b = 0; b < n; ++b) {
    S(b, b) = exact_value(e.J(b, b), values);
    for (unsigned i = 0; i < c; ++i) S(b, n + i) = S(n + i, b) = exact_value(e.R(r.constraint_rows[i], b), values);
  }
  // Each column of T as integers over a common denominator, divided out at the end: the
  // elimination then mixes T's big denominators (products of radii along a chain) into no gcd.
  std::vector<cln::cl_I> den(cols, cln::cl_I(1));
  for (unsigned j = 0; j < cols; ++j) {
    for (unsigned b = 0; b < n; ++b)
      if (!torques(b, j).is_zero()) den[j] = cln::lcm(den[j], cln::denominator(rational_value(torques(b, j))));
    for (unsigned b = 0; b < n; ++b) {
      if (torques(b, j).is_zero()) continue;
      const cln::cl_RA t = rational_value(torques(b, j));
      rhs(b, j) = GiNaC::numeric(cln::cl_N(cln::numerator(t) * cln::exquo(den[j], cln::denominator(t))));
    }
  }
  // Bodies first: their pivots are the diagonal J, and eliminating them leaves -R_c J^-1 R_c^T,
  // which couples only meshes that share a body, so forward elimination fills within its band.
  // Only the kept bodies' accelerations are solved for, and the multipliers they depend on.
  std::vector<int> rows(r.kept.begin(), r.kept.end());
  GiNaC::matrix y = exact_solve_rows(S, rhs, rows);
  for (unsigned i = 0; i < y.rows(); ++i)
    for (unsigned j = 0; j < cols; ++j)
      if (!y(i, j).is_zero()) y(i, j) = as_number(y(i, j)).div(GiNaC::numeric(cln::cl_N(den[j])));
  return y;
}

}  // namespace pogear
