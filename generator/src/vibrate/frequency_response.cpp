// See frequency_response.hpp. jw I - H is upper Hessenberg, so Givens rotations make it upper
// triangular in O(n^2): unitary, hence backward stable, with no pivoting decision to get wrong.
#include "vibrate/frequency_response.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <optional>
#include <string>

#include <fmt/format.h>

#include "common/input_error.hpp"
#include "common/matrix_balancing.hpp"
#include "pogear/hybrid_modes.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

HessenbergSystem hessenberg_system(const NumericSystem& s, const MatrixErrors* errors) {
  return hessenberg_system(s, errors, balancing_scales(s.M));
}

HessenbergSystem hessenberg_system(const NumericSystem& s, const MatrixErrors* errors, const Eigen::VectorXd& d) {
  // Balanced first: D^-1 M D with D of powers of 2 is exact and has the same H, and the rounding
  // bounds below are normwise, so they are only as good as M's rows and columns are comparable. The
  // states mix speeds (rad/s) with mesh forces (N), whose rows of M are up to 1e9 times larger: an
  // unbalanced bound of 1e-6 |H| failed at every frequency on a vehicle driveline where the
  // balanced one holds with digits to spare.
  const Eigen::MatrixXd Mb = d.cwiseInverse().asDiagonal() * s.M * d.asDiagonal();
  const Eigen::HessenbergDecomposition<Eigen::MatrixXd> hd(Mb);
  const Eigen::MatrixXd Q = hd.matrixQ();
  HessenbergSystem out;
  out.H = hd.matrixH();
  out.N = Q.transpose() * (d.cwiseInverse().asDiagonal() * s.N);
  out.C = (s.C + s.E * s.M) * d.asDiagonal() * Q;
  out.D = s.D + s.E * s.N;
  out.norm_M = Mb.norm();
  out.error_N = Eigen::VectorXd::Zero(s.N.cols());
  out.error_C = Eigen::VectorXd::Zero(out.C.rows());
  out.error_D = Eigen::MatrixXd::Zero(out.D.rows(), out.D.cols());
  if (errors) {
    // The same balancing and unitary Q: 2-norms of columns (N) and rows (C) are Q's invariants.
    const Eigen::MatrixXd E = s.E.cwiseAbs();
    out.error_M = (d.cwiseInverse().asDiagonal() * errors->M * d.asDiagonal()).norm();
    out.error_N = (d.cwiseInverse().asDiagonal() * errors->N).colwise().norm().transpose();
    out.error_C = ((errors->C + E * errors->M) * d.asDiagonal()).rowwise().norm();
    out.error_D = errors->D + E * errors->N;
  }
  return out;
}

bool accurate(std::complex<double> h, double error) {
  const double m = std::abs(h);
  return std::isnormal(m) && std::isfinite(error) && error <= response_accuracy * m;
}

TransferValues transfer_matrix(const HessenbergSystem& s, double omega) {
  using cd = std::complex<double>;
  const Eigen::Index n = s.H.rows();
  Eigen::MatrixXcd A = -s.H.cast<cd>();
  A.diagonal().array() += cd(0, omega);
  const double norm_A = A.norm();
  Eigen::MatrixXcd X = s.N.cast<cd>();
  for (Eigen::Index k = 0; k + 1 < n; ++k) {
    const cd a = A(k, k), b = A(k + 1, k);
    const double r = std::hypot(std::abs(a), std::abs(b));
    if (r == 0) continue;
    const cd c = a / r, sn = b / r;  // [conj(c) conj(s); -s c] [a; b] = [r; 0]
    for (Eigen::Index j = k; j < n; ++j) {
      const cd u = A(k, j), v = A(k + 1, j);
      A(k, j) = std::conj(c) * u + std::conj(sn) * v;
      A(k + 1, j) = -sn * u + c * v;
    }
    for (Eigen::Index j = 0; j < X.cols(); ++j) {
      const cd u = X(k, j), v = X(k + 1, j);
      X(k, j) = std::conj(c) * u + std::conj(sn) * v;
      X(k + 1, j) = -sn * u + c * v;
    }
  }
  A.triangularView<Eigen::Upper>().solveInPlace(X);
  const Eigen::MatrixXcd C = s.C.cast<cd>();
  // Y = C R^-1 (rows), from R^T Y^T = C^T: |C (jwI - M)^-1| = |Y|, the Givens factor being unitary.
  const Eigen::MatrixXcd Yt = A.transpose().triangularView<Eigen::Lower>().solve(C.transpose());
  TransferValues out;
  out.H = C * X + s.D.cast<cd>();
  const double gamma = 8 * static_cast<double>(std::max<Eigen::Index>(n, 1)) * std::numeric_limits<double>::epsilon();
  const Eigen::MatrixXd terms = s.C.cwiseAbs() * X.cwiseAbs() + s.D.cwiseAbs();
  out.error.resize(out.H.rows(), out.H.cols());
  for (Eigen::Index o = 0; o < out.H.rows(); ++o)
    for (Eigen::Index i = 0; i < out.H.cols(); ++i)
      out.error(o, i) = gamma * ((norm_A + s.norm_M) * Yt.col(o).norm() * X.col(i).norm() + terms(o, i)) +
                        Yt.col(o).norm() * (s.error_M * X.col(i).norm() + s.error_N(i)) +
                        s.error_C(o) * X.col(i).norm() + s.error_D(o, i);
  return out;
}

namespace {

std::vector<double> log_grid(const FrequencyGrid& g) {
  std::vector<double> f(g.points);
  const double a = std::log(g.from_hz), b = std::log(g.to_hz);
  for (int i = 0; i < g.points; ++i)
    f[i] = g.points == 1 ? g.from_hz : std::exp(a + (b - a) * i / (g.points - 1));
  if (g.points > 1) f.back() = g.to_hz;
  return f;
}

// The maximum of |H| between grid points f0 < f1 < f2 with |H(f1)| the largest of the three:
// golden section in log f, to a bracket of 1e-12 relative.
double refine_peak(const HessenbergSystem& s, int out, int in, double f0, double f2) {
  auto mag = [&](double logf) { return std::abs(transfer_matrix(s, 2 * std::numbers::pi * std::exp(logf)).H(out, in)); };
  const double g = (std::sqrt(5.0) - 1) / 2;
  double a = std::log(f0), b = std::log(f2);
  double x1 = b - g * (b - a), x2 = a + g * (b - a);
  double m1 = mag(x1), m2 = mag(x2);
  while (b - a > 1e-12) {
    if (m1 < m2) {
      a = x1, x1 = x2, m1 = m2;
      x2 = a + g * (b - a), m2 = mag(x2);
    } else {
      b = x2, x2 = x1, m2 = m1;
      x1 = b - g * (b - a), m1 = mag(x1);
    }
  }
  return std::exp((a + b) / 2);
}

// "rad/s" -> "(rad/s)", "N m" -> "(N m)", "N" -> "N": a unit of H reads (rad/s)/(N m).
std::string unit_text(const Topology& topology, Variable v) {
  const std::string u(unit_of(topology, v));
  return u.find_first_of("/ ") == std::string::npos ? u : "(" + u + ")";
}

// The system the response is of: the specialized one, or, when it has engaged brakes and clutches
// or torque-limited controllers, its mode with every element stuck and every controller within its
// limits (hybrid_modes.hpp): dx/dt = A x + B u, and the elements' and controllers' torques
// T = Kx x + Kv u folded into the outputs, which read them as inputs.
struct AnalysedSystem {
  NumericSystem system;
  std::optional<MatrixErrors> errors;  // of a mode's matrices
  Eigen::VectorXd balance;             // the scales that balance the system's M
};

AnalysedSystem analysed_system(const SpecializedScene& model, const SpecializedSystem& sys) {
  NumericSystem ns = numeric_system(model, sys);
  const auto nu = static_cast<Eigen::Index>(input_signals(sys).size());
  const auto ne = static_cast<Eigen::Index>(sys.friction_elements.size() + sys.limited_controllers.size());
  if (ne == 0) {
    Eigen::VectorXd d = balancing_scales(ns.M);
    return {std::move(ns), std::nullopt, std::move(d)};
  }
  const rt::hybrid_detail::ModeMatrices m =
      rt::hybrid_detail::mode_matrices(hybrid_system(model, sys, ns), (std::uint32_t{1} << ne) - 1);
  if (m.singular) {
    std::string names;
    for (const FrictionRun& f : model.friction) names += (names.empty() ? "" : ", ") + f.name;
    throw InputError(SourceLocation{model.scene.file, 0, 0},
                     m.ill_conditioned
                         ? fmt::format("the engaged elements {} join bodies of inertias too disparate for double "
                                       "precision to determine their torques; check the inertias", names)
                         : fmt::format("the engaged elements {} constrain the gear more than once (their torques are "
                                       "undetermined); engage fewer of them",
                                       names));
  }
  // m.stuck lists the elements, then the controllers: the order of their torque columns.
  const Eigen::MatrixXd Dt = ns.D.middleCols(nu, ne), Nt = ns.N.middleCols(nu, ne);
  NumericSystem out;
  out.M = m.A;
  out.N = m.B.leftCols(nu);
  out.C = ns.C + Dt * m.Kx;
  out.D = ns.D.leftCols(nu) + Dt * m.Kv.leftCols(nu);
  out.E = ns.E;
  // Each entry is a sum of products of the system's entries with the torques' gains, rounded: a few
  // ulps of the sum of their magnitudes. An entry that is zero in exact arithmetic (a locked gear's
  // B) comes out as that rounding, and the bound keeps it from being read as a response.
  const double gamma = 8 * static_cast<double>(ns.M.rows() + ne) * std::numeric_limits<double>::epsilon();
  const Eigen::MatrixXd Kx = m.Kx.cwiseAbs(), Kv = m.Kv.leftCols(nu).cwiseAbs();
  MatrixErrors e;
  e.M = gamma * (ns.M.cwiseAbs() + Nt.cwiseAbs() * Kx);
  e.N = gamma * (ns.N.leftCols(nu).cwiseAbs() + Nt.cwiseAbs() * Kv);
  e.C = gamma * (ns.C.cwiseAbs() + Dt.cwiseAbs() * Kx);
  e.D = gamma * (ns.D.leftCols(nu).cwiseAbs() + Dt.cwiseAbs() * Kv);
  // Balanced as the system's M, not as A: a stuck body's row of A is zero in exact arithmetic, and
  // balancing A would scale its rounding up without limit.
  return {std::move(out), std::move(e), balancing_scales(ns.M)};
}

}  // namespace

Scene response_scene(const Scene& scene, const std::vector<Variable>& inputs, const std::vector<Variable>& outputs,
                     const std::vector<int>& engaged) {
  // Unit inputs on the asked bodies and the asked outputs: the specialization gives N, C, D, E for
  // exactly these (a zero input would not be an input).
  Scene s = scene;
  s.inputs.clear();
  for (const Variable u : inputs) s.inputs.push_back(InputSpec{u.index, rt::Constant{1}, {}, std::nullopt});
  s.outputs = outputs;
  // The engaged elements stuck throughout, the others open (out of the equations).
  s.engagement.clear();
  for (const int k : engaged) s.engagement.push_back(EngagementSpec{k, rt::Constant{1}, {}, std::nullopt});
  return s;
}

std::vector<TransferFunction> frequency_response(const Scene& scene, const std::vector<Variable>& inputs,
                                                 const std::vector<Variable>& outputs, const FrequencyGrid& grid,
                                                 const std::vector<int>& engaged) {
  Scene s = response_scene(scene, inputs, outputs, engaged);
  for (const Variable y : outputs)
    s.effects.mesh_forces = s.effects.mesh_forces || y.kind == VariableKind::force || y.kind == VariableKind::spring_force;
  s.compare_rigid = s.effects.elastic();
  s.tunable.clear();
  s.start = Start::given;      // the response is of the system, from any state
  s.speeds_in_rpm = false;     // transfer functions in SI
  const SpecializedScene model = specialize(s);
  const AnalysedSystem main_system = analysed_system(model, model.main);
  const HessenbergSystem main = hessenberg_system(main_system.system, main_system.errors ? &*main_system.errors : nullptr,
                                                  main_system.balance);
  std::optional<HessenbergSystem> rigid;
  if (model.rigid) {
    const AnalysedSystem r = analysed_system(model, *model.rigid);
    rigid = hessenberg_system(r.system, r.errors ? &*r.errors : nullptr, r.balance);
  }

  const std::vector<double> f = log_grid(grid);
  const std::size_t nu = inputs.size(), ny = outputs.size();
  std::vector<TransferFunction> out(nu * ny);
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t o = 0; o < ny; ++o) {
      TransferFunction& t = out[i * ny + o];
      t.input = inputs[i], t.output = outputs[o];
      t.input_name = variable_name(model.derivation.symbols, t.input);
      t.output_name = variable_name(model.derivation.symbols, t.output);
      t.unit = unit_text(model.derivation.topology, t.output) + "/" + unit_text(model.derivation.topology, t.input);
      t.frequency_hz = f;
    }
  const bool undamped = !s.effects.mesh_damping && !s.effects.shaft_damping && !s.effects.bearing_friction;
  for (const double fk : f) {
    const double w = 2 * std::numbers::pi * fk;
    const TransferValues h = transfer_matrix(main, w);
    TransferValues hr;
    if (rigid) hr = transfer_matrix(*rigid, w);
    for (std::size_t i = 0; i < nu; ++i)
      for (std::size_t o = 0; o < ny; ++o) {
        TransferFunction& t = out[i * ny + o];
        t.undamped = undamped;
        t.value.push_back(h.H(o, i));
        t.accurate.push_back(accurate(h.H(o, i), h.error(o, i)));
        if (!rigid) continue;
        t.rigid.push_back(hr.H(o, i));
        t.rigid_accurate.push_back(accurate(hr.H(o, i), hr.error(o, i)));
      }
  }
  if (undamped) {
    // The resonances are poles at the natural frequencies: each one a pair whose output sees it
    // shows |H| growing as 1/distance (10^4 times from 1e-3 to 1e-7 away); a mode the input does
    // not excite, or the output does not see, leaves |H| flat there.
    const Eigen::VectorXcd poles = Eigen::EigenSolver<Eigen::MatrixXd>(balanced(main_system.system.M), false).eigenvalues();
    std::vector<double> natural;
    for (Eigen::Index k = 0; k < poles.size(); ++k) {
      const double fn = poles(k).imag() / (2 * std::numbers::pi);
      if (poles(k).imag() > 0 && fn >= grid.from_hz && fn <= grid.to_hz) natural.push_back(fn);
    }
    std::sort(natural.begin(), natural.end());
    for (const double fn : natural) {
      const TransferValues near = transfer_matrix(main, 2 * std::numbers::pi * fn * (1 + 1e-7));
      const TransferValues off = transfer_matrix(main, 2 * std::numbers::pi * fn * (1 + 1e-3));
      for (std::size_t i = 0; i < nu; ++i)
        for (std::size_t o = 0; o < ny; ++o)
          if (std::abs(near.H(o, i)) > 100 * std::abs(off.H(o, i)))
            out[i * ny + o].peaks.push_back(ResonancePeak{fn, std::numeric_limits<double>::infinity(), std::nullopt});
    }
    return out;
  }
  for (std::size_t i = 0; i < nu; ++i)
    for (std::size_t o = 0; o < ny; ++o) {
      TransferFunction& t = out[i * ny + o];
      for (std::size_t k = 1; k + 1 < f.size(); ++k) {
        if (!t.accurate[k - 1] || !t.accurate[k] || !t.accurate[k + 1]) continue;
        // A rise within the values' accuracy is rounding on a flat stretch, not a resonance.
        const double m0 = std::abs(t.value[k - 1]), m1 = std::abs(t.value[k]), m2 = std::abs(t.value[k + 1]);
        if (!(m1 > m0 * (1 + response_accuracy) && m1 > m2 * (1 + response_accuracy))) continue;
        ResonancePeak p;
        p.frequency_hz = refine_peak(main, static_cast<int>(o), static_cast<int>(i), f[k - 1], f[k + 1]);
        const double w = 2 * std::numbers::pi * p.frequency_hz;
        const TransferValues h = transfer_matrix(main, w);
        if (!accurate(h.H(o, i), h.error(o, i))) continue;
        p.magnitude = std::abs(h.H(o, i));
        if (rigid) {
          const TransferValues hr = transfer_matrix(*rigid, w);
          if (accurate(hr.H(o, i), hr.error(o, i))) p.over_rigid = p.magnitude / std::abs(hr.H(o, i));
        }
        t.peaks.push_back(p);
      }
    }
  return out;
}

}  // namespace pogear
