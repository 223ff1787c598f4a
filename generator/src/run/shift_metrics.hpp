// Shift metrics (docs/friction-elements.md, "Shift metrics"): what a calibration engineer judges a
// shift by, measured after the run from its CSV and events file, written as DIR/<scene>.shift.json.
#pragma once

#include <optional>
#include <ostream>
#include <string>
#include <vector>

#include "pogear/signals.hpp"
#include "specialize/specialization.hpp"

namespace pogear {

// A run's CSV read back: the columns' names and units (`T_B1 [N m]` is T_B1 in N m), the rows, t first.
struct RunTable {
  std::vector<std::string> names, units;
  std::vector<std::vector<double>> rows;
  std::optional<std::size_t> column(const std::string& name) const;
};

// One row of DIR/<name>.events.csv: `t [s],element,from,to`.
struct RunEvent {
  double t = 0;
  std::string element, from, to;
};

// An engaged brake or clutch as the shift metrics see it: its name (its CSV columns T_, slip_, E_) and
// command.
struct ShiftElement {
  std::string name;
  rt::Signal command;
};

// Where some command changes: [start, end] (a step is a window of no length), the windows of all
// elements merged where they overlap or touch.
struct CommandWindow {
  double start = 0, end = 0;
};

struct Phase {
  double start = 0, end = 0;
};

struct Extremum {
  double value = 0, at = 0;  // the value and the sample time it is taken at
};

struct ElementShift {
  std::string name;
  double slip_time = 0;        // s slipping within the shift, from the events
  double heat = 0;             // J: E at the shift's end minus E at its start
  // W: the largest |T slip| over the shift's samples, slip in rad/s; none when it slips between
  // samples only
  std::optional<Extremum> peak_slip_power;
  int events = 0;              // its changes of state within the shift
};

struct OutputTorque {
  double before = 0;  // at the last sample before the shift's start
  Extremum min, max;
  std::optional<double> min_ratio, max_ratio;  // min / before, max / before; none when before is 0
};

struct ShiftMeasure {
  double start = 0, end = 0, commands_end = 0;
  std::vector<std::string> offgoing, oncoming;
  std::optional<Phase> torque_phase, inertia_phase;
  std::optional<double> lockup;  // the on-coming element's last `stuck` event
  std::vector<ElementShift> elements;
  std::optional<OutputTorque> output_torque;
  std::optional<Extremum> peak_jerk;
  std::vector<std::string> omitted;  // `metric: why`, for each metric this shift cannot give
};

struct ShiftMetrics {
  std::string scene;
  std::string output_torque, jerk;  // the CSV columns they are read from; empty when it has none
  std::vector<std::string> omitted;  // `metric: why`, for what no shift of the run can give
  std::vector<ShiftMeasure> shifts;
};

// Throw std::runtime_error naming the file when it cannot be read or is not a run's file.
RunTable read_run_table(const std::string& path);
std::vector<RunEvent> read_run_events(const std::string& path);

// The windows in [0, horizon] where some element's command changes, in time order.
std::vector<CommandWindow> command_windows(const std::vector<ShiftElement>& elements, double horizon);

// Every shift of the run: one per command window. `elements` in the CSV's order (the engaged ones).
ShiftMetrics measure_shifts(const RunTable& table, const std::vector<RunEvent>& events,
                            const std::vector<ShiftElement>& elements, double horizon);

// The JSON of DIR/<scene>.shift.json (keys in a fixed order, SI units in their names).
std::string shift_metrics_json(const ShiftMetrics& m);
// One line per shift for the summary of `pogear simulate`.
std::vector<std::string> shift_summary_lines(const ShiftMetrics& m);

// For a scene with brakes or clutches: reads DIR/<scene><suffix>.csv and .events.csv (suffix ""
// or ".rigid"), writes DIR/<scene><suffix>.shift.json (atomically), prints its summary lines (the
// rigid run's after "rigid: ") and `wrote PATH` on `out`.
void write_shift_metrics(const SpecializedScene& model, const std::string& dir, const std::string& suffix,
                         std::ostream& out);

}  // namespace pogear
