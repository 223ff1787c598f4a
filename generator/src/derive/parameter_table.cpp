// Values print to 6 significant digits, as the other report numbers; the text as given is exact.
#include "derive/parameter_table.hpp"

#include <fmt/format.h>

namespace pogear {

std::vector<std::vector<std::string>> parameter_table(const Derivation& d) {
  std::vector<std::vector<std::string>> rows;
  auto pitch_radius = [&](const std::string& name) {
    for (const Body& b : d.topology.bodies)
      for (const Wheel& w : b.wheels)
        if (w.teeth > 0 && w.radius_parameter == name) return true;
    return false;
  };
  for (const Parameter& p : d.topology.parameters) {
    const std::string unit = p.value.has_unit ? " " + describe(p.value.dimension) : "";
    const std::string line = fmt::format("line {}", p.where.line);
    rows.push_back({p.name, p.text, fmt::format("{:.6g}{}", p.value.si, unit),
                    pitch_radius(p.name) ? "its teeth, " + line : line});
  }
  for (const DerivedRadius& r : d.radius.derived) {
    std::string mesh;
    for (const auto& g : d.radius.relations)
      if (g.parameter == r.parameter) mesh = d.topology.meshes[g.mesh].name;
    rows.push_back({r.parameter, "(geometry)", fmt::format("{:.6g} m", r.value), "mesh " + mesh});
  }
  return rows;
}

}  // namespace pogear
