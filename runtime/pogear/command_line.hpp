// What a run of a scene is set to (SceneRun) and the generated simulators' command line that sets
// it: one table of options, from which the parser, its messages, pogear's call of a compiled
// simulator (command_line) and the generated main's usage comment all come.
#pragma once

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <optional>
#include <span>
#include <string>
#include <string_view>
#include <system_error>
#include <utility>
#include <vector>

#include "pogear/number_text.hpp"
#include "pogear/run_limits.hpp"
#include "pogear/scene_run.hpp"
#include "pogear/solver.hpp"

namespace pogear::rt {

enum class OptionKey { solver, tolerance, step, out, repeat, max_steps, param, no_csv, quiet, help };

struct SimulatorOption {
  OptionKey key;
  std::string name;   // "--solver"
  std::string value;  // what it takes, as the usage line writes it; empty for a flag
};

// The generated simulators' options, in the order messages and the usage line list them; `--solver`
// offers the solvers compiled into the simulator.
inline std::vector<SimulatorOption> simulator_options(std::span<const Solver> compiled = all_solvers) {
  return {{OptionKey::solver, "--solver", solver_names(compiled, "|")},
          {OptionKey::tolerance, "--tolerance", "R"},
          {OptionKey::step, "--step", "S"},
          {OptionKey::out, "--out", "DIR"},
          {OptionKey::repeat, "--repeat", "N"},
          {OptionKey::max_steps, "--max-steps", "N"},
          {OptionKey::param, "--param", "NAME=VALUE"},
          {OptionKey::no_csv, "--no-csv", ""},
          {OptionKey::quiet, "--quiet", ""},
          {OptionKey::help, "--help", ""}};
}

// "[--solver exact|rk4|dopri5|implicit]", "[--no-csv]": one option of the usage line.
inline std::string option_synopsis(const SimulatorOption& o) {
  return "[" + o.name + (o.value.empty() ? "" : " " + o.value) + "]";
}

// "PROGRAM [--solver ...] ...": the usage line, wrapped before `width` characters; continuation
// lines are indented under the first option.
inline std::vector<std::string> usage_lines(const std::string& program, std::size_t width,
                                            std::span<const Solver> compiled = all_solvers) {
  std::vector<std::string> lines{"Usage: " + program};
  const std::string indent(lines[0].size(), ' ');
  for (const SimulatorOption& o : simulator_options(compiled)) {
    const std::string item = option_synopsis(o);
    if (lines.back().size() + 1 + item.size() > width && lines.back().size() > indent.size()) lines.push_back(indent);
    lines.back() += " " + item;
  }
  return lines;
}

// The arguments that make parse_command_line set `run`'s options (not its name, horizon and
// sample: those are the scene's, compiled into the simulator).
inline std::vector<std::string> command_line(const SceneRun& run) {
  std::vector<std::string> args;
  for (const SimulatorOption& o : simulator_options()) {
    switch (o.key) {
      case OptionKey::solver: args.insert(args.end(), {o.name, std::string(solver_name(run.solver))}); break;
      case OptionKey::tolerance: args.insert(args.end(), {o.name, detail::shortest(run.options.rtol)}); break;
      case OptionKey::step: args.insert(args.end(), {o.name, detail::shortest(run.options.h)}); break;
      case OptionKey::out: args.insert(args.end(), {o.name, run.out_dir}); break;
      case OptionKey::repeat: args.insert(args.end(), {o.name, std::to_string(run.repeat)}); break;
      case OptionKey::max_steps: args.insert(args.end(), {o.name, std::to_string(run.options.max_steps)}); break;
      case OptionKey::param:
        for (const auto& [name, value] : run.params) args.insert(args.end(), {o.name, name + "=" + value});
        break;
      case OptionKey::no_csv:
        if (!run.csv) args.push_back(o.name);
        break;
      case OptionKey::quiet:
        if (run.quiet) args.push_back(o.name);
        break;
      case OptionKey::help: break;
    }
  }
  return args;
}

// Reads the generated simulator's options into `run`; on bad usage prints
// `PROGRAM: error: what; what to do` and returns false (the caller exits with 1). Every number
// must be all of its argument and inside the ranges of run_limits.hpp, which the scene file obeys too.
// `compiled` are the solvers the simulator has; --solver refuses the others. --help sets run.help.
inline bool parse_command_line(int argc, char** argv, SceneRun& run, std::span<const Solver> compiled = all_solvers) {
  const char* program = argv[0];
  auto usage_error = [&](const std::string& message) {
    std::fprintf(stderr, "%s: error: %s\n", program, message.c_str());
    return false;
  };
  // A number in [lo, hi]; `what` says what the option takes, for the message.
  auto number = [&](const std::string& option, const char* text, double lo, double hi, const std::string& what,
                    bool whole, double& out) {
    const std::optional<double> v = detail::parse_finite(text);
    if (!v) return usage_error(option + " '" + text + "' is not a finite number; give " + what);
    if (!(*v >= lo && *v <= hi) || (whole && *v != std::floor(*v)))
      return usage_error(option + " " + text + " is out of range; give " + what);
    out = *v;
    return true;
  };
  const std::string tolerance_range = "a relative tolerance from " + detail::num(limits::min_tolerance) + " to " +
                                      detail::num(limits::max_tolerance) + ", e.g. 1e-8";
  const std::string step_range = "a step in seconds as a plain number (no unit), from " +
                                 detail::num(limits::min_step) + " to " + detail::num(limits::max_step) +
                                 ", e.g. 5e-05";
  const std::string max_steps_range = "a whole number from " + std::to_string(limits::min_max_steps) + " to " +
                                      std::to_string(limits::max_max_steps) + ", e.g. 10000000";
  const std::string repeat_range = "a whole number from 1 to " + std::to_string(limits::max_repeat) + ", e.g. 10";
  const std::vector<SimulatorOption> options = simulator_options(compiled);
  std::optional<std::string> solver_given;  // checked once every option is read, as it always was
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    const SimulatorOption* option = nullptr;
    for (const SimulatorOption& o : options)
      if (o.name == a) option = &o;
    if (!option) {
      std::string names;
      for (const SimulatorOption& o : options) names += (names.empty() ? "" : ", ") + o.name;
      return usage_error("unknown option '" + a + "'; options are " + names);
    }
    const bool takes_value = !option->value.empty();
    if (takes_value && i + 1 >= argc) return usage_error(a + " needs a value");
    const char* v = takes_value ? argv[++i] : nullptr;
    double x = 0;
    switch (option->key) {
      case OptionKey::solver: solver_given = v; break;
      case OptionKey::tolerance:
        if (!number(a, v, limits::min_tolerance, limits::max_tolerance, tolerance_range, false, x)) return false;
        set_tolerance(run.options, x);
        break;
      case OptionKey::step:
        if (!number(a, v, limits::min_step, limits::max_step, step_range, false, x)) return false;
        run.options.h = x;
        break;
      case OptionKey::max_steps:
        if (!number(a, v, static_cast<double>(limits::min_max_steps), static_cast<double>(limits::max_max_steps),
                    max_steps_range, true, x))
          return false;
        run.options.max_steps = static_cast<long>(x);
        break;
      case OptionKey::repeat:
        if (!number(a, v, 1, static_cast<double>(limits::max_repeat), repeat_range, true, x)) return false;
        run.repeat = static_cast<int>(x);
        break;
      case OptionKey::out:
        if (!*v) return usage_error("--out needs a directory name, not an empty one; give e.g. --out results");
        run.out_dir = v;
        break;
      case OptionKey::param: {
        const std::string_view pv = v;
        const auto eq = pv.find('=');
        if (eq == std::string_view::npos || eq == 0)
          return usage_error("--param '" + std::string(pv) + "' is not NAME=VALUE; give a tunable parameter and "
                             "its value, e.g. --param J_c=0.5");
        run.params.emplace_back(std::string(pv.substr(0, eq)), std::string(pv.substr(eq + 1)));
        break;
      }
      case OptionKey::no_csv: run.csv = false; break;
      case OptionKey::quiet: run.quiet = true; break;
      case OptionKey::help: run.help = true; break;
    }
  }
  if (solver_given) {
    const std::optional<Solver> solver = parse_solver(*solver_given);
    if (!solver)
      return usage_error("unknown solver '" + *solver_given + "'; the solvers are " + solver_names(", "));
    run.solver = *solver;
  }
  if (std::find(compiled.begin(), compiled.end(), run.solver) == compiled.end() && !run.help) {
    const std::string name(solver_name(run.solver));
    return usage_error(std::string("this simulator was compiled with the solver") + (compiled.size() == 1 ? " " : "s ") +
                       solver_names(compiled, ", ") + " only, not " +
                       name + (solver_given ? "" : " (the scene's)") + "; `pogear simulate SCENE --solver " + name +
                       "` builds and runs one that has it, `pogear generate SCENE --solvers all` writes one with "
                       "every solver");
  }
  if (run.csv && !run.help) {
    std::error_code ec;
    std::filesystem::create_directories(run.out_dir, ec);
    if (ec)
      return usage_error("cannot create the output directory '" + run.out_dir + "' (" + ec.message() +
                         "); give --out a directory you can create or write to");
  }
  return true;
}

}  // namespace pogear::rt
