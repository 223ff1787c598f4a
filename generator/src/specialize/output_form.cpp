// The outputs' matrices come from the same expressions outputs() prints, with dx/dt = M x + N u put
// in exactly where M and N are exact numbers, so that C x + D u and outputs() differ by rounding only.
#include "specialize/output_form.hpp"

#include <vector>

#include "common/exact_algebra.hpp"
#include "specialize/linear_form.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// a + b c for matrices of exact numbers. Each row's products are summed as integers over one
// common denominator and reduced once: a sum of rationals reduces at every addition, and M of a
// long chain has long numbers.
GiNaC::matrix exact_plus_product(const GiNaC::matrix& a, const GiNaC::matrix& b, const GiNaC::matrix& c) {
  using GiNaC::numeric;
  numeric c_denominator = 1;
  for (unsigned k = 0; k < c.rows(); ++k)
    for (unsigned j = 0; j < c.cols(); ++j) c_denominator = GiNaC::lcm(c_denominator, as_number(c(k, j)).denom());
  std::vector<std::vector<numeric>> c_scaled(c.rows(), std::vector<numeric>(c.cols()));
  for (unsigned k = 0; k < c.rows(); ++k)
    for (unsigned j = 0; j < c.cols(); ++j) c_scaled[k][j] = as_number(c(k, j)).mul(c_denominator);
  GiNaC::matrix sum(a.rows(), a.cols());
  for (unsigned i = 0; i < a.rows(); ++i) {
    numeric b_denominator = 1;
    for (unsigned k = 0; k < b.cols(); ++k) b_denominator = GiNaC::lcm(b_denominator, as_number(b(i, k)).denom());
    std::vector<numeric> row(a.cols(), numeric(0));
    for (unsigned k = 0; k < b.cols(); ++k) {
      if (b(i, k).is_zero()) continue;
      const numeric factor = as_number(b(i, k)).mul(b_denominator);
      for (unsigned j = 0; j < a.cols(); ++j)
        if (!c_scaled[k][j].is_zero()) row[j] = row[j].add(factor.mul(c_scaled[k][j]));
    }
    const numeric denominator = b_denominator.mul(c_denominator);
    for (unsigned j = 0; j < a.cols(); ++j) sum(i, j) = as_number(a(i, j)).add(row[j].div(denominator));
  }
  return sum;
}

}  // namespace

OutputForm output_form(const SpecializedSystem& sys, const SymbolTable& symbols) {
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size(), ny = sys.outputs.size();
  // y = C x + D u + E dx/dt, read off the output expressions.
  std::vector<ex> variables;
  for (const StatePort& x : sys.states) variables.push_back(variable_symbol(symbols, x.variable));
  for (const InputPort& u : sys.inputs) variables.push_back(variable_symbol(symbols, u.variable));
  for (const StatePort& x : sys.states) variables.push_back(variable_symbol(symbols, derivative_of(x.variable)));
  const GiNaC::matrix all = linear_coefficients(output_values(sys), variables);
  OutputForm f{GiNaC::matrix(ny, nx), GiNaC::matrix(ny, nu), GiNaC::matrix(ny, nx), false};
  for (std::size_t i = 0; i < ny; ++i) {
    for (std::size_t j = 0; j < nx; ++j) f.C(i, j) = all(i, j);
    for (std::size_t j = 0; j < nu; ++j) f.D(i, j) = all(i, nx + j);
    for (std::size_t j = 0; j < nx; ++j) {
      f.E(i, j) = all(i, nx + nu + j);
      f.reads_derivatives = f.reads_derivatives || !f.E(i, j).is_zero();
    }
  }
  // dx/dt = M x + N u, exact numbers unless solved numerically (SpecializedSystem::implicit): C + E M and
  // D + E N, exactly.
  if (f.reads_derivatives && !sys.implicit) {
    f.C = exact_plus_product(f.C, f.E, sys.M);
    f.D = exact_plus_product(f.D, f.E, sys.N);
    f.E = GiNaC::matrix(ny, nx);
    f.reads_derivatives = false;
  }
  return f;
}

}  // namespace pogear
