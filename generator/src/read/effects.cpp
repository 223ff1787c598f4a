// A model with meshes and shafts is compliant in both or rigid in both: the rigid model has no
// partly elastic form (docs/model-format.md, "Shafts").
#include "read/effects.hpp"

#include <fmt/format.h>

namespace pogear {

Effects read_effects(const SceneReader& r, const toml::node& n, const Topology& t) {
  Effects e;
  for (const std::string& name : r.strings(n, "effects")) {
    if (name == "mesh_compliance") e.mesh_compliance = true;
    else if (name == "shaft_compliance") e.shaft_compliance = true;
    else if (name == "mesh_damping") e.mesh_damping = true;
    else if (name == "shaft_damping") e.shaft_damping = true;
    else if (name == "bearing_friction") e.bearing_friction = true;
    else if (name == "mesh_forces") e.mesh_forces = true;
    else
      r.fail(n, fmt::format("unknown effect '{}'; the effects are mesh_compliance, shaft_compliance, mesh_damping, "
                            "shaft_damping, bearing_friction, mesh_forces", name));
  }
  const bool meshes = toothed_mesh_count(t) > 0, shafts = has_shafts(t);
  if (!meshes && (e.mesh_compliance || e.mesh_damping))
    r.fail(n, fmt::format("model {} has no [[mesh]], so {} has nothing to act on; its shafts' effects are "
                          "shaft_compliance and shaft_damping", t.name, e.mesh_compliance ? "mesh_compliance" : "mesh_damping"));
  if (!shafts && (e.shaft_compliance || e.shaft_damping))
    r.fail(n, fmt::format("model {} has no [[shaft]], so {} has nothing to act on; drop it", t.name,
                          e.shaft_compliance ? "shaft_compliance" : "shaft_damping"));
  if (e.mesh_damping && !e.mesh_compliance)
    r.fail(n, "mesh_damping needs mesh_compliance: a rigid mesh has no deflection to damp; add mesh_compliance "
              "or drop mesh_damping");
  if (e.shaft_damping && !e.shaft_compliance)
    r.fail(n, "shaft_damping needs shaft_compliance: a rigid shaft has no twist to damp; add shaft_compliance "
              "or drop shaft_damping");
  if (meshes && shafts && e.mesh_compliance != e.shaft_compliance) {
    const char* named = e.mesh_compliance ? "mesh_compliance" : "shaft_compliance";
    const char* missing = e.mesh_compliance ? "shaft_compliance" : "mesh_compliance";
    r.fail(n, fmt::format("{0} without {1}: pogear derives a gear whose meshes and shafts are both compliant or both "
                          "rigid, not one of each; add {1} or drop {0}", named, missing));
  }
  return e;
}

}  // namespace pogear
