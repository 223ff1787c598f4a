// The signals and commands that start on an event, in the hybrid engine's terms.
#include "specialize/triggered_signals.hpp"

#include <algorithm>
#include <string>
#include <utility>

#include "names/symbols.hpp"

namespace pogear {

std::vector<rt::TriggeredSignal> triggered_signals(const SpecializedScene& model, const SpecializedSystem& sys) {
  std::vector<rt::TriggeredSignal> out;
  // The trigger's element among the engaged ones (check_signal_starts: it is one of them).
  auto add = [&](bool command, std::size_t index, const SignalStart& start, std::string name) {
    const auto k = std::find_if(model.friction.begin(), model.friction.end(),
                                [&](const FrictionRun& f) { return f.element == start.element; });
    out.push_back({command, static_cast<int>(index), static_cast<int>(k - model.friction.begin()), start.state,
                   start.delay, std::move(name), start.before});
  };
  std::size_t signal = 0;
  for (const InputPort& u : sys.inputs) {
    if (!u.signal) continue;
    if (u.start) add(false, signal, *u.start, variable_name(model.derivation.symbols, u.variable));
    ++signal;
  }
  for (std::size_t i = 0; i < model.friction.size(); ++i)
    if (model.friction[i].start) add(true, i, *model.friction[i].start, "command_" + model.friction[i].name);
  return out;
}

}  // namespace pogear
