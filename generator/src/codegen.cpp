// Generated code is deterministic (every expression goes through print_expression), readable
// (states and inputs get their names as local constants) and needs only Eigen and the runtime.
// Every piece of it is a CppText: user text (names, paths, titles, units) enters only through
// cpp_text's escaping and checking functions, never as a raw string.
#include "codegen.hpp"

#include <filesystem>
#include <set>
#include <stdexcept>

#include <fmt/format.h>

#include "cpp_text.hpp"
#include "printer.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// Above this many entries of x, u, u (the exact method's augmented matrix is nx + 2 nu square),
// systems use heap-backed Eigen types: Eigen refuses fixed-size objects above 128 KB on the stack
// (an (nx + 2 nu)^2 matrix of doubles reaches it at 128), and fixed sizes stop paying off long before.
constexpr std::size_t max_fixed_size = 64;

bool fixed_sizes(const SimSystem& sys) { return sys.states.size() + 2 * sys.inputs.size() <= max_fixed_size; }

CppText lines(const std::vector<CppText>& parts, const CppText& separator) {
  CppText s;
  for (std::size_t i = 0; i < parts.size(); ++i) s += (i ? separator : CppText{}) + parts[i];
  return s;
}

CppText literal_list(const std::vector<std::string>& v) {
  std::vector<CppText> parts;
  for (const auto& x : v) parts.push_back(string_literal(x));
  return lines(parts, code(", "));
}

CppText effects_list(const Effects& e) {
  std::vector<CppText> on;
  if (e.mesh_compliance) on.push_back(code("mesh_compliance"));
  if (e.mesh_damping) on.push_back(code("mesh_damping"));
  if (e.bearing_friction) on.push_back(code("bearing_friction"));
  if (e.mesh_forces) on.push_back(code("mesh_forces"));
  return on.empty() ? code("none (rigid, frictionless)") : lines(on, code(", "));
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

std::vector<ex> entries(const std::vector<const GiNaC::matrix*>& matrices) {
  std::vector<ex> all;
  for (const GiNaC::matrix* m : matrices)
    for (unsigned i = 0; i < m->rows(); ++i)
      for (unsigned j = 0; j < m->cols(); ++j) all.push_back((*m)(i, j));
  return all;
}

CppText index_code(std::size_t i) { return integer_code(static_cast<long long>(i)); }

// `const double omega_c = x[0];` for each state, input and parameter the body uses.
CppText aliases(const SimSystem& sys, const std::set<std::string>& used, const CppText& xname) {
  CppText s;
  for (std::size_t i = 0; i < sys.states.size(); ++i)
    if (used.count(sys.states[i])) s += code("    const double {} = {}[{}];\n", identifier(sys.states[i]), xname, index_code(i));
  for (std::size_t i = 0; i < sys.inputs.size(); ++i)
    if (used.count(sys.inputs[i])) s += code("    const double {} = u[{}];\n", identifier(sys.inputs[i]), index_code(i));
  for (const auto& p : sys.params)
    if (used.count(p.name)) s += code("    const double {} = p.{};\n", identifier(p.name), identifier(p.name));
  return s;
}

CppText ops(const OperationCount& c) {
  return code("{} operations ({} multiplications, {} additions)", integer_code(c.total()),
              integer_code(c.multiplications), integer_code(c.additions));
}

// `    NAME(i, j) = value;` for the nonzero entries of m.
CppText matrix_entries(const GiNaC::matrix& m, const CppText& name) {
  CppText s;
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      if (!m(i, j).is_zero())
        s += code("    {}({}, {}) = {};\n", name, index_code(i), index_code(j), expression_code(m(i, j)));
  return s;
}

CppText system_struct(const SimSystem& sys, const CppText& struct_name) {
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size(), ny = sys.outputs.size();
  const bool fixed = fixed_sizes(sys);
  CppText s;
  s += code("// {}\n", comment_text(sys.equations));
  s += code("struct {} {{\n", struct_name);
  s += code("  static constexpr int nx = {}, nu = {}, ny = {};\n", index_code(nx), index_code(nu), index_code(ny));
  auto names = [&](const CppText& what, const std::vector<std::string>& v, const CppText& size) {
    s += code("  static constexpr std::array<std::string_view, {}> {}{{{}}};\n", size, what, literal_list(v));
  };
  names(code("state_names"), sys.states, code("nx"));
  names(code("state_units"), sys.state_units, code("nx"));
  names(code("input_names"), sys.inputs, code("nu"));
  names(code("output_names"), sys.outputs, code("ny"));
  names(code("output_units"), sys.output_units, code("ny"));
  if (fixed) {
    s += code("  using State = Eigen::Matrix<double, nx, 1>;\n");
    s += code("  using Input = Eigen::Matrix<double, nu, 1>;\n");
    s += code("  using Output = Eigen::Matrix<double, ny, 1>;\n");
    s += code("  using StateMatrix = Eigen::Matrix<double, nx, nx>;\n");
    s += code("  using InputMatrix = Eigen::Matrix<double, nx, nu>;\n\n");
  } else {
    s += code("  // Sized at run time: fixed-size matrices this large would not fit on the stack.\n");
    s += code("  using State = Eigen::VectorXd;\n");
    s += code("  using Input = Eigen::VectorXd;\n");
    s += code("  using Output = Eigen::VectorXd;\n");
    s += code("  using StateMatrix = Eigen::MatrixXd;\n");
    s += code("  using InputMatrix = Eigen::MatrixXd;\n\n");
  }

  if (sys.params.empty()) {
    s += code("  struct Params {{}};  // no tunable parameters: all are literals below\n\n");
  } else {
    s += code("  // Tunable parameters (SI), set at run time; every other parameter is a literal below.\n");
    s += code("  struct Params {{\n");
    for (const auto& p : sys.params) s += code("    double {} = {};\n", identifier(p.name), number_code(p.value));
    s += code("  }};\n\n");
  }

  s += code("  static State initial_state() {{\n");
  s += fixed ? code("    State x;\n") : code("    State x(nx);\n");
  std::vector<CppText> x0;
  for (std::size_t i = 0; i < nx; ++i) x0.push_back(number_code(sys.x0[i]));
  s += code("    x << {};\n    return x;\n  }}\n\n", lines(x0, code(", ")));

  if (sys.implicit) {
    const ImplicitForm& f = *sys.implicit;
    s += code("  // L dx/dt = A x + B u, from the tunable parameters; L is symmetric positive definite.\n");
    s += code("  static void implicit_form([[maybe_unused]] const Params& p, StateMatrix& L, StateMatrix& A, "
              "InputMatrix& B) {{\n");
    s += aliases(sys, symbols_in(entries({&f.L, &f.A, &f.B})), code("x"));
    s += fixed ? code("    L.setZero();\n    A.setZero();\n    B.setZero();\n")
               : code("    L.setZero(nx, nx);\n    A.setZero(nx, nx);\n    B.setZero(nx, nu);\n");
    s += matrix_entries(f.L, code("L")) + matrix_entries(f.A, code("A")) + matrix_entries(f.B, code("B"));
    s += code("  }}\n\n");
  }

  // rhs
  {
    s += code("  // dx/dt: {}.\n", ops(sys.rhs_ops));
    s += code("  static void rhs([[maybe_unused]] const Params& p, [[maybe_unused]] const State& x,\n"
              "                  [[maybe_unused]] const Input& u, State& dx) {{\n");
    if (sys.implicit) {
      s += code("    StateMatrix M;\n    InputMatrix N;\n    matrices(p, M, N);\n");
      s += code("    dx.noalias() = M * x;\n    dx.noalias() += N * u;\n");
    } else {
      const auto used = symbols_in(sys.rhs, sys.rhs_temporaries);
      if (!fixed) s += code("    dx.resize(nx);\n");
      s += aliases(sys, used, code("x"));
      for (const auto& a : sys.rhs_temporaries)
        s += code("    const double {} = {};\n", identifier(a.name), expression_code(a.value));
      for (std::size_t i = 0; i < nx; ++i) s += code("    dx[{}] = {};\n", index_code(i), expression_code(sys.rhs[i]));
    }
    s += code("  }}\n\n");
  }
  // outputs
  {
    // The derivatives among the temporaries reuse the rhs's inputs and states.
    const auto used = symbols_in(sys.output_values, sys.output_temporaries);
    s += code("  // Outputs: {}.\n", ops(sys.output_ops));
    s += code("  static void outputs([[maybe_unused]] const Params& p, [[maybe_unused]] const State& x,\n"
              "                      [[maybe_unused]] const Input& u, Output& y) {{\n");
    if (!fixed) s += code("    y.resize(ny);\n");
    s += aliases(sys, used, code("x"));
    if (sys.output_derivatives) {
      s += fixed ? code("    State dx;\n") : code("    State dx(nx);\n");
      s += code("    rhs(p, x, u, dx);\n");
      for (std::size_t j = 0; j < nx; ++j)
        if (used.count("d" + sys.states[j]))
          s += code("    const double {} = dx[{}];\n", identifier("d" + sys.states[j]), index_code(j));
    }
    for (const auto& a : sys.output_temporaries)
      s += code("    const double {} = {};\n", identifier(a.name), expression_code(a.value));
    for (std::size_t i = 0; i < ny; ++i) s += code("    y[{}] = {};\n", index_code(i), expression_code(sys.output_values[i]));
    s += code("  }}\n\n");
  }
  // matrices
  {
    s += code("  // The linear form dx/dt = M x + N u, for exact stepping and as the implicit method's Jacobian.\n");
    s += code("  static void matrices([[maybe_unused]] const Params& p, StateMatrix& M, InputMatrix& N) {{\n");
    if (sys.implicit) {
      s += code("    StateMatrix L, A;\n    InputMatrix B;\n    implicit_form(p, L, A, B);\n");
      s += code("    const Eigen::LLT<StateMatrix> factors(L);\n");
      s += code("    M = factors.solve(A);\n    N = factors.solve(B);\n");
    } else {
      s += aliases(sys, symbols_in(entries({&sys.M, &sys.N})), code("x"));
      s += fixed ? code("    M.setZero();\n    N.setZero();\n") : code("    M.setZero(nx, nx);\n    N.setZero(nx, nu);\n");
      s += matrix_entries(sys.M, code("M")) + matrix_entries(sys.N, code("N"));
    }
    s += code("  }}\n");
  }
  // energy_matrix: what pogear/scene_runner.hpp checks a run against (see SimSystem::L).
  s += code("\n  // The stored energy E = x^T L x / 2. The power balance bounds it by the initial energy and the\n"
            "  // inputs' work; a run that outgrows the bound has diverged (the runner checks each sample).\n");
  s += code("  static void energy_matrix([[maybe_unused]] const Params& p, StateMatrix& L) {{\n");
  s += aliases(sys, symbols_in(entries({&sys.L})), code("x"));
  s += fixed ? code("    L.setZero();\n") : code("    L.setZero(nx, nx);\n");
  s += matrix_entries(sys.L, code("L"));
  s += code("  }}\n");
  s += code("}};\n");
  return s;
}

CppText numbers(const std::vector<double>& v) {
  std::vector<CppText> parts;
  for (double x : v) parts.push_back(number_code(x));
  return lines(parts, code(", "));
}

CppText signal_code(const SignalSpec& g) {
  switch (g.kind) {
    case SignalKind::constant: return code("pogear::rt::Constant{{{}}}", number_code(g.value));
    case SignalKind::step:
      return code("pogear::rt::Step{{{}, {}, {}}}", number_code(g.before), number_code(g.value), number_code(g.time));
    case SignalKind::ramp:
      return code("pogear::rt::Ramp{{{}, {}, {}}}", number_code(g.time), number_code(g.value), number_code(g.before));
    case SignalKind::sine:
      return code("pogear::rt::Sine{{{}, {}, {}, {}}}", number_code(g.value), number_code(g.frequency),
                  number_code(g.phase), number_code(g.offset));
    case SignalKind::table: return code("pogear::rt::Table{{{{{}}}, {{{}}}}}", numbers(g.table_t), numbers(g.table_v));
  }
  return CppText{};
}

CppText signals_function(const SimModel& model, const SimSystem& sys, const CppText& name) {
  CppText s = code("// Input signals of {}, in the order of its inputs.\n", name);
  s += code("inline std::vector<pogear::rt::Signal> {}_signals() {{\n  return {{", name);
  for (std::size_t i = 0; i < sys.input_signal.size(); ++i)
    s += (i ? code(",\n          ") : CppText{}) + code("/* {} */ ", comment_text(sys.inputs[i])) +
         signal_code(model.scene.inputs[sys.input_signal[i]].signal);
  s += code("}};\n}}\n");
  return s;
}

// Only the file name: generated files must not depend on where pogear was run from.
CppText file_name(const std::string& path) {
  return comment_text(std::filesystem::path(path).filename().string());
}

// `{"J_c", &params.J_c, {{"kg*meters^2", 1.0}, {"kg*m^2", 1.0}}, ">0"}` for set_parameters.
CppText parameter_fields(const SimSystem& sys, const CppText& params) {
  std::vector<CppText> fields;
  for (const auto& p : sys.params) {
    std::vector<CppText> units;
    for (const auto& u : p.units) units.push_back(code("{{{}, {}}}", string_literal(u.unit), number_code(u.si)));
    fields.push_back(code("{{{}, &{}.{}, {{{}}}, {}}}", string_literal(p.name), params, identifier(p.name),
                          lines(units, code(", ")), string_literal(p.sign)));
  }
  return lines(fields, code(",\n       "));
}

GeneratedSources generate(const SimModel& model) {
  const Scene& sc = model.scene;
  const Derivation& d = model.derivation;
  const CppText name = identifier(sc.name);
  const CppText header_name = code("{}.hpp", name), main_name = code("{}_main.cpp", name);
  GeneratedSources g;
  g.header_name = header_name.str();
  g.main_name = main_name.str();
  const bool needs_solve = model.main.implicit || (model.rigid && model.rigid->implicit);

  CppText h;
  h += code("// {}: generated by pogear from the scene {}; do not edit.\n", header_name, file_name(sc.file));
  h += code("// Model: {} ({}, as the scene names it){}\n", comment_text(d.topology.name), comment_text(sc.model_ref),
            d.topology.title.empty() ? CppText{} : code(", {}", comment_text(d.topology.title)));
  std::vector<CppText> inputs;
  for (const auto& i : model.main.inputs) inputs.push_back(comment_text(i));
  h += code("// Effects: {}. Inputs: {}.\n", effects_list(sc.effects), inputs.empty() ? code("none") : lines(inputs, code(", ")));
  h += code("// Equations (Zanasi & Tebaldi, Planetary Gear Modeling Using the Power-Oriented Graphs Technique):\n");
  h += code("//   {}\n", comment_text(model.main.equations));
  if (model.rigid) h += code("//   {} (for comparison)\n", comment_text(model.rigid->equations));
  h += code("// Units are SI: rad/s, N, N m. Parameters are literals unless listed in Params.\n");
  h += code("#pragma once\n\n#include <array>\n#include <string_view>\n#include <vector>\n\n#include <Eigen/Core>\n");
  if (needs_solve) h += code("#include <Eigen/Cholesky>\n");
  h += code("\n#include <pogear/signals.hpp>\n\n");
  h += code("namespace pogear_generated::{} {{\n\n", name);
  h += code("inline constexpr std::string_view scene_name = {};\n", string_literal(sc.name));
  h += code("inline constexpr double horizon = {};  // s\n", number_code(sc.horizon));
  h += code("inline constexpr double sample_period = {};  // s\n", number_code(sc.sample));
  h += code("inline constexpr std::string_view default_solver = {};\n", string_literal(solver_name(sc.solver)));
  h += code("inline constexpr double default_tolerance = {};\n", number_code(sc.tolerance));
  h += code("inline constexpr double default_step = {};  // s\n", number_code(sc.step));
  h += code("inline constexpr long default_max_steps = {};\n\n", integer_code(sc.max_steps));
  const CppText main_struct = model.main.kind == "elastic" ? code("Elastic") : code("Rigid");
  h += system_struct(model.main, main_struct) + code("\n");
  h += signals_function(model, model.main, main_struct) + code("\n");
  if (model.rigid) {
    h += system_struct(*model.rigid, code("Rigid")) + code("\n");
    h += signals_function(model, *model.rigid, code("Rigid")) + code("\n");
  }
  h += code("}}  // namespace pogear_generated::{}\n", name);
  g.header = h.str();

  CppText m;
  m += code("// {}: generated by pogear from the scene {}; do not edit.\n", main_name, file_name(sc.file));
  m += code("// Simulates the scene and writes DIR/{}.csv{}.\n", name,
            model.rigid ? code(" and DIR/{}.rigid.csv", name) : CppText{});
  m += code("// Usage: PROGRAM [--solver exact|rk4|dopri5|implicit] [--tolerance R] [--step S] [--out DIR]\n"
            "//                [--max-steps N] [--param NAME=VALUE] [--no-csv] [--repeat N] [--quiet]\n");
  m += code("#include \"{}\"\n\n#include <pogear/parameters.hpp>\n#include <pogear/scene_runner.hpp>\n\n", header_name);
  m += code("namespace scene = pogear_generated::{};\n\n", name);
  m += code("int main(int argc, char** argv) {{\n");
  m += code("  pogear::rt::SceneRun run;\n");
  m += code("  run.name = scene::scene_name;\n  run.horizon = scene::horizon;\n  run.sample = scene::sample_period;\n");
  m += code("  run.solver = scene::default_solver;\n  run.options.rtol = scene::default_tolerance;\n");
  m += code("  run.options.atol = scene::default_tolerance * 1e-2;\n");
  m += code("  run.options.h = scene::default_step;\n  run.options.max_steps = scene::default_max_steps;\n");
  m += code("  if (!pogear::rt::parse_command_line(argc, argv, run)) return 1;\n");
  m += code("  scene::{}::Params params;\n", main_struct);
  m += code("  if (!pogear::rt::set_parameters(run.params, {{{}}}, argv[0])) return 1;\n",
            parameter_fields(model.main, code("params")));
  m += code("  const scene::{} system;\n", main_struct);
  m += code("  int status = pogear::rt::run_system(system, params, scene::{}_signals(), scene::{}::initial_state(), run, \"\");\n",
            main_struct, main_struct);
  if (model.rigid) {
    m += code("  scene::Rigid::Params rigid_params;\n");
    for (const auto& p : model.rigid->params)
      m += code("  rigid_params.{} = params.{};\n", identifier(p.name), identifier(p.name));
    m += code("  if (status == 0)\n    status = pogear::rt::run_system(scene::Rigid{{}}, rigid_params, scene::Rigid_signals(), "
              "scene::Rigid::initial_state(), run, \".rigid\");\n");
  }
  m += code("  return status;\n}}\n");
  g.main = m.str();
  return g;
}

}  // namespace

GeneratedSources generate_sources(const SimModel& model) {
  try {
    return generate(model);
  } catch (const std::invalid_argument& e) {
    // The readers check every name and number; what still fails here is refused, not written.
    throw InputError(SourceLocation{model.scene.file, 0, 0},
                     fmt::format("cannot generate the simulator: {}; report this scene as a pogear bug", e.what()));
  }
}

std::string operation_summary(const SimModel& model) {
  std::string s;
  auto one = [&](const SimSystem& sys) {
    s += fmt::format("{} ({} states, {} inputs, {} outputs): rhs {}; outputs {}\n", sys.kind, sys.states.size(),
                     sys.inputs.size(), sys.outputs.size(), ops(sys.rhs_ops).str(), ops(sys.output_ops).str());
    s += diagnostics_text(system_diagnostics(model, sys), "  ");
  };
  one(model.main);
  if (model.rigid) one(*model.rigid);
  return s;
}

}  // namespace pogear
