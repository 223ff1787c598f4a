// Reduction to the rigid model. Ranks and row choices are taken numerically at the model's
// parameter values (which satisfy the geometry relations); the algebra itself is symbolic.
#include "derive/rigid_model.hpp"

#include <stdexcept>
#include <utility>

#include <cln/integer.h>
#include <cln/rational.h>

#include "common/block_triangular_solve.hpp"
#include "common/exact_algebra.hpp"
#include "derive/force_recovery.hpp"
#include "derive/kept_velocities.hpp"
#include "common/numeric_rank.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

cln::cl_RA rational_value(const ex& x) {
  const GiNaC::numeric v = as_number(x);
  if (!v.is_rational()) throw std::domain_error("a parameter value is not a rational number");
  return cln::the<cln::cl_RA>(v.to_cl_N());
}

}  // namespace

RigidModel reduce_to_rigid(const Topology& t, const ElasticModel& e, const GiNaC::exmap& values,
                           const std::vector<std::string>& keep, const SourceLocation& where, const SymbolTable& s,
                           bool closed_forms) {
  const int n = static_cast<int>(t.bodies.size());
  const Eigen::MatrixXd Rn = evaluate_matrix(e.R, values);
  RigidModel r;
  r.rank = numeric_rank(Rn);

  const KeptVelocities chosen = choose_kept_velocities(t, e.R, Rn, r.rank, keep, where, values, s);
  r.kept = chosen.kept;
  r.eliminated = chosen.eliminated;

  r.constraint_rows = independent_rows(Rn, r.eliminated);
  r.Q1 = kernel_basis(e.R, r.constraint_rows, r.kept, r.eliminated);
  const unsigned k = r.kept.size();
  if (closed_forms) {
    r.L1 = GiNaC::matrix(k, k);
    r.A1 = GiNaC::matrix(k, k);
    r.B1 = r.Q1.transpose();
  } else {
    r.L1 = r.A1 = r.B1 = GiNaC::matrix(0, 0);
  }
  // L1 and A1 are symmetric; each sum is built at once (adding term by term re-sorts it each time).
  for (unsigned i = 0; i < k && closed_forms; ++i)
    for (unsigned j = i; j < k; ++j) {
      GiNaC::exvector l, a;
      for (int b = 0; b < n; ++b) {
        const ex q = normal_product(r.Q1(b, i), r.Q1(b, j));
        if (q.is_zero()) continue;
        l.push_back(e.J(b, b) * q);
        a.push_back(-e.B_J(b, b) * q);
      }
      r.L1(i, j) = r.L1(j, i) = GiNaC::add(l);
      r.A1(i, j) = r.A1(j, i) = GiNaC::add(a);
    }

  ForceRecovery forces = recover_mesh_forces(t, e, r.Q1, r.kept, r.rank, Rn, values, s);
  r.force_recovery = std::move(forces.forces);
  r.reactions = e.forces;
  r.force_bodies = std::move(forces.force_bodies);
  r.redundant_meshes = forces.redundant_meshes;
  return r;
}

RigidValues exact_rigid_values(const RigidModel& r, const ElasticModel& e, const GiNaC::exmap& values) {
  RigidValues v;
  v.Q1 = exact_matrix(r.Q1, values);
  const unsigned n = v.Q1.rows(), k = v.Q1.cols();
  v.L1 = GiNaC::matrix(k, k);
  v.A1 = GiNaC::matrix(k, k);
  // Integers over common denominators: Q1(b, i) = q[b][i] / qden[i], J_b = jn[b] / jden and
  // B_J(b) = bn[b] / bden, so that each entry of L1 = Q1^T J Q1 and A1 = -Q1^T B_J Q1 is an integer
  // sum reduced once, where summing the rationals term by term takes a gcd of numbers of thousands
  // of bits per term for a long chain.
  std::vector<cln::cl_RA> J(n), BJ(n);
  cln::cl_I jden = 1, bden = 1;
  for (unsigned b = 0; b < n; ++b) {
    J[b] = rational_value(exact_value(e.J(b, b), values));
    BJ[b] = rational_value(exact_value(e.B_J(b, b), values));
    jden = cln::lcm(jden, cln::denominator(J[b]));
    bden = cln::lcm(bden, cln::denominator(BJ[b]));
  }
  std::vector<cln::cl_I> jn(n), bn(n), qden(k, cln::cl_I(1));
  for (unsigned b = 0; b < n; ++b) {
    jn[b] = cln::numerator(J[b]) * cln::exquo(jden, cln::denominator(J[b]));
    bn[b] = cln::numerator(BJ[b]) * cln::exquo(bden, cln::denominator(BJ[b]));
  }
  std::vector<std::vector<cln::cl_I>> q(n, std::vector<cln::cl_I>(k, cln::cl_I(0)));
  for (unsigned i = 0; i < k; ++i) {
    for (unsigned b = 0; b < n; ++b)
      if (!v.Q1(b, i).is_zero()) qden[i] = cln::lcm(qden[i], cln::denominator(rational_value(v.Q1(b, i))));
    for (unsigned b = 0; b < n; ++b)
      if (!v.Q1(b, i).is_zero()) {
        const cln::cl_RA x = rational_value(v.Q1(b, i));
        q[b][i] = cln::numerator(x) * cln::exquo(qden[i], cln::denominator(x));
      }
  }
  for (unsigned i = 0; i < k; ++i)
    for (unsigned j = i; j < k; ++j) {
      cln::cl_I l = 0, a = 0;
      for (unsigned b = 0; b < n; ++b) {
        if (cln::zerop(q[b][i]) || cln::zerop(q[b][j])) continue;
        const cln::cl_I qq = q[b][i] * q[b][j];
        l = l + jn[b] * qq;
        a = a - bn[b] * qq;
      }
      const cln::cl_I d = qden[i] * qden[j];
      v.L1(i, j) = v.L1(j, i) = GiNaC::numeric(cln::cl_N(l / (jden * d)));
      v.A1(i, j) = v.A1(j, i) = GiNaC::numeric(cln::cl_N(a / (bden * d)));
    }
  return v;
}

GiNaC::matrix exact_rigid_response(const RigidModel& r, const ElasticModel& e, const GiNaC::exmap& values,
                                   const GiNaC::matrix& torques) {
  // With omega' = Q1 y (the constraint rows force it, their kernel being exactly span Q1) the
  // first block row J Q1 y + R_c^T lambda = T, multiplied by Q1^T (R_c Q1 = 0), is L1 y = Q1^T T;
  // and y = omega' at the kept bodies, where Q1 is the identity. So this is L1^-1 Q1^T T without
  // L1: the saddle-point matrix has the sparsity of R (a few entries per row, banded along a
  // chain) and entries of a few machine words, where L1 is dense with entries of thousands of
  // bits for a long chain, costly to eliminate exactly.
  const unsigned n = e.J.rows(), c = r.constraint_rows.size(), s = n + c, cols = torques.cols();
  GiNaC::matrix S(s, s), rhs(s, cols);
  for (unsigned b = 0; b < n; ++b) {
    S(b, b) = exact_value(e.J(b, b), values);
    for (unsigned i = 0; i < c; ++i) S(b, n + i) = S(n + i, b) = exact_value(e.R(r.constraint_rows[i], b), values);
  }
  // Each column of T as integers over a common denominator, divided out at the end: the
  // elimination then mixes T's big denominators (products of radii along a chain) into no gcd.
  std::vector<cln::cl_I> den(cols, cln::cl_I(1));
  for (unsigned j = 0; j < cols; ++j) {
    for (unsigned b = 0; b < n; ++b)
      if (!torques(b, j).is_zero()) den[j] = cln::lcm(den[j], cln::denominator(rational_value(torques(b, j))));
    for (unsigned b = 0; b < n; ++b) {
      if (torques(b, j).is_zero()) continue;
      const cln::cl_RA t = rational_value(torques(b, j));
      rhs(b, j) = GiNaC::numeric(cln::cl_N(cln::numerator(t) * cln::exquo(den[j], cln::denominator(t))));
    }
  }
  // Bodies first: their pivots are the diagonal J, and eliminating them leaves -R_c J^-1 R_c^T,
  // which couples only meshes that share a body, so forward elimination fills within its band.
  // Only the kept bodies' accelerations are solved for, and the multipliers they depend on.
  std::vector<int> rows(r.kept.begin(), r.kept.end());
  GiNaC::matrix y = exact_solve_rows(S, rhs, rows);
  for (unsigned i = 0; i < y.rows(); ++i)
    for (unsigned j = 0; j < cols; ++j)
      if (!y(i, j).is_zero()) y(i, j) = as_number(y(i, j)).div(GiNaC::numeric(cln::cl_N(den[j])));
  return y;
}

}  // namespace pogear
