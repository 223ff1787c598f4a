// block_triangular_solve, kernel_basis and normal_product against GiNaC's own linear algebra, on
// small symbolic matrices written out here: the results must be equal as rational functions.
#include <gtest/gtest.h>
#include <ginac/ginac.h>

#include "common/block_triangular_solve.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;
using GiNaC::matrix;
using GiNaC::symbol;

bool is_zero_matrix(const matrix& m) {
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      if (!m(i, j).normal().is_zero()) return false;
  return true;
}

matrix difference(const matrix& a, const matrix& b) { return a.sub(b); }

// GiNaC's Gaussian elimination on the whole matrix, the solve that block_triangular_solve avoids.
matrix reference_solve(const matrix& A, const matrix& B) { return A.inverse().mul(B); }

TEST(BlockTriangularSolve, PermutedTriangularSystem) {
  // No equation has its own unknown on the diagonal: the matching must pair row 0 with x1 and row 1
  // with x0 before the blocks (each 1 x 1) can be solved in order.
  const symbol a("a"), b("b"), c("c"), d("d"), e("e"), x("x"), y("y"), z("z");
  const matrix A{{0, a, 0}, {b, 0, 0}, {c, d, e}};
  const matrix B{{x}, {y}, {z}};
  const matrix X = block_triangular_solve(A, B);
  EXPECT_TRUE(is_zero_matrix(difference(A.mul(X), B)));
  EXPECT_TRUE(is_zero_matrix(difference(X, reference_solve(A, B))));
  EXPECT_TRUE((X(0, 0) - y / b).normal().is_zero()) << X(0, 0);
  EXPECT_TRUE((X(1, 0) - x / a).normal().is_zero()) << X(1, 0);
}

TEST(BlockTriangularSolve, CoupledBlockThenItsDependents) {
  // Rows 0 and 1 couple x0 and x1 (a 2 x 2 block, as in a chain of stages); x2 then x3 follow.
  const symbol a("a"), b("b"), c("c"), d("d"), e("e"), f("f"), g("g"), h("h"), k("k");
  const matrix A{{a, b, 0, 0}, {c, d, 0, 0}, {0, e, f, 0}, {g, 0, h, k}};
  const matrix B{{1, 0}, {0, 1}, {2, 0}, {0, 3}};
  const matrix X = block_triangular_solve(A, B);
  EXPECT_TRUE(is_zero_matrix(difference(A.mul(X), B)));
  EXPECT_TRUE(is_zero_matrix(difference(X, reference_solve(A, B))));
}

TEST(BlockTriangularSolve, NumbersAndSymbolsMixed) {
  const symbol r("r");
  const matrix A{{2, 0, 0}, {r, 3, 0}, {1, r, 5}};
  const matrix B{{4}, {0}, {1}};
  const matrix X = block_triangular_solve(A, B);
  // Forward substitution by hand: x0 = 2, x1 = -2 r / 3, x2 = (1 - 2 + 2 r^2 / 3) / 5.
  EXPECT_TRUE((X(0, 0) - 2).normal().is_zero()) << X(0, 0);
  EXPECT_TRUE((X(1, 0) + 2 * r / 3).normal().is_zero()) << X(1, 0);
  EXPECT_TRUE((X(2, 0) - (-1 + 2 * r * r / 3) / 5).normal().is_zero()) << X(2, 0);
}

TEST(KernelBasis, SpansTheKernelWithIdentityAtTheKeptVelocity) {
  // Two meshes in a row (sun s, planet p, ring-like third body q): R omega = 0 leaves one freedom.
  const symbol r1("r1"), r2("r2"), r3("r3"), r4("r4");
  const matrix R{{r1, -r2, 0}, {0, r3, r4}};
  const matrix Q = kernel_basis(R, {0, 1}, {0}, {1, 2});
  ASSERT_EQ(Q.rows(), 3u);
  ASSERT_EQ(Q.cols(), 1u);
  EXPECT_TRUE(is_zero_matrix(R.mul(Q)));
  EXPECT_TRUE((Q(0, 0) - 1).normal().is_zero()) << Q(0, 0);
  // omega_1 = r1 / r2 omega_0 from the first row, omega_2 = -r3 / r4 omega_1 from the second.
  EXPECT_TRUE((Q(1, 0) - r1 / r2).normal().is_zero()) << Q(1, 0);
  EXPECT_TRUE((Q(2, 0) + r1 * r3 / (r2 * r4)).normal().is_zero()) << Q(2, 0);
}

TEST(NormalProduct, EqualsNormalOfTheProduct) {
  const symbol a("a"), b("b"), c("c");
  const std::pair<ex, ex> cases[] = {
      {a / b, b / c},                  // monomials: the shortcut
      {(a + b) / c, c / (a + b)},      // sums: normal's gcds cancel them
      {2 * a * a / (3 * b), 9 * b / a},
  };
  for (const auto& [x, y] : cases) EXPECT_TRUE((normal_product(x, y) - (x * y).normal()).normal().is_zero()) << x << " * " << y;
}

}  // namespace
}  // namespace pogear::test
