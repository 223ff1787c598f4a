// Reads scene files. Every name a scene uses is checked against its model here, so the later
// stages can assume a consistent scene.
#include "read/scene.hpp"

#include <algorithm>
#include <cerrno>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <set>
#include <sstream>

#include <fmt/format.h>
#include <sys/stat.h>
#include <toml++/toml.h>

#include "pogear/run_limits.hpp"
#include "common/cpp_text.hpp"
#include "pogear/signal_table.hpp"
#include "read/model_parameters.hpp"
#include "names/model_variables.hpp"
#include "read/effects.hpp"
#include "read/gear_table.hpp"
#include "read/loads_and_controllers.hpp"
#include "read/driveline_table.hpp"
#include "read/vehicle_table.hpp"
#include "read/scene_reader.hpp"
#include "read/signal_start.hpp"
#include "read/actuator_table.hpp"
#include "read/thermal_table.hpp"
#include "read/simulation_table.hpp"
#include "read/friction_curve.hpp"
#include "read/slip_control.hpp"
#include "read/toml_reader.hpp"
#include "read/tooth_counts.hpp"

namespace pogear {
namespace {

namespace fs = std::filesystem;

// Tunable parameters become variables of the generated C++, beside the states, inputs and the
// functions' own arguments; these names would not compile there.
bool clashes_with_generated_code(const std::string& name, const Scene& s) {
  static const std::set<std::string> arguments{"p", "x", "u", "dx", "y", "M", "N"};  // of rhs, outputs, matrices
  return is_cpp_reserved(name) || arguments.count(name) || find_variable(s.model, name).has_value() ||
         find_scene_variable(s, name, {VariableKind::controller_torque, VariableKind::controller_integral,
                                       VariableKind::controller_error, VariableKind::set_point})
             .has_value();
}

// The scene's [parameters] replace the model's texts, and every parameter is evaluated again (a
// parameter defined through an overridden one follows it).
void apply_overrides(const SceneReader& r, const toml::node& n, Topology& t) {
  if (!n.is_table()) r.fail(n, "[parameters] must be a table");
  for (const auto& [key, value] : *n.as_table()) {
    const std::string name(key.str());
    const auto p = std::find_if(t.parameters.begin(), t.parameters.end(), [&](const Parameter& q) { return q.name == name; });
    if (p == t.parameters.end())
      throw InputError(toml_location(r.file, key.source()), fmt::format("'{}' is not a parameter of the model {}", name, t.name));
    p->where = r.loc(value);
    p->column_offset = 1;
    if (value.is_string()) {
      p->text = *value.value<std::string>();
    } else if (value.is_integer() || value.is_floating_point()) {
      if (!std::isfinite(*value.value<double>())) r.fail(value, fmt::format("parameter '{}' is not finite", name));
      p->text = fmt::format("{}", *value.value<double>());
      p->column_offset = 0;
    } else {
      r.fail(value, "a parameter override is a number (SI) or a string such as \"2000*Newton/mm\"");
    }
  }
  evaluate_parameters(t.parameters);
  // An override of 0 for an inertia or a length for a stiffness would reach the algebra as a
  // singular matrix; it is the scene's mistake, and the location is the override's.
  check_parameter_roles(t);
  check_centre_distances(t);
}

// What loads and controllers cannot be combined with (yet), each refused at the line that asks for it.
void check_loads_and_controllers(const Scene& s) {
  if (s.loads.empty() && s.controllers.empty()) return;
  // A slip controller's gains and limits are its element's capacity times the scene's per-unit
  // values, folded into the controller's law at the scene's capacity.
  for (const ControllerSpec& c : s.controllers) {
    if (c.supplies < 0) continue;
    const FrictionElement& f = s.model.friction_elements[static_cast<std::size_t>(c.supplies)];
    if (const std::string t = tunable_behind(s.model, s.tunable, f.capacity_parameter); !t.empty())
      throw InputError(s.tunable_where,
                       fmt::format("the capacity of {} ({}) depends on tunable '{}', and {}'s slip controller takes its "
                                   "gains and limits at the scene's capacity; drop '{}' from tunable, or set it in "
                                   "[parameters] and generate one simulator per value",
                                   f.name, f.capacity_parameter, t, f.name, t));
  }
  // A computed start would need the controllers' torques at t = 0, which their states give.
  if (s.start != Start::given && !s.controllers.empty()) {
    const bool speed = std::any_of(s.controllers.begin(), s.controllers.end(), [](const ControllerSpec& c) { return c.supplies < 0; });
    const std::string sections = !speed ? "[slip_control]" : has_slip_control(s) ? "[controllers] and [slip_control]" : "[controllers]";
    if (!s.initial_engaged.empty())
      throw InputError(s.start_where, fmt::format("a start in a gear is not available with {}; give every initial speed "
                                                  "in [initial] instead of the gear", sections));
    throw InputError(s.start_where, fmt::format("start = \"rigid\" and \"steady\" are not available with {}; give the "
                                                "initial speeds in [initial]", sections));
  }
  if (s.start == Start::steady && has_quadratic_load(s))
    throw InputError(s.start_where, "start = \"steady\" solves a linear equilibrium, which a quadratic load does not "
                                    "have; start from given speeds, or with start = \"rigid\"");
}

// The scene's solver, or dopri5 for a nonlinear scene that names none, refused (rt::solver_refusal)
// at the line that asks for it. Some solver runs every scene: dopri5 runs them all.
void check_solver(Scene& s, bool engaged) {
  const auto curved = [&](const EngagementSpec& e) {
    return engages(s, e.element) && varies_with_slip(s.model.friction_elements[static_cast<std::size_t>(e.element)]);
  };
  const rt::SystemTraits traits{.nonlinear = nonlinear(s),
                                .engages_friction = engaged,
                                .limits_torque = std::any_of(s.controllers.begin(), s.controllers.end(),
                                                             [](const ControllerSpec& c) { return c.limited(); }),
                                .driveline = s.engine || s.converter,
                                .slip_control = has_slip_control(s),
                                .friction_curve = std::any_of(s.engagement.begin(), s.engagement.end(), curved),
                                .actuator_lag = std::any_of(s.actuators.begin(), s.actuators.end(),
                                                            [](const ActuatorSpec& a) { return a.time_constant > 0; })};
  const std::vector<Solver> admissible = rt::admissible_solvers(traits);
  if ((traits.nonlinear || traits.slip_control || traits.friction_curve || traits.actuator_lag) && !s.solver_given)
    s.solver = Solver::dopri5;
  if (const auto refusal = rt::solver_refusal(s.solver, traits)) {
    // A quadratic load can be made linear; an engine's or a converter's torques cannot.
    const bool load = refusal->cause == rt::solver_refusal(Solver::exact, {.nonlinear = true})->cause;
    throw InputError(s.solver_where, fmt::format("{}; use solver = {}{}", rt::describe(*refusal),
                                                 rt::solver_alternatives(admissible, true), load ? ", or a linear load" : ""));
  }
}

}  // namespace

bool has_quadratic_load(const Scene& scene) {
  return std::any_of(scene.loads.begin(), scene.loads.end(), [](const LoadSpec& l) { return l.quadratic != 0; });
}

bool nonlinear(const Scene& scene) { return scene.engine || scene.converter || has_quadratic_load(scene); }

bool identically_zero(const rt::Signal& signal) {
  struct Zero {
    bool operator()(const rt::Constant& c) const { return c.v == 0; }
    bool operator()(const rt::Step& s) const { return s.after == 0 && s.before == 0; }
    bool operator()(const rt::Ramp& r) const { return r.slope == 0 && r.initial == 0; }
    bool operator()(const rt::Sine& s) const {
      return (s.amplitude == 0 || s.frequency_hz == 0) && s.offset == 0 && (s.amplitude == 0 || std::sin(s.phase_rad) == 0);
    }
    bool operator()(const rt::Table& t) const {
      return std::all_of(t.v.begin(), t.v.end(), [](double v) { return v == 0; });
    }
    bool operator()(const rt::GradeLoad& g) const { return g.sine == 0 && g.cosine == 0; }
  };
  return std::visit(Zero{}, signal);
}

Solver parse_solver(const std::string& name, const SourceLocation& where) {
  if (const std::optional<Solver> solver = rt::parse_solver(name)) return *solver;
  throw InputError(where, fmt::format("unknown solver '{}'; the solvers are {}", name, rt::solver_names(", ")));
}

Scene parse_scene_text(const std::string& text, const std::string& path) {
  SceneReader r{{path}};
  const toml::table root = parse_toml_document(
      text, path, max_model_file_bytes,
      fmt::format("the scene file is larger than {} bytes; a model or scene file is a few kilobytes",
                  max_model_file_bytes));
  r.only_keys(root, {"name", "model", "effects", "keep", "compare_rigid", "tunable", "outputs", "inputs", "initial",
                     "parameters", "simulation", "engagement", "speed_unit", "loads", "controllers", "vehicle", "engine",
                     "converter", "thermal", "actuators", "slip_control"},
              "the scene file");
  Scene s;
  s.file = path;
  s.digest = text_digest(text);
  s.name = fs::path(path).stem().string();
  if (const toml::node* n = root.get("name")) s.name = r.string(*n, "name");
  const SourceLocation name_where = root.get("name") ? r.loc(*root.get("name")) : SourceLocation{path, 0, 0};
  if (!is_name(s.name))
    throw InputError(name_where, fmt::format("scene name '{}' must be letters, digits and '_' (it names C++ code and files)", s.name));
  if (s.name.size() > max_name_length)
    throw InputError(name_where, fmt::format("the scene name is {} characters long; names have at most {}", s.name.size(), max_name_length));
  // The generated code lives in namespace pogear_generated::<name>.
  if (is_cpp_reserved(s.name))
    throw InputError(name_where, fmt::format("scene name '{}' is a C++ keyword or macro, which cannot name the generated "
                                             "code; choose another name", s.name));

  const toml::node* model = root.get("model");
  if (!model) throw InputError(SourceLocation{path, 0, 0}, "the scene names no model; add model = \"path/to/model.toml\"");
  const fs::path scene_dir = fs::path(path).parent_path();
  const std::string model_name = r.string(*model, "model");
  s.model_ref = model_name;
  // The path is quoted in a comment of the generated code, which a line break would end.
  if (std::any_of(model_name.begin(), model_name.end(), [](char c) { return c == '\n' || c == '\r'; }))
    r.fail(*model, "the model path contains a line break; give the path of the model file");
  if (model_name.empty()) r.fail(*model, "the model path is empty; give the path of the model file, e.g. model = \"gear.toml\"");
  // TOML strings may hold \u0000; the system would read the path only up to it.
  if (model_name.find('\0') != std::string::npos)
    r.fail(*model, "the model path contains a NUL character; give the path of the model file");
  s.model_file = (fs::path(model_name).is_absolute() ? fs::path(model_name) : scene_dir / model_name).lexically_normal().string();
  if (struct stat st {}; ::stat(s.model_file.c_str(), &st) != 0) {
    if (errno == ENOENT || errno == ENOTDIR)
      r.fail(*model, fmt::format("model file '{}' does not exist; give its path relative to the scene file", s.model_file));
    r.fail(*model, fmt::format("model file '{}' cannot be opened ({}); check the path and its links", s.model_file,
                               std::strerror(errno)));
  }
  s.model = parse_topology(s.model_file);
  const Topology& topology = s.model;
  r.model = &topology;
  // Before anything that evaluates a quantity: [initial] and [inputs] may name parameters.
  if (const toml::node* n = root.get("parameters")) apply_overrides(r, *n, s.model);

  // The tunables before any other quantity of the scene: one that names a tunable is a number of the
  // generated code and is refused (SceneReader::evaluated). Their names are checked below, once the
  // scene's own parameters (a lock-up clutch's capacity) and variables are known.
  const toml::node* tunable_node = root.get("tunable");
  if (tunable_node) {
    s.tunable = r.strings(*tunable_node, "tunable");
    s.tunable_where = r.loc(*tunable_node);
    r.tunable = &s.tunable;
  }

  // Before the effects, which ask for the compliance of its half-shafts.
  if (const toml::node* n = root.get("vehicle")) read_vehicle(r, *n, scene_dir, s);
  // Before [engagement], which may command the converter's lock-up clutch.
  if (const toml::node* n = root.get("engine")) read_engine(r, *n, scene_dir, s);
  if (const toml::node* n = root.get("converter")) read_converter(r, *n, s);
  if (const toml::node* n = root.get("effects")) s.effects = read_effects(r, *n, topology);
  // Before the tunables, whose names must not be the controllers' variables.
  if (const toml::node* n = root.get("loads")) {
    s.loads = read_loads(r, *n);
    s.loads_where = r.loc(*n);
  }
  if (s.vehicle) add_road_load(s);

  if (const toml::node* n = root.get("controllers")) {
    s.controllers = read_controllers(r, *n, scene_dir, s.model);
    s.controllers_where = r.loc(*n);
  }
  if (const toml::node* n = root.get("keep")) {
    s.keep = r.strings(*n, "keep");
    s.keep_where = r.loc(*n);
    for (const auto& k : s.keep) {
      if (const std::string why = fixed_body_refusal(topology, k, "keep"); !why.empty()) r.fail(*n, why);
      if (find_body(topology, k) < 0) r.fail(*n, fmt::format("keep names '{}', which is not a body of the model", k));
    }
  } else {
    s.keep_where = SourceLocation{path, 0, 0};
  }
  if (const toml::node* n = root.get("speed_unit")) {
    const std::string unit = r.string(*n, "speed_unit");
    if (unit != "rpm" && unit != "rad/s") r.fail(*n, "speed_unit is \"rad/s\" (the default) or \"rpm\"");
    s.speeds_in_rpm = unit == "rpm";
  }
  if (const toml::node* n = root.get("compare_rigid")) {
    if (!n->is_boolean()) r.fail(*n, "compare_rigid must be true or false");
    s.compare_rigid = **n->as_boolean();
    if (s.compare_rigid && !s.effects.elastic())
      r.fail(*n, fmt::format("compare_rigid compares the elastic model with the rigid one, but this scene is already rigid "
                             "(no {0}); drop compare_rigid or add {0}",
                             toothed_mesh_count(topology) > 0 ? "mesh_compliance" : "shaft_compliance"));
  }

  std::set<std::string> parameter_names;
  for (const auto& p : topology.parameters) parameter_names.insert(p.name);
  if (const toml::node* n = tunable_node) {
    std::set<std::string> seen;
    for (const auto& name : s.tunable) {
      if (!parameter_names.count(name)) r.fail(*n, fmt::format("tunable '{}' is not a parameter of the model", name));
      if (!seen.insert(name).second) r.fail(*n, fmt::format("tunable '{}' is listed twice", name));
      if (clashes_with_generated_code(name, s))
        r.fail(*n, fmt::format("tunable '{}' cannot be a variable of the generated C++ (a keyword, a macro or a name "
                               "the code uses itself); rename the parameter in the model", name));
    }
  }

  if (const toml::node* n = root.get("inputs")) {
    if (!n->is_table()) r.fail(*n, "[inputs] must be a table of tau_<body> = signal");
    for (const auto& [key, value] : *n->as_table()) {
      const std::string name(key.str());
      const auto tau = find_variable(topology, name, {VariableKind::torque});
      if (const std::string why = fixed_variable_refusal(topology, name); !why.empty())
        throw InputError(toml_location(path, key.source()), why);
      if (!tau)
        throw InputError(toml_location(path, key.source()),
                         fmt::format("input '{}' names no body; inputs are tau_<body>, e.g. tau_{}", name,
                                     topology.bodies.front().name));
      const rt::Signal signal = read_signal(r, value, scene_dir);
      s.inputs.push_back(InputSpec{tau->index, signal, r.loc(value), read_signal_start(r, value, signal, scene_dir, SignalQuantity::torque)});
    }
    // Inputs in body order, the order of the model's tau vector.
    std::sort(s.inputs.begin(), s.inputs.end(), [](const InputSpec& a, const InputSpec& b) { return a.body < b.body; });
  }

  if (const toml::node* n = root.get("engagement")) {
    if (!n->is_table()) r.fail(*n, "[engagement] must be a table of <element> = command");
    if (topology.friction_elements.empty())
      r.fail(*n, fmt::format("[engagement] commands brakes and clutches, but the model {} has none; add [[brake]] or "
                             "[[clutch]] to the model, or drop [engagement]", topology.name));
    for (const auto& [key, value] : *n->as_table()) {
      const std::string name(key.str());
      const int k = find_friction_element(topology, name);
      if (k < 0) {
        std::string names;
        for (const auto& e : topology.friction_elements) names += (names.empty() ? "" : ", ") + e.name;
        throw InputError(toml_location(path, key.source()),
                         fmt::format("'{}' is not a brake or clutch of the model; its elements are {}", name, names));
      }
      const rt::Signal command = read_signal(r, value, scene_dir, SignalQuantity::engagement);
      s.engagement.push_back(EngagementSpec{k, command, r.loc(value), read_signal_start(r, value, command, scene_dir, SignalQuantity::engagement)});
    }
    std::sort(s.engagement.begin(), s.engagement.end(),
              [](const EngagementSpec& a, const EngagementSpec& b) { return a.element < b.element; });
  }
  if (const toml::node* n = root.get("thermal")) s.thermal = read_thermal(r, *n);
  if (const toml::node* n = root.get("actuators")) s.actuators = read_actuators(r, *n);
  if (const toml::node* n = root.get("slip_control")) read_slip_control(r, *n, scene_dir, s);

  if (const toml::node* n = root.get("initial")) {
    if (!n->is_table()) r.fail(*n, "[initial] must be a table of omega_<body> and F_<mesh> values");
    s.initial_where = r.loc(*n);
    bool start_given = false;
    for (const auto& [key, value] : *n->as_table()) {
      const std::string name(key.str());
      if (name == "start") {
        const std::string start = r.string(value, "start");
        s.start_where = r.loc(value);
        if (start == "rigid") s.start = Start::rigid;
        else if (start == "steady") s.start = Start::steady;
        else if (start == "given") s.start = Start::given;
        else r.fail(value, fmt::format("start \"{}\" is not known; write \"given\" (the default), \"rigid\" or \"steady\"", start));
        start_given = true;
        continue;
      }
      if (name == "gear" || name == "engaged") {
        if (!s.initial_engaged.empty())
          r.fail(value, "[initial] names the gear it starts in once: gear = \"1\" or engaged = [\"A\", \"D\"], not both");
        InitialGear gear = read_initial_gear(r, value, name, topology);
        s.initial_engaged = std::move(gear.engaged);
        s.initial_gear = std::move(gear.name);
        s.initial_engaged_where = gear.where;
        continue;
      }
      const auto v = find_scene_variable(s, name, {VariableKind::velocity, VariableKind::force, VariableKind::controller_torque});
      if (const std::string why = fixed_variable_refusal(topology, name); !why.empty())
        throw InputError(toml_location(path, key.source()), why);
      if (!v)
        throw InputError(toml_location(path, key.source()),
                         has_shafts(topology)
                             ? fmt::format("'{}' is none of omega_<body>, F_<mesh>, T_<shaft> and Tc_<controller> of the "
                                           "scene; name a body's speed, a mesh's force, a shaft's torque or a "
                                           "controller's start torque", name)
                             : fmt::format("'{}' is neither omega_<body>, F_<mesh> nor Tc_<controller> of the scene; "
                                           "name a body's speed, a mesh's force or a controller's start torque", name));
      if (v->kind == VariableKind::controller_torque) {
        // The controller starts at this torque through its integral's initial value.
        const ControllerSpec& c = s.controllers[static_cast<std::size_t>(v->index)];
        if (c.ki == 0)
          r.fail(value, fmt::format("controller '{}' has no integral (ki = 0) to start at a given torque; its torque at "
                                    "t = 0 is kp times the speed error: drop {}", c.name, name));
        s.initial[*v] = r.quantity(value, torque_dimension(), name);
        // A limited controller's torque never leaves its limits; a start outside them would be
        // clamped at the first step, which is not the start asked for.
        const double start = s.initial[*v];
        if (start > c.torque_max || start < c.torque_min)
          r.fail(value, fmt::format("{} = {} N m is {} controller '{}''s {}, {} N m; give a start torque within its limits",
                                    name, start, start > c.torque_max ? "above" : "below", c.name,
                                    start > c.torque_max ? "torque_max" : "torque_min",
                                    start > c.torque_max ? c.torque_max : c.torque_min));
      } else if (v->kind == VariableKind::velocity) {
        s.initial[*v] = r.quantity(value, angular_velocity_dimension(), name);
      } else {
        const bool shaft = topology.meshes[static_cast<std::size_t>(v->index)].shaft;
        if (!s.effects.elastic())
          throw InputError(toml_location(path, key.source()),
                           fmt::format("initial {} '{}' needs {}: the rigid model has no force states",
                                       shaft ? "shaft torque" : "force", name, shaft ? "shaft_compliance" : "mesh_compliance"));
        s.initial[*v] = r.quantity(value, shaft ? torque_dimension() : force_dimension(), name);
      }
    }
    // A start in a gear is on the gear's rigid model, at the named speeds unless at equilibrium.
    if (!s.initial_engaged.empty() && !start_given) {
      s.start = Start::rigid;
      s.start_where = s.initial_engaged_where;
    } else if (!s.initial_engaged.empty() && s.start == Start::given) {
      r.fail(*n->as_table()->get("start"), "a start in a gear is \"rigid\" (the default: at the named speeds, with "
                                           "eq. (8)'s forces and torques) or \"steady\"; remove start, or write \"steady\"");
    }
  }

  if (const toml::node* n = root.get("outputs")) {
    s.outputs_where = r.loc(*n);
    const std::vector<std::string> listed = r.strings(*n, "outputs");
    // No outputs at all is what leaving the key out gives (every speed and force), not none.
    if (listed.empty())
      r.fail(*n, "outputs = [] names no output; name the speeds and forces to write, or leave outputs out for all of "
                 "them");
    for (const auto& o : listed) {
      const auto v = find_scene_variable(s, o, {VariableKind::velocity, VariableKind::force, VariableKind::spring_force,
                                                VariableKind::controller_torque, VariableKind::vehicle_speed,
                                                VariableKind::vehicle_acceleration, VariableKind::vehicle_jerk,
                                                VariableKind::engine_torque, VariableKind::pump_torque,
                                                VariableKind::turbine_torque});
      if (const std::string why = fixed_variable_refusal(topology, o); !why.empty()) r.fail(*n, why);
      if (!v)
        r.fail(*n, fmt::format("output '{}' is none of omega_<body>, F_<mesh>, Fspring_<mesh>, {}Tc_<controller>", o,
                               has_shafts(topology) ? "T_<shaft>, Tspring_<shaft>, " : ""));
      if (std::find(s.outputs.begin(), s.outputs.end(), *v) != s.outputs.end())
        r.fail(*n, fmt::format("output '{}' is listed twice", o));
      const bool shaft = (v->kind == VariableKind::force || v->kind == VariableKind::spring_force) &&
                         topology.meshes[static_cast<std::size_t>(v->index)].shaft;
      if ((v->kind == VariableKind::force || v->kind == VariableKind::spring_force) && !s.effects.mesh_forces)
        r.fail(*n, fmt::format("output '{}' is a {}, but the scene does not ask for mesh_forces; add it to effects", o,
                               shaft ? "shaft torque" : "mesh force"));
      if (v->kind == VariableKind::spring_force && !s.effects.elastic())
        r.fail(*n, fmt::format("output '{}' is the spring's {} alone, which only a compliant {} has; add {} to effects, "
                               "or ask for {}, what the rigid {} transmits",
                               o, shaft ? "torque" : "force", shaft ? "shaft" : "mesh",
                               shaft ? "shaft_compliance" : "mesh_compliance",
                               variable_name(topology, {VariableKind::force, v->index}), shaft ? "shaft" : "mesh"));
      s.outputs.push_back(*v);
    }
  }

  if (const toml::node* n = root.get("simulation")) read_simulation(r, *n, s);
  const bool engaged = std::any_of(s.engagement.begin(), s.engagement.end(), [&](const EngagementSpec& e) { return engages(s, e.element); });
  check_slip_control(s);
  check_loads_and_controllers(s);
  check_signal_starts(s);
  check_thermal(s);
  check_actuators(s);
  check_driveline(s);
  check_solver(s, engaged);
  check_vehicle_jerk(s);
  for (const EngagementSpec& e : s.engagement) {
    // A capacity may follow a tunable (FrictionRun::tuned_capacity); a static ratio may not.
    const FrictionElement& f = topology.friction_elements[static_cast<std::size_t>(e.element)];
    for (const std::string& name : referenced_names(f.static_ratio))
      if (const std::string t = tunable_behind(topology, s.tunable, name); !t.empty())
        throw InputError(s.tunable_where,
                         fmt::format("the static_ratio of {} ({}) depends on tunable '{}', and a simulation takes "
                                     "static ratios at the scene's value; drop '{}' from tunable",
                                     f.name, f.static_ratio, t, t));
  }
  // A command is piecewise linear: its extremes over the run are at 0, the horizon and its breakpoints.
  // A triggered command's times count from its event, and its `before` is a command as well.
  for (const EngagementSpec& e : s.engagement)
    for (const rt::Signal* command : {&e.command, e.start && e.start->before ? &*e.start->before : nullptr}) {
      if (!command) continue;
      std::vector<double> times = rt::breakpoints(*command, 0.0, s.horizon);
      times.push_back(0.0);
      times.push_back(s.horizon);
      for (double t : times)
        for (double p : {rt::value(*command, t), rt::value(*command, std::nextafter(t, 0.0))})
          if (!(p >= 0 && p <= 1))
            throw InputError(e.where, fmt::format("the command of {} is {} at {}; an engagement command is from 0 "
                                                  "(open) to 1 (fully engaged) over the whole run",
                                                  topology.friction_elements[static_cast<std::size_t>(e.element)].name,
                                                  p, e.start && command == &e.command ? fmt::format("{} s after its start", t)
                                                                                      : fmt::format("t = {} s", t)));
    }
  return s;
}

Scene parse_scene(const std::string& path) {
  return parse_scene_text(read_input_file(path, max_model_file_bytes, "scene file"), path);
}

}  // namespace pogear
