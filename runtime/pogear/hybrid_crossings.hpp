// Triggers on a speed or a slip crossing a value, as the hybrid engine runs them: each one a monitor,
// a torque-limited element without torque whose law is the watched quantity, so that its crossing is
// located, proven absent over whole steps and reported like every other event.
#pragma once

#include <cmath>
#include <limits>
#include <string>

#include "pogear/hybrid_modes.hpp"

namespace pogear::rt::hybrid {

// Why the system's crossings cannot run, or nullptr.
inline const char* crossing_mismatch(const HybridSystem& sys) {
  for (const TriggeredSignal& s : sys.triggered) {
    if (!s.crossing) continue;
    const CrossingTrigger& c = *s.crossing;
    if (!std::isfinite(c.value)) return "a triggered signal waits for a crossing of a value that is not finite";
    if (c.slip_of >= 0) {
      if (c.slip_of >= sys.S.rows()) return "a triggered signal waits for the slip of no brake or clutch of the system";
      if (!(c.value > 0)) return "a triggered signal waits for a slip's magnitude to cross a value not above zero";
    } else if (c.speed.size() != sys.M.rows()) {
      return "a triggered signal waits for a speed that is not a row over the system's states";
    }
  }
  return nullptr;
}

// The system with one monitor per crossing after its controllers' torque limits: a zero column of
// N (it acts on nothing), its law the quantity (|slip| as the slip within [-value, value], a speed
// against a one-sided limit), and the triggered signal waiting for the monitor's change of regime:
// "stuck" (within its limits) as a slip's magnitude falls below the value, "slipping" (at a limit)
// as it rises above it or as a speed passes the value. The friction elements keep their indices,
// so the events, samples and modes a run reports leave the monitors out (HybridData::nm).
inline HybridSystem with_crossing_monitors(const HybridSystem& sys) {
  HybridSystem out = sys;
  const int nm = crossing_count(sys);
  if (nm == 0 || crossing_mismatch(sys)) return out;  // the run refuses the latter first
  const Eigen::Index nw = sys.N.cols();
  out.N.conservativeResize(Eigen::NoChange, nw + nm);
  out.N.rightCols(nm).setZero();
  for (TorqueLimitData& l : out.limits) {
    l.law_w.conservativeResize(nw + nm);
    l.law_w.tail(nm).setZero();
  }
  const double inf = std::numeric_limits<double>::infinity();
  const int first = static_cast<int>(sys.S.rows() + static_cast<Eigen::Index>(sys.limits.size()));
  int m = 0;
  for (TriggeredSignal& s : out.triggered) {
    if (!s.crossing) continue;
    const CrossingTrigger& c = *s.crossing;
    TorqueLimitData monitor;
    monitor.name = "the trigger of " + s.name;
    monitor.law_w = Eigen::RowVectorXd::Zero(nw + nm);
    if (c.slip_of >= 0) {
      monitor.law_x = sys.S.row(c.slip_of);
      monitor.torque_min = -c.value;
      monitor.torque_max = c.value;
      s.state = c.upward ? ElementState::slipping : ElementState::stuck;
    } else {
      monitor.law_x = c.speed;
      (c.upward ? monitor.torque_max : monitor.torque_min) = c.value;
      (c.upward ? monitor.torque_min : monitor.torque_max) = c.upward ? -inf : inf;
      s.state = ElementState::slipping;
    }
    out.limits.push_back(std::move(monitor));
    s.element = first + m++;
  }
  return out;
}

}  // namespace pogear::rt::hybrid
