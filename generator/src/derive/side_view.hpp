// The side view of a gear (docs/design.md §2, the paper's Sec. III-A): the rows of R of its toothed
// meshes, the geometry relations and the numeric radii checked against them.
#pragma once

#include "derive/radius_matrix.hpp"

namespace pogear {

// R's rows of the meshes of `t` (toothed only, every body turning, the fixed ones included as
// columns past the turning ones), the relations, the contact sides, derived radii and angled pairs.
// Throws InputError or GeometryConflict for a layout that cannot be, located in the model.
RadiusMatrix derive_side_view(const Topology& t, const SymbolTable& s);

}  // namespace pogear
