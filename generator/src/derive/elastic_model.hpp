// The full elastic POG model of eqs. (2)-(3): L x' = A x + B u, x = (omega, F), u = tau.
#pragma once

#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "derive/radius_matrix.hpp"

namespace pogear {

struct ElasticModel {
  std::vector<std::string> velocities;  // omega_<body>, in body order
  std::vector<std::string> forces;      // F_<mesh>, in mesh order
  std::vector<std::string> torques;     // tau_<body>
  GiNaC::matrix J, B_J;  // n x n diagonal: inertias, bearing friction
  GiNaC::matrix K, B_K;  // m x m diagonal: mesh stiffness, mesh damping
  GiNaC::matrix R;       // m x n
  GiNaC::matrix L, A, B; // (n+m) x (n+m), (n+m) x (n+m), (n+m) x n
};

ElasticModel assemble_elastic_model(const Topology& topology, const RadiusMatrix& radius, const SymbolTable& symbols);

}  // namespace pogear
