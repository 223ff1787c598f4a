// See block_triangular_solve.hpp: a maximum matching and Tarjan's strongly connected components
// order the equations; each small diagonal block is inverted symbolically.
#include "common/block_triangular_solve.hpp"

#include <algorithm>
#include <stdexcept>

namespace pogear {
namespace {

using GiNaC::ex;

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

}  // namespace

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

ex normal_product(const ex& a, const ex& b) {
  if (a.is_zero() || b.is_zero()) return 0;
  if (is_monomial(a) && is_monomial(b)) return a * b;
  return (a * b).normal();
}

}  // namespace pogear
