// What a simulator's run needs that does not depend on the model's size: its command line, CSV
// files, messages and timing, and the exact method's matrix exponential and the rk4 limit on matrices
// of any size. Compiled once into libpogear_runtime, so that a generated simulator compiles only its
// model's code; a program that defines POGEAR_RT_HEADER_ONLY before including gets it inline instead
// (and must then not link libpogear_runtime).
#pragma once

#include <Eigen/Core>
#include <memory>
#include <span>
#include <string>
#include <vector>

#include "pogear/api.hpp"
#include "pogear/driver_loops.hpp"
#include "pogear/scene_run.hpp"
#include "pogear/signals.hpp"
#include "pogear/solver.hpp"


namespace pogear::rt {

class CsvWriter;

POGEAR_RT_ABI_BEGIN

// Reads a generated simulator's command line into `run` (parse_command_line, with the solvers it was
// compiled with). Returns -1 when the simulator should run, else its exit status: 0 after --help
// (usage and solvers printed), 1 after a usage error (printed).
POGEAR_RT_API int read_command_line(int argc, char** argv, SceneRun& run, std::span<const Solver> compiled);

// The exact method's matrices for steps of h (ExactDiscretization's), and the estimate of their
// relative rounding error over the first measured_rows states (all by default).
struct ExactMatrices {
  Eigen::MatrixXd Phi, Gamma0, Gamma1;
  double rounding = 0;
};
POGEAR_RT_API ExactMatrices exact_matrices(const Eigen::MatrixXd& M, const Eigen::MatrixXd& N, double h,
                                           Eigen::Index measured_rows = -1);

// The constant terms of the energy bound of a run (EnergyBound, run_system.hpp): sqrt(E(x0)) with
// E(x) = x^T L x / 2, and W / sqrt(2) with W = sum_i |N e_i|_L max over [0, horizon] of |u_i|.
struct EnergyBoundTerms {
  double root_e0 = 0, rate = 0;
};
POGEAR_RT_API EnergyBoundTerms energy_bound_terms(const Eigen::MatrixXd& L, const Eigen::MatrixXd& N,
                                                  const std::vector<Signal>& signals, const Eigen::VectorXd& x0,
                                                  double horizon);

// rk4_stability_limit (stability_limit.hpp) of M.
POGEAR_RT_API double rk4_step_limit(const Eigen::MatrixXd& M);
// event_check_step (stability_limit.hpp) of A.
POGEAR_RT_API double event_step_limit(const Eigen::MatrixXd& A);

// A = V diag(lambda) W with W = V^-1, when A is diagonalizable with a well-conditioned V (ok), and
// W B: the modal coordinates xi = W x of dx/dt = A x + B v obey xi' = lambda xi + W B v, one by one.
struct ModalForm {
  bool ok = false;
  Eigen::VectorXcd lambda;
  Eigen::MatrixXcd V, W, WB;
};
POGEAR_RT_API ModalForm modal_form(const Eigen::MatrixXd& A, const Eigen::MatrixXd& B);

// What to do about a run whose energy exceeded what the passive gear can hold, for the solver that
// ran it: a step or tolerance for the integrators; for exact stepping, which is stable at any step,
// the parameters, since only rounding of extreme values makes it grow. `linear`: exact stepping can
// run the system (no quadratic load), so it may be offered.
POGEAR_RT_API std::string divergence_advice(Solver solver, bool linear = true);

// One system's run around its driver: the rk4 step check, the CSV file of each repetition, the
// divergence message, the timing and the closing report or error, all under the label
// SCENE<suffix> and into OUT/SCENE<suffix>.csv.
class SystemRunLog {
 public:
  // The outputs' names and units head the CSV's columns.
  POGEAR_RT_API SystemRunLog(const SceneRun& run, const std::string& suffix, const std::vector<std::string>& names,
                             const std::vector<std::string>& units);
  POGEAR_RT_API ~SystemRunLog();
  SystemRunLog(const SystemRunLog&) = delete;
  SystemRunLog& operator=(const SystemRunLog&) = delete;

  // Whether rk4's step is within its stability limit for M; prints the error if not.
  POGEAR_RT_API bool rk4_step_stable(const Eigen::MatrixXd& M) const;
  // Before each repetition: opens its CSV file (with --no-csv, none). False after printing an error.
  POGEAR_RT_API bool begin();
  bool writes_csv() const { return csv_ != nullptr; }
  POGEAR_RT_API void row(double t, const double* y, long n);
  // The run diverged at t, with sqrt(E) `ratio` times the bound: the run's message from now on
  // (`linear`: as divergence_advice's).
  POGEAR_RT_API void diverged(double t, double ratio, bool linear = true);
  // After each repetition: commits the CSV file (marked incomplete if the run failed) and records
  // the time. False after printing an error.
  POGEAR_RT_API bool end(RunStatus& st);
  // The exit status of the system's runs: 0 (the report printed unless --quiet), or 3 after
  // printing why the run failed.
  POGEAR_RT_API int finish(const RunStatus& st) const;

 private:
  const SceneRun& run_;
  std::string label_;
  std::vector<std::string> columns_;
  std::unique_ptr<CsvWriter> csv_;
  std::string diverged_;
  std::vector<double> seconds_;
  double start_ = 0;
};

POGEAR_RT_ABI_END

}  // namespace pogear::rt

#if defined(POGEAR_RT_HEADER_ONLY)
#include "pogear/run_support.ipp"
#endif
