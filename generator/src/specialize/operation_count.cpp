// See operation_count.hpp: counted on the expression trees as printed, signs not counted.
#include "specialize/operation_count.hpp"

#include <algorithm>
#include <cstdlib>

#include "specialize/specialization.hpp"

namespace pogear {

using GiNaC::ex;

OperationCount count_operations(const ex& e) {
  OperationCount c;
  if (GiNaC::is_a<GiNaC::add>(e)) {
    c.additions += static_cast<int>(e.nops()) - 1;
  } else if (GiNaC::is_a<GiNaC::mul>(e)) {
    int factors = 0;
    for (const ex& f : e)
      if (!(GiNaC::is_a<GiNaC::numeric>(f) && (f.is_equal(-1) || f.is_equal(1)))) ++factors;
    c.multiplications += std::max(0, factors - 1);
  } else if (GiNaC::is_a<GiNaC::power>(e)) {
    if (GiNaC::is_a<GiNaC::numeric>(e.op(1)) && GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_integer()) {
      const int p = std::abs(GiNaC::ex_to<GiNaC::numeric>(e.op(1)).to_int());
      c.multiplications += std::max(0, p - 1) + (GiNaC::ex_to<GiNaC::numeric>(e.op(1)).is_negative() ? 1 : 0);
    } else {
      c.multiplications += 1;
    }
  }
  for (const ex& op : e) {
    const OperationCount o = count_operations(op);
    c.multiplications += o.multiplications;
    c.additions += o.additions;
  }
  return c;
}

OperationCount count_all(const std::vector<Assignment>& temps, const std::vector<ex>& values) {
  OperationCount c;
  auto add = [&](const ex& e) {
    const OperationCount o = count_operations(e);
    c.multiplications += o.multiplications;
    c.additions += o.additions;
  };
  for (const auto& a : temps) add(a.value);
  for (const auto& v : values) add(v);
  return c;
}

OperationCount implicit_operations(const ImplicitForm& f) {
  std::vector<ex> entries;
  for (const GiNaC::matrix* m : {&f.L, &f.A, &f.B})
    for (unsigned i = 0; i < m->rows(); ++i)
      for (unsigned j = 0; j < m->cols(); ++j) entries.push_back((*m)(i, j));
  OperationCount c = count_all({}, entries);
  const int k = static_cast<int>(f.L.rows()), columns = static_cast<int>(f.A.cols() + f.B.cols());
  c.multiplications += k * k * k / 6 + k + columns * k * k + columns * k;
  c.additions += k * k * k / 6 + columns * k * (k - 1) + columns * k;
  return c;
}

}  // namespace pogear
