// From a specialized scene to CSV files and figures: everything `pogear simulate` does after
// reading its options, so that the command line stays a thin shell over the library.
#include "run/simulate_scene.hpp"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <optional>
#include <filesystem>
#include <stdexcept>
#include <vector>

#include <fmt/format.h>

#include "common/child_process.hpp"
#include "codegen/codegen.hpp"
#include "report/run_summary.hpp"
#include "common/input_error.hpp"
#include "run/interpreted_run.hpp"
#include "run/parameter_options.hpp"
#include "common/output_file.hpp"
#include "run/plot.hpp"
#include "run/shift_metrics.hpp"
#include "run/simulator_cache.hpp"
#include "specialize/start_state.hpp"

namespace pogear {

namespace fs = std::filesystem;

rt::SceneRun scene_run(const Scene& scene) {
  rt::SceneRun run;
  run.name = scene.name;
  run.horizon = scene.horizon;
  run.sample = scene.sample;
  run.solver = scene.solver;
  rt::set_tolerance(run.options, scene.tolerance);
  run.options.h = scene.step;
  run.options.max_steps = scene.max_steps;
  run.speeds_in_rpm = scene.speeds_in_rpm;
  return run;
}

std::uintmax_t csv_bytes_bound(const SpecializedScene& model) {
  const double samples = std::ceil(model.scene.horizon / model.scene.sample) + 1;
  double numbers = samples * static_cast<double>(model.main.outputs.size() + 1);
  if (model.rigid) numbers += samples * static_cast<double>(model.rigid->outputs.size() + 1);
  return static_cast<std::uintmax_t>(std::min(numbers * 25, 1e18));
}

void check_output_size(const SpecializedScene& model, bool allow_large) {
  const std::uintmax_t bytes = csv_bytes_bound(model);
  if (allow_large || bytes <= max_csv_bytes) return;
  const Scene& sc = model.scene;
  throw InputError(sc.sample_where.file.empty() ? SourceLocation{sc.file, 0, 0} : sc.sample_where,
                   fmt::format("the CSV files of this scene may take up to {:.3g} GB ({:.4g} samples of {} columns); "
                               "the limit is {:.3g} GB: raise sample, shorten the horizon or list fewer outputs, or "
                               "pass --large-output to write them all the same",
                               static_cast<double>(bytes) / 1e9, std::ceil(sc.horizon / sc.sample) + 1,
                               model.main.outputs.size() + 1, static_cast<double>(max_csv_bytes) / 1e9));
}

namespace {

// The files an earlier run of the scene may have left in dir that this run did not write (one with
// brakes since taken out leaves its events, one with compare_rigid its rigid CSV): listed, not
// removed, since pogear cannot tell them from a file of the user's that bears such a name. A file
// this run wrote was put in place after it started; the kernel stamps files from a coarse clock,
// up to a few milliseconds behind the one read here, hence the second's margin.
void list_stale_outputs(const std::string& name, const std::string& dir, fs::file_time_type started,
                        std::ostream& out) {
  started -= std::chrono::seconds(1);
  for (const char* suffix : {".csv", ".rigid.csv", ".events.csv", ".rigid.events.csv", ".velocities.svg",
                             ".forces.svg", ".shafts.svg", ".controllers.svg", ".vehicle.svg",
                             ".shift.svg", ".shift.json", ".rigid.shift.json"}) {
    const fs::path path = fs::path(dir) / (name + suffix);
    std::error_code ec;
    if (!fs::is_regular_file(fs::symlink_status(path, ec))) continue;
    const fs::file_time_type written = fs::last_write_time(path, ec);
    if (!ec && written < started)
      out << "note: " << path.string() << " is from an earlier run; this run did not write it\n";
  }
}

}  // namespace

int run_compiled(const std::string& exe, const rt::SceneRun& run) {
  ChildRequest request;
  request.argv = rt::command_line(run);
  request.argv.insert(request.argv.begin(), exe);
  std::fflush(stdout);
  const ChildResult result = run_child(request);
  if (result.signal != 0)
    throw std::runtime_error(fmt::format("the simulator {} died of {}; run it by hand to see why", exe, result.describe()));
  return result.exit_code;
}

int simulate_scene(const SpecializedScene& model, const SimulateOptions& options, std::ostream& out) {
  check_output_size(model, options.large_output);
  rt::SceneRun run = scene_run(model.scene);
  if (options.solver) run.solver = *options.solver;
  if (options.tolerance) rt::set_tolerance(run.options, *options.tolerance);
  const std::vector<ParameterOption> params = read_parameter_options(model, options.params);
  for (const ParameterOption& p : params) run.params.emplace_back(p.name, rt::detail::shortest(p.value));
  std::optional<SpecializedScene> at_params;
  if (!params.empty()) at_params = at_parameter_options(model, params);
  // A start in a gear holds its elements within the capacities, which --param may move: checked at
  // its values as [parameters]' would be.
  if (at_params && !model.scene.initial_engaged.empty()) {
    try {
      start_state(*at_params);
    } catch (const InputError& e) {
      throw InputError(SourceLocation{model.scene.file, 0, 0}, fmt::format("--param: {}", e.message()));
    }
  }
  const rt::SystemTraits traits = solver_traits(model);
  if (const auto refusal = rt::solver_refusal(run.solver, traits))
    throw InputError(SourceLocation{model.scene.file, 0, 0},
                     fmt::format("{}; use --solver {}", rt::describe(*refusal),
                                 rt::solver_alternatives(rt::admissible_solvers(traits), false)));
  run.out_dir = options.out_dir;
  run.repeat = options.repeat;
  ensure_directory(options.out_dir);
  const fs::file_time_type started = fs::file_time_type::clock::now();
  // The summary of the run as it goes: with --solver's method, --tolerance and the --param values,
  // whose notes (a fixed step's error, an adaptive method's cost, the frequencies) are their own.
  std::optional<SpecializedScene> as_run;
  if (run.solver != model.scene.solver || options.tolerance || !params.empty()) {
    as_run = at_params ? std::move(*at_params) : model;
    as_run->scene.solver = run.solver;
    if (options.tolerance) as_run->scene.tolerance = *options.tolerance;
  }
  out << operation_summary(as_run ? *as_run : model) << std::flush;
  int status = 0;
  if (options.interpreted) {
    status = run_interpreted(as_run ? *as_run : model, run);  // at the --param values
  } else {
    // One simulator for every --param and --tolerance: they are its options, not its sources.
    const CompiledSimulator simulator = build_simulator(generate_sources(model, {run.solver}));
    if (simulator.cached()) out << "simulator " << simulator.executable() << "\n" << std::flush;
    status = run_compiled(simulator.executable(), run);
  }
  if (status != 0) return status;
  for (const auto& svg : plot_scene(model, options.out_dir)) out << "wrote " << svg << "\n";
  if (!model.friction.empty()) {
    write_shift_metrics(model, options.out_dir, "", out);
    if (model.rigid) write_shift_metrics(model, options.out_dir, ".rigid", out);
  }
  list_stale_outputs(model.scene.name, options.out_dir, started, out);
  return 0;
}

}  // namespace pogear
