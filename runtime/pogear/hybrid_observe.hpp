// What a hybrid run reports: the elements' states, their changes (events), the samples, and the
// observers that receive them.
#pragma once

#include <Eigen/Core>
#include <cstdint>
#include <functional>

namespace pogear::rt {

enum class ElementState { open, slipping, stuck };
inline const char* state_name(ElementState s) {
  return s == ElementState::open ? "open" : s == ElementState::slipping ? "slipping" : "stuck";
}

// A change of element's state; or, with `started` >= 0, triggered signal `started`
// (HybridSystem::triggered) starting at t, its trigger's element in `element`.
struct HybridEvent {
  double t = 0;
  int element = 0;
  ElementState from = ElementState::open, to = ElementState::open;
  int started = -1;
};

// What the run knows at a sample: state, the full input w (stuck torques recovered), slips, the
// energy each element has dissipated (brakes and clutches, then torque limits: none) followed by the
// work each state torque has done on its body (HybridSystem::state_torques, in order), and the mode
// (bit k set when element k is stuck).
struct HybridSample {
  const Eigen::VectorXd& x;
  const Eigen::VectorXd& w;
  const Eigen::VectorXd& slip;
  const Eigen::VectorXd& energy;
  std::uint32_t mode;
};

// Chattering guard: a run stops when one element changes state more often than this within one
// sample period, or more than this many times (elements + 1) events are located within one.
// Physical shifts change each element a few times in a whole run; a Zeno sequence exceeds any bound.
inline constexpr int max_events_per_sample = 100;

using SampleObserver = std::function<bool(double, const HybridSample&)>;
using EventObserver = std::function<void(const HybridEvent&)>;

}  // namespace pogear::rt
