// The scene file's quantities and signals; every complaint located at the value it concerns.
#include "read/scene_reader.hpp"

#include <algorithm>
#include <numbers>

#include <cmath>

#include <fmt/format.h>

#include "common/quantity.hpp"
#include "read/model_parameters.hpp"
#include "read/slip_control.hpp"
#include "pogear/parameters.hpp"
#include "pogear/signal_table.hpp"

namespace pogear {

namespace fs = std::filesystem;

void add_scene_parameter(const SceneReader& r, const toml::node& where, std::string_view table, Topology& t,
                         const std::string& name, double value, const Dimension& dim, const std::string& unit) {
  if (find_parameter(t, name))
    r.fail(where, fmt::format("the model has a parameter '{}', which {} defines; rename the model's", name, table));
  if (value != 0 && !(std::abs(value) >= rt::kSmallestParameter && std::abs(value) <= rt::kLargestParameter))
    r.fail(where, fmt::format("{} makes {} = {:g} (SI), outside the range pogear computes with, {:g} to {:g}; "
                              "check {} values and their units", table, name, value, rt::kSmallestParameter,
                              rt::kLargestParameter, table == "[vehicle]" ? "the vehicle's" : "its"));
  Parameter p;
  p.name = name;
  p.text = fmt::format("{:.17g}{}", value, unit.empty() ? "" : "*" + unit);
  p.value = Quantity{value, dim, !unit.empty()};
  p.where = r.loc(where);
  t.parameters.push_back(std::move(p));
}

std::vector<std::string> SceneReader::strings(const toml::node& n, std::string_view what) const {
  if (!n.is_array()) fail(n, fmt::format("{} must be a list of strings, e.g. [\"a\", \"b\"]", what));
  std::vector<std::string> out;
  for (const toml::node& e : *n.as_array()) out.push_back(string(e, what));
  return out;
}

std::string tunable_behind(const Topology& t, const std::vector<std::string>& tunable, const std::string& name) {
  if (std::find(tunable.begin(), tunable.end(), name) != tunable.end()) return name;
  const auto p = std::find_if(t.parameters.begin(), t.parameters.end(), [&](const Parameter& q) { return q.name == name; });
  if (p == t.parameters.end()) return "";
  for (const std::string& ref : referenced_names(p->text))
    if (ref != name)
      if (std::string found = tunable_behind(t, tunable, ref); !found.empty()) return found;
  return "";
}

Quantity SceneReader::evaluated(const toml::node& n, const Dimension& dim, std::string_view what) const {
  Quantity q;
  if (n.is_integer() || n.is_floating_point()) {
    q.si = *n.value<double>();
  } else if (n.is_string()) {
    const std::string text = *n.value<std::string>();
    q = evaluate_quantity(text, parameter_quantities(*model), loc(n), 1);
    if (tunable)
      for (const std::string& name : referenced_names(text))
        if (const std::string t = tunable_behind(*model, *tunable, name); !t.empty())
          fail(n, fmt::format("{} names {}, but the simulator takes this value at the scene's value of it, whatever "
                              "--param sets; write the value without '{}', or drop '{}' from tunable", what,
                              t == name ? fmt::format("tunable '{}'", t)
                                        : fmt::format("'{}', which is defined through tunable '{}'", name, t),
                              name, t));
  } else {
    fail(n, fmt::format("{} must be a number (SI) or a string with a unit", what));
  }
  if (q.has_unit && !(q.dimension == dim))
    fail(n, q.dimension == Dimension{}
                ? fmt::format("{} has no unit (rad, deg, rev and pi are plain numbers); it needs {}", what,
                              describe(dim))
                : fmt::format("{} has unit {}; it needs {}", what, describe(q.dimension), describe(dim)));
  if (!std::isfinite(q.si)) fail(n, fmt::format("{} is not finite", what));
  return q;
}

Quantity SceneReader::checked_quantity(const toml::node& n, const Dimension& dim, std::string_view what) const {
  const Quantity q = evaluated(n, dim, what);
  // Hz is 1/s, which in a speed would be read as rad/s: 2 pi short of the revolutions it usually means.
  Dimension acceleration = angular_velocity_dimension();
  acceleration.exponent[2] -= 1;
  if (n.is_string() && (dim == angular_velocity_dimension() || dim == acceleration) &&
      n.value<std::string>()->find("Hz") != std::string::npos)
    fail(n, fmt::format("{} is in Hz, which for a speed could mean rev/s or rad/s; give it in rpm or rad/s, e.g. "
                        "\"600*rpm\"", what));
  return q;
}

double SceneReader::quantity(const toml::node& n, const Dimension& dim, std::string_view what) const {
  const Quantity q = checked_quantity(n, dim, what);
  // A speed or a torque without a unit is ambiguous (rad/s or rpm? N m or kN m?): it needs one.
  if (!q.has_unit && (dim == angular_velocity_dimension() || dim == torque_dimension())) {
    const std::string value = n.is_string() ? *n.value<std::string>() : fmt::format("{}", q.si);
    fail(n, dim == torque_dimension()
                ? fmt::format("{} has no unit ({}); a torque needs one, e.g. \"{}*N*m\"", what, value, value)
                : fmt::format("{} has no unit ({}); a speed needs one, e.g. \"{}*rpm\" or \"{}*rad/s\"", what,
                              value, value, value));
  }
  return q.si;
}

double SceneReader::frequency_hz(const toml::node& n, std::string_view what) const {
  // rpm, rev, rad, deg and pi make a speed in rad/s, which as a frequency would be read as cycles per
  // second: 60*rpm would be 2 pi Hz.
  if (n.is_string())
    for (const std::string& unit : referenced_units(*n.value<std::string>()))
      if (unit == "rpm" || unit == "rev" || unit == "rad" || unit == "deg" || unit == "pi")
        fail(n, fmt::format("{} is in cycles per second; give it in Hz or kHz, e.g. \"50*Hz\" ({} would make it an "
                            "angular speed, 2 pi times the frequency: 3000*rpm turns at 50*Hz)",
                            what, unit));
  Dimension hz;
  hz.exponent[2] = -1;
  const double f = evaluated(n, hz, what).si;
  if (!(f > 0)) fail(n, fmt::format("{} is {} Hz; a sine's frequency is positive (a constant input is {{ constant = ... }}, "
                                    "and the sign of a sine is its amplitude's or its phase's)", what, f));
  // Beyond it no gear's dynamics respond, and the phase 2 pi f t loses its digits within a run.
  constexpr double highest = 1e6;
  if (f > highest)
    fail(n, fmt::format("{} is {:g} Hz, above {:g} Hz, far beyond a gear's dynamics and what its sine can be computed "
                        "at in double precision; give the frequency in Hz", what, f, highest));
  return f;
}

double SceneReader::coefficient(const toml::node& n, const Dimension& dim, std::string_view what,
                                std::string_view example_unit) const {
  if (n.is_string() && n.value<std::string>()->find("Hz") != std::string::npos)
    fail(n, fmt::format("{} is per Hz, which for a speed could mean per rev/s or per rad/s; give it per rad/s, e.g. "
                        "\"{}\"", what, example_unit));
  const Quantity q = checked_quantity(n, dim, what);
  if (!q.has_unit) {
    const std::string text = n.is_string() ? *n.value<std::string>() : fmt::format("{}", q.si);
    fail(n, fmt::format("{} has no unit ({}); give it with its unit, e.g. \"{}\"", what, text, example_unit));
  }
  return q.si;
}

namespace {

// A table signal from its CSV file; `at` is the `table =` value, where complaints about the whole
// file point (a complaint about one line points into the table).
rt::Signal read_table_signal(const SceneReader& r, const toml::node& at, const std::string& table_file,
                             const std::string& layout) {
  rt::TableError error;
  const auto table = rt::load_table_csv(table_file, error);
  if (!table) {
    // A row's complaint points into the table; one about the whole file (missing, empty, too
    // large) points at this `table =`.
    if (error.line > 0)
      throw InputError(SourceLocation{table_file, static_cast<int>(error.line), 0}, error.message + "; " + layout);
    std::string advice;
    if (error.kind == rt::TableErrorKind::cannot_open) advice = "; give its path relative to the scene file";
    else if (error.kind == rt::TableErrorKind::no_data_rows) advice = "; " + layout;
    throw InputError(r.loc(at), fmt::format("table '{}': {}{}", table_file, error.message, advice));
  }
  return rt::Table{table->t, table->v};
}

// A table written in the scene: rows [time, value] with their units, read as a CSV file's rows are
// (times forward, equal times a jump).
rt::Signal inline_table_signal(const SceneReader& r, const toml::node& n, const Dimension& dim, const std::string& example) {
  const toml::array& rows = *n.as_array();
  if (rows.empty()) r.fail(n, "the table has no rows; give rows [time, value], e.g. table = " + example);
  if (rows.size() > rt::max_table_rows)
    r.fail(n, fmt::format("the table has more than {} rows; resample it more coarsely", rt::max_table_rows));
  rt::Table table;
  for (const toml::node& row : rows) {
    const toml::array* pair = row.as_array();
    if (!pair || pair->size() != 2) r.fail(row, "a row of the table is [time, value], e.g. table = " + example);
    const double time = r.quantity(*pair->get(0), time_dimension(), "a table's time");
    const double value = r.quantity(*pair->get(1), dim, "a table's value");
    if (!table.t.empty() && time < table.t.back())
      r.fail(*pair->get(0), fmt::format("time {} s is before the previous row's ({} s); the rows go forward in time",
                                        time, table.t.back()));
    table.t.push_back(time);
    table.v.push_back(value);
  }
  return table;
}

}  // namespace

// An input torque, an engagement command or a speed set-point. An engagement command's sine form is
// refused: the exact method is exact for piecewise linear commands, and events are located on them.
rt::Signal read_signal(const SceneReader& r, const toml::node& n, const fs::path& scene_dir, SignalQuantity what) {
  const bool engagement = what == SignalQuantity::engagement || what == SignalQuantity::throttle;
  const Dimension torque = engagement || what == SignalQuantity::angle ? Dimension{}
                           : what == SignalQuantity::speed ? angular_velocity_dimension()
                                                           : torque_dimension();
  const char* name = what == SignalQuantity::throttle ? "the throttle"
                     : engagement                      ? "an engagement command"
                     : what == SignalQuantity::speed   ? "a set-point"
                     : what == SignalQuantity::angle   ? "the grade"
                                                       : "an input torque";
  if (!n.is_table()) return rt::Constant{r.quantity(n, torque, name)};
  const toml::table& t = *n.as_table();
  auto get = [&](std::string_view key) { return t.get(key); };
  if (const toml::node* w = get("when"); w && (what == SignalQuantity::throttle || what == SignalQuantity::angle))
    r.fail(*w, fmt::format("{} cannot wait for an event; give it as a table of time", name));
  // A road's grade: an angle, or a table of it in degrees (the load's hold in exact stepping is
  // stated for a piecewise linear angle).
  if (what == SignalQuantity::angle) {
    const toml::node* v = get("table");
    if (!v || t.size() != 1)
      r.fail(n, "grade is an angle, e.g. \"3*deg\", or { table = \"file.csv\" } with two columns: time [s], grade [deg]");
    if (v->is_array())
      r.fail(*v, "a grade's table is a CSV file, { table = \"grade.csv\" } with two columns: time [s], grade [deg]");
    const std::string file = r.string(*v, "table");
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : scene_dir / file;
    rt::Signal table = read_table_signal(r, *v, path.lexically_normal().string(),
                                         "the table needs two columns: time [s], grade [deg]");
    for (double& a : std::get<rt::Table>(table).v) a *= std::numbers::pi / 180;
    return table;
  }
  if (const toml::node* v = get("constant")) {
    if (get("when")) r.fail(*get("when"), "a constant has nothing to start on an event; give a step, ramp or table");
    r.only_keys(t, {"constant"}, "a constant signal");
    return rt::Constant{r.quantity(*v, torque, "constant")};
  }
  if (const toml::node* v = get("step")) {
    r.only_keys(t, {"step", "at", "before", "when", "delay"}, "a step signal");
    if (get("when") && get("before"))
      r.fail(*get("before"), "a step that starts on an event holds its 'before' until its 'at'; give what comes before "
                             "the event as a table or ramp of its own");
    rt::Step s;
    s.after = r.quantity(*v, torque, "step");
    if (!get("at")) r.fail(n, "a step needs at = \"<time>\", e.g. at = \"0.5*s\"");
    s.time = r.quantity(*get("at"), time_dimension(), "at");
    if (get("before")) s.before = r.quantity(*get("before"), torque, "before");
    return s;
  }
  if (const toml::node* v = get("ramp")) {
    r.only_keys(t, {"ramp", "start", "initial", "when", "delay", "before"}, "a ramp signal");
    rt::Ramp s;
    Dimension slope = torque;
    slope.exponent[2] -= 1;
    s.slope = r.quantity(*v, slope, engagement ? "ramp (a slope, e.g. \"2/s\")"
                                    : what == SignalQuantity::speed ? "ramp (a slope, e.g. \"500*rpm/s\")"
                                                                    : "ramp (a slope, e.g. \"50*Nm/s\")");
    if (get("start")) s.start_time = r.quantity(*get("start"), time_dimension(), "start");
    if (get("initial")) s.initial = r.quantity(*get("initial"), torque, "initial");
    return s;
  }
  if (const toml::node* v = get("sine"); v && engagement)
    r.fail(*v, "an engagement command is constant, a step, a ramp or a table (piecewise linear, so that events are "
               "located exactly); give the sine as a table");
  if (const toml::node* v = get("sine")) {
    if (get("when"))
      r.fail(*get("when"), "a sine has no value to hold until an event; start a table of its points instead");
    r.only_keys(t, {"sine", "frequency", "phase", "offset"}, "a sine signal");
    rt::Sine s;
    s.amplitude = r.quantity(*v, torque, "sine (its amplitude)");
    if (!get("frequency")) r.fail(n, "a sine needs frequency = \"<f>*Hz\"");
    s.frequency_hz = r.frequency_hz(*get("frequency"), "frequency");
    if (get("phase")) s.phase_rad = r.quantity(*get("phase"), Dimension{}, "phase");
    if (get("offset")) s.offset = r.quantity(*get("offset"), torque, "offset");
    return s;
  }
  if (const toml::node* v = get("table")) {
    r.only_keys(t, {"table", "when", "delay", "before"}, "a table signal");
    if (v->is_array())
      return inline_table_signal(r, *v, torque,
                                 engagement ? "[[\"1.9*s\", 1], [\"2*s\", 0]]"
                                 : what == SignalQuantity::speed ? "[[\"0*s\", \"0*rpm\"], [\"1*s\", \"600*rpm\"]]"
                                                                 : "[[\"0*s\", \"0*Nm\"], [\"1*s\", \"100*Nm\"]]");
    const std::string file = r.string(*v, "table");
    const fs::path path = fs::path(file).is_absolute() ? fs::path(file) : scene_dir / file;
    return read_table_signal(r, *v, path.lexically_normal().string(),
                             engagement ? "the table needs two columns: time [s], engagement command [0 to 1]"
                             : what == SignalQuantity::speed ? "the table needs two columns: time [s], speed [rad/s]"
                                                             : "the table needs two columns: time [s], torque [N m]");
  }
  r.fail(n, "a signal is { constant = ... }, { step = ..., at = ... }, { ramp = ... }, { sine = ..., "
            "frequency = ... }, { table = \"file.csv\" } or { table = [[time, value], ...] }");
}

bool identically_zero(const rt::Signal& signal, const std::optional<SignalStart>& start) {
  return identically_zero(signal) && !(start && start->before && !identically_zero(*start->before));
}

bool engages(const Scene& s, int element) {
  if (slip_controller_of(s, element) >= 0) return true;  // the controller engages it
  return std::any_of(s.engagement.begin(), s.engagement.end(), [&](const EngagementSpec& e) {
    return e.element == element && !identically_zero(e.command, e.start);
  });
}

void fail_no_friction_element(const SceneReader& r, const toml::node& where, std::string_view name,
                              std::string_view purpose) {
  std::string names;
  for (const FrictionElement& e : r.model->friction_elements) names += (names.empty() ? "" : ", ") + e.name;
  r.fail(where, fmt::format("'{}' is no brake or clutch of the model{}; {}", name,
                            names.empty() ? std::string(", which has none") : " (it has " + names + ")", purpose));
}

double value_at_start(const rt::Signal& signal, const std::optional<SignalStart>& start) {
  return rt::value(start ? rt::held_until_start(signal, start->before) : signal, 0.0);
}

}  // namespace pogear
