// Shift metrics from a run's files: the command windows from the scene's commands, the phases and
// slip times from the located events (exact times), the heat, powers and output extrema from the CSV's
// samples. Every definition is docs/friction-elements.md's "Shift metrics".
#include "run/shift_metrics.hpp"

#include <algorithm>
#include <charconv>
#include <cmath>
#include <filesystem>
#include <fstream>
#include <limits>
#include <numbers>
#include <stdexcept>

#include <fmt/format.h>

#include "common/csv_rows.hpp"
#include "common/json_text.hpp"
#include "common/output_file.hpp"
#include "read/slip_control.hpp"
#include "specialize/triggered_signals.hpp"

namespace pogear {

namespace {

std::ifstream open_run_file(const std::string& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec))
    throw std::runtime_error(fmt::format("the simulation wrote no {}; run the simulator by hand to see why", path));
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(fmt::format("cannot read {} for the shift metrics; check its permissions", path));
  return in;
}

std::vector<std::string> split_fields(const std::string& line) {
  std::vector<std::string> fields(1);
  for (const char c : line)
    if (c == ',') fields.emplace_back();
    else fields.back().push_back(c);
  return fields;
}

// Linear between the samples around t (t within the table's times).
double sampled_value(const RunTable& table, std::size_t col, double t) {
  const auto& r = table.rows;
  const auto after = std::upper_bound(r.begin(), r.end(), t, [](double x, const auto& row) { return x < row[0]; });
  if (after == r.begin()) return r.front()[col];
  if (after == r.end()) return r.back()[col];
  const auto& a = *(after - 1);
  const auto& b = *after;
  return a[col] + (t - a[0]) / (b[0] - a[0]) * (b[col] - a[col]);
}

// An element's states over the run: the state before its first event, then each event's time and
// new state.
struct Timeline {
  std::string initial;
  std::vector<std::pair<double, std::string>> changes;
  std::vector<const RunEvent*> events;

  // The state after every event before t (at t itself: before the events at t).
  std::string before(double t) const {
    std::string s = initial;
    for (const auto& [at, to] : changes)
      if (at < t) s = to;
    return s;
  }
  double slipping_time(double t0, double t1) const {
    double total = 0, since = t0;
    std::string s = before(t0);
    for (const auto& [at, to] : changes) {
      if (at < t0 || at > t1) continue;
      if (s == "slipping") total += at - since;
      s = to;
      since = at;
    }
    return s == "slipping" ? total + (t1 - since) : total;
  }
};

Timeline timeline(const std::string& name, std::size_t bit, const RunTable& table, std::size_t mode_col,
                  std::size_t torque_col, const std::vector<RunEvent>& events) {
  Timeline tl;
  for (const RunEvent& e : events)
    if (e.element == name) {
      if (tl.events.empty()) tl.initial = e.from;
      tl.changes.emplace_back(e.t, e.to);
      tl.events.push_back(&e);
    }
  if (tl.events.empty()) {  // no change of state: the first sample's mode bit and torque say which
    const auto& row = table.rows.front();
    const bool stuck = (static_cast<unsigned long>(row[mode_col]) >> bit) & 1u;
    tl.initial = stuck ? "stuck" : row[torque_col] != 0 ? "slipping" : "open";
  }
  return tl;
}

std::size_t required(const RunTable& table, const std::string& name) {
  if (const auto c = table.column(name)) return *c;
  throw std::runtime_error(fmt::format("the run's CSV has no column {} for the shift metrics", name));
}

double left_value(const rt::Signal& s, double t) {
  return rt::value(s, std::nextafter(t, -std::numeric_limits<double>::infinity()));
}

// The shift's window [start, end] and the elements it hands over, with the phases from their events.
void measure_phases(ShiftMeasure& m, const std::vector<ShiftElement>& elements, const std::vector<Timeline>& lines,
                    double next_start) {
  std::vector<std::size_t> off, on;
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const double before = left_value(elements[k].command, m.start), after = rt::value(elements[k].command, m.commands_end);
    if (after < before) off.push_back(k), m.offgoing.push_back(elements[k].name);
    if (after > before) on.push_back(k), m.oncoming.push_back(elements[k].name);
  }
  m.end = m.commands_end;
  for (const auto* group : {&off, &on})
    for (const std::size_t k : *group)
      for (const auto& [t, to] : lines[k].changes)
        if (t >= m.start && t < next_start) m.end = std::max(m.end, t);
  // Release: the off-going elements leave `stuck` for good (elastic ringing may stick them again for
  // a fraction of a millisecond after the first break-away); the latest of them.
  std::optional<double> release;
  for (const std::size_t k : off) {
    if (lines[k].before(m.start) != "stuck") {
      m.omitted.push_back(fmt::format("torque_phase: {} is not stuck at the shift's start", elements[k].name));
      release.reset();
      break;
    }
    std::optional<double> left;
    for (const RunEvent* e : lines[k].events)
      if (e->t >= m.start && e->t <= m.end && e->from == "stuck") left = e->t;
    if (!left) {
      m.omitted.push_back(fmt::format("torque_phase: {} stays stuck through the shift", elements[k].name));
      release.reset();
      break;
    }
    release = std::max(release.value_or(*left), *left);
  }
  if (off.empty()) m.omitted.emplace_back("torque_phase: no element's command falls (no off-going element)");
  for (const std::size_t k : on) {
    std::optional<double> locked;
    for (const RunEvent* e : lines[k].events)
      if (e->t >= m.start && e->t <= m.end && e->to == "stuck") locked = e->t;
    if (!locked || lines[k].before(std::nextafter(m.end, m.end + 1)) != "stuck") {
      m.omitted.push_back(fmt::format("lockup: {} is not stuck at the shift's end", elements[k].name));
      m.lockup.reset();
      break;
    }
    m.lockup = std::max(m.lockup.value_or(*locked), *locked);
  }
  if (on.empty()) m.omitted.emplace_back("lockup: no element's command rises (no on-coming element)");
  if (release) m.torque_phase = Phase{m.start, *release};
  if (release && m.lockup && *m.lockup >= *release) m.inertia_phase = Phase{*release, *m.lockup};
  else if (release && m.lockup) m.omitted.emplace_back("inertia_phase: the on-coming element locks before the off-going one lets go");
  else m.omitted.emplace_back("inertia_phase: needs both the off-going element's release and the on-coming one's lock-up");
}

// The largest |f(row)| over the samples in [t0, t1], with its signed value.
template <class F>
std::optional<Extremum> sampled_peak(const RunTable& table, double t0, double t1, F f) {
  std::optional<Extremum> best;
  for (const auto& row : table.rows)
    if (row[0] >= t0 && row[0] <= t1 && (!best || std::abs(f(row)) > std::abs(best->value))) best = Extremum{f(row), row[0]};
  return best;
}

}  // namespace

std::optional<std::size_t> RunTable::column(const std::string& name) const {
  const auto it = std::find(names.begin(), names.end(), name);
  if (it == names.end()) return std::nullopt;
  return static_cast<std::size_t>(it - names.begin());
}

RunTable read_run_table(const std::string& path) {
  std::ifstream in = open_run_file(path);
  RunTable table;
  std::string line;
  if (std::getline(in, line))
    for (const std::string& field : split_fields(line)) {
      const auto open = field.find(" [");
      const bool unit = open != std::string::npos && field.back() == ']';
      table.names.push_back(unit ? field.substr(0, open) : field);
      table.units.push_back(unit ? field.substr(open + 2, field.size() - open - 3) : "");
    }
  std::vector<double> row;
  while (std::getline(in, line))
    if (parse_csv_numbers(line, table.names.size(), row) && !row.empty()) table.rows.push_back(row);
  if (table.names.empty() || table.names.front() != "t" || table.rows.empty())
    throw std::runtime_error(fmt::format("{} holds no rows of a run for the shift metrics", path));
  return table;
}

std::vector<RunEvent> read_run_events(const std::string& path) {
  std::ifstream in = open_run_file(path);
  std::vector<RunEvent> events;
  std::string line;
  std::getline(in, line);
  if (line != "t [s],element,from,to") throw std::runtime_error(fmt::format("{} is not a run's events file", path));
  while (std::getline(in, line)) {
    if (line.empty() || line.front() == '#') continue;
    std::vector<std::string> f = split_fields(line);
    RunEvent e;
    const auto [end, ec] = std::from_chars(f[0].data(), f[0].data() + f[0].size(), e.t);
    if (f.size() != 4 || ec != std::errc() || end != f[0].data() + f[0].size())
      throw std::runtime_error(fmt::format("{}: cannot read the event `{}`", path, line));
    e.element = f[1], e.from = f[2], e.to = f[3];
    events.push_back(std::move(e));
  }
  return events;
}

std::vector<CommandWindow> command_windows(const std::vector<ShiftElement>& elements, double horizon) {
  std::vector<CommandWindow> pieces;
  for (const ShiftElement& e : elements) {
    std::vector<double> times = rt::breakpoints(e.command, 0, horizon);
    times.insert(times.begin(), 0.0);
    times.push_back(horizon);
    for (std::size_t i = 0; i + 1 < times.size(); ++i) {
      const double a = times[i], b = times[i + 1];
      if (i > 0 && left_value(e.command, a) != rt::value(e.command, a)) pieces.push_back({a, a});  // a step
      if (rt::value(e.command, a) != left_value(e.command, b)) pieces.push_back({a, b});           // a ramp
    }
  }
  std::sort(pieces.begin(), pieces.end(), [](const auto& x, const auto& y) { return x.start < y.start; });
  std::vector<CommandWindow> merged;
  for (const CommandWindow& p : pieces)
    if (!merged.empty() && p.start <= merged.back().end) merged.back().end = std::max(merged.back().end, p.end);
    else merged.push_back(p);
  return merged;
}

ShiftMetrics measure_shifts(const RunTable& table, const std::vector<RunEvent>& events,
                            const std::vector<ShiftElement>& elements, double horizon) {
  ShiftMetrics m;
  const std::size_t mode_col = required(table, "mode");
  std::vector<Timeline> lines;
  std::vector<std::size_t> torque, slip, energy;
  std::vector<double> slip_scale;  // to rad/s
  for (std::size_t k = 0; k < elements.size(); ++k) {
    const std::string& name = elements[k].name;
    torque.push_back(required(table, "T_" + name));
    slip.push_back(required(table, "slip_" + name));
    energy.push_back(required(table, "E_" + name));
    slip_scale.push_back(table.units[slip.back()] == "rpm" ? std::numbers::pi / 30 : 1.0);
    lines.push_back(timeline(name, k, table, mode_col, torque.back(), events));
  }
  const std::optional<std::size_t> out_torque = table.column("T_half_shafts"), jerk = table.column("vehicle_jerk");
  if (out_torque) m.output_torque = "T_half_shafts";
  else m.omitted.emplace_back("output_torque: the CSV has no torque of the output (a [vehicle]'s T_half_shafts); "
                              "from the output's speed it would take a derivative of sampled speeds, which the "
                              "sample period does not resolve where the meshes ring faster than it");
  if (jerk) m.jerk = "vehicle_jerk";
  else m.omitted.emplace_back("peak_jerk: the CSV has no vehicle_jerk (a [vehicle] on compliant half-shafts, elastic "
                              "model); second differences of sampled speeds alias the meshes' ringing, and the rigid "
                              "model's acceleration jumps at every event");
  const double t_last = table.rows.back()[0];
  const std::vector<CommandWindow> windows = command_windows(elements, std::min(horizon, t_last));
  for (std::size_t i = 0; i < windows.size(); ++i) {
    ShiftMeasure s;
    s.start = windows[i].start;
    s.commands_end = windows[i].end;
    const double next_start = i + 1 < windows.size() ? windows[i + 1].start : std::numeric_limits<double>::infinity();
    measure_phases(s, elements, lines, next_start);
    s.end = std::min(s.end, t_last);
    for (std::size_t k = 0; k < elements.size(); ++k) {
      ElementShift e{elements[k].name, lines[k].slipping_time(s.start, s.end),
                     sampled_value(table, energy[k], s.end) - sampled_value(table, energy[k], s.start), {}, 0};
      // A stuck element dissipates nothing: its sampled slip is rounding (the zero-slip rule).
      e.peak_slip_power = sampled_peak(table, s.start, s.end, [&](const auto& row) {
                            const bool stuck = (static_cast<unsigned long>(row[mode_col]) >> k) & 1u;
                            return stuck ? 0.0 : std::abs(row[torque[k]] * row[slip[k]] * slip_scale[k]);
                          });
      for (const RunEvent* ev : lines[k].events) e.events += ev->t >= s.start && ev->t <= s.end;
      // An element that slips only between samples has no sampled slip power to take a peak of.
      const bool sampled = std::any_of(table.rows.begin(), table.rows.end(), [&](const auto& row) {
        return row[0] >= s.start && row[0] <= s.end && !((static_cast<unsigned long>(row[mode_col]) >> k) & 1u) &&
               row[torque[k]] * row[slip[k]] != 0;
      });
      if (e.slip_time > 0 && !sampled) {
        e.peak_slip_power.reset();
        s.omitted.push_back(fmt::format("peak_slip_power of {}: it slips for {:.3g} s, between samples only",
                                        e.name, e.slip_time));
      }
      s.elements.push_back(std::move(e));
    }
    if (out_torque) {
      const auto before = std::find_if(table.rows.rbegin(), table.rows.rend(), [&](const auto& r) { return r[0] < s.start; });
      if (before == table.rows.rend()) {
        s.omitted.emplace_back("output_torque: no sample before the shift's start");
      } else {
        OutputTorque o{(*before)[*out_torque], {std::numeric_limits<double>::infinity(), 0}, {-std::numeric_limits<double>::infinity(), 0}, {}, {}};
        for (const auto& row : table.rows) {
          if (row[0] < s.start || row[0] > s.end) continue;
          if (row[*out_torque] < o.min.value) o.min = {row[*out_torque], row[0]};
          if (row[*out_torque] > o.max.value) o.max = {row[*out_torque], row[0]};
        }
        if (o.before != 0) o.min_ratio = o.min.value / o.before, o.max_ratio = o.max.value / o.before;
        else s.omitted.emplace_back("output_torque ratios: the output torque before the shift is 0");
        if (std::isfinite(o.min.value)) s.output_torque = o;
        else s.omitted.emplace_back("output_torque: no sample within the shift");
      }
    }
    if (jerk) s.peak_jerk = sampled_peak(table, s.start, s.end, [&](const auto& row) { return row[*jerk]; });
    m.shifts.push_back(std::move(s));
  }
  return m;
}

namespace {

std::string json_extremum(const Extremum& e, const std::string& unit) {
  return fmt::format("{{\"value_{}\": {}, \"at_s\": {}}}", unit, json_number(e.value), json_number(e.at));
}

std::string json_phase(const std::optional<Phase>& p) {
  if (!p) return "null";
  return fmt::format("{{\"start_s\": {}, \"end_s\": {}, \"duration_s\": {}}}", json_number(p->start), json_number(p->end),
                     json_number(p->end - p->start));
}

std::string json_optional(const std::optional<double>& v) { return v ? json_number(*v) : "null"; }

std::string json_list(const std::vector<std::string>& items, const std::string& indent) {
  if (items.empty()) return "[]";
  std::string s = "[\n";
  for (std::size_t i = 0; i < items.size(); ++i) s += indent + "  " + items[i] + (i + 1 < items.size() ? ",\n" : "\n");
  return s + indent + "]";
}

std::vector<std::string> quoted(const std::vector<std::string>& v) {
  std::vector<std::string> q;
  for (const std::string& s : v) q.push_back(json_string(s));
  return q;
}

}  // namespace

std::string shift_metrics_json(const ShiftMetrics& m) {
  std::vector<std::string> shifts;
  for (std::size_t i = 0; i < m.shifts.size(); ++i) {
    const ShiftMeasure& s = m.shifts[i];
    const std::string in = "      ";
    std::string j = fmt::format("{{\n{}\"shift\": {},\n{}\"start_s\": {},\n{}\"end_s\": {},\n{}\"commands_end_s\": {},\n", in,
                                i + 1, in, json_number(s.start), in, json_number(s.end), in, json_number(s.commands_end));
    j += fmt::format("{}\"offgoing\": {},\n{}\"oncoming\": {},\n", in, json_strings(s.offgoing), in, json_strings(s.oncoming));
    j += fmt::format("{}\"torque_phase\": {},\n{}\"inertia_phase\": {},\n", in, json_phase(s.torque_phase), in,
                     json_phase(s.inertia_phase));
    j += fmt::format("{}\"lockup_s\": {},\n{}\"time_to_lockup_s\": {},\n", in, json_optional(s.lockup), in,
                     s.lockup ? json_number(*s.lockup - s.start) : "null");
    std::vector<std::string> elements;
    for (const ElementShift& e : s.elements)
      elements.push_back(fmt::format("{{\"element\": {}, \"slip_time_s\": {}, \"heat_J\": {}, \"peak_slip_power\": {}, \"events\": {}}}",
                                     json_string(e.name), json_number(e.slip_time), json_number(e.heat),
                                     e.peak_slip_power ? json_extremum(*e.peak_slip_power, "W") : "null", e.events));
    j += fmt::format("{}\"elements\": {},\n", in, json_list(elements, in));
    if (s.output_torque) {
      const OutputTorque& o = *s.output_torque;
      j += fmt::format("{}\"output_torque\": {{\"before_Nm\": {}, \"min\": {}, \"max\": {}, \"min_ratio\": {}, \"max_ratio\": {}}},\n",
                       in, json_number(o.before), json_extremum(o.min, "Nm"), json_extremum(o.max, "Nm"),
                       json_optional(o.min_ratio), json_optional(o.max_ratio));
    } else {
      j += in + "\"output_torque\": null,\n";
    }
    j += fmt::format("{}\"peak_jerk\": {},\n", in, s.peak_jerk ? json_extremum(*s.peak_jerk, "m_per_s3") : "null");
    j += fmt::format("{}\"omitted\": {}\n    }}", in, json_list(quoted(s.omitted), in));
    shifts.push_back(j);
  }
  std::string j = "{\n  \"scene\": " + json_string(m.scene) + ",\n";
  j += "  \"output_torque\": " + (m.output_torque.empty() ? std::string("null") : json_string(m.output_torque)) + ",\n";
  j += "  \"jerk\": " + (m.jerk.empty() ? std::string("null") : json_string(m.jerk)) + ",\n";
  j += "  \"omitted\": " + json_list(quoted(m.omitted), "  ") + ",\n";
  j += "  \"shifts\": " + json_list(shifts, "  ") + "\n}\n";
  return j;
}

std::vector<std::string> shift_summary_lines(const ShiftMetrics& m) {
  std::vector<std::string> lines;
  auto names = [](const std::vector<std::string>& v) {
    std::string s;
    for (const std::string& n : v) s += (s.empty() ? "" : ",") + n;
    return s.empty() ? std::string("-") : s;
  };
  for (std::size_t i = 0; i < m.shifts.size(); ++i) {
    const ShiftMeasure& s = m.shifts[i];
    std::string line = fmt::format("shift {} at {:.6g} s: {} -> {}", i + 1, s.start, names(s.offgoing), names(s.oncoming));
    if (s.torque_phase) line += fmt::format(", torque phase {:.4g} s", s.torque_phase->end - s.torque_phase->start);
    if (s.inertia_phase) line += fmt::format(", inertia phase {:.4g} s", s.inertia_phase->end - s.inertia_phase->start);
    if (s.lockup) line += fmt::format(", lock-up at {:.6g} s ({:.4g} s)", *s.lockup, *s.lockup - s.start);
    std::string heat;
    for (const ElementShift& e : s.elements)
      if (e.heat > 0)
        heat += e.heat >= 1000 ? fmt::format("{} {} {:.4g} kJ", heat.empty() ? ", heat" : ",", e.name, e.heat / 1000)
                               : fmt::format("{} {} {:.4g} J", heat.empty() ? ", heat" : ",", e.name, e.heat);
    lines.push_back(line + heat);
    std::string output;
    if (s.output_torque && s.output_torque->min_ratio)
      output = fmt::format("output torque {:.3g}–{:.3g} of the {:.4g} N m before", *s.output_torque->min_ratio,
                           *s.output_torque->max_ratio, s.output_torque->before);
    if (s.peak_jerk) output += fmt::format("{}peak jerk {:.4g} m/s^3 at {:.6g} s", output.empty() ? "" : ", ", s.peak_jerk->value, s.peak_jerk->at);
    if (!output.empty()) lines.push_back("  " + output);
  }
  return lines;
}

void write_shift_metrics(const SpecializedScene& model, const std::string& dir, const std::string& suffix,
                         std::ostream& out) {
  namespace fs = std::filesystem;
  const std::string name = model.scene.name;
  const std::vector<RunEvent> events = read_run_events((fs::path(dir) / (name + suffix + ".events.csv")).string());
  // A command that started on an event, as the run applied it (its start in the events file).
  // A slip-controlled element's command: its own until its controller starts (at the controller's
  // start time, or as its target starts), then rising to 1 at the hand-over, where the controller
  // goes off (its command is no signal of the scene).
  std::vector<ShiftElement> elements;
  for (const FrictionRun& f : model.friction) {
    double started = std::numeric_limits<double>::infinity();
    for (const RunEvent& e : events)
      if (e.element == started_command_name(f.name) && e.to == "started") started = e.t;
    rt::Signal command = signal_as_run(f.command, f.start, started, model.scene.horizon);
    if (const int c = slip_controller_of(model.scene, f.element); c >= 0) {
      const ControllerSpec& k = model.scene.controllers[static_cast<std::size_t>(c)];
      double on = k.set_point_start ? std::numeric_limits<double>::infinity() : k.start, off = model.scene.horizon;
      for (const RunEvent& e : events) {
        if (e.element == "ref_" + k.name && e.to == "started") on = e.t;
        if (e.element == k.name && e.to == "off") off = std::min(off, e.t);
      }
      if (on < off) {  // its pieces before the start, then the rise
        rt::Table t{{0.0}, {rt::value(command, 0.0)}};
        for (const double b : rt::breakpoints(command, 0.0, on))
          for (const double v : {left_value(command, b), rt::value(command, b)})
            if (b > 0 && b < on && (b != t.t.back() || v != t.v.back())) t.t.push_back(b), t.v.push_back(v);
        t.t.insert(t.t.end(), {on, off, model.scene.horizon}), t.v.insert(t.v.end(), {left_value(command, on), 1.0, 1.0});
        command = std::move(t);
      }
    }
    elements.push_back({f.name, std::move(command)});
  }
  ShiftMetrics m = measure_shifts(read_run_table((fs::path(dir) / (name + suffix + ".csv")).string()), events, elements,
                                  model.scene.horizon);
  m.scene = name;
  const std::string path = (fs::path(dir) / (name + suffix + ".shift.json")).string();
  write_file_atomically(path, shift_metrics_json(m));
  for (const std::string& line : shift_summary_lines(m)) out << (suffix.empty() ? "" : "rigid: ") << line << "\n";
  out << "wrote " << path << "\n";
}

}  // namespace pogear
