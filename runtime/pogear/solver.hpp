// The integration methods a run can use, their names as scenes and command lines write them, and
// their options: decided here once for the scene reader, the generated simulators and pogear.
#pragma once

#include <algorithm>
#include <array>
#include <limits>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <vector>

#include "pogear/number_text.hpp"

namespace pogear::rt {

enum class Solver { exact, rk4, dopri5, implicit };

inline constexpr std::array<Solver, 4> all_solvers{Solver::exact, Solver::rk4, Solver::dopri5, Solver::implicit};

inline constexpr std::string_view solver_name(Solver s) {
  switch (s) {
    case Solver::exact: return "exact";
    case Solver::rk4: return "rk4";
    case Solver::dopri5: return "dopri5";
    case Solver::implicit: return "implicit";
  }
  return "exact";
}

inline constexpr std::optional<Solver> parse_solver(std::string_view name) {
  for (Solver s : all_solvers)
    if (solver_name(s) == name) return s;
  return std::nullopt;
}

// The names of the solvers of `list` joined by `separator`, in the order of all_solvers ("exact,
// dopri5"); without a list, all of them ("exact, rk4, dopri5, implicit"), for messages and usage lines.
inline std::string solver_names(std::span<const Solver> list, std::string_view separator) {
  std::string names;
  for (Solver s : all_solvers) {
    if (std::find(list.begin(), list.end(), s) == list.end()) continue;
    if (!names.empty()) names += separator;
    names += solver_name(s);
  }
  return names;
}
inline std::string solver_names(std::string_view separator) { return solver_names(all_solvers, separator); }

// What a system holds that some solvers cannot run: a quadratic load (no M and N to discretize, and
// no fixed step whose stability can be checked), and events (brakes or clutches engaged, controllers'
// torque limits), which rk4's fixed steps cannot locate.
struct SystemTraits {
  bool nonlinear = false;
  bool engages_friction = false;
  bool limits_torque = false;
  bool driveline = false;  // an engine or a converter, nonlinear whatever the loads
  bool slip_control = false;  // a slip controller: its element's heat is quadratic in the state
  bool friction_curve = false;  // friction that varies with slip: a slipping element's torque varies with the state
  bool actuator_lag = false;  // an actuator's first-order lag: an engagement exponential between breakpoints
};

// Why a solver cannot run a system: what the system holds (`cause`), and how that meets the solver
// (`reason`, which follows the cause after a comma). Each caller adds its own remedy.
struct SolverRefusal {
  std::string_view cause;   // "a quadratic load makes the scene nonlinear"
  std::string_view reason;  // "which exact stepping does not integrate"
};

inline std::string describe(const SolverRefusal& r) {
  std::string text(r.cause);
  text += ", ";
  text += r.reason;
  return text;
}

// The one decision of which solvers may run a system; nullopt when `s` can. Events refuse rk4 first;
// a nonlinear system (with events or without) is run by dopri5 and implicit.
inline constexpr std::optional<SolverRefusal> solver_refusal(Solver s, const SystemTraits& system) {
  const std::string_view nonlinear = system.driveline ? "an engine or a converter makes the scene nonlinear"
                                                      : "a quadratic load makes the scene nonlinear";
  if (system.engages_friction && s == Solver::rk4)
    return SolverRefusal{"the scene engages brakes or clutches",
                         "which rk4 does not simulate (its fixed steps cannot locate their events)"};
  if (system.limits_torque && s == Solver::rk4)
    return SolverRefusal{"a controller with torque limits switches at events",
                         "which rk4 does not locate (its fixed steps)"};
  if (system.nonlinear && s == Solver::exact) return SolverRefusal{nonlinear, "which exact stepping does not integrate"};
  if (system.slip_control && s == Solver::exact)
    return SolverRefusal{"a slip controller makes its element's heat quadratic in the state",
                         "which exact stepping does not integrate"};
  if (system.friction_curve && s == Solver::exact)
    return SolverRefusal{"a friction curve makes a slipping element's torque vary with its slip",
                         "which exact stepping does not integrate"};
  if (system.actuator_lag && s == Solver::exact)
    return SolverRefusal{"an actuator's lag makes its element's engagement exponential between the command's breakpoints",
                         "which exact stepping does not integrate"};
  if (system.nonlinear && s == Solver::rk4)
    return SolverRefusal{nonlinear, "which rk4's fixed step cannot be checked against its stability limit"};
  return std::nullopt;
}

// The solvers of `list` as a refusal's remedy offers them: "exact, dopri5 or implicit", or quoted as a
// scene writes them: "\"dopri5\" or \"implicit\"".
inline std::string solver_alternatives(std::span<const Solver> list, bool quoted) {
  std::string text;
  for (std::size_t i = 0; i < list.size(); ++i) {
    if (i > 0) text += i + 1 == list.size() ? " or " : ", ";
    const std::string name(solver_name(list[i]));
    text += quoted ? "\"" + name + "\"" : name;
  }
  return text;
}

// The solvers of all_solvers that can run the system, in that order.
inline std::vector<Solver> admissible_solvers(const SystemTraits& system) {
  std::vector<Solver> out;
  for (Solver s : all_solvers)
    if (!solver_refusal(s, system)) out.push_back(s);
  return out;
}

struct SolverOptions {
  double rtol = 1e-8, atol = 1e-10;
  double h = 1e-4;  // rk4 and exact: largest step; dopri5 and implicit: first step
  double h_max = std::numeric_limits<double>::infinity();
  long max_steps = 100000000;  // adaptive methods count rejected attempts too
};

// Scenes and command lines give one tolerance, the relative one; the absolute tolerance follows it
// two decades lower, so that states near zero (a body at rest) are held to about the same number
// of digits as the large ones, without a second setting to keep in step.
inline constexpr double absolute_per_relative_tolerance = 1e-2;

inline void set_tolerance(SolverOptions& options, double relative) {
  options.rtol = relative;
  options.atol = relative * absolute_per_relative_tolerance;
}

}  // namespace pogear::rt
