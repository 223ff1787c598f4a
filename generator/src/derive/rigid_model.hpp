// The rigid reduced model (K -> infinity) for the velocities the user keeps: omega = Q1 x1 with
// R Q1 = 0, L1 = Q1^T J Q1, A1 = -Q1^T B_J Q1, B1 = Q1^T, and the mesh forces of eq. (8).
#pragma once

#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "derive/elastic_model.hpp"
#include "derive/force_recovery.hpp"
#include "derive/kept_velocities.hpp"

namespace pogear {

struct RigidModel {
  std::vector<int> kept;        // body indices of x1, in the order the user gave
  std::vector<int> eliminated;  // the other bodies, in body order
  std::vector<int> constraint_rows;  // rows of R independent on `eliminated`: their kernel is span Q1
  int rank = 0;                 // rank of R under the geometry relations
  GiNaC::matrix Q1;
  GiNaC::matrix L1, A1, B1;  // closed forms; 0 x 0 when not asked for (reduce_to_rigid)
  // Eq. (8), F = (R R^T)^-1 R g with g = tau - J Q1 dx1/dt - B_J Q1 x1, written as the equal
  // (on every rigid motion) F = (R_S^T)^-1 g_S over the bodies S = force_bodies: one expression
  // per mesh in tau_<body>, omega_<kept> and domega_<kept> (= d omega/dt). When R R^T is
  // singular (redundant meshes) eq. (8) does not exist; then F = K R (R^T K R)^+ g, the
  // stiffness-weighted split of docs/design.md §4, with its weights as numbers.
  std::vector<GiNaC::ex> force_recovery;
  std::vector<std::string> reactions;  // what force_recovery recovers: F_<mesh>, then T_<element> when engaged
  std::vector<int> force_bodies;
  bool redundant_meshes = false;
};

// The reduction for one set of kept velocities, under the constraints elastic.R (the gear's R, or
// [R; E_S] with friction elements S stuck, whose rows then recover their torques); `values` are the model's parameters as exact
// numbers (Derivation::values), for ranks and valid sets. It reads the elastic model and the
// symbol table and changes neither, so another set of constraints costs one more call, sharing R
// and the elastic model. Throws InputError (at `keep_where`) when the number kept is not
// n - rank(R) or the kept set does not parametrize ker R; the message names the tied velocities
// and lists valid sets. Without `closed_forms` L1, A1 and B1 are left empty: a simulator with
// every parameter a number needs only Q1 (exact_rigid_response), and for a long chain they are
// most of the work.
RigidModel reduce_to_rigid(const Topology& topology, const ElasticModel& elastic, const GiNaC::exmap& values,
                           const std::vector<std::string>& keep, const SourceLocation& keep_where,
                           const SymbolTable& symbols, bool closed_forms = true);

// Q1, L1 and A1 with `values` (symbol -> exact number, every parameter they hold) put in: the
// numbers the closed forms give, computed from Q1's entries instead of the closed forms, which
// grow like k^4 for a chain of k stages. Throws std::domain_error if a value is missing.
struct RigidValues {
  GiNaC::matrix Q1, L1, A1;  // exact numbers
};
RigidValues exact_rigid_values(const RigidModel& rigid, const ElasticModel& elastic, const GiNaC::exmap& values);

// L1^-1 Q1^T T for the torques T (n x c; exact numbers), i.e. dx1/dt of the rigid model under
// each column of T, exactly, at `values` (every parameter of J and R). Solved through the
// sparse saddle-point system [J R_c^T; R_c 0] of the constraint rows, not through L1.
GiNaC::matrix exact_rigid_response(const RigidModel& rigid, const ElasticModel& elastic, const GiNaC::exmap& values,
                                   const GiNaC::matrix& torques);

}  // namespace pogear
