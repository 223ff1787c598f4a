// What the scene reader's parts share: a TomlReader whose quantities may name the model's
// parameters, and the signals of inputs and engagement commands.
#pragma once

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include <toml++/toml.h>

#include "pogear/signals.hpp"
#include "common/quantity.hpp"
#include "read/toml_reader.hpp"
#include "read/scene.hpp"
#include "read/topology.hpp"

namespace pogear {

struct SceneReader : TomlReader {
  const Topology* model = nullptr;
  // The scene's tunables, once read: a quantity of the scene is a number of the generated code, so it
  // may not name one (nor a parameter defined through one), which --param would change without it.
  const std::vector<std::string>* tunable = nullptr;

  std::vector<std::string> strings(const toml::node& n, std::string_view what) const;

  // A quantity with a unit of the given dimension, its parameters the model's; bare numbers are SI,
  // except for speeds and torques, which need a unit.
  double quantity(const toml::node& n, const Dimension& dim, std::string_view what) const;
  // The same for a gain or a load coefficient (`example_unit` shows one): it needs a unit, and Hz is
  // refused, which per speed could mean per rev/s or per rad/s.
  double coefficient(const toml::node& n, const Dimension& dim, std::string_view what, std::string_view example_unit) const;
  // A frequency in Hz (cycles per second): angle units are refused, which would make it an angular
  // speed read as cycles, 2 pi off.
  double frequency_hz(const toml::node& n, std::string_view what) const;

 private:
  // The quantity, checked: its dimension when it has a unit, finite.
  Quantity evaluated(const toml::node& n, const Dimension& dim, std::string_view what) const;
  // The same, and no Hz in a speed.
  Quantity checked_quantity(const toml::node& n, const Dimension& dim, std::string_view what) const;
};

// Refuses `name` at `where` as no brake or clutch of the model, listing those it has, then why the
// scene names one (`purpose`).
[[noreturn]] void fail_no_friction_element(const SceneReader& r, const toml::node& where, std::string_view name,
                                           std::string_view purpose);

// The tunable that parameter `name` is or is defined through (directly or through other
// parameters), or "". The model's evaluation has ruled out cycles.
std::string tunable_behind(const Topology& t, const std::vector<std::string>& tunable, const std::string& name);

// What a signal of the scene is: an input torque, a dimensionless engagement command or an engine's
// throttle (piecewise linear), a controller's speed set-point, or a road's grade.
enum class SignalQuantity { torque, engagement, speed, angle, throttle };

// A signal; a table's file is found relative to `scene_dir`.
rt::Signal read_signal(const SceneReader& r, const toml::node& n, const std::filesystem::path& scene_dir,
                       SignalQuantity what = SignalQuantity::torque);

// Adds a parameter a scene table defines (`table` names it in messages), its text the SI value with
// its unit, refused when the model has one of that name or the value leaves pogear's range.
void add_scene_parameter(const SceneReader& r, const toml::node& where, std::string_view table, Topology& t,
                         const std::string& name, double value, const Dimension& dim, const std::string& unit);

}  // namespace pogear
