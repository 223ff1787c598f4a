// A system struct is deterministic (every expression goes through expression_code) and readable:
// states, inputs and tunables get their names as local constants, each function reads only
// what it uses, and every function of x and u also has its linear form as matrices.
#include "codegen/codegen_system.hpp"

#include <set>
#include <variant>

#include "specialize/output_form.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

// Above this many entries of x, u, u (the exact method's augmented matrix is nx + 2 nu square),
// systems use heap-backed Eigen types: Eigen refuses fixed-size objects above 128 KB on the stack
// (an (nx + 2 nu)^2 matrix of doubles reaches it at 128), and fixed sizes stop paying off long before.
constexpr std::size_t max_fixed_size = 64;

bool fixed_sizes(const SpecializedSystem& sys) { return sys.states.size() + 2 * sys.inputs.size() <= max_fixed_size; }

CppText literal_list(const std::vector<std::string>& v) {
  std::vector<CppText> parts;
  for (const auto& x : v) parts.push_back(string_literal(x));
  return join(parts, code(", "));
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

// A system as its struct's functions print it: its ports named by the model, and in a product the
// bodies' variables after the parameters (print_expression).
struct SystemCode {
  const SpecializedSystem& sys;
  const Derivation& d;
  const Scene* scene;  // its engine and converter
  GiNaC::exset printed_last;
  bool fixed;
  CppText expression(const ex& e) const { return expression_code(e, printed_last); }
};

}  // namespace

CppText numbers(const std::vector<double>& v) {
  std::vector<CppText> parts;
  for (double x : v) parts.push_back(number_code(x));
  return join(parts, code(", "));
}

CppText signal_code(const rt::Signal& signal) {
  struct Code {
    CppText operator()(const rt::Constant& c) const { return code("pogear::rt::Constant{{{}}}", number_code(c.v)); }
    CppText operator()(const rt::Step& s) const {
      return code("pogear::rt::Step{{{}, {}, {}}}", number_code(s.before), number_code(s.after), number_code(s.time));
    }
    CppText operator()(const rt::Ramp& r) const {
      return code("pogear::rt::Ramp{{{}, {}, {}}}", number_code(r.start_time), number_code(r.slope),
                  number_code(r.initial));
    }
    CppText operator()(const rt::Sine& s) const {
      return code("pogear::rt::Sine{{{}, {}, {}, {}}}", number_code(s.amplitude), number_code(s.frequency_hz),
                  number_code(s.phase_rad), number_code(s.offset));
    }
    CppText operator()(const rt::Table& t) const {
      return code("pogear::rt::Table{{{{{}}}, {{{}}}}}", numbers(t.t), numbers(t.v));
    }
    CppText operator()(const rt::GradeLoad& g) const {
      return code("pogear::rt::GradeLoad{{{}, {}, {}}}", (*this)(g.angle), number_code(g.sine), number_code(g.cosine));
    }
  };
  return std::visit(Code{}, signal);
}

namespace {

// `const double omega_c = x[0];` for each state, input and parameter the body uses.
CppText aliases(const SystemCode& c, const std::set<std::string>& used, const CppText& xname) {
  const SpecializedSystem& sys = c.sys;
  CppText s;
  for (std::size_t i = 0; i < sys.states.size(); ++i)
    if (const std::string name = variable_name(c.d.symbols, sys.states[i].variable); used.count(name))
      s += code("    const double {} = {}[{}];\n", identifier(name), xname, index_code(i));
  for (std::size_t i = 0; i < sys.inputs.size(); ++i)
    if (const std::string name = variable_name(c.d.symbols, sys.inputs[i].variable); used.count(name))
      s += code("    const double {} = u[{}];\n", identifier(name), index_code(i));
  for (const auto& p : sys.params)
    if (used.count(p.name)) s += code("    const double {} = p.{};\n", identifier(p.name), identifier(p.name));
  return s;
}

// `    NAME(i, j) = value;` for the nonzero entries of m.
CppText matrix_entries(const SystemCode& c, const GiNaC::matrix& m, const CppText& name) {
  CppText s;
  for (unsigned i = 0; i < m.rows(); ++i)
    for (unsigned j = 0; j < m.cols(); ++j)
      if (!m(i, j).is_zero())
        s += code("    {}({}, {}) = {};\n", name, index_code(i), index_code(j), c.expression(m(i, j)));
  return s;
}

// A scene's engine and converter: their tables, and the speeds of their bodies over the states.
CppText driveline_function(const SystemCode& c) {
  const SpecializedSystem& sys = c.sys;
  const Scene& sc = *c.scene;
  CppText s = code("  // The engine's and the converter's torques (Tengine, Tpump, Tturbine: the inputs after the signals)\n"
                   "  // are functions of their bodies' speeds, their tables and the throttle: the hybrid runs compute them\n"
                   "  // (pogear/driveline.hpp). Speeds [rad/s], torques [N m], capacity factor [(rad/s)/sqrt(N m)].\n");
  s += code("  static pogear::rt::DrivelineData driveline([[maybe_unused]] const Params& p) {{\n");
  s += aliases(c, symbols_in(entries({&sys.driveline_speeds})), code("x"));
  s += code("    Eigen::MatrixXd speeds;\n    speeds.setZero({}, nx);\n", index_code(sys.driveline.size()));
  s += matrix_entries(c, sys.driveline_speeds, code("speeds"));
  s += code("    pogear::rt::DrivelineData d;\n");
  for (std::size_t i = 0; i < sys.driveline.size(); ++i) {
    const CppText row = code("speeds.row({})", index_code(i));
    switch (sys.driveline[i].kind) {
      case VariableKind::engine_torque: {
        const rt::EngineData& e = sc.engine->map;
        std::vector<CppText> rows;
        for (const auto& r : e.torque) rows.push_back(code("{{{}}}", numbers(r)));
        s += code("    d.engine = pogear::rt::EngineData{{{{{}}}, {{{}}}, {{{}}}}};\n", numbers(e.speeds), numbers(e.throttles),
                  join(rows, code(", ")));
        s += code("    d.throttle = {};\n    d.engine_speed = {};\n", signal_code(sc.engine->throttle), row);
        break;
      }
      case VariableKind::pump_torque: {
        const rt::ConverterData& k = sc.converter->curves;
        s += code("    d.converter = pogear::rt::ConverterData{{{{{{{}}}, {{{}}}}}, {{{{{}}}, {{{}}}}}}};\n",
                  numbers(k.capacity.x), numbers(k.capacity.y), numbers(k.torque_ratio.x), numbers(k.torque_ratio.y));
        s += code("    d.pump_speed = {};\n", row);
        break;
      }
      default: s += code("    d.turbine_speed = {};\n", row);
    }
  }
  s += code("    return d;\n  }}\n\n");
  return s;
}

CppText types(bool fixed) {
  if (fixed)
    return code("  using State = Eigen::Matrix<double, nx, 1>;\n"
                "  using Input = Eigen::Matrix<double, nu, 1>;\n"
                "  using Output = Eigen::Matrix<double, ny, 1>;\n"
                "  using StateMatrix = Eigen::Matrix<double, nx, nx>;\n"
                "  using InputMatrix = Eigen::Matrix<double, nx, nu>;\n"
                "  using OutputMatrix = Eigen::Matrix<double, ny, nx>;\n"
                "  using FeedthroughMatrix = Eigen::Matrix<double, ny, nu>;\n\n");
  return code("  // Sized at run time: fixed-size matrices this large would not fit on the stack.\n"
              "  using State = Eigen::VectorXd;\n"
              "  using Input = Eigen::VectorXd;\n"
              "  using Output = Eigen::VectorXd;\n"
              "  using StateMatrix = Eigen::MatrixXd;\n"
              "  using InputMatrix = Eigen::MatrixXd;\n"
              "  using OutputMatrix = Eigen::MatrixXd;\n"
              "  using FeedthroughMatrix = Eigen::MatrixXd;\n\n");
}

CppText rhs_function(const SystemCode& c) {
  const SpecializedSystem& sys = c.sys;
  CppText s = code("  // dx/dt: {}.\n", operation_text(sys.rhs_ops));
  s += code("  static void rhs([[maybe_unused]] const Params& p, [[maybe_unused]] const State& x,\n"
            "                  [[maybe_unused]] const Input& u, State& dx) {{\n");
  if (sys.implicit && sys.nonlinear) {
    // L dx/dt = A x + B u + Q TQ, the quadratic loads' torques TQ temporaries of the state.
    const ImplicitForm& f = *sys.implicit;
    s += code("    StateMatrix L, A;\n    InputMatrix B;\n    implicit_form(p, L, A, B);\n");
    s += aliases(c, symbols_in(entries({&f.Q}), sys.rhs_temporaries), code("x"));
    for (const auto& a : sys.rhs_temporaries)
      s += code("    const double {} = {};\n", identifier(a.name), c.expression(a.value));
    s += code("    State f = A * x;\n    f.noalias() += B * u;\n");
    const std::size_t first = sys.rhs_temporaries.size() - f.Q.cols();  // the loads' TQ come last, in Q's order
    for (unsigned i = 0; i < f.Q.rows(); ++i)
      for (unsigned q = 0; q < f.Q.cols(); ++q)
        if (!f.Q(i, q).is_zero())
          s += code("    f[{}] += {};\n", index_code(i), c.expression(f.Q(i, q) * sys.rhs_temporaries[first + q].symbol));
    s += code("    dx = Eigen::LLT<StateMatrix>(L).solve(f);\n");
  } else if (sys.implicit) {
    s += code("    StateMatrix M;\n    InputMatrix N;\n    matrices(p, M, N);\n");
    s += code("    dx.noalias() = M * x;\n    dx.noalias() += N * u;\n");
  } else {
    if (!c.fixed) s += code("    dx.resize(nx);\n");
    s += aliases(c, symbols_in(sys.rhs, sys.rhs_temporaries), code("x"));
    for (const auto& a : sys.rhs_temporaries)
      s += code("    const double {} = {};\n", identifier(a.name), c.expression(a.value));
    for (std::size_t i = 0; i < sys.states.size(); ++i)
      s += code("    dx[{}] = {};\n", index_code(i), c.expression(sys.rhs[i]));
  }
  return s + code("  }}\n\n");
}

// The mesh forces of eq. (8) read dx/dt, which rhs computes: the outputs call it rather than
// repeat its expressions.
CppText outputs_function(const SystemCode& c) {
  const SpecializedSystem& sys = c.sys;
  const bool fixed = c.fixed;
  const auto used = symbols_in(output_values(sys));
  CppText s = code("  // Outputs: {}.\n", operation_text(sys.output_ops));
  s += code("  static void outputs([[maybe_unused]] const Params& p, [[maybe_unused]] const State& x,\n"
            "                      [[maybe_unused]] const Input& u, Output& y) {{\n");
  if (!fixed) s += code("    y.resize(ny);\n");
  s += aliases(c, used, code("x"));
  if (sys.output_derivatives) {
    s += fixed ? code("    State dx;\n") : code("    State dx(nx);\n");
    s += code("    rhs(p, x, u, dx);\n");
    for (std::size_t j = 0; j < sys.states.size(); ++j)
      if (const std::string name = variable_name(c.d.symbols, derivative_of(sys.states[j].variable)); used.count(name))
        s += code("    const double {} = dx[{}];\n", identifier(name), index_code(j));
  }
  for (std::size_t i = 0; i < sys.outputs.size(); ++i)
    s += code("    y[{}] = {};\n", index_code(i), c.expression(sys.outputs[i].value));
  return s + code("  }}\n\n");
}

CppText matrices_function(const SystemCode& c) {
  const SpecializedSystem& sys = c.sys;
  CppText s = sys.nonlinear ? code("  // The linear part M x + N u of dx/dt (the quadratic loads' torques left out): the implicit method's\n"
                                   "  // Jacobian, exact at rest.\n")
                            : code("  // The linear form dx/dt = M x + N u, for exact stepping and as the implicit method's Jacobian.\n");
  s += code("  static void matrices([[maybe_unused]] const Params& p, StateMatrix& M, InputMatrix& N) {{\n");
  if (sys.implicit) {
    s += code("    StateMatrix L, A;\n    InputMatrix B;\n    implicit_form(p, L, A, B);\n");
    s += code("    const Eigen::LLT<StateMatrix> factors(L);\n");
    s += code("    M = factors.solve(A);\n    N = factors.solve(B);\n");
  } else {
    s += aliases(c, symbols_in(entries({&sys.M, &sys.N})), code("x"));
    s += c.fixed ? code("    M.setZero();\n    N.setZero();\n") : code("    M.setZero(nx, nx);\n    N.setZero(nx, nu);\n");
    s += matrix_entries(c, sys.M, code("M")) + matrix_entries(c, sys.N, code("N"));
  }
  return s + code("  }}\n\n");
}

// Exact coefficients where dx/dt is symbolic; with an implicit form, the outputs' dependence on
// dx/dt is applied to the solved M and N.
CppText output_matrices_function(const SystemCode& c) {
  const bool fixed = c.fixed;
  const OutputForm f = output_form(c.sys, c.d.symbols);
  CppText s = code("  // The outputs' linear form y = C x + D u: outputs() with its terms collected, equal to it up to\n"
                   "  // rounding (batched sweeps compute C x + D u).\n");
  s += code("  static void output_matrices([[maybe_unused]] const Params& p, OutputMatrix& C, FeedthroughMatrix& D) {{\n");
  s += aliases(c, symbols_in(entries({&f.C, &f.D, &f.E})), code("x"));
  s += fixed ? code("    C.setZero();\n    D.setZero();\n") : code("    C.setZero(ny, nx);\n    D.setZero(ny, nu);\n");
  s += matrix_entries(c, f.C, code("C")) + matrix_entries(c, f.D, code("D"));
  if (f.reads_derivatives) {
    s += code("    // y also reads dx/dt = M x + N u through E (the mesh forces of eq. 8).\n");
    s += fixed ? code("    OutputMatrix E;\n    E.setZero();\n") : code("    OutputMatrix E;\n    E.setZero(ny, nx);\n");
    s += matrix_entries(c, f.E, code("E"));
    s += code("    StateMatrix M;\n    InputMatrix N;\n    matrices(p, M, N);\n");
    s += code("    C.noalias() += E * M;\n    D.noalias() += E * N;\n");
  }
  return s + code("  }}\n\n");
}

}  // namespace

CppText operation_text(const OperationCount& c) {
  return code("{} operations ({} multiplications, {} additions)", integer_code(c.total()),
              integer_code(c.multiplications), integer_code(c.additions));
}

CppText system_struct(const SpecializedSystem& sys, const Scene& scene, const Derivation& d, const CppText& struct_name) {
  const std::size_t nx = sys.states.size(), nu = sys.inputs.size(), ny = sys.outputs.size();
  const bool fixed = fixed_sizes(sys);
  const SystemCode c{sys, d, &scene, body_variable_symbols(d.symbols), fixed};
  CppText s;
  s += code("// {}\n", comment_text(sys.equations));
  s += code("struct {} {{\n", struct_name);
  s += code("  static constexpr int nx = {}, nu = {}, ny = {};\n", index_code(nx), index_code(nu), index_code(ny));
  auto names = [&](const CppText& what, const std::vector<std::string>& v, const CppText& size) {
    s += code("  static constexpr std::array<std::string_view, {}> {}{{{}}};\n", size, what, literal_list(v));
  };
  names(code("state_names"), port_names(d.symbols, state_variables(sys)), code("nx"));
  names(code("state_units"), state_units(d.topology, sys), code("nx"));
  names(code("input_names"), port_names(d.symbols, input_variables(sys)), code("nu"));
  names(code("output_names"), port_names(d.symbols, output_variables(sys)), code("ny"));
  names(code("output_units"), output_units(d.topology, sys), code("ny"));
  s += types(fixed);

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
  for (const StatePort& x : sys.states) x0.push_back(number_code(x.initial));
  s += code("    x << {};\n    return x;\n  }}\n\n", join(x0, code(", ")));

  if (sys.implicit) {
    const ImplicitForm& f = *sys.implicit;
    s += code("  // L dx/dt = A x + B u, from the tunable parameters; L is symmetric positive definite.\n");
    s += code("  static void implicit_form([[maybe_unused]] const Params& p, StateMatrix& L, StateMatrix& A, "
              "InputMatrix& B) {{\n");
    s += aliases(c, symbols_in(entries({&f.L, &f.A, &f.B})), code("x"));
    s += fixed ? code("    L.setZero();\n    A.setZero();\n    B.setZero();\n")
               : code("    L.setZero(nx, nx);\n    A.setZero(nx, nx);\n    B.setZero(nx, nu);\n");
    s += matrix_entries(c, f.L, code("L")) + matrix_entries(c, f.A, code("A")) + matrix_entries(c, f.B, code("B"));
    s += code("  }}\n\n");
  }
  s += rhs_function(c) + outputs_function(c) + matrices_function(c);
  if (sys.nonlinear) {  // nothing to collect into C and D
    s += code("  // Nonlinear (a quadratic load): exact stepping, which needs dx/dt = M x + N u, is refused.\n"
              "  static constexpr bool nonlinear = true;\n\n");
    const auto nq = index_code(sys.quadratic_coefficients.size());
    s += code("  // The quadratic loads' torques TQ = -c s |s|, s = speeds x, and the columns through which they enter\n"
              "  // dx/dt: the hybrid runs (pogear/hybrid.hpp) take them as inputs that are functions of the state.\n");
    s += code("  static void quadratic_loads([[maybe_unused]] const Params& p, Eigen::MatrixXd& columns, "
              "Eigen::MatrixXd& speeds,\n                              Eigen::VectorXd& coefficients) {{\n");
    if (sys.implicit) {  // columns L^-1 Q
      const ImplicitForm& f = *sys.implicit;
      s += aliases(c, symbols_in(entries({&f.Q, &sys.quadratic_speeds})), code("x"));
      s += code("    StateMatrix L, A;\n    InputMatrix B;\n    implicit_form(p, L, A, B);\n");
      s += code("    Eigen::MatrixXd Q = Eigen::MatrixXd::Zero(nx, {});\n", nq);
      s += matrix_entries(c, f.Q, code("Q"));
      s += code("    columns = Eigen::LLT<StateMatrix>(L).solve(Q);\n    speeds.setZero({}, nx);\n    coefficients.resize({});\n",
                nq, nq);
    } else {
      s += aliases(c, symbols_in(entries({&sys.quadratic_columns, &sys.quadratic_speeds})), code("x"));
      s += code("    columns.setZero(nx, {});\n    speeds.setZero({}, nx);\n    coefficients.resize({});\n", nq, nq, nq);
      s += matrix_entries(c, sys.quadratic_columns, code("columns"));
    }
    s += matrix_entries(c, sys.quadratic_speeds, code("speeds"));
    for (std::size_t i = 0; i < sys.quadratic_coefficients.size(); ++i)
      s += code("    coefficients[{}] = {};\n", index_code(i), c.expression(sys.quadratic_coefficients[i]));
    s += code("  }}\n\n");
    if (!sys.driveline.empty()) s += driveline_function(c);
  } else {
    s += output_matrices_function(c);
  }

  if (!sys.limited_controllers.empty()) {
    s += code("  // Controllers with torque limits: the last {} inputs are their torques, whose laws T = X x + W u\n"
              "  // hold while they are within their limits (pogear/hybrid.hpp runs the events at the limits).\n",
              index_code(sys.limited_controllers.size()));
    s += code("  static void torque_limit_laws([[maybe_unused]] const Params& p, Eigen::MatrixXd& X, Eigen::MatrixXd& W) {{\n");
    s += code("    X.setZero({}, nx);\n    W.setZero({}, nu);\n", index_code(sys.limited_controllers.size()),
              index_code(sys.limited_controllers.size()));
    s += aliases(c, symbols_in(entries({&sys.limit_law_x, &sys.limit_law_u})), code("x"));
    s += matrix_entries(c, sys.limit_law_x, code("X")) + matrix_entries(c, sys.limit_law_u, code("W"));
    s += code("  }}\n\n");
  }
  if (!sys.friction_elements.empty() || !sys.limited_controllers.empty()) {
    s += code("  // Brakes and clutches: the {} inputs before any controller's are their torques (-T on an element's\n"
              "  // first body, +T on its second); their slips are s = S x. pogear/hybrid.hpp runs the modes of\n"
              "  // stick and slip.\n",
              index_code(sys.friction_elements.size()));
    s += code("  static void slip_matrix([[maybe_unused]] const Params& p, Eigen::MatrixXd& S) {{\n");
    s += aliases(c, symbols_in(entries({&sys.slip})), code("x"));
    s += code("    S.setZero({}, nx);\n", index_code(sys.friction_elements.size()));
    s += matrix_entries(c, sys.slip, code("S"));
    s += code("  }}\n\n");
  }
  // energy_matrix: what pogear/run_system.hpp checks a run against (see SpecializedSystem::L).
  if (sys.L.rows() == 0)
    return s + code("  // No energy bound: a speed controller feeds in power that no bound of the inputs limits.\n}};\n");
  s += code("  // The stored energy E = x^T L x / 2. The power balance bounds it by the initial energy and the\n"
            "  // inputs' work; a run that outgrows the bound has diverged (the runner checks each sample).\n");
  s += code("  static void energy_matrix([[maybe_unused]] const Params& p, StateMatrix& L) {{\n");
  s += aliases(c, symbols_in(entries({&sys.L})), code("x"));
  s += fixed ? code("    L.setZero();\n") : code("    L.setZero(nx, nx);\n");
  s += matrix_entries(c, sys.L, code("L"));
  s += code("  }}\n");
  s += code("}};\n");
  return s;
}

}  // namespace pogear
