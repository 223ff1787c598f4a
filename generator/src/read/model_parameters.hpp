// The model's parameter table (Topology::parameters): read once with the model, with a scene's
// overrides applied by the scene reader, and only read after that. Lookups never add entries.
#pragma once

#include <map>
#include <string>
#include <vector>

#include "read/topology.hpp"

namespace pogear {

// Gives every parameter its value from its text; they may refer to each other.
void evaluate_parameters(std::vector<Parameter>& parameters);
// Every parameter a role needs must exist (radii may come from the geometry later), carry the
// right unit and a sensible sign; also after a scene's overrides, which may change any of them.
void check_parameter_roles(const Topology& t);

// A friction element's static_ratio (static over kinetic friction), from 1 to 10; throws InputError
// at its value otherwise.
double static_friction_ratio(const Topology& t, const FrictionElement& e);
const Parameter* find_parameter(const Topology& t, const std::string& name);
// The parameters' values by name: what an expression of a scene or a command-line option may name.
std::map<std::string, Quantity> parameter_quantities(const Topology& t);
double parameter_value(const Topology& t, const std::string& name);  // SI; throws if absent

}  // namespace pogear
