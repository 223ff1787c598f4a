// Which velocities the rigid model may keep: the sets that parametrize ker R, and the checks and
// messages for the set the user asked for.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>
#include <ginac/ginac.h>

#include "names/symbols.hpp"
#include "read/topology.hpp"

namespace pogear {

struct KeptVelocities {
  std::vector<int> kept;        // body indices, in the order the user gave
  std::vector<int> eliminated;  // the other bodies, in body order
};

// The bodies named by `keep` and the others. Throws InputError (at `where`) when a name is not a
// body or is repeated, when the number kept is not n - rank, or when the kept set does not
// parametrize ker R; the message names the tied velocities and lists valid sets.
KeptVelocities choose_kept_velocities(const Topology& t, const GiNaC::matrix& R, const Eigen::MatrixXd& Rn, int rank,
                                      const std::vector<std::string>& keep, const SourceLocation& where,
                                      const GiNaC::exmap& values, const SymbolTable& s);

// Sets of velocities that can be kept, in body order, at most `limit` of them.
std::vector<std::vector<int>> valid_keep_sets(const Eigen::MatrixXd& R_numeric, std::size_t limit);

}  // namespace pogear
