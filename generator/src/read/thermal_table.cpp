// A scene's [thermal]: per brake or clutch a heat capacity, a conductance to a fixed ambient
// temperature and a start temperature, read with their units.
#include "read/thermal_table.hpp"

#include <algorithm>
#include <string>

#include <fmt/format.h>

#include "common/quantity.hpp"

namespace pogear {
namespace {

// 0 degC in K.
constexpr double kZeroCelsius = 273.15;

// An absolute temperature in degC from "90*degC" or "363.15*K": the unit's name tells the scale's zero.
double temperature(const SceneReader& r, const toml::node& n, std::string_view what) {
  const double v = r.quantity(n, temperature_dimension(), what);
  const std::vector<std::string> units = n.is_string() ? referenced_units(*n.value<std::string>()) : std::vector<std::string>{};
  const bool kelvin = std::count(units.begin(), units.end(), "K") > 0, celsius = std::count(units.begin(), units.end(), "degC") > 0;
  if (kelvin == celsius)
    r.fail(n, fmt::format("{} needs a unit of temperature, degC or K (not both), e.g. \"90*degC\"", what));
  const double celsius_value = kelvin ? v - kZeroCelsius : v;
  if (!(celsius_value > -kZeroCelsius)) r.fail(n, fmt::format("{} is at or below absolute zero", what));
  return celsius_value;
}

}  // namespace

std::vector<ThermalSpec> read_thermal(const SceneReader& r, const toml::node& n) {
  const toml::table& t = r.table(n, "[thermal]");
  std::vector<ThermalSpec> out;
  for (const auto& [key, value] : t) {
    const std::string name(key.str());
    ThermalSpec th;
    th.element = find_friction_element(*r.model, name);
    if (th.element < 0) fail_no_friction_element(r, value, name, "[thermal] gives an element's heat capacity and cooling");
    const toml::table& e = r.table(value, fmt::format("[thermal] {}", name));
    r.only_keys(e, {"heat_capacity", "conductance", "ambient", "initial"}, fmt::format("[thermal] {}", name));
    th.where = r.loc(value);
    const toml::node* capacity = e.get("heat_capacity");
    const toml::node* ambient = e.get("ambient");
    if (!capacity || !ambient)
      r.fail(value, fmt::format("[thermal] {} needs heat_capacity (e.g. \"800*J/K\") and ambient (e.g. \"90*degC\"); "
                                "conductance (W/K, default 0: no cooling) and initial (default: ambient) are optional", name));
    th.heat_capacity = r.coefficient(*capacity, heat_capacity_dimension(), "heat_capacity", "J/K");
    if (!(th.heat_capacity > 0)) r.fail(*capacity, "heat_capacity is above zero: the element's heat raises its temperature");
    if (const toml::node* g = e.get("conductance")) {
      th.conductance = r.coefficient(*g, thermal_conductance_dimension(), "conductance", "W/K");
      if (!(th.conductance >= 0)) r.fail(*g, "conductance is not negative: the element loses heat to the ambient");
    }
    th.ambient = temperature(r, *ambient, "ambient");
    const toml::node* initial = e.get("initial");
    th.initial = initial ? temperature(r, *initial, "initial") : th.ambient;
    out.push_back(th);
  }
  std::sort(out.begin(), out.end(), [](const ThermalSpec& a, const ThermalSpec& b) { return a.element < b.element; });
  return out;
}

void check_thermal(const Scene& s) {
  for (const ThermalSpec& th : s.thermal) {
    const std::string& name = s.model.friction_elements[static_cast<std::size_t>(th.element)].name;
    if (!engages(s, th.element))
      throw InputError(th.where, fmt::format("the scene does not engage {}, so it never heats; give {} a command in "
                                             "[engagement], or drop it from [thermal]", name, name));
  }
}

}  // namespace pogear
