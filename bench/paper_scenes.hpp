// The two paper scenes as benchmark problems, from the checked-in generated simulators: every
// harness runs its methods on exactly this generated code.
#pragma once

#include "bench_common.hpp"
#include "paper_one_stage.hpp"
#include "paper_two_stage.hpp"

namespace bench {

// The elastic and the rigid system of a generated scene namespace.
#define BENCH_SCENE_PROBLEMS(ns)                                                                               \
  make_problem<ns::Elastic>(ns::scene_name, "elastic", paper_scene_signals(), ns::Elastic::initial_state(),    \
                            ns::horizon, ns::sample_period, ns::default_step),                                 \
      make_problem<ns::Rigid>(ns::scene_name, "rigid", paper_scene_signals(), ns::Rigid::initial_state(),      \
                              ns::horizon, ns::sample_period, ns::default_step)

// Calls f(elastic_problem, rigid_problem) for the one-stage, then the two-stage scene.
template <class F>
void for_each_paper_scene(F&& f) {
  f(BENCH_SCENE_PROBLEMS(pogear_generated::paper_one_stage));
  f(BENCH_SCENE_PROBLEMS(pogear_generated::paper_two_stage));
}

}  // namespace bench
