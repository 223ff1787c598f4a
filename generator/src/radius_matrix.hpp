// The radius matrix R from the side-view contact velocities (DESIGN.md §2, the paper's Sec. III-A),
// and the geometry relations the layout imposes on the radii (r_c = r_p + r_s1, ...).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "symbols.hpp"
#include "topology.hpp"

namespace pogear {

// One radius or axis distance that the layout fixes in terms of the others.
struct GeometryRelation {
  std::string parameter;  // the dependent one, e.g. r_c
  GiNaC::ex rhs;          // in independent radii only, e.g. r_p + r_s1
  int mesh = -1;          // the mesh whose contact implies it
};

// Which side of its own axis a wheel touches its mate: +1 above, -1 below (the side view).
struct ContactSides {
  int first = +1;
  int second = +1;
};

struct RadiusMatrix {
  GiNaC::matrix R;  // meshes x bodies, entries in the model's named radii
  std::vector<GeometryRelation> relations;
  std::vector<ContactSides> sides;  // per mesh
  std::map<std::string, double> values;  // every parameter in SI, the derived radii included
  std::vector<std::string> derived;      // radii not in the file, computed from the relations
};

// Derives R and the geometry relations, and checks the numeric radii against them.
// Throws InputError naming the parameter, both values and the mesh for an inconsistency.
RadiusMatrix derive_radius_matrix(const Topology& topology, Symbols& symbols);

// lhs == rhs substitutions for every relation, to take ranks and simplify "under the geometry".
GiNaC::exmap geometry_substitutions(const RadiusMatrix& rm, Symbols& symbols);

std::string describe_mesh(const Topology& t, int mesh);  // "mesh ps (p with s1 of body s)"

}  // namespace pogear
