// Brakes and clutches engaged: the constraint rows E_S they add to R (docs/friction-elements.md),
// the names on a command line that choose them, and the gear's motion with them engaged.
#pragma once

#include <string>
#include <vector>

#include <Eigen/Dense>
#include <ginac/ginac.h>

#include "read/topology.hpp"

namespace pogear {

// One row e_k per engaged element k (indices into Topology::friction_elements): +a_i at its
// first body, -a_j at its second, a the bodies' arrows, so that e_k omega is its slip.
GiNaC::matrix engagement_rows(const Topology& t, const std::vector<int>& engaged);
// [R; E]: the constraints of the gear with those elements stuck.
GiNaC::matrix stacked(const GiNaC::matrix& R, const GiNaC::matrix& E);
// The same at numbers, for ranks: E's rows scaled to R's largest entry, so that one relative
// threshold judges both (a row scale changes no rank and no kernel).
Eigen::MatrixXd stacked_for_rank(const Eigen::MatrixXd& Rn, const GiNaC::matrix& E);

// Element names, comma-separated ("B1,C2"), as indices in file order. Throws InputError at
// `where` for an unknown or repeated name, listing the elements.
std::vector<int> parse_engaged(const Topology& t, const std::string& list, const SourceLocation& where);
std::string engaged_names(const Topology& t, const std::vector<int>& engaged, const std::string& separator);

}  // namespace pogear
