// The radius matrix R from the side-view contact velocities (docs/design.md §2, the paper's Sec. III-A),
// pinion pairs at an angle in their carrier's frame, and the geometry relations the layout imposes
// on the radii (r_c = r_p + r_s1, ...).
#pragma once

#include <map>
#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "names/symbols.hpp"
#include "read/topology.hpp"

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

// A mesh between two pinions of one carrier whose axes are not on one line through the central
// axis (Ravigneaux and double-pinion sets): its row is taken in the carrier's frame, where both
// axes are fixed, and the layout only has to close the triangle of the two axis distances and the
// centre distance.
struct AngledMesh {
  int mesh = -1;
  double angle = 0;  // rad, between the two pinions' axes seen from the central axis
};

// A radius or axis distance the model leaves out, with the value its relation gives.
struct DerivedRadius {
  std::string parameter;
  double value = 0;  // SI
};

struct RadiusMatrix {
  GiNaC::matrix R;  // meshes x bodies, entries in the model's named radii
  // Per fixed body, the column of R it would have (one entry per mesh): F's torque on it is
  // -column . F, so the housing holds it with +column . F.
  std::vector<GiNaC::exvector> fixed_columns;
  std::vector<GeometryRelation> relations;
  std::vector<ContactSides> sides;  // per mesh
  std::vector<DerivedRadius> derived;  // radii not in the file, computed from the relations
  std::vector<AngledMesh> angled;      // in mesh order
};

// Derives R and the geometry relations, and checks the numeric radii against them.
// Throws InputError naming the parameter, both values and the mesh for an inconsistency.
RadiusMatrix derive_radius_matrix(const Topology& topology, const SymbolTable& symbols);

// lhs == rhs substitutions for every relation, to take ranks and simplify "under the geometry".
GiNaC::exmap geometry_substitutions(const RadiusMatrix& rm, const SymbolTable& symbols);

std::string describe_mesh(const Topology& t, int mesh);  // "mesh ps (p with s1 of body s)"

}  // namespace pogear
