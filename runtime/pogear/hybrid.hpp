// Brakes and clutches in a run: stick–slip friction as modes of a linear system (the set of stuck
// elements), stepped within a mode exactly (events located on the exact trajectory) or by dopri5 or
// TR-BDF2 (events located on their dense output).
#pragma once

#include <Eigen/Dense>
#include <cstdint>
#include <functional>
#include <memory>

#include "pogear/api.hpp"
#include "pogear/hybrid_modes.hpp"
#include "pogear/hybrid_observe.hpp"
#include "pogear/run_support.hpp"
#include "pogear/signals.hpp"
#include "pogear/solver.hpp"

namespace pogear::rt {

// How a run steps within a mode: exact (a sample period per step where no event can fall in it,
// shorter steps near events, events on the exact trajectory), or dopri5 / implicit with their
// tolerances, first and largest step and max_steps (events on the dense output). rk4 has no dense
// output to locate events on: it is refused.
struct HybridMethod {
  Solver solver = Solver::exact;
  SolverOptions options;
};

// The hybrid run: steps, locates events and resolves modes (hybrid_driver.hpp). An engine keeps the
// modes and discretizations it has met from one run to the next; it is not shared between threads.
// Its definitions (hybrid.ipp) are compiled once, into libpogear_runtime.
POGEAR_RT_ABI_BEGIN

class HybridEngineCore;

class HybridEngine {
 public:
  HybridEngine(const HybridSystem& sys, double horizon, HybridMethod method = {});
  ~HybridEngine();
  HybridEngine(const HybridEngine&) = delete;
  HybridEngine& operator=(const HybridEngine&) = delete;

  // Integrates from x0 at t = 0 to the horizon, landing on every sample time (obs is called there,
  // t = 0 included, and may return false to stop) and every breakpoint of the inputs and commands.
  // on_event is called for every change of an element's state. Fails the run on a non-finite state,
  // an over-constrained set of stuck elements, or chattering.
  RunStatus run(const Eigen::VectorXd& x0, double sample, const SampleObserver& obs, const EventObserver& on_event);

  int modes_met() const;
  long steps() const;
  long rhs_evals() const;  // of dopri5 and implicit (exact stepping has none)

 private:
  std::unique_ptr<HybridEngineCore> core_;
};

POGEAR_RT_ABI_END

}  // namespace pogear::rt

#if defined(POGEAR_RT_HEADER_ONLY)
#include "pogear/hybrid.ipp"
#endif
