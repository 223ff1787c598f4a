// How far a generated system's output_matrices(p, C, D) is from its outputs(p, x, u, y): included
// by the runtime tests and compiled into checker programs over freshly generated headers.
#pragma once

#include <algorithm>
#include <random>

namespace pogear::test {

// The largest |C x + D u - y| over 20 random points, relative to the largest term of C x + D u.
// Velocities of tens of rad/s, forces of thousands of N and torques of hundreds of N m, signs mixed.
template <class System>
double output_matrices_error(const typename System::Params& p) {
  typename System::OutputMatrix C;
  typename System::FeedthroughMatrix D;
  System::output_matrices(p, C, D);
  std::mt19937 random(11);
  std::uniform_real_distribution<double> velocity(-50, 50), force(-5e3, 5e3), torque(-300, 300);
  double worst = 0;
  for (int point = 0; point < 20; ++point) {
    typename System::State x;
    typename System::Input u;
    for (int i = 0; i < System::nx; ++i) x[i] = System::state_units[i] == "N" ? force(random) : velocity(random);
    for (int j = 0; j < System::nu; ++j) u[j] = torque(random);
    typename System::Output y;
    System::outputs(p, x, u, y);
    const typename System::Output linear = C * x + D * u;
    const double scale = (C.cwiseAbs() * x.cwiseAbs() + D.cwiseAbs() * u.cwiseAbs()).maxCoeff();
    worst = std::max(worst, (linear - y).cwiseAbs().maxCoeff() / scale);
  }
  return worst;
}

}  // namespace pogear::test
