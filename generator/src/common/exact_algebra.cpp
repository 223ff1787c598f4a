// Exact rational numbers and matrices: the products, solutions and evaluations at parameter
// values that every stage uses on R, L and the closed forms.
#include "common/exact_algebra.hpp"

#include <optional>
#include <stdexcept>
#include <vector>

#include <cln/dfloat.h>
#include <cln/rational.h>
#include <cln/real.h>

namespace pogear {

GiNaC::numeric exact_number(double v) {
  return GiNaC::numeric(cln::cl_N(cln::rational(cln::cl_DF(v))));
}

double to_double(const GiNaC::ex& e) {
  const GiNaC::ex v = e.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
    throw std::domain_error("expression does not evaluate to a real number");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

namespace {

using GiNaC::ex;
using GiNaC::numeric;

// The exact number of e at `values`, or nothing when e holds something else. Exact rational
// arithmetic gives the one value whatever the order of the operations, so this equals subs.
std::optional<numeric> walk(const ex& e, const GiNaC::exmap& values) {
  if (GiNaC::is_exactly_a<numeric>(e)) return GiNaC::ex_to<numeric>(e);
  if (GiNaC::is_a<GiNaC::symbol>(e)) {
    const auto it = values.find(e);
    if (it == values.end() || !GiNaC::is_exactly_a<numeric>(it->second)) return std::nullopt;
    return GiNaC::ex_to<numeric>(it->second);
  }
  const bool sum = GiNaC::is_exactly_a<GiNaC::add>(e);
  if (sum || GiNaC::is_exactly_a<GiNaC::mul>(e)) {
    numeric acc = sum ? 0 : 1;
    for (const ex& op : e) {
      const auto v = walk(op, values);
      if (!v) return std::nullopt;
      acc = sum ? acc.add(*v) : acc.mul(*v);
    }
    return acc;
  }
  if (GiNaC::is_exactly_a<GiNaC::power>(e) && GiNaC::is_exactly_a<numeric>(e.op(1)) &&
      GiNaC::ex_to<numeric>(e.op(1)).is_integer()) {
    const auto base = walk(e.op(0), values);
    if (!base) return std::nullopt;
    if (base->is_zero() && GiNaC::ex_to<numeric>(e.op(1)).is_negative()) return std::nullopt;  // subs says why
    return base->power(GiNaC::ex_to<numeric>(e.op(1)));
  }
  return std::nullopt;
}

}  // namespace

ex exact_value(const ex& e, const GiNaC::exmap& values) {
  if (auto v = walk(e, values)) return *v;
  return e.subs(values);
}

numeric as_number(const ex& e) {
  if (!GiNaC::is_exactly_a<numeric>(e)) throw std::domain_error("expression is not a number");
  return GiNaC::ex_to<numeric>(e);
}

GiNaC::matrix exact_product(const GiNaC::matrix& a, const GiNaC::matrix& b) {
  GiNaC::matrix out(a.rows(), b.cols());
  for (unsigned i = 0; i < a.rows(); ++i) {
    std::vector<numeric> row(b.cols(), numeric(0));
    for (unsigned l = 0; l < a.cols(); ++l) {
      if (a(i, l).is_zero()) continue;
      const numeric x = as_number(a(i, l));
      for (unsigned j = 0; j < b.cols(); ++j)
        if (!b(l, j).is_zero()) row[j] = row[j].add(x.mul(as_number(b(l, j))));
    }
    for (unsigned j = 0; j < b.cols(); ++j) out(i, j) = row[j];
  }
  return out;
}

GiNaC::matrix exact_solve(const GiNaC::matrix& a, const GiNaC::matrix& b) {
  std::vector<int> all(a.rows());
  for (unsigned i = 0; i < a.rows(); ++i) all[i] = static_cast<int>(i);
  return exact_solve_rows(a, b, all);
}

GiNaC::matrix exact_solve_rows(const GiNaC::matrix& a, const GiNaC::matrix& b, const std::vector<int>& rows) {
  const unsigned n = a.rows(), m = b.cols();
  // Gaussian elimination on [a | b], pivot = first nonzero: exact, so any pivot gives the same x.
  std::vector<std::vector<numeric>> w(n, std::vector<numeric>(n + m, numeric(0)));
  for (unsigned i = 0; i < n; ++i) {
    for (unsigned j = 0; j < n; ++j) w[i][j] = as_number(a(i, j));
    for (unsigned j = 0; j < m; ++j) w[i][n + j] = as_number(b(i, j));
  }
  // Forward elimination below the pivots only, then back substitution: a banded a (R R^T of a
  // chain) stays banded, where eliminating above the pivots too would fill it. Pivot rows are
  // not scaled: after the swaps row c holds unknown c, divided by its pivot only if needed.
  for (unsigned c = 0; c < n; ++c) {
    unsigned p = c;
    while (p < n && w[p][c].is_zero()) ++p;
    if (p == n) throw std::domain_error("exact_solve: singular matrix");
    std::swap(w[p], w[c]);
    const numeric inv = w[c][c].inverse();
    for (unsigned r = c + 1; r < n; ++r) {
      if (w[r][c].is_zero()) continue;
      const numeric f = w[r][c].mul(inv);
      w[r][c] = 0;
      for (unsigned j = c + 1; j < n + m; ++j)
        if (!w[c][j].is_zero()) w[r][j] = w[r][j].sub(f.mul(w[c][j]));
    }
  }
  // Unknown c is needed if asked for or if a needed unknown above it depends on it (w is upper
  // triangular now). In the rigid saddle-point system no one needs the eliminated bodies' ones.
  std::vector<bool> needed(n, false);
  for (int r : rows) needed.at(r) = true;
  for (unsigned c = 0; c < n; ++c)
    for (unsigned r = 0; r < c && !needed[c]; ++r) needed[c] = needed[r] && !w[r][c].is_zero();
  for (unsigned c = n; c-- > 0;) {
    if (!needed[c]) continue;
    const numeric inv = w[c][c].inverse();
    for (unsigned j = n; j < n + m; ++j)
      if (!w[c][j].is_zero()) w[c][j] = w[c][j].mul(inv);
    for (unsigned r = 0; r < c; ++r) {
      if (!needed[r] || w[r][c].is_zero()) continue;
      const numeric f = w[r][c];
      for (unsigned j = n; j < n + m; ++j)
        if (!w[c][j].is_zero()) w[r][j] = w[r][j].sub(f.mul(w[c][j]));
    }
  }
  GiNaC::matrix x(rows.size(), m);
  for (std::size_t i = 0; i < rows.size(); ++i)
    for (unsigned j = 0; j < m; ++j) x(i, j) = w[rows[i]][n + j];
  return x;
}

Eigen::MatrixXd evaluate_matrix(const GiNaC::matrix& m, const GiNaC::exmap& values) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = to_double(exact_value(m(i, j), values));
  return out;
}

GiNaC::matrix exact_matrix(const GiNaC::matrix& m, const GiNaC::exmap& values) {
  GiNaC::matrix out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = exact_value(m(i, j), values);
  return out;
}

}  // namespace pogear
