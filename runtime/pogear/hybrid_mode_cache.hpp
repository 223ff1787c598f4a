// The modes a run meets and, per mode and step length, their exact discretizations and event proofs:
// computed on first use, kept in the workspace's ModeCache.
#pragma once

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <limits>
#include <numbers>
#include <utility>

#include "pogear/hybrid_data.hpp"

namespace pogear::rt::hybrid {

// The mode's matrices, with its modal form and event_step.
inline const ModeMatrices& mode_of(const HybridSystem& sys, ModeCache& cache, std::uint32_t mask) {
  auto it = cache.modes.find(mask);
  if (it == cache.modes.end()) {
    it = cache.modes.emplace(mask, hybrid_detail::mode_matrices(sys, mask)).first;
    if (!it->second.singular) {
      auto& md = it->second;
      md.modal = modal_form(md.A, md.B);
      // event_check_step from the modal form's eigenvalues (the same solver on the same matrix)
      // rather than a second eigenvalue solve.
      if (md.A.rows() > 0 && md.modal.lambda.size() == md.A.rows()) {
        const double omega = md.modal.lambda.imag().cwiseAbs().maxCoeff();
        md.event_step = !(omega >= 0) ? 0.0
                        : omega > 0   ? std::numbers::pi / (4 * omega)
                                      : std::numeric_limits<double>::infinity();
      } else {
        md.event_step = event_step_limit(md.A);
      }
    }
  }
  return it->second;
}

// The entry of `cache` for mode `mask` and a step within 1e-9 h of h, or its end: steps between
// grid times differ by the rounding of those times only, far below the rounding of t itself.
template <class Map>
auto near_step(Map& cache, std::uint32_t mask, double h) {
  auto it = cache.lower_bound(std::make_pair(mask, h * (1 - 1e-9)));
  return it != cache.end() && it->first.first == mask && it->first.second <= h * (1 + 1e-9) ? it : cache.end();
}

// An exponential that cannot be trusted (its rounding estimate, exact.hpp): the run stops after the
// step that used it, before its state is observed.
inline void note_accuracy(HybridData& d, const ExactMatrices& e, double h) {
  if (!(e.rounding <= kExactMaxRounding) && !d.inaccurate) d.inaccurate = std::make_pair(h, e.rounding);
}

// The mode's exact step of h (or of a length within 1e-9 h of it), on the state augmented with the
// slip integrals.
inline const ExactMatrices& discretization(const HybridSystem& sys, HybridData& d, std::uint32_t mask, double h) {
  auto& cache = d.cache.discretizations;
  auto it = near_step(cache, mask, h);
  if (it == cache.end()) {
    if (cache.size() > kStepLengthsKept) cache.clear();
    const auto& m = mode_of(sys, d.cache, mask);
    it = cache.emplace(std::make_pair(mask, h), exact_matrices(m.augmented_A, m.augmented_B, h, d.nx)).first;
    note_accuracy(d, it->second, h);
  }
  return it->second;
}

// The mode's proof maps for steps of h (or of a length within 1e-9 h of it), one function per
// element: its slip S_k x, or while it is stuck its torque Kx_j x + Kv_j w; a controller's law in
// either regime.
inline const StepProof& step_proof_of(const HybridSystem& sys, HybridData& d, std::uint32_t mask, double h) {
  auto& cache = d.cache.proofs;
  auto it = near_step(cache, mask, h);
  if (it == cache.end()) {
    if (cache.size() > kStepLengthsKept) cache.clear();
    const auto& m = mode_of(sys, d.cache, mask);
    Eigen::MatrixXd C = d.S, D = Eigen::MatrixXd::Zero(d.ne, d.nw);
    for (std::size_t j = 0; j < m.stuck.size(); ++j) {
      C.row(m.stuck[j]) = m.Kx.row(static_cast<Eigen::Index>(j));
      D.row(m.stuck[j]) = m.Kv.row(static_cast<Eigen::Index>(j));
    }
    for (int k = d.nf; k < d.ne; ++k) {
      C.row(k) = limit(sys, d, k).law_x;
      D.row(k) = limit(sys, d, k).law_w;
    }
    it = cache.emplace(std::make_pair(mask, h), step_proof(m.modal, m.A, m.B, C, D, h)).first;
  }
  return it->second;
}

// How often the mode has taken a step of h (or of a length within 1e-9 h of it) by its Taylor series,
// this one included.
inline int count_taylor_use(ModeCache& cache, std::uint32_t mask, double h) {
  auto& uses = cache.taylor_uses;
  const auto key = std::make_pair(mask, h * (1 - 1e-9));
  auto it = std::lower_bound(uses.begin(), uses.end(), key, [](const auto& e, const auto& k) { return e.first < k; });
  if (it == uses.end() || it->first.first != mask || !(it->first.second <= h * (1 + 1e-9))) {
    if (uses.size() > kStepLengthsKept) uses.clear();
    // Sorted by (mode, length): the first entry not below (mask, h).
    it = uses.insert(std::lower_bound(uses.begin(), uses.end(), std::make_pair(mask, h),
                                      [](const auto& e, const auto& k) { return e.first < k; }),
                     std::make_pair(std::make_pair(mask, h), 0));
  }
  return ++it->second;
}

}  // namespace pogear::rt::hybrid
