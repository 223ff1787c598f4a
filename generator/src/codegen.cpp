// Generated code is deterministic (every expression goes through print_expression), readable
// (states and inputs get their names as local constants) and needs only Eigen and the runtime.
#include "codegen.hpp"

#include <filesystem>
#include <set>

#include <fmt/format.h>

#include "printer.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

std::string quoted_list(const std::vector<std::string>& v) {
  std::string s;
  for (std::size_t i = 0; i < v.size(); ++i) s += (i ? ", " : "") + fmt::format("\"{}\"", v[i]);
  return s;
}

std::string effects_list(const Effects& e) {
  std::vector<std::string> on;
  if (e.mesh_compliance) on.push_back("mesh_compliance");
  if (e.mesh_damping) on.push_back("mesh_damping");
  if (e.bearing_friction) on.push_back("bearing_friction");
  if (e.mesh_forces) on.push_back("mesh_forces");
  std::string s;
  for (const auto& x : on) s += (s.empty() ? "" : ", ") + x;
  return s.empty() ? "none (rigid, frictionless)" : s;
}

void collect_symbols(const ex& e, std::set<std::string>& names) {
  if (GiNaC::is_a<GiNaC::symbol>(e)) names.insert(GiNaC::ex_to<GiNaC::symbol>(e).get_name());
  for (const ex& op : e) collect_symbols(op, names);
}

// The names a function body reads: its values' and its temporaries' symbols.
std::set<std::string> symbols_in(const std::vector<ex>& values, const std::vector<Assignment>& temporaries = {}) {
  std::set<std::string> names;
  for (const auto& e : values) collect_symbols(e, names);
  for (const auto& a : temporaries) collect_symbols(a.value, names);
  return names;
}

// `const double omega_c = x[0];` for each state, input and parameter the body uses.
std::string aliases(const SimSystem& sys, const std::set<std::string>& used, const char* xname) {
  std::string s;
  for (std::size_t i = 0; i < sys.states.size(); ++i)
    if (used.count(sys.states[i])) s += fmt::format("    const double {} = {}[{}];\n", sys.states[i], xname, i);
  for (std::size_t i = 0; i < sys.inputs.size(); ++i)
    if (used.count(sys.inputs[i])) s += fmt::format("    const double {} = u[{}];\n", sys.inputs[i], i);
  for (const auto& p : sys.params)
    if (used.count(p)) s += fmt::format("    const double {} = p.{};\n", p, p);
  return s;
}

std::string cpp(const ex& e) { return print_expression(e, Notation::cpp); }

std::string ops(const OperationCount& c) {
  return fmt::format("{} operations ({} multiplications, {} additions)", c.total(), c.multiplications, c.additions);
}

std::string system_struct(const SimSystem& sys, const std::string& struct_name) {
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size(), ny = sys.outputs.size();
  std::string s;
  s += fmt::format("// {}\n", sys.equations);
  s += fmt::format("struct {} {{\n", struct_name);
  s += fmt::format("  static constexpr int nx = {}, nu = {}, ny = {};\n", nx, nu, ny);
  auto names = [&](const char* what, const std::vector<std::string>& v, const char* size) {
    s += fmt::format("  static constexpr std::array<std::string_view, {}> {}{{{}}};\n", size, what, quoted_list(v));
  };
  names("state_names", sys.states, "nx");
  names("state_units", sys.state_units, "nx");
  names("input_names", sys.inputs, "nu");
  names("output_names", sys.outputs, "ny");
  names("output_units", sys.output_units, "ny");
  s += "  using State = Eigen::Matrix<double, nx, 1>;\n";
  s += "  using Input = Eigen::Matrix<double, nu, 1>;\n";
  s += "  using Output = Eigen::Matrix<double, ny, 1>;\n";
  s += "  using StateMatrix = Eigen::Matrix<double, nx, nx>;\n";
  s += "  using InputMatrix = Eigen::Matrix<double, nx, nu>;\n\n";

  if (sys.params.empty()) {
    s += "  struct Params {};  // no tunable parameters: all are literals below\n\n";
  } else {
    s += "  // Tunable parameters (SI), set at run time; every other parameter is a literal below.\n";
    s += "  struct Params {\n";
    for (std::size_t i = 0; i < sys.params.size(); ++i)
      s += fmt::format("    double {} = {};\n", sys.params[i], cpp_double(sys.param_values[i]));
    s += "  };\n\n";
  }

  s += "  static State initial_state() {\n    State x;\n";
  s += "    x << ";
  for (std::size_t i = 0; i < nx; ++i) s += (i ? ", " : "") + cpp_double(sys.x0[i]);
  s += ";\n    return x;\n  }\n\n";

  // rhs
  {
    const auto used = symbols_in(sys.rhs, sys.rhs_temporaries);
    s += fmt::format("  // dx/dt: {}.\n", ops(sys.rhs_ops));
    s += "  static void rhs([[maybe_unused]] const Params& p, [[maybe_unused]] const State& x,\n"
         "                  [[maybe_unused]] const Input& u, State& dx) {\n";
    s += aliases(sys, used, "x");
    for (const auto& a : sys.rhs_temporaries) s += fmt::format("    const double {} = {};\n", a.name, cpp(a.value));
    for (std::size_t i = 0; i < nx; ++i) s += fmt::format("    dx[{}] = {};\n", i, cpp(sys.rhs[i]));
    s += "  }\n\n";
  }
  // outputs
  {
    // The derivatives among the temporaries reuse the rhs's inputs and states.
    const auto used = symbols_in(sys.output_values, sys.output_temporaries);
    s += fmt::format("  // Outputs: {}.\n", ops(sys.output_ops));
    s += "  static void outputs([[maybe_unused]] const Params& p, [[maybe_unused]] const State& x,\n"
         "                      [[maybe_unused]] const Input& u, Output& y) {\n";
    s += aliases(sys, used, "x");
    for (const auto& a : sys.output_temporaries) s += fmt::format("    const double {} = {};\n", a.name, cpp(a.value));
    for (std::size_t i = 0; i < ny; ++i) s += fmt::format("    y[{}] = {};\n", i, cpp(sys.output_values[i]));
    s += "  }\n\n";
  }
  // matrices
  {
    std::vector<ex> all;
    for (unsigned i = 0; i < sys.M.rows(); ++i)
      for (unsigned j = 0; j < sys.M.cols(); ++j) all.push_back(sys.M(i, j));
    for (unsigned i = 0; i < sys.N.rows(); ++i)
      for (unsigned j = 0; j < sys.N.cols(); ++j) all.push_back(sys.N(i, j));
    s += "  // The linear form dx/dt = M x + N u, for exact stepping and as the implicit method's Jacobian.\n";
    s += "  static void matrices([[maybe_unused]] const Params& p, StateMatrix& M, InputMatrix& N) {\n";
    s += aliases(sys, symbols_in(all), "x");
    s += "    M.setZero();\n    N.setZero();\n";
    for (unsigned i = 0; i < sys.M.rows(); ++i)
      for (unsigned j = 0; j < sys.M.cols(); ++j)
        if (!sys.M(i, j).is_zero()) s += fmt::format("    M({}, {}) = {};\n", i, j, cpp(sys.M(i, j)));
    for (unsigned i = 0; i < sys.N.rows(); ++i)
      for (unsigned j = 0; j < sys.N.cols(); ++j)
        if (!sys.N(i, j).is_zero()) s += fmt::format("    N({}, {}) = {};\n", i, j, cpp(sys.N(i, j)));
    s += "  }\n";
  }
  s += "};\n";
  return s;
}

std::string signal_code(const SignalSpec& g) {
  switch (g.kind) {
    case SignalKind::constant: return fmt::format("pogear::rt::Constant{{{}}}", cpp_double(g.value));
    case SignalKind::step:
      return fmt::format("pogear::rt::Step{{{}, {}, {}}}", cpp_double(g.before), cpp_double(g.value), cpp_double(g.time));
    case SignalKind::ramp:
      return fmt::format("pogear::rt::Ramp{{{}, {}, {}}}", cpp_double(g.time), cpp_double(g.value), cpp_double(g.before));
    case SignalKind::sine:
      return fmt::format("pogear::rt::Sine{{{}, {}, {}, {}}}", cpp_double(g.value), cpp_double(g.frequency),
                         cpp_double(g.phase), cpp_double(g.offset));
    case SignalKind::table: {
      std::string t, v;
      for (std::size_t i = 0; i < g.table_t.size(); ++i) {
        t += (i ? ", " : "") + cpp_double(g.table_t[i]);
        v += (i ? ", " : "") + cpp_double(g.table_v[i]);
      }
      return fmt::format("pogear::rt::Table{{{{{}}}, {{{}}}}}", t, v);
    }
  }
  return "";
}

std::string signals_function(const SimModel& model, const SimSystem& sys, const std::string& name) {
  std::string s = fmt::format("// Input signals of {}, in the order of its inputs.\n", name);
  s += fmt::format("inline std::vector<pogear::rt::Signal> {}_signals() {{\n  return {{", name);
  for (std::size_t i = 0; i < sys.input_signal.size(); ++i)
    s += std::string(i ? ",\n          " : "") + "/* " + sys.inputs[i] + " */ " +
         signal_code(model.scene.inputs[sys.input_signal[i]].signal);
  s += "};\n}\n";
  return s;
}

// Only the file name: generated files must not depend on where pogear was run from.
std::string file_name(const std::string& path) { return std::filesystem::path(path).filename().string(); }

}  // namespace

GeneratedSources generate_sources(const SimModel& model) {
  const Scene& sc = model.scene;
  const Derivation& d = model.derivation;
  GeneratedSources g;
  g.header_name = sc.name + ".hpp";
  g.main_name = sc.name + "_main.cpp";

  std::string h;
  h += fmt::format("// {}: generated by pogear from the scene {}; do not edit.\n", g.header_name, file_name(sc.file));
  h += fmt::format("// Model: {} ({}, as the scene names it){}\n", d.topology.name, sc.model_ref,
                   d.topology.title.empty() ? "" : ", " + d.topology.title);
  h += fmt::format("// Effects: {}. Inputs: {}.\n", effects_list(sc.effects),
                   model.main.inputs.empty() ? "none" : [&] {
                     std::string s;
                     for (const auto& i : model.main.inputs) s += (s.empty() ? "" : ", ") + i;
                     return s;
                   }());
  h += "// Equations (Zanasi & Tebaldi, Planetary Gear Modeling Using the Power-Oriented Graphs Technique):\n";
  h += fmt::format("//   {}\n", model.main.equations);
  if (model.rigid) h += fmt::format("//   {} (for comparison)\n", model.rigid->equations);
  h += "// Units are SI: rad/s, N, N m. Parameters are literals unless listed in Params.\n";
  h += "#pragma once\n\n#include <array>\n#include <string_view>\n#include <vector>\n\n#include <Eigen/Core>\n\n";
  h += "#include <pogear/signals.hpp>\n\n";
  h += fmt::format("namespace pogear_generated::{} {{\n\n", sc.name);
  h += fmt::format("inline constexpr std::string_view scene_name = \"{}\";\n", sc.name);
  h += fmt::format("inline constexpr double horizon = {};  // s\n", cpp_double(sc.horizon));
  h += fmt::format("inline constexpr double sample_period = {};  // s\n", cpp_double(sc.sample));
  h += fmt::format("inline constexpr std::string_view default_solver = \"{}\";\n", solver_name(sc.solver));
  h += fmt::format("inline constexpr double default_tolerance = {};\n", cpp_double(sc.tolerance));
  h += fmt::format("inline constexpr double default_step = {};  // s\n", cpp_double(sc.step));
  h += fmt::format("inline constexpr long default_max_steps = {};\n\n", sc.max_steps);
  const std::string main_struct = model.main.kind == "elastic" ? "Elastic" : "Rigid";
  h += system_struct(model.main, main_struct) + "\n";
  h += signals_function(model, model.main, main_struct) + "\n";
  if (model.rigid) {
    h += system_struct(*model.rigid, "Rigid") + "\n";
    h += signals_function(model, *model.rigid, "Rigid") + "\n";
  }
  h += fmt::format("}}  // namespace pogear_generated::{}\n", sc.name);
  g.header = h;

  std::string m;
  m += fmt::format("// {}: generated by pogear from the scene {}; do not edit.\n", g.main_name, file_name(sc.file));
  m += fmt::format("// Simulates the scene and writes DIR/{}.csv{}.\n", sc.name,
                   model.rigid ? fmt::format(" and DIR/{}.rigid.csv", sc.name) : "");
  m += "// Usage: PROGRAM [--solver exact|rk4|dopri5|implicit] [--tolerance R] [--step S] [--out DIR]\n"
       "//                [--max-steps N] [--no-csv] [--repeat N] [--quiet]\n";
  m += fmt::format("#include \"{}\"\n\n#include <pogear/scene_runner.hpp>\n\n", g.header_name);
  m += fmt::format("namespace scene = pogear_generated::{};\n\n", sc.name);
  m += "int main(int argc, char** argv) {\n";
  m += "  pogear::rt::SceneRun run;\n";
  m += "  run.name = scene::scene_name;\n  run.horizon = scene::horizon;\n  run.sample = scene::sample_period;\n";
  m += "  run.solver = scene::default_solver;\n  run.options.rtol = scene::default_tolerance;\n";
  m += "  run.options.atol = scene::default_tolerance * 1e-2;\n";
  m += "  run.options.h = scene::default_step;\n  run.options.max_steps = scene::default_max_steps;\n";
  m += "  if (!pogear::rt::parse_command_line(argc, argv, run)) return 1;\n";
  m += fmt::format("  const scene::{} system;\n", main_struct);
  m += fmt::format("  int status = pogear::rt::run_system(system, {{}}, scene::{}_signals(), scene::{}::initial_state(), run, \"\");\n",
                   main_struct, main_struct);
  if (model.rigid)
    m += "  if (status == 0)\n    status = pogear::rt::run_system(scene::Rigid{}, {}, scene::Rigid_signals(), "
         "scene::Rigid::initial_state(), run, \".rigid\");\n";
  m += "  return status;\n}\n";
  g.main = m;
  return g;
}

std::string operation_summary(const SimModel& model) {
  std::string s;
  auto one = [&](const SimSystem& sys) {
    s += fmt::format("{} ({} states, {} inputs, {} outputs): rhs {}; outputs {}\n", sys.kind, sys.states.size(),
                     sys.inputs.size(), sys.outputs.size(), ops(sys.rhs_ops), ops(sys.output_ops));
    s += diagnostics_text(system_diagnostics(model, sys), "  ");
  };
  one(model.main);
  if (model.rigid) one(*model.rigid);
  return s;
}

}  // namespace pogear
