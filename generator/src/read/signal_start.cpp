// Signals that start on an event: `when` (an element's change of state, or a slip or speed crossing
// a value), `delay` and `before`, read from a signal's table and checked against the scene.
#include "read/signal_start.hpp"

#include <algorithm>
#include <string>
#include <string_view>
#include <vector>

#include <fmt/format.h>

#include "common/quantity.hpp"
#include "read/model_parameters.hpp"

namespace pogear {

namespace fs = std::filesystem;

namespace {

constexpr std::string_view kWhenForms =
    "when = \"<element> slipping\", \"<element> stuck\", \"|slip_<element>| < <speed>\" or \"omega_<body> > <speed>\" "
    "(< or >), e.g. when = \"C stuck\" or when = \"|slip_C| < 50*rpm\"";

[[noreturn]] void fail_no_element(const SceneReader& r, const toml::node& when, std::string_view name) {
  fail_no_friction_element(r, when, name, kWhenForms);
}

// The speed a crossing's text gives after its comparison (at `offset` in the string), with the
// checks of SceneReader::quantity: a unit of angular speed (not Hz), finite, no tunable.
double crossing_value(const SceneReader& r, const toml::node& when, const std::string& text, std::size_t offset) {
  const std::string value = text.substr(offset);
  if (value.empty()) r.fail(when, fmt::format("'{}' gives no speed to cross; give {}", text, kWhenForms));
  const Quantity q = evaluate_quantity(value, parameter_quantities(*r.model), r.loc(when), 1 + static_cast<int>(offset));
  if (!q.has_unit || !(q.dimension == angular_velocity_dimension()) || value.find("Hz") != std::string::npos)
    r.fail(when, fmt::format("the speed '{}' needs a unit of angular speed, e.g. \"50*rpm\" or \"5*rad/s\"", value));
  if (!std::isfinite(q.si)) r.fail(when, fmt::format("the speed '{}' is not finite", value));
  if (r.tunable)
    for (const std::string& name : referenced_names(value))
      if (const std::string t = tunable_behind(*r.model, *r.tunable, name); !t.empty())
        r.fail(when, fmt::format("the speed '{}' names '{}', which --param would change without it; write it without "
                                 "'{}', or drop '{}' from tunable", value, name, name, t));
  return q.si;
}

// `|slip_<element>| < v` or `omega_<body> > v` (either comparison), or none when `text` has neither.
std::optional<CrossingStart> read_crossing(const SceneReader& r, const toml::node& when, const std::string& text) {
  const std::size_t op = text.find_first_of("<>");
  if (op == std::string::npos) return std::nullopt;
  std::string quantity = text.substr(0, op);
  while (!quantity.empty() && quantity.back() == ' ') quantity.pop_back();
  const std::size_t value_at = std::min(text.size(), text.find_first_not_of(' ', op + 1));
  CrossingStart c;
  c.upward = text[op] == '>';
  const std::string_view q = quantity;
  if (q.size() > 7 && q.starts_with("|slip_") && q.ends_with("|")) {
    std::string_view name = q.substr(6, q.size() - 7);
    while (!name.empty() && name.back() == ' ') name.remove_suffix(1);  // "|slip_B2 |"
    c.slip_of = find_friction_element(*r.model, std::string(name));
    if (c.slip_of < 0) fail_no_element(r, when, name);
  } else if (q.size() > 6 && q.starts_with("omega_")) {
    const std::string_view name = q.substr(6);
    for (std::size_t b = 0; b < r.model->bodies.size(); ++b)
      if (r.model->bodies[b].name == name) c.body = static_cast<int>(b);
    if (c.body < 0) {
      for (const Body& b : r.model->grounded)
        if (b.name == name)
          r.fail(when, fmt::format("'{}' is fixed to the housing: its speed is zero and crosses nothing; give a body "
                                   "that turns", name));
      std::string names;
      for (const Body& b : r.model->bodies) names += (names.empty() ? "" : ", ") + b.name;
      r.fail(when, fmt::format("'{}' is no body of the model (it has {}); {}", name, names, kWhenForms));
    }
  } else {
    r.fail(when, fmt::format("'{}' is no speed a signal can wait for; give {}", quantity, kWhenForms));
  }
  c.value = crossing_value(r, when, text, value_at);
  if (c.slip_of >= 0 && !(c.value > 0))
    r.fail(when, fmt::format("a slip's magnitude crosses a speed above 0, not {} rad/s; for the element's lock-up "
                             "give when = \"{} stuck\"", c.value, r.model->friction_elements[static_cast<std::size_t>(c.slip_of)].name));
  return c;
}

}  // namespace

// `when = "<element> slipping"` (or stuck) and `delay`: the signal's times then count from that
// event plus the delay, so they may not be negative (the signal would have changed before it).
std::optional<SignalStart> read_signal_start(const SceneReader& r, const toml::node& n, const rt::Signal& signal,
                                             const fs::path& scene_dir, SignalQuantity what) {
  const toml::table* t = n.as_table();
  const toml::node* when = t ? t->get("when") : nullptr;
  if (!when) {
    for (const char* key : {"delay", "before"})  // a step's own `before` is its value until `at`
      if (t && t->get(key) && !(std::string_view(key) == "before" && std::holds_alternative<rt::Step>(signal)))
        r.fail(*t->get(key), fmt::format("{} needs {}", key, kWhenForms));
    return std::nullopt;
  }
  std::string text = r.string(*when, "when");
  // Spaces around the whole are no part of it (the column of a message then counts from the first word).
  text.erase(0, std::min(text.size(), text.find_first_not_of(' ')));
  while (!text.empty() && text.back() == ' ') text.pop_back();
  SignalStart start;
  start.where = r.loc(*when);
  start.crossing = read_crossing(r, *when, text);
  if (!start.crossing) {
    const std::size_t space = text.find(' ');
    const std::string element = text.substr(0, space), state = space == std::string::npos ? "" : text.substr(space + 1);
    if (state != "slipping" && state != "stuck")
      r.fail(*when, fmt::format("'{}' is no event a signal can wait for; give {}", text, kWhenForms));
    start.state = state == "stuck" ? rt::ElementState::stuck : rt::ElementState::slipping;
    start.element = find_friction_element(*r.model, element);
    if (start.element < 0) fail_no_element(r, *when, element);
  }
  if (const toml::node* d = t->get("delay")) {
    start.delay = r.quantity(*d, time_dimension(), "delay");
    if (!(start.delay >= 0)) r.fail(*d, "a delay is not negative; the signal starts at the event or after it");
  }
  if (const toml::node* b = t->get("before")) {
    start.before = read_signal(r, *b, scene_dir, what);
    // A signal of time: none of a started signal's keys (a step's own `before` is its own).
    for (const char* key : {"when", "delay", "before"})
      if (const toml::node* k = b->is_table() ? b->as_table()->get(key) : nullptr;
          k && !(std::string_view(key) == "before" && std::holds_alternative<rt::Step>(*start.before)))
        r.fail(*k, fmt::format("what a signal is before its event is a signal of time; give it without {}", key));
  }
  double first = 0;
  rt::for_each_break(signal, [&](double b) { first = std::min(first, b); });
  if (first < 0)
    r.fail(n, fmt::format("a signal that starts on an event counts its times from it, but this one changes at {} s; "
                          "give its times from 0", first));
  return start;
}

// A signal waits for an element the scene engages: an open one never slips or sticks.
void check_signal_starts(const Scene& s) {
  std::vector<const SignalStart*> starts;
  for (const InputSpec& in : s.inputs) starts.push_back(in.start ? &*in.start : nullptr);
  for (const EngagementSpec& e : s.engagement) starts.push_back(e.start ? &*e.start : nullptr);
  for (const ControllerSpec& c : s.controllers) starts.push_back(c.set_point_start ? &*c.set_point_start : nullptr);
  for (const SignalStart* start : starts) {
    if (!start) continue;
    if (start->crossing && start->crossing->slip_of < 0) {
      // The runs read the speed off the outputs (a body's speed is always in the model).
      const Variable speed{VariableKind::velocity, start->crossing->body};
      if (!s.outputs.empty() && std::find(s.outputs.begin(), s.outputs.end(), speed) == s.outputs.end()) {
        const std::string name = "omega_" + s.model.bodies[static_cast<std::size_t>(speed.index)].name;
        throw InputError(start->where, fmt::format("the signal waits for {}, which the scene's outputs leave out; add "
                                                   "\"{}\" to outputs", name, name));
      }
      continue;
    }
    const int element = start->crossing ? start->crossing->slip_of : start->element;
    const std::string& name = s.model.friction_elements[static_cast<std::size_t>(element)].name;
    if (!engages(s, element))
      throw InputError(start->where, start->crossing
                                         ? fmt::format("the signal waits for the slip of {}, which the scene does not "
                                                       "engage, so its runs have no slip of it; give {} a command in "
                                                       "[engagement], or wait for a body's speed (omega_<body>)",
                                                       name, name)
                                         : fmt::format("the signal waits for {}, which the scene does not engage, so it "
                                                       "never slips or sticks; give {} a command in [engagement]",
                                                       name, name));
  }
}

}  // namespace pogear
