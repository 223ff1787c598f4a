// See parameter_table.hpp. The exact value is the SI double's exact rational, as every stage that
// folds a parameter into the algebra has always taken it.
#include "derive/parameter_table.hpp"

#include <fmt/format.h>

#include "common/exact_algebra.hpp"

namespace pogear {
namespace {

// A pitch radius m Z / 2, or an operating one a Z / (Z_2 +- Z_1).
bool is_pitch_radius(const Topology& t, const std::string& name) {
  for (const Body* b : every_body(t))
    for (const Wheel& w : b->wheels)
      if (w.teeth > 0 && w.radius_parameter == name) return true;
  for (const Mesh& m : t.meshes)
    if (!m.centre_distance.empty() && (contact_radius(t, m, m.first) == name || contact_radius(t, m, m.second) == name)) return true;
  return false;
}

}  // namespace

std::vector<ParameterValue> parameter_table(const Topology& t, const RadiusMatrix& radius) {
  std::vector<ParameterValue> table;
  for (const Parameter& p : t.parameters)
    table.push_back({p.name, p.text, p.value.si, exact_number(p.value.si),
                     p.value.has_unit ? describe(p.value.dimension) : "", p.where,
                     is_pitch_radius(t, p.name) ? ParameterOrigin::teeth : ParameterOrigin::file, ""});
  for (const DerivedRadius& r : radius.derived) {
    ParameterValue v;
    v.name = r.parameter;
    v.si = r.value;
    v.exact = exact_number(r.value);
    v.unit = "m";
    v.origin = ParameterOrigin::geometry;
    for (const auto& g : radius.relations)
      if (g.parameter == r.parameter) v.mesh = t.meshes[g.mesh].name;
    table.push_back(std::move(v));
  }
  return table;
}

std::vector<std::vector<std::string>> parameter_report_rows(const std::vector<ParameterValue>& table) {
  std::vector<std::vector<std::string>> rows;
  for (const ParameterValue& p : table) {
    const std::string value = fmt::format("{:.6g}{}", p.si, p.unit.empty() ? "" : " " + p.unit);
    const std::string line = fmt::format("line {}", p.where.line);
    switch (p.origin) {
      case ParameterOrigin::file: rows.push_back({p.name, p.text, value, line}); break;
      case ParameterOrigin::teeth: rows.push_back({p.name, p.text, value, "its teeth, " + line}); break;
      case ParameterOrigin::geometry: rows.push_back({p.name, "(geometry)", value, "mesh " + p.mesh}); break;
    }
  }
  return rows;
}

}  // namespace pogear
