// See vibration_analysis.hpp. Errors of the command line are located at the scene file, as the
// other commands' option errors are (`pogear derive --keep`).
#include "vibrate/vibration_analysis.hpp"

#include <algorithm>
#include <cmath>
#include <numbers>
#include <sstream>

#include <fmt/format.h>

#include "derive/engagement.hpp"
#include "read/loads_and_controllers.hpp"
#include "read/model_parameters.hpp"
#include "common/output_file.hpp"
#include "specialize/parameter_folding.hpp"
#include "common/printer.hpp"
#include "common/quantity.hpp"
#include "read/scene.hpp"
#include "read/toml_reader.hpp"

namespace pogear {

bool is_scene_file(const std::string& path) {
  const std::string text = read_input_file(path, max_model_file_bytes, "file");
  const toml::table root = parse_toml_document(text, path, max_model_file_bytes, "the file is larger than 1 MB");
  return root.contains("model");
}

namespace {

// What the modes of a file are computed from: the derivation, the parameter values (the scene's),
// which damping they include, and the engaged elements.
struct ModesInput {
  Derivation d;
  GiNaC::exmap values;
  std::string damping;
  std::vector<int> engaged;
  std::vector<std::string> open_in_scene;  // the scene's brakes and clutches left open (no --engaged)
};

// The brakes and clutches a scene commands, when no --engaged says which of them to hold: the
// modes and responses are then of the gear with all of them open.
std::vector<std::string> scene_elements_left_open(const Scene& scene, bool engaged_given) {
  std::vector<std::string> names;
  if (engaged_given) return names;
  for (const EngagementSpec& e : scene.engagement)
    names.push_back(scene.model.friction_elements[static_cast<std::size_t>(e.element)].name);
  return names;
}

ModesInput modes_input(const std::string& path, const std::optional<std::string>& engaged) {
  const SourceLocation where{path, 0, 0};
  auto stuck = [&](const Topology& t) {
    return engaged ? parse_engaged(t, *engaged, where) : std::vector<int>{};
  };
  if (!is_scene_file(path)) {
    Derivation d = derive_model(path, std::nullopt, where);
    GiNaC::exmap values = d.values;
    std::vector<int> e = stuck(d.topology);
    const std::string damping = !has_shafts(d.topology)           ? "mesh damping"
                                : toothed_mesh_count(d.topology) == 0 ? "shaft damping"
                                                                      : "mesh and shaft damping";
    return {std::move(d), std::move(values), damping + " and bearing friction, as the model defines them", std::move(e), {}};
  }
  const Scene scene = parse_scene(path);
  if (!scene.effects.elastic())
    throw InputError(where, fmt::format("the scene simulates the rigid model (no {0} in its effects), which has no "
                                        "elastic modes; add {0} to its effects, or give the model file",
                                        toothed_mesh_count(scene.model) > 0 ? "mesh_compliance" : "shaft_compliance"));
  std::optional<std::vector<std::string>> keep;
  if (!scene.keep.empty()) keep = scene.keep;
  Derivation d = derive_topology(scene.model, keep, scene.keep_where, false);
  std::vector<std::string> damping;
  if (scene.effects.mesh_damping) damping.push_back("mesh damping");
  if (scene.effects.shaft_damping) damping.push_back("shaft damping");
  if (scene.effects.bearing_friction) damping.push_back("bearing friction");
  const std::string which = damping.empty() ? std::string("none (the scene's effects have no damping)")
                            : damping.size() == 1
                                ? damping[0] + ", as the scene calls for"
                                : joined(std::vector<std::string>(damping.begin(), damping.end() - 1), ", ") + " and " +
                                      damping.back() + ", as the scene calls for";
  GiNaC::exmap values = scene_values(scene, d).numbers;
  std::vector<int> e = stuck(d.topology);
  return {std::move(d), std::move(values), which, std::move(e), scene_elements_left_open(scene, engaged.has_value())};
}

// An input speed from the command line in rpm: a quantity with a unit of angular velocity, above 0
// (it may name the model's parameters, as a scene's quantities do).
double input_speed_rpm(const std::string& text, const Topology& t, const SourceLocation& where) {
  Quantity q;
  try {
    q = evaluate_quantity(text, parameter_quantities(t), where, 0);
  } catch (const InputError& e) {
    throw InputError(where, fmt::format("--to '{}': {}", text, e.message()));
  }
  if (!q.has_unit || q.dimension != angular_velocity_dimension())
    throw InputError(where, fmt::format("--to '{}' is not a speed; give it with its unit, e.g. --to 6000*rpm", text));
  // Hz is 1/s, which as a speed would be read as rad/s: 2 pi short of the revolutions it usually means.
  if (text.find("Hz") != std::string::npos)
    throw InputError(where, fmt::format("--to '{}' is in Hz, which for a speed could mean rev/s or rad/s; give it in "
                                        "rpm or rad/s, e.g. --to 6000*rpm", text));
  // Divided by the evaluator's own rpm, so that --to 8000*rpm is 8000 exactly.
  const double rpm = q.si / evaluate_quantity("rpm", {}, where, 0).si;
  constexpr double most = 1e8;  // far above any gear (turbines run at 1e5 rpm)
  if (!(rpm > 0) || !(rpm <= most))
    throw InputError(where, fmt::format("--to '{}' is not a speed from 0 to {:g} rpm; the diagram runs from 0 to it",
                                        text, most));
  return rpm;
}

}  // namespace

VibrationModes modes_of_file(const std::string& path, const std::optional<std::string>& engaged) {
  try {
    const ModesInput in = modes_input(path, engaged);
    VibrationModes out = vibration_modes(in.d, in.values, in.damping, in.engaged);
    out.open_in_scene = in.open_in_scene;
    return out;
  } catch (const std::domain_error& e) {
    throw InputError(SourceLocation{path, 0, 0}, e.what());
  }
}

ModesWithCampbell campbell_of_file(const std::string& path, const std::optional<std::string>& engaged,
                                   const CampbellRequest& request) {
  const SourceLocation where{path, 0, 0};
  try {
    const ModesInput in = modes_input(path, engaged);
    const Topology& t = in.d.topology;
    auto body = [&](const std::string& name, const std::string& option) {
      const int b = find_body(t, name);
      if (const std::string why = fixed_body_refusal(t, name, option); !why.empty()) throw InputError(where, why);
      if (b < 0) {
        std::vector<std::string> names;
        for (const Body& x : t.bodies) names.push_back(x.name);
        throw InputError(where, fmt::format("{} '{}' is not a body of the model; the bodies are {}", option, name, joined(names)));
      }
      return b;
    };
    const int input = body(request.input, "--input");
    std::vector<int> held;
    if (request.hold) {
      std::stringstream list(*request.hold);
      std::string name;
      while (std::getline(list, name, ',')) {
        if (name.empty()) throw InputError(where, "--hold has an empty name; give bodies separated by single commas, e.g. --hold r,s");
        const int b = body(name, "--hold");
        if (std::find(held.begin(), held.end(), b) != held.end())
          throw InputError(where, fmt::format("--hold names '{}' twice; name each body once", name));
        held.push_back(b);
      }
      if (held.empty() || request.hold->back() == ',')
        throw InputError(where, "--hold has an empty name; give bodies separated by single commas, e.g. --hold r,s");
    }
    if (request.harmonics < 1 || request.harmonics > max_harmonics)
      throw InputError(where, fmt::format("--harmonics {} is not from 1 to {}", request.harmonics, max_harmonics));
    const double max_rpm = request.to ? input_speed_rpm(*request.to, t, where) : 0.0;
    ModesWithCampbell out;
    out.modes = vibration_modes(in.d, in.values, in.damping, in.engaged);
    out.modes.open_in_scene = in.open_in_scene;
    // A held body is held: the natural frequencies on the line are the held gear's.
    const VibrationModes held_modes =
        held.empty() ? out.modes : vibration_modes(in.d, in.values, in.damping, in.engaged, held);
    out.campbell = campbell_diagram(in.d, in.values, held_modes, in.engaged, input, held, max_rpm, request.harmonics);
    return out;
  } catch (const std::domain_error& e) {
    throw InputError(where, e.what());
  }
}

namespace {

double frequency(const std::string& text, const std::string& option, const Topology& t, const SourceLocation& where) {
  Quantity q;
  try {
    q = evaluate_quantity(text, parameter_quantities(t), where, 0);
  } catch (const InputError& e) {
    throw InputError(where, fmt::format("{} '{}': {}", option, text, e.message()));
  }
  // Hz, rad/s and rpm are all 1/s, rad being a number; only Hz and kHz count cycles per second.
  if (q.dimension != angular_velocity_dimension() || text.find("Hz") == std::string::npos)
    throw InputError(where, fmt::format("{} '{}' is not a frequency in Hz; give it in Hz or kHz, e.g. {} 10*Hz",
                                        option, text, option));
  if (!(q.si > 0) || !std::isfinite(q.si))
    throw InputError(where, fmt::format("{} '{}' is not a positive frequency; the response is drawn on a logarithmic "
                                        "axis from a frequency above 0", option, text));
  return q.si;
}

}  // namespace

std::string open_elements_warning(const std::vector<std::string>& open, std::string_view what) {
  if (open.empty()) return {};
  std::string names;
  for (const std::string& n : open) names += (names.empty() ? "" : ", ") + n;
  return fmt::format("warning: the scene's brakes and clutches ({}) are open in these {}: they are of the free gear, "
                     "not of a gear the scene engages{}\n",
                     names, what, what == "modes" ? "; give --engaged with the elements that hold, e.g. --engaged " + open.front() : "");
}

SceneResponse response_of(const ResponseRequest& request) {
  const SourceLocation where{request.scene_file, 0, 0};
  if (!is_scene_file(request.scene_file))
    throw InputError(where, "this is a model file; response needs a scene, which says the effects and parameters to "
                            "analyse: write one that names this model (docs/scene-format.md)");
  const Scene scene = parse_scene(request.scene_file);
  // A frequency response is of a linear system: with a quadratic load it would be of the linear
  // part only, the gear linearized at rest, which the scene does not say.
  if (scene.engine || scene.converter)
    throw InputError(where, "the scene is nonlinear (an engine or a converter), and a frequency response is of a linear "
                            "system; analyse a scene of the gear without [engine] and [converter], driven by tau_ inputs");
  if (nonlinear(scene))
    throw InputError(where, "the scene is nonlinear (a quadratic load), and a frequency response is of a linear "
                            "system; drop the load's quadratic part (or linearize it: a linear load of 2 c omega at "
                            "the operating speed omega)");
  if (request.inputs.empty())
    throw InputError(where, "--input names no torque; give one or more, comma-separated, e.g. tau_" +
                                scene.model.bodies.front().name);
  if (request.outputs.empty())
    throw InputError(where, "--output names no variable; give one or more, comma-separated, e.g. omega_" +
                                scene.model.bodies.front().name);
  FrequencyGrid grid;
  grid.from_hz = frequency(request.from, "--from", scene.model, where);
  grid.to_hz = frequency(request.to, "--to", scene.model, where);
  grid.points = request.points;
  if (!(grid.from_hz < grid.to_hz))
    throw InputError(where, fmt::format("the frequency range --from {} --to {} is empty; give --from below --to",
                                        request.from, request.to));
  std::vector<Variable> inputs, outputs;
  for (const std::string& name : request.inputs) {
    const auto v = find_variable(scene.model, name, {VariableKind::torque});
    if (!v) throw InputError(where, fmt::format("--input '{}' is not tau_<body> of the model; give the torque of one "
                                                "of its bodies, e.g. tau_{}", name, scene.model.bodies.front().name));
    if (std::find(inputs.begin(), inputs.end(), *v) == inputs.end()) inputs.push_back(*v);
  }
  for (const std::string& name : request.outputs) {
    const auto v = find_scene_variable(scene, name, {VariableKind::velocity, VariableKind::force, VariableKind::spring_force,
                                                     VariableKind::controller_torque});
    if (!v && has_shafts(scene.model))
      throw InputError(where, fmt::format("--output '{}' is none of omega_<body>, F_<mesh>, T_<shaft> and "
                                          "Tc_<controller> of the scene; give the velocity of a body, the force of a "
                                          "mesh, the torque of a shaft or a controller's torque, e.g. omega_{}",
                                          name, scene.model.bodies.front().name));
    if (!v)
      throw InputError(where, fmt::format("--output '{}' is neither omega_<body>, F_<mesh> nor Tc_<controller> of the "
                                          "scene; give the velocity of a body, the force of a mesh or a controller's "
                                          "torque, e.g. omega_{}",
                                          name, scene.model.bodies.front().name));
    if (std::find(outputs.begin(), outputs.end(), *v) == outputs.end()) outputs.push_back(*v);
  }
  // One CSV per pair, a row of four numbers per frequency, 25 bytes a number at most.
  const double bytes = 100.0 * grid.points * static_cast<double>(inputs.size() * outputs.size());
  if (bytes > static_cast<double>(max_csv_bytes))
    throw InputError(where, fmt::format("the CSV files of this response may take up to {:.3g} GB ({} points for each "
                                        "of {} input-output pairs); the limit is {:.3g} GB: give fewer --points, "
                                        "inputs or outputs",
                                        bytes / 1e9, grid.points, inputs.size() * outputs.size(),
                                        static_cast<double>(max_csv_bytes) / 1e9));
  const std::vector<int> engaged =
      request.engaged ? parse_engaged(scene.model, *request.engaged, where) : std::vector<int>{};
  return SceneResponse{scene.name, frequency_response(scene, inputs, outputs, grid, engaged),
                       scene_elements_left_open(scene, request.engaged.has_value())};
}

}  // namespace pogear
