// Operation counts of generated expressions: the multiplications and additions the generated
// rhs and outputs compute, reported in the generated header.
#pragma once

#include <vector>

#include <ginac/ginac.h>

namespace pogear {

struct OperationCount {
  int multiplications = 0;  // divisions included
  int additions = 0;        // subtractions included
  int total() const { return multiplications + additions; }
};

OperationCount count_operations(const GiNaC::ex& e);

struct Assignment;    // specialization.hpp
struct ImplicitForm;  // specialization.hpp
OperationCount count_all(const std::vector<Assignment>& temps, const std::vector<GiNaC::ex>& values);
// The entries of L, A and B, one Cholesky factorization of L, its solves for M = L^-1 A and
// N = L^-1 B, and M x + N u: what the generated rhs computes (the solve's counts are the usual
// leading terms, not a count of Eigen's code).
OperationCount implicit_operations(const ImplicitForm& f);

}  // namespace pogear
