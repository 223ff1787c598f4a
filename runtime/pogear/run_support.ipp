// The definitions of run_support.hpp: compiled into libpogear_runtime (runtime/src/run_support.cpp),
// or included inline by run_support.hpp under POGEAR_RT_HEADER_ONLY.
#include <algorithm>
#include <chrono>
#include <complex>
#include <cstdio>

#include "pogear/command_line.hpp"
#include "pogear/csv.hpp"
#include "pogear/exact.hpp"
#include "pogear/parameters.hpp"
#include "pogear/run_support.hpp"
#include "pogear/stability_limit.hpp"

namespace pogear::rt {

namespace detail {
// The largest |u(t)| of a signal over [t0, t1]: a sine's offset plus its amplitude; every other
// signal is linear between its breakpoints, so its extremes are at the ends and on either side of a
// breakpoint.
inline double input_bound(const Signal& s, double t0, double t1) {
  if (const auto* sine = std::get_if<Sine>(&s)) return std::abs(sine->offset) + std::abs(sine->amplitude);
  if (const auto* g = std::get_if<GradeLoad>(&s)) return std::hypot(g->sine, g->cosine);
  double m = std::max(std::abs(value(s, t0)), std::abs(value(s, t1)));
  for (double b : breakpoints(s, t0, t1))
    m = std::max({m, std::abs(value(s, b)), std::abs(value(s, std::nextafter(b, t0)))});
  return m;
}

inline double seconds_now() {
  return std::chrono::duration<double>(std::chrono::steady_clock::now().time_since_epoch()).count();
}
}  // namespace detail

POGEAR_RT_ABI_BEGIN

POGEAR_RT_API int read_command_line(int argc, char** argv, SceneRun& run, std::span<const Solver> compiled) {
  if (!parse_command_line(argc, argv, run, compiled)) return 1;
  if (!run.help) return -1;
  for (const std::string& line : usage_lines(argv[0], 100, compiled)) std::printf("%s\n", line.c_str());
  std::printf("Simulates the scene %s; compiled with the solver%s %s (the scene's: %s).\n", run.name.c_str(),
              compiled.size() == 1 ? "" : "s", solver_names(compiled, ", ").c_str(),
              std::string(solver_name(run.solver)).c_str());
  return 0;
}

POGEAR_RT_API bool set_parameters(const std::vector<std::pair<std::string, std::string>>& given,
                           const std::vector<ParameterField>& fields, const char* program) {
  auto fail = [&](const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
    return false;
  };
  std::string names;
  for (const ParameterField& f : fields) names += (names.empty() ? "" : ", ") + std::string(f.name);
  for (const auto& [name, text] : given) {
    const ParameterField* field = nullptr;
    for (const ParameterField& f : fields)
      if (f.name == name) field = &f;
    if (!field)
      return fail(fields.empty()
                      ? "--param " + name + ": this simulator has no tunable parameters; list the parameters to set "
                            "at run time in the scene's tunable = [...] and generate it again"
                      : "--param " + name + ": no tunable parameter has this name; the tunable parameters are " + names);
    std::string accepted = "a number in SI units";
    for (const ParameterUnit& u : field->units) accepted += ", or NUMBER*" + std::string(u.unit);
    const std::optional<double> v = parameter_value(text, *field);
    if (!v) return fail("--param " + name + "=" + text + " is not a value; give " + accepted);
    if ((field->sign == "positive" && !(*v > 0)) || (field->sign == "non-negative" && !(*v >= 0)))
      return fail("--param " + name + "=" + text + ": " + name + " must be " + std::string(field->sign) +
                  "; give " + accepted);
    if (*v != 0 && !(std::abs(*v) >= kSmallestParameter && std::abs(*v) <= kLargestParameter))
      return fail("--param " + name + "=" + text + " is outside the range pogear computes with, " +
                  detail::num(kSmallestParameter) + " to " + detail::num(kLargestParameter) +
                  " in magnitude (SI); check the value and its unit");
    *field->value = *v;
  }
  return true;
}


POGEAR_RT_API ExactMatrices exact_matrices(const Eigen::MatrixXd& M, const Eigen::MatrixXd& N, double h,
                                           Eigen::Index measured_rows) {
  ExactDiscretization<Eigen::Dynamic, Eigen::Dynamic> d(M, N, h, measured_rows);
  return {std::move(d.Phi), std::move(d.Gamma0), std::move(d.Gamma1), d.rounding};
}

POGEAR_RT_API EnergyBoundTerms energy_bound_terms(const Eigen::MatrixXd& L, const Eigen::MatrixXd& N,
                                                  const std::vector<Signal>& signals, const Eigen::VectorXd& x0,
                                                  double horizon) {
  EnergyBoundTerms terms;
  terms.root_e0 = std::sqrt(std::max(0.0, 0.5 * x0.dot(L * x0)));
  double w = 0;
  for (Eigen::Index i = 0; i < N.cols(); ++i)
    w += std::sqrt(std::max(0.0, N.col(i).dot(L * N.col(i)))) *
         detail::input_bound(signals[static_cast<std::size_t>(i)], 0.0, horizon);
  terms.rate = w / std::sqrt(2.0);
  return terms;
}

POGEAR_RT_API double rk4_step_limit(const Eigen::MatrixXd& M) { return rk4_stability_limit(M); }
POGEAR_RT_API double event_step_limit(const Eigen::MatrixXd& A) { return event_check_step(A); }

POGEAR_RT_API ModalForm modal_form(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B) {
  ModalForm f;
  if (A.rows() == 0) return f;
  const Eigen::EigenSolver<Eigen::MatrixXd> es(A, true);
  if (es.info() != Eigen::Success) return f;
  f.lambda = es.eigenvalues();
  f.V = es.eigenvectors();
  const Eigen::PartialPivLU<Eigen::MatrixXcd> lu(f.V);
  f.W = lu.inverse();
  // A defective or nearly defective A has no trustworthy modal coordinates: their amplitudes would
  // be huge and cancel. 1e8 keeps a bound built on them within 1e-8 of the state's size.
  const double condition = f.V.cwiseAbs().rowwise().sum().maxCoeff() * f.W.cwiseAbs().rowwise().sum().maxCoeff();
  f.ok = f.W.allFinite() && condition < 1e8;
  f.WB = f.W * B.cast<std::complex<double>>();
  return f;
}

POGEAR_RT_API SystemRunLog::SystemRunLog(const SceneRun& run, const std::string& suffix,
                                         const std::vector<std::string>& names, const std::vector<std::string>& units)
    : run_(run), label_(run.name + suffix), columns_{"t [s]"} {
  for (std::size_t i = 0; i < names.size() && i < units.size(); ++i) columns_.push_back(names[i] + " [" + units[i] + "]");
}

POGEAR_RT_API SystemRunLog::~SystemRunLog() = default;

POGEAR_RT_API bool SystemRunLog::rk4_step_stable(const Eigen::MatrixXd& M) const {
  const double limit = rk4_stability_limit(M);
  if (run_.options.h <= limit) return true;
  std::fprintf(stderr,
               "%s: error: rk4 step %g s is above its stability limit %g s for this scene (fastest mode); "
               "use --step %g or smaller, or --solver exact or implicit\n",
               label_.c_str(), run_.options.h, limit, 0.9 * limit);
  return false;
}

POGEAR_RT_API bool SystemRunLog::begin() {
  csv_.reset();
  diverged_.clear();
  if (run_.csv) {
    csv_ = std::make_unique<CsvWriter>(run_.out_dir + "/" + label_ + ".csv", columns_);
    if (!csv_->ok()) {
      std::fprintf(stderr, "%s: error: %s\n", label_.c_str(), csv_->error().c_str());
      return false;
    }
  }
  start_ = detail::seconds_now();
  return true;
}

POGEAR_RT_API void SystemRunLog::row(double t, const double* y, long n) {
  csv_->field(t);
  for (long i = 0; i < n; ++i) csv_->field(y[i]);
  csv_->end_row();
}

POGEAR_RT_API std::string divergence_advice(Solver solver, bool linear) {
  switch (solver) {
    case Solver::rk4: return linear ? "use a smaller --step, or --solver exact or implicit" : "use --solver implicit";
    case Solver::dopri5:
      return linear ? "use a tighter --tolerance, or --solver exact or implicit"
                    : "use a tighter --tolerance, or --solver implicit";
    case Solver::implicit: return linear ? "use a tighter --tolerance, or --solver exact" : "use a tighter --tolerance";
    case Solver::exact: break;
  }
  return "exact stepping is stable at any step, so the growth is rounding: check the parameters for values far "
         "from the gear's (--param, [parameters]) and the stiffness ratio `pogear derive` reports";
}

POGEAR_RT_API void SystemRunLog::diverged(double t, double ratio, bool linear) {
  char times[32];
  std::snprintf(times, sizeof times, "%.3g", ratio * ratio);
  diverged_ = "the solution diverged at t = " + detail::num(t) + ": its energy is " + times +
              " times what the initial state and the inputs can supply; " + divergence_advice(run_.solver, linear);
}

POGEAR_RT_API bool SystemRunLog::end(RunStatus& st) {
  if (!diverged_.empty()) st.message = diverged_;
  if (csv_) {
    if (st.ok ? !csv_->commit() : !csv_->commit_incomplete(st.message)) {
      std::fprintf(stderr, "%s: error: %s\n", label_.c_str(), csv_->error().c_str());
      return false;
    }
  }
  seconds_.push_back(detail::seconds_now() - start_);
  return true;
}

POGEAR_RT_API int SystemRunLog::finish(const RunStatus& st) const {
  if (!st.ok) {
    std::fprintf(stderr, "%s: error: %s%s\n", label_.c_str(), st.message.c_str(),
                 run_.csv ? "; the CSV keeps what was computed and is marked incomplete" : "");
    return 3;
  }
  std::vector<double> seconds = seconds_;
  std::sort(seconds.begin(), seconds.end());
  if (!run_.quiet)
    std::printf("%s: %s, %ld steps, %ld rhs evaluations, %.6g s wall (median of %d)%s\n", label_.c_str(),
                std::string(solver_name(run_.solver)).c_str(), st.steps, st.rhs_evals,
                seconds.empty() ? 0.0 : seconds[seconds.size() / 2], run_.repeat,
                run_.csv ? (", wrote " + run_.out_dir + "/" + label_ + ".csv").c_str() : "");
  return 0;
}

POGEAR_RT_ABI_END

}  // namespace pogear::rt
