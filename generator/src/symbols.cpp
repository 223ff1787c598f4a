// Numeric evaluation of symbolic expressions at a model's parameter values.
#include "symbols.hpp"

#include <stdexcept>

#include <cln/dfloat.h>
#include <cln/rational.h>
#include <cln/real.h>

namespace pogear {

GiNaC::numeric exact_number(double v) {
  return GiNaC::numeric(cln::cl_N(cln::rational(cln::cl_DF(v))));
}

GiNaC::exmap numeric_substitutions(Symbols& s, const std::map<std::string, double>& values) {
  GiNaC::exmap m;
  for (const auto& [name, v] : values) m[symbol(s, name)] = exact_number(v);
  return m;
}

double to_double(const GiNaC::ex& e) {
  const GiNaC::ex v = e.evalf();
  if (!GiNaC::is_a<GiNaC::numeric>(v) || !GiNaC::ex_to<GiNaC::numeric>(v).is_real())
    throw std::domain_error("expression does not evaluate to a real number");
  return GiNaC::ex_to<GiNaC::numeric>(v).to_double();
}

}  // namespace pogear

namespace pogear {
Eigen::MatrixXd evaluate_matrix(const GiNaC::matrix& m, const GiNaC::exmap& values) {
  Eigen::MatrixXd out(m.rows(), m.cols());
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j) out(i, j) = to_double(m(i, j).subs(values));
  return out;
}
}  // namespace pogear
