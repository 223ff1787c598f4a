// The two generated files: the header (provenance, the scene's settings, the parameter table and
// the system structs of codegen_system, Eigen alone) and the main (input signals and runs, with the
// runtime). Every piece is a CppText: user text (names, paths, titles, units) enters only through
// cpp_text's escaping and checking functions, never as a raw string.
#include "codegen/codegen.hpp"

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <map>
#include <stdexcept>
#include <variant>

#include <fmt/format.h>

#include "build_config/build_config.hpp"
#include "codegen/codegen_system.hpp"
#include "common/cpp_text.hpp"
#include "names/symbols.hpp"
#include "specialize/initial_state.hpp"
#include "specialize/element_thermal.hpp"
#include "specialize/torque_limits.hpp"
#include "specialize/triggered_signals.hpp"
#include "pogear/command_line.hpp"
#include "common/printer.hpp"

namespace pogear {
namespace {

CppText effects_list(const Effects& e) {
  std::vector<CppText> on;
  if (e.mesh_compliance) on.push_back(code("mesh_compliance"));
  if (e.shaft_compliance) on.push_back(code("shaft_compliance"));
  if (e.mesh_damping) on.push_back(code("mesh_damping"));
  if (e.shaft_damping) on.push_back(code("shaft_damping"));
  if (e.bearing_friction) on.push_back(code("bearing_friction"));
  if (e.mesh_forces) on.push_back(code("mesh_forces"));
  return on.empty() ? code("none (rigid, frictionless)") : join(on, code(", "));
}

CppText signals_function(const SpecializedSystem& sys, const SymbolTable& symbols, const CppText& name) {
  CppText s = code("// Input signals of {}, in the order of its inputs.\n", name);
  s += code("inline std::vector<pogear::rt::Signal> {}_signals() {{\n  return {{", name);
  bool first = true;
  for (const InputPort& u : sys.inputs) {
    if (!u.signal) continue;  // the inputs with signals come first
    s += (first ? CppText{} : code(",\n          ")) + code("/* {} */ ", comment_text(variable_name(symbols, u.variable))) +
         signal_code(*u.signal);
    first = false;
  }
  s += code("}};\n}}\n");
  return s;
}

// The tunables the elements' capacities read, in the order of the scene's list.
std::vector<std::string> capacity_tunables(const SpecializedScene& model) {
  std::vector<std::string> used;
  for (const std::string& name : model.scene.tunable)
    if (std::any_of(model.friction.begin(), model.friction.end(), [&](const FrictionRun& f) {
          return f.tuned_capacity.has(parameter_symbol(model.derivation.symbols, name));
        }))
      used.push_back(name);
  return used;
}

// The engaged brakes and clutches as the runtime takes them: name, capacity [N m], static ratio,
// command p(t), one-way, and a friction curve where friction varies with slip. A capacity that
// follows a tunable reads it from the system's Params (Elastic's and Rigid's have every tunable).
CppText friction_function(const SpecializedScene& model) {
  const bool curves = std::any_of(model.friction.begin(), model.friction.end(),
                                  [](const FrictionRun& f) { return !f.friction_curve.t.empty(); });
  const bool tuned = has_tuned_capacity(model);
  const auto actuated = [](const FrictionRun& f) { return f.fill_delay > 0 || f.time_constant > 0; };
  const bool actuators = std::any_of(model.friction.begin(), model.friction.end(), actuated);
  const bool held = std::any_of(model.friction.begin(), model.friction.end(), [](const FrictionRun& f) { return f.held_at_start; });
  CppText s = code("// Brakes and clutches engaged by the scene, in the order of the systems' friction torque inputs:\n"
                   "// name, kinetic torque capacity [N m], static / kinetic friction, engagement command p(t), one-way{}{}{}.\n",
                   curves ? code(",\n// friction curve (kinetic torque over capacity against |slip| [rad/s])") : CppText{},
                   actuators || held ? code(",\n// actuator fill delay and lag time constant [s] (tau de/dt = p(t - delay) - e)") : CppText{},
                   held ? code(",\n// held stuck at t = 0 by the start in a gear") : CppText{});
  if (tuned) {
    s += code("// Capacities follow tunable parameters: p is the Params of the system run.\n");
    s += code("template <class Params>\ninline std::vector<pogear::rt::FrictionElementData> friction_elements(const Params& p) {{\n");
    for (const std::string& name : capacity_tunables(model))
      s += code("  const double {} = p.{};\n", identifier(name), identifier(name));
    s += code("  return {{");
  } else {
    s += code("inline std::vector<pogear::rt::FrictionElementData> friction_elements() {{\n  return {{");
  }
  for (std::size_t i = 0; i < model.friction.size(); ++i) {
    const FrictionRun& f = model.friction[i];
    const CppText capacity = GiNaC::is_a<GiNaC::numeric>(f.tuned_capacity) ? number_code(f.capacity)
                                                                            : expression_code(f.tuned_capacity, {});
    // The optional fields in order, each written where a later one is.
    const bool actuator = actuated(f) || f.held_at_start;
    const CppText curve = f.friction_curve.t.empty() ? (actuator ? code(", {{}}") : CppText{})
                                                     : code(", ") + signal_code(f.friction_curve);
    s += (i ? code(",\n          ") : CppText{}) +
         code("{{{}, {}, {}, {}, {}{}{}{}}}", string_literal(f.name), capacity, number_code(f.static_ratio),
              signal_code(f.command), f.one_way ? code("true") : code("false"), curve,
              actuator ? code(", {}, {}", number_code(f.fill_delay), number_code(f.time_constant)) : CppText{},
              f.held_at_start ? code(", true") : CppText{});
  }
  s += code("}};\n}}\n");
  return s;
}

// The elements whose temperature the runs give: element index, heat capacity [J/K], conductance
// [W/K], ambient and initial temperatures [degC].
CppText thermal_function(const std::vector<rt::ElementThermal>& thermal) {
  CppText s = code("// Temperatures of brakes and clutches: element (in friction_elements()), heat capacity [J/K],\n"
                   "// conductance to the ambient [W/K], ambient and initial temperatures [degC].\n");
  s += code("inline std::vector<pogear::rt::ElementThermal> friction_thermal() {{\n  return {{");
  for (std::size_t i = 0; i < thermal.size(); ++i) {
    const rt::ElementThermal& t = thermal[i];
    s += (i ? code(",\n          ") : CppText{}) +
         code("{{{}, {}, {}, {}, {}}}", integer_code(t.element), number_code(t.heat_capacity), number_code(t.conductance),
              number_code(t.ambient), number_code(t.initial));
  }
  s += code("}};\n}}\n");
  return s;
}

// A torque limit as generated code writes it (an absent limit is infinite).
CppText limit_code(double v) {
  if (std::isfinite(v)) return number_code(v);
  return v > 0 ? code("std::numeric_limits<double>::infinity()") : code("-std::numeric_limits<double>::infinity()");
}

// The controllers with torque limits as the runtime takes them (torque_limit_data; their laws come
// from the system's torque_limit_laws).
CppText torque_limits_function(const SpecializedScene& model, const SpecializedSystem& sys, const CppText& name) {
  CppText s = code("// Controllers with torque limits of {}, in the order of its last inputs: name, torque_min and\n"
                   "// torque_max [N m], laws (from torque_limit_laws); a slip controller's brake or clutch, start [s],\n"
                   "// trigger and integral state (-1, 0, -1, -1 for a speed controller).\n", name);
  s += code("inline std::vector<pogear::rt::TorqueLimitData> {}_torque_limits() {{\n  return {{", name);
  const std::vector<rt::TorqueLimitData> limits = torque_limit_data(model, sys, triggered_signals(model, sys));
  for (std::size_t i = 0; i < limits.size(); ++i) {
    const rt::TorqueLimitData& l = limits[i];
    s += (i ? code(",\n          ") : CppText{}) +
         code("{{{}, {}, {}, {{}}, {{}}, {}, {}, {}, {}}}", string_literal(l.name), limit_code(l.torque_min),
              limit_code(l.torque_max), integer_code(l.supplies), number_code(l.starts_at), integer_code(l.started_by),
              integer_code(l.integral));
  }
  s += code("}};\n}}\n");
  return s;
}

// The signals and commands of `sys` that start on an event, as the hybrid engine takes them: input
// or command, its index, the trigger's element (among the friction elements), state and delay [s],
// the name the events file gives its start, its `before`, and a crossing instead of the element.
CppText triggered_function(const std::vector<rt::TriggeredSignal>& triggered, const CppText& name) {
  CppText s = code("// Signals of {} that start on an event: command?, index, trigger's element, state, delay [s], name,\n"
                   "// what the signal is until then (none: the value before its own times), and a crossing instead of\n"
                   "// the element's change of state (the slip of an element or a speed output, the value [rad/s], upward?).\n",
                   name);
  s += code("inline std::vector<pogear::rt::TriggeredSignal> {}_triggered_signals() {{\n  return {{", name);
  for (std::size_t i = 0; i < triggered.size(); ++i) {
    const rt::TriggeredSignal& t = triggered[i];
    const CppText crossing =
        t.crossing ? code(", pogear::rt::CrossingTrigger{{{}, {{}}, {}, {}, {}}}", integer_code(t.crossing->slip_of),
                          string_literal(t.crossing->output), number_code(t.crossing->value),
                          t.crossing->upward ? code("true") : code("false"))
                   : code(", std::nullopt");
    s += (i ? code(",\n          ") : CppText{}) +
         code("{{{}, {}, {}, pogear::rt::ElementState::{}, {}, {}, {}{}}}", t.command ? code("true") : code("false"),
              integer_code(t.index), integer_code(t.element), identifier(rt::state_name(t.state)),
              number_code(t.delay), string_literal(t.name),
              t.before ? code("pogear::rt::Signal{{{}}}", signal_code(*t.before)) : code("std::nullopt"), crossing);
  }
  s += code("}};\n}}\n");
  return s;
}

// Only the file name: generated files must not depend on where pogear was run from.
CppText file_name(const std::string& path) {
  return comment_text(std::filesystem::path(path).filename().string());
}

// `{"J_c", &params.J_c, {{"kg*meters^2", 1.0}, {"kg*m^2", 1.0}}, ">0"}` for set_parameters.
CppText parameter_fields(const SpecializedSystem& sys, const CppText& params) {
  std::vector<CppText> fields;
  for (const auto& p : sys.params) {
    std::vector<CppText> units;
    for (const auto& u : p.units) units.push_back(code("{{{}, {}}}", string_literal(u.unit), number_code(u.si)));
    fields.push_back(code("{{{}, &{}.{}, {{{}}}, {}}}", string_literal(p.name), params, identifier(p.name),
                          join(units, code(", ")), string_literal(p.sign)));
  }
  return join(fields, code(",\n       "));
}

// `namespace parameters { inline constexpr double r_c = 0.148;  // m, "14.8*cm" (model.toml:61) }`:
// a number in the functions below is traced to the parameters it was computed from.
CppText parameters_namespace(const SpecializedScene& model) {
  const std::vector<std::string>& tunable = model.scene.tunable;
  CppText s = code("// The model's parameters in SI, with the scene's overrides, as written and where. The functions\n"
                   "// below have them folded in as numbers, except the tunables, which they read from Params.\n");
  s += code("namespace parameters {{\n");
  for (const ParameterValue& p : model.derivation.parameters) {
    const CppText origin = p.origin == ParameterOrigin::geometry ? code("derived from the geometry")
                           : p.where.line > 0 ? code("\"{}\" ({}:{})", comment_text(p.text), file_name(p.where.file),
                                                  integer_code(p.where.line))
                                              : code("\"{}\"", comment_text(p.text));
    const bool tuned = std::find(tunable.begin(), tunable.end(), p.name) != tunable.end();
    s += code("inline constexpr double {} = {};  // {}, {}{}\n", identifier(p.name), number_code(p.si),
              comment_text(p.unit.empty() ? "SI, no unit written" : p.unit), origin,
              tuned ? code(", tunable (Params::{})", identifier(p.name)) : CppText{});
  }
  return s + code("}}  // namespace parameters\n\n");
}

// What generated this header from what: a header that differs from another in these was made
// from another model or scene text, or by another pogear.
CppText provenance(const SpecializedScene& model) {
  CppText s = code("inline constexpr std::string_view pogear_version = {};\n", string_literal(build_config::version));
  s += code("// Digests (64-bit FNV-1a, hex) of the model's and the scene's file text, as pogear read them.\n");
  s += code("inline constexpr std::string_view model_digest = {};\n", string_literal(model.derivation.topology.digest));
  s += code("inline constexpr std::string_view scene_digest = {};\n\n", string_literal(model.scene.digest));
  return s;
}

GeneratedSources generate(const SpecializedScene& model, const std::vector<rt::Solver>& solvers) {
  const Scene& sc = model.scene;
  const Derivation& d = model.derivation;
  const CppText name = identifier(sc.name);
  const CppText header_name = code("{}.hpp", name), main_name = code("{}_main.cpp", name);
  GeneratedSources g;
  g.header_name = header_name.str();
  g.main_name = main_name.str();
  const bool needs_solve = model.main.implicit || (model.rigid && model.rigid->implicit);

  CppText h;
  h += code("// {}: generated by pogear {} from the scene {}; do not edit.\n", header_name,
            comment_text(build_config::version), file_name(sc.file));
  h += code("// Model: {} ({}, as the scene names it){}\n", comment_text(d.topology.name), comment_text(sc.model_ref),
            d.topology.title.empty() ? CppText{} : code(", {}", comment_text(d.topology.title)));
  std::vector<CppText> inputs;
  for (const InputPort& u : model.main.inputs) inputs.push_back(comment_text(variable_name(d.symbols, u.variable)));
  h += code("// Effects: {}. Inputs: {}.\n", effects_list(sc.effects), inputs.empty() ? code("none") : join(inputs, code(", ")));
  h += code("// Equations (Zanasi & Tebaldi, Planetary Gear Modeling Using the Power-Oriented Graphs Technique):\n");
  h += code("//   {}\n", comment_text(model.main.equations));
  for (const LoadSpec& l : sc.loads)
    h += code("//   load on {}: TL = -({} + {} omega + {} omega |omega|) [N m, N m s, N m s^2]\n",
              comment_text(d.topology.bodies[static_cast<std::size_t>(l.body)].name), number_code(l.constant),
              number_code(l.linear), number_code(l.quadratic));
  for (std::size_t c = 0; c < sc.controllers.size(); ++c) {
    const ControllerSpec& k = sc.controllers[c];
    if (k.supplies >= 0)
      h += code("//   slip controller {}: Tc = {} e + {} theta as {}'s torque, e = ref - slip_{}, theta' = e [N m s, N m],\n"
                "//     from its start until {} locks\n",
                comment_text(k.name), number_code(k.kp), number_code(k.ki),
                comment_text(d.topology.friction_elements[static_cast<std::size_t>(k.supplies)].name),
                comment_text(d.topology.friction_elements[static_cast<std::size_t>(k.supplies)].name),
                comment_text(d.topology.friction_elements[static_cast<std::size_t>(k.supplies)].name));
    else
      h += code("//   controller {}: Tc = {} e + {} theta on {}, e = ref - omega_{}, theta' = e [N m s, N m]\n",
                comment_text(k.name), number_code(k.kp), number_code(k.ki),
                comment_text(d.topology.bodies[static_cast<std::size_t>(k.body)].name),
                comment_text(d.topology.bodies[static_cast<std::size_t>(k.measured)].name));
    if (k.limited())
      h += code("//     within [{}, {}] N m, held at a limit beyond it (events){}\n", limit_code(k.torque_min),
                limit_code(k.torque_max),
                k.ki != 0 ? code("; there theta' = e + (Tc - law) / (ki {} s), its back-calculation",
                                 number_code(k.tracking_time))
                          : CppText{});
  }
  if (model.rigid) h += code("//   {} (for comparison)\n", comment_text(model.rigid->equations));
  h += code("// Units are SI: rad/s, N, N m. Parameters are literals (see namespace parameters) unless listed in Params.\n");
  const bool limits = !model.main.limited_controllers.empty();
  const bool hybrid = !model.friction.empty() || limits || !model.main.driveline.empty();
  h += code("#pragma once\n\n#include <array>\n{}#include <string_view>\n#include <vector>\n\n#include <Eigen/Core>\n",
            limits ? code("#include <limits>\n") : CppText{});
  if (needs_solve) h += code("#include <Eigen/Cholesky>\n");
  h += code("\n{}{}{}#include <pogear/signals.hpp>\n", !model.main.driveline.empty() ? code("#include <pogear/driveline.hpp>\n") : CppText{},
            model.scene.thermal.empty() ? CppText{} : code("#include <pogear/element_thermal.hpp>\n"),
            hybrid ? code("#include <pogear/hybrid_modes.hpp>\n") : CppText{});
  h += code("\nnamespace pogear_generated::{} {{\n\n", name);
  h += provenance(model);
  h += code("inline constexpr std::string_view scene_name = {};\n", string_literal(sc.name));
  h += code("inline constexpr double horizon = {};  // s\n", number_code(sc.horizon));
  h += code("inline constexpr double sample_period = {};  // s\n", number_code(sc.sample));
  h += code("inline constexpr std::string_view default_solver = {};\n", string_literal(solver_name(sc.solver)));
  h += code("inline constexpr double default_tolerance = {};\n", number_code(sc.tolerance));
  h += code("inline constexpr double default_step = {};  // s\n", number_code(sc.step));
  h += code("inline constexpr long default_max_steps = {};\n\n", integer_code(sc.max_steps));
  h += parameters_namespace(model);
  const CppText main_struct = model.main.kind == SystemKind::elastic ? code("Elastic") : code("Rigid");
  h += system_struct(model.main, model.scene, d, main_struct) + code("\n");
  if (model.rigid) h += system_struct(*model.rigid, model.scene, d, code("Rigid")) + code("\n");
  // The scene's signals and commands as written, so that a program of its own runs the scene as the
  // generated main does and changes only what it studies.
  h += signals_function(model.main, d.symbols, main_struct);
  if (model.rigid) h += code("\n") + signals_function(*model.rigid, d.symbols, code("Rigid"));
  if (hybrid) h += code("\n") + friction_function(model);
  if (limits) {
    h += code("\n") + torque_limits_function(model, model.main, main_struct);
    if (model.rigid) h += code("\n") + torque_limits_function(model, *model.rigid, code("Rigid"));
  }
  const std::vector<rt::ElementThermal> thermal = element_thermal(model);
  if (!thermal.empty()) h += code("\n") + thermal_function(thermal);
  const std::vector<rt::TriggeredSignal> triggered = triggered_signals(model, model.main);
  if (!triggered.empty()) {
    h += code("\n") + triggered_function(triggered, main_struct);
    if (model.rigid) h += code("\n") + triggered_function(triggered_signals(model, *model.rigid), code("Rigid"));
  }
  h += code("\n}}  // namespace pogear_generated::{}\n", name);
  g.header = h.str();

  CppText m;
  m += code("// {}: generated by pogear {} from the scene {}; do not edit.\n", main_name,
            comment_text(build_config::version), file_name(sc.file));
  m += code("// Simulates the scene and writes DIR/{}.csv{}{}.\n", name,
            model.rigid ? code(" and DIR/{}.rigid.csv", name) : CppText{},
            model.friction.empty() ? CppText{} : code(", with its brakes' and clutches' events in .events.csv files"));
  for (const std::string& line : rt::usage_lines("PROGRAM", 100, solvers)) m += code("// {}\n", comment_text(line));
  m += code("#include \"{}\"\n\n{}#include <pogear/parameters.hpp>\n#include <pogear/run_system.hpp>\n\n",
            header_name, hybrid ? code("#include <pogear/hybrid_run.hpp>\n") : CppText{});
  m += code("namespace scene = pogear_generated::{};\n\n", name);
  std::vector<CppText> solver_codes;
  for (rt::Solver s : solvers) solver_codes.push_back(code("pogear::rt::Solver::{}", identifier(std::string(rt::solver_name(s)))));
  m += code("namespace {{\n\n");
  m += code("// The solvers compiled into this simulator (`pogear generate --solvers`): each costs compile time.\n");
  m += code("using Solvers = pogear::rt::Solvers<{}>;\n", join(solver_codes, code(", ")));
  // The optional last arguments of run_hybrid_system: the triggered signals, then the temperatures.
  auto last_arguments = [&](const CppText& system) {
    if (thermal.empty()) return triggered.empty() ? CppText{} : code(", scene::{}_triggered_signals()", system);
    return (triggered.empty() ? code(", {{}}") : code(", scene::{}_triggered_signals()", system)) +
           code(", scene::friction_thermal()");
  };
  const CppText main_triggers = last_arguments(main_struct), rigid_triggers = last_arguments(code("Rigid"));
  m += code("\n}}  // namespace\n\n");
  m += code("int main(int argc, char** argv) {{\n");
  m += code("  pogear::rt::SceneRun run;\n");
  m += code("  run.name = scene::scene_name;\n  run.horizon = scene::horizon;\n  run.sample = scene::sample_period;\n");
  m += code("  run.solver = pogear::rt::parse_solver(scene::default_solver).value();\n");
  m += code("  pogear::rt::set_tolerance(run.options, scene::default_tolerance);\n");
  m += code("  run.options.h = scene::default_step;\n  run.options.max_steps = scene::default_max_steps;\n");
  if (model.scene.speeds_in_rpm) m += code("  run.speeds_in_rpm = true;\n");
  m += code("  if (const int exit = pogear::rt::read_command_line(argc, argv, run, Solvers::list); exit >= 0) return exit;\n");
  m += code("  scene::{}::Params params;\n", main_struct);
  m += code("  if (!pogear::rt::set_parameters(run.params, {{{}}}, argv[0])) return 1;\n",
            parameter_fields(model.main, code("params")));
  m += code("  const scene::{} system;\n", main_struct);
  const bool tuned = has_tuned_capacity(model);
  if (hybrid)
    m += code("  int status = pogear::rt::run_hybrid_system(system, params, scene::{}_signals(), scene::friction_elements({}), {}"
              "scene::{}::initial_state(), run, \"\"{});\n", main_struct, tuned ? code("params") : CppText{},
              limits ? code("scene::{}_torque_limits(), ", main_struct) : CppText{}, main_struct, main_triggers);
  else
    m += code("  int status = pogear::rt::run_system<Solvers>(system, params, scene::{}_signals(), scene::{}::initial_state(), run, \"\");\n",
              main_struct, main_struct);
  if (model.rigid) {
    m += code("  scene::Rigid::Params rigid_params;\n");
    for (const auto& p : model.rigid->params)
      m += code("  rigid_params.{} = params.{};\n", identifier(p.name), identifier(p.name));
    if (hybrid)
      m += code("  if (status == 0)\n    status = pogear::rt::run_hybrid_system(scene::Rigid{{}}, rigid_params, scene::Rigid_signals(), "
                "scene::friction_elements({}), {}scene::Rigid::initial_state(), run, \".rigid\"{});\n",
                tuned ? code("rigid_params") : CppText{}, limits ? code("scene::Rigid_torque_limits(), ") : CppText{},
                rigid_triggers);
    else
      m += code("  if (status == 0)\n    status = pogear::rt::run_system<Solvers>(scene::Rigid{{}}, rigid_params, scene::Rigid_signals(), "
                "scene::Rigid::initial_state(), run, \".rigid\");\n");
  }
  m += code("  return status;\n}}\n");
  g.main = m.str();
  return g;
}

}  // namespace

GeneratedSources generate_sources(const SpecializedScene& model, std::vector<rt::Solver> solvers) {
  // The scene's solver, and those asked for, in the order of rt::all_solvers.
  std::vector<rt::Solver> compiled;
  for (rt::Solver s : rt::all_solvers)
    if ((solvers.empty() && s == model.scene.solver) || std::find(solvers.begin(), solvers.end(), s) != solvers.end())
      compiled.push_back(s);
  for (const rt::Solver s : compiled)
    if (const auto refusal = rt::solver_refusal(s, solver_traits(model)))
      throw InputError(SourceLocation{model.scene.file, 0, 0},
                       fmt::format("{}; leave {} out of --solvers", rt::describe(*refusal), rt::solver_name(s)));
  try {
    return generate(model, compiled);
  } catch (const std::logic_error& e) {
    // The readers check every name and number; what still fails here (a name or number cpp_text
    // refuses, a coefficient that should be a number) is refused, not written.
    throw InputError(SourceLocation{model.scene.file, 0, 0},
                     fmt::format("cannot generate the simulator: {}; report this scene as a pogear bug", e.what()));
  }
}

}  // namespace pogear
