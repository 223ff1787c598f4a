// The model's parameter table as one value, built once by the derivation and read by the reports,
// the folding of a scene's values and the generated code's `namespace parameters`.
#pragma once

#include <string>
#include <vector>

#include <ginac/ginac.h>

#include "derive/radius_matrix.hpp"

namespace pogear {

// Where a parameter's value comes from.
enum class ParameterOrigin {
  file,      // the model's [parameters] (a scene's override applied)
  teeth,     // a pitch radius, m Z / 2 from the wheel's teeth
  geometry,  // a radius the model leaves out, derived from a geometry relation of `mesh`
};

struct ParameterValue {
  std::string name;
  std::string text;  // as written ("14.8*cm", or m Z / 2 from teeth); empty for a derived radius
  double si = 0;
  GiNaC::numeric exact;  // si as an exact rational
  std::string unit;      // SI ("kg*m^2"); empty when none was written
  SourceLocation where;  // the line that defines it; none for a derived radius
  ParameterOrigin origin = ParameterOrigin::file;
  std::string mesh;      // a derived radius's mesh
};

// The file's parameters in the model's order, then the radii the geometry derives.
std::vector<ParameterValue> parameter_table(const Topology& t, const RadiusMatrix& radius);

// The table as the reports print it: name, text as given, SI value with unit (6 significant
// digits, as the other report numbers), and where it is defined ("line 41", "its teeth, line 12",
// "mesh sp").
std::vector<std::vector<std::string>> parameter_report_rows(const std::vector<ParameterValue>& table);

}  // namespace pogear
