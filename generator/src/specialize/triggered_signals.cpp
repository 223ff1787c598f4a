// The signals and commands that start on an event, in the hybrid engine's terms.
#include "specialize/triggered_signals.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "names/symbols.hpp"

namespace pogear {

std::vector<rt::TriggeredSignal> triggered_signals(const SpecializedScene& model, const SpecializedSystem& sys) {
  std::vector<rt::TriggeredSignal> out;
  // The trigger's element, or the element whose slip crosses, among the engaged ones
  // (check_signal_starts: it is one of them); a body's speed by its output.
  auto add = [&](bool command, std::size_t index, const SignalStart& start, std::string name) {
    std::optional<rt::CrossingTrigger> crossing;
    if (const auto& c = start.crossing) {
      crossing = rt::CrossingTrigger{};
      crossing->value = c->value;
      crossing->upward = c->upward;
      if (c->slip_of >= 0) crossing->slip_of = friction_run_index(model, c->slip_of);
      else crossing->output = "omega_" + model.scene.model.bodies[static_cast<std::size_t>(c->body)].name;
    }
    out.push_back({command, static_cast<int>(index), crossing ? -1 : friction_run_index(model, start.element), start.state, start.delay,
                   std::move(name), start.before, std::move(crossing)});
  };
  std::size_t signal = 0;
  for (const InputPort& u : sys.inputs) {
    if (!u.signal) continue;
    if (u.start) add(false, signal, *u.start, variable_name(model.derivation.symbols, u.variable));
    ++signal;
  }
  for (std::size_t i = 0; i < model.friction.size(); ++i)
    if (model.friction[i].start) add(true, i, *model.friction[i].start, started_command_name(model.friction[i].name));
  return out;
}

std::string started_command_name(const std::string& element) { return "command_" + element; }

rt::Signal signal_as_run(const rt::Signal& signal, const std::optional<SignalStart>& start, double started, double horizon) {
  if (!start) return signal;
  const rt::Signal before = rt::held_until_start(signal, start->before);
  if (!(started < horizon)) return before;
  rt::Signal after = signal;
  rt::move_times(after, signal, started);
  rt::Table table;
  auto add = [&](double t, double v) {
    table.t.push_back(t);
    table.v.push_back(v);
  };
  // Each piece through its ends: the left value at a breakpoint, then the right one where it jumps.
  auto pieces = [&](const rt::Signal& s, double from, double to) {
    for (const double b : rt::breakpoints(s, from, to)) {
      const double left = rt::value(s, std::nextafter(b, from)), right = rt::value(s, b);
      add(b, left);
      if (right != left) add(b, right);
    }
  };
  add(0, rt::value(before, 0.0));
  pieces(before, 0, started);
  if (started > 0) add(started, rt::value(before, std::nextafter(started, 0.0)));
  add(started, rt::value(after, started));
  pieces(after, started, horizon);
  add(horizon, rt::value(after, horizon));
  return table;
}

}  // namespace pogear
