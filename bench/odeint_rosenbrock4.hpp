// A C++17 boundary around Boost.Odeint's rosenbrock4: Boost 1.74's uBLAS, which rosenbrock4 needs,
// does not compile as C++20 (it calls std::allocator::construct), while the generated code and the
// runtime need C++20. The harness passes the generated right-hand side in through a callback.
#pragma once

#include <string>
#include <vector>

namespace bench {

struct LinearOde {
  int n = 0;
  void* context = nullptr;
  void (*rhs)(void* context, double t, const double* x, double* dx) = nullptr;
  const double* jacobian = nullptr;  // n x n, column-major; constant (a linear model, constant inputs)
  void (*observe)(void* context, double t, const double* x) = nullptr;
};

struct Rosenbrock4Result {
  bool ok = true;
  std::string message;
  long steps = 0;
};

// Dense-output rosenbrock4 (odeint's make_dense_output) driven by integrate_times onto `times`.
Rosenbrock4Result integrate_rosenbrock4(const LinearOde& ode, const double* x0, const std::vector<double>& times,
                                        double atol, double rtol, double first_step);

}  // namespace bench
