// Symbolic solves with the sparse matrices of radii: A X = B block by block in A's block triangular
// form, the kernel basis Q1 of R built on it, and products of its entries kept in lowest terms.
#pragma once

#include <vector>

#include <ginac/ginac.h>

namespace pogear {

// A X = B for a nonsingular symbolic A, block by block in A's block triangular form: equations
// matched to unknowns along A's nonzeros, and the strongly connected components of "equation
// uses the unknown another one is matched to" (Tarjan), which come out dependencies first. Each
// diagonal block is nonsingular (their determinants multiply to det A) and small: 2 x 2 for a
// chain of stages, where solving all of A at once worked on e x e rational functions.
GiNaC::matrix block_triangular_solve(const GiNaC::matrix& A, const GiNaC::matrix& B);

// Q with R_rows Q = 0 and identity rows at the kept velocities; `rows` are independent on the
// eliminated columns (independent_rows), so this is ker R.
GiNaC::matrix kernel_basis(const GiNaC::matrix& R, const std::vector<int>& rows, const std::vector<int>& kept,
                           const std::vector<int>& elim);

// normal(a b), without normal's polynomial gcds when both are monomials (every entry of Q1 for
// a chain of stages is one): their product is already in lowest terms.
GiNaC::ex normal_product(const GiNaC::ex& a, const GiNaC::ex& b);

}  // namespace pogear
