// See gear_table.hpp. A gear is named by plain names only: reports print them as they are.
#include "read/gear_table.hpp"

#include <algorithm>
#include <cctype>
#include <tuple>

#include <fmt/format.h>

#include "common/printer.hpp"

namespace pogear {
namespace {

std::string element_names(const Topology& t) {
  std::vector<std::string> names;
  for (const FrictionElement& e : t.friction_elements) names.push_back(e.name);
  return joined(names);
}

}  // namespace

// [gears]: "<name>" = ["<element>", ...], in the order written. Whether each is a gear (one degree
// of freedom, input and output turning) depends on the input and output, which `pogear ratios` checks.
std::vector<NamedGear> read_gears(const TomlReader& r, const toml::node& n, const Topology& t) {
  std::vector<NamedGear> gears;
  if (!n.is_table()) r.fail(n, "[gears] must be a table of gears, e.g. \"1\" = [\"A\", \"D\"]");
  // A TOML table is ordered by key; the gears keep the file's order.
  std::vector<std::pair<const toml::key*, const toml::node*>> entries;
  for (const auto& [key, value] : *n.as_table()) entries.emplace_back(&key, &value);
  std::sort(entries.begin(), entries.end(), [](const auto& a, const auto& b) {
    const toml::source_position pa = a.first->source().begin, pb = b.first->source().begin;
    return std::tie(pa.line, pa.column) < std::tie(pb.line, pb.column);
  });
  for (const auto& [key, node] : entries) {
    const toml::node& value = *node;
    const std::string name(key->str());
    NamedGear gear{name, {}, toml_location(r.file, key->source())};
    const bool plain = !name.empty() && name.size() <= max_name_length &&
                       std::all_of(name.begin(), name.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)) || c == '_'; });
    if (!plain)
      throw InputError(gear.where, fmt::format("a gear's name is letters, digits and '_', at most {} characters, e.g. "
                                               "\"1\" or R; rename the gear", max_name_length));
    if (!value.is_array())
      r.fail(value, fmt::format("gear '{}' must list the brakes and clutches it engages, e.g. \"{}\" = [\"{}\"]", name,
                                name, t.friction_elements.empty() ? std::string("B1") : t.friction_elements.front().name));
    for (const toml::node& e : *value.as_array()) {
      const std::string element = r.identifier(e, "a brake or clutch of a gear");
      const auto it = std::find_if(t.friction_elements.begin(), t.friction_elements.end(),
                                   [&](const FrictionElement& f) { return f.name == element; });
      if (it == t.friction_elements.end()) {
        const std::string names = element_names(t);
        r.fail(e, names.empty() ? fmt::format("gear '{}' names '{}', but the model has no brake or clutch; add "
                                              "[[brake]] and [[clutch]] entries", name, element)
                                : fmt::format("gear '{}' names '{}', which is no brake or clutch of the model; they "
                                              "are {}", name, element, names));
      }
      const int k = static_cast<int>(it - t.friction_elements.begin());
      if (std::find(gear.engaged.begin(), gear.engaged.end(), k) != gear.engaged.end())
        r.fail(e, fmt::format("gear '{}' names '{}' twice", name, element));
      gear.engaged.push_back(k);
    }
    std::sort(gear.engaged.begin(), gear.engaged.end());
    for (const NamedGear& other : gears)
      if (other.engaged == gear.engaged)
        throw InputError(gear.where, fmt::format("gear '{}' engages the same elements as gear '{}' (line {}); give each "
                                                 "gear its own elements", name, other.name, other.where.line));
    gears.push_back(std::move(gear));
  }
  return gears;
}

InitialGear read_initial_gear(const SceneReader& r, const toml::node& value, const std::string& key, const Topology& t) {
  InitialGear gear{{}, "", r.loc(value)};
  if (key == "gear") {
    const std::string name = r.string(value, "gear");
    const auto g = std::find_if(t.gears.begin(), t.gears.end(), [&](const NamedGear& x) { return x.name == name; });
    if (g == t.gears.end()) {
      std::vector<std::string> gears;
      for (const NamedGear& x : t.gears) gears.push_back(x.name);
      r.fail(value, gears.empty() ? fmt::format("gear '{}': the model names no gears ([gears]); name the elements the "
                                                "start engages, e.g. engaged = [\"{}\"]", name,
                                                t.friction_elements.empty() ? std::string("B1") : t.friction_elements.front().name)
                                  : fmt::format("'{}' is not a gear of the model; its gears are {}", name, joined(gears)));
    }
    if (g->engaged.empty()) r.fail(value, fmt::format("gear '{}' engages no brake or clutch; start from given speeds", name));
    gear.engaged = g->engaged;
    gear.name = name;
    return gear;
  }
  const std::vector<std::string> names = r.strings(value, "engaged");
  if (names.empty()) r.fail(value, "engaged = [] names no brake or clutch; name those stuck at t = 0, or leave it out");
  for (const std::string& name : names) {
    const int k = find_friction_element(t, name);
    if (k < 0)
      r.fail(value, fmt::format("engaged names '{}', which is no brake or clutch of the model; they are {}", name,
                                element_names(t)));
    if (std::find(gear.engaged.begin(), gear.engaged.end(), k) != gear.engaged.end())
      r.fail(value, fmt::format("engaged names '{}' twice", name));
    gear.engaged.push_back(k);
  }
  std::sort(gear.engaged.begin(), gear.engaged.end());
  return gear;
}

}  // namespace pogear
