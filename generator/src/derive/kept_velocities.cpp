// See kept_velocities.hpp: the valid sets by a depth-first walk over the bodies, pruned by ranks.
#include "derive/kept_velocities.hpp"

#include <algorithm>

#include <fmt/format.h>

#include "common/block_triangular_solve.hpp"
#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"
#include "derive/derivation_errors.hpp"

namespace pogear {
namespace {

using GiNaC::ex;

std::string names_of(const Topology& t, const std::vector<int>& bodies, const char* sep = ",") {
  std::string s;
  for (int b : bodies) s += (s.empty() ? "" : sep) + t.bodies[b].name;
  return s;
}

std::vector<std::string> body_names(const Topology& t, const std::vector<int>& bodies) {
  std::vector<std::string> names;
  for (int b : bodies) names.push_back(t.bodies[b].name);
  return names;
}

[[noreturn]] void fail_tied(const Topology& t, const GiNaC::matrix& R, const Eigen::MatrixXd& Rn,
                            const std::vector<int>& kept, const std::vector<std::vector<int>>& valid,
                            const SourceLocation& where, const GiNaC::exmap& values, const SymbolTable& s) {
  TiedVelocities::Details tied;
  tied.kept = body_names(t, kept);
  for (const auto& v : valid) tied.valid.push_back(body_names(t, v));
  if (!valid.empty()) {
    // Name the smallest group of kept velocities that every rigid motion ties together.
    std::vector<int> other;
    for (int b = 0; b < static_cast<int>(t.bodies.size()); ++b)
      if (std::find(valid[0].begin(), valid[0].end(), b) == valid[0].end()) other.push_back(b);
    const GiNaC::matrix Q = kernel_basis(R, independent_rows(Rn, other), valid[0], other);
    const Eigen::MatrixXd Qn = evaluate_matrix(Q, values);
    bool found = false;
    // A kept body at rest in every rigid motion (held, or locked to the housing) is named alone:
    // with one kept velocity there is no pair to name, and "tied together" would mislead.
    for (std::size_t a = 0; a < kept.size() && !found; ++a)
      if (Qn.row(kept[a]).isZero(0.0)) {
        found = true;
        tied.first = t.bodies[kept[a]].name;
        tied.first_speed = variable_name(t, {VariableKind::velocity, kept[a]});
        tied.tie = TiedVelocities::Tie::at_rest;
      }
    for (std::size_t a = 0; a < kept.size() && !found; ++a)
      for (std::size_t b = a + 1; b < kept.size() && !found; ++b) {
        Eigen::MatrixXd pair(2, Qn.cols());
        pair << Qn.row(kept[a]), Qn.row(kept[b]);
        if (numeric_rank(pair) == 2) continue;
        found = true;
        int j = 0;
        while (j < Qn.cols() && Qn(kept[a], j) == 0.0) ++j;
        tied.first = t.bodies[kept[a]].name;
        tied.first_speed = variable_name(t, {VariableKind::velocity, kept[a]});
        if (j == Qn.cols()) {
          tied.tie = TiedVelocities::Tie::at_rest;
        } else {
          const ex ratio = (Q(kept[b], j) / Q(kept[a], j)).normal();
          tied.tie = TiedVelocities::Tie::in_ratio;
          tied.second = t.bodies[kept[b]].name;
          const GiNaC::realsymbol& first = variable_symbol(s, {VariableKind::velocity, kept[a]});
          const GiNaC::realsymbol& second = variable_symbol(s, {VariableKind::velocity, kept[b]});
          tied.relation = second == ratio * first;
          tied.speeds = {first, second};
        }
      }
  }
  throw TiedVelocities(where, std::move(tied));
}

}  // namespace

KeptVelocities choose_kept_velocities(const Topology& t, const GiNaC::matrix& R, const Eigen::MatrixXd& Rn, int rank,
                                      const std::vector<std::string>& keep, const SourceLocation& where,
                                      const GiNaC::exmap& values, const SymbolTable& s) {
  const int n = static_cast<int>(t.bodies.size());
  const int dof = n - rank;
  KeptVelocities out;
  for (const auto& name : keep) {
    const int b = find_body(t, name);
    if (const std::string why = fixed_body_refusal(t, name, "keep"); !why.empty()) throw InputError(where, why);
    if (b < 0) throw InputError(where, fmt::format("cannot keep '{}': there is no such body", name));
    if (std::find(out.kept.begin(), out.kept.end(), b) != out.kept.end())
      throw InputError(where, fmt::format("'{}' is kept twice", name));
    out.kept.push_back(b);
  }
  if (dof == 0) {
    std::string fixed;
    for (const Body& b : t.grounded) fixed += (fixed.empty() ? "" : ", ") + b.name;
    // Rigid shafts join their bodies like meshes; one to the housing holds its body.
    const std::string rows = !has_shafts(t) ? "meshes" : toothed_mesh_count(t) == 0 ? "rigid shafts" : "meshes and rigid shafts";
    throw InputError(where, t.grounded.empty()
                                ? fmt::format("the gear cannot turn: its {} leave its {} bodies no degree of "
                                              "freedom (rank of R {}); check the {}", rows, n, rank, rows)
                                : fmt::format("the gear cannot turn: with {} fixed, its {} leave its {} other "
                                              "bodies no degree of freedom (rank of R {}); fix fewer bodies",
                                              fixed, rows, n, rank));
  }
  const auto valid = valid_keep_sets(Rn, 12);
  if (static_cast<int>(out.kept.size()) != dof) {
    throw InputError(where, fmt::format("{} {} kept, but this gear has {} degrees of freedom ({} bodies, "
                                        "rank of R {}); keep {}, e.g. {}",
                                        out.kept.size(), out.kept.size() == 1 ? "velocity" : "velocities", dof, n,
                                        rank, dof,
                                        valid.empty() ? "" : names_of(t, valid[0])));
  }
  for (int b = 0; b < n; ++b)
    if (std::find(out.kept.begin(), out.kept.end(), b) == out.kept.end()) out.eliminated.push_back(b);
  if (numeric_rank(columns(Rn, out.eliminated)) != static_cast<int>(out.eliminated.size()))
    fail_tied(t, R, Rn, out.kept, valid, where, values, s);
  return out;
}

std::vector<std::vector<int>> valid_keep_sets(const Eigen::MatrixXd& Rn, std::size_t limit) {
  const int n = static_cast<int>(Rn.cols());
  const int rank = numeric_rank(Rn);
  const int k = n - rank;
  if (k == 0) return {{}};
  // Depth first over the bodies in order, keeping before eliminating, yields the sets in
  // lexicographic order. A branch is entered only if it can still be completed: its eliminated
  // columns independent and, with the undecided ones, spanning R's columns (then they extend to
  // a basis). So each set costs O(n) ranks, where walking all C(n, k) subsets is exponential for
  // gears whose valid sets are rare.
  std::vector<std::vector<int>> out;
  std::vector<int> kept, elim;
  auto completable = [&](int next) {
    if (numeric_rank(columns(Rn, elim)) != static_cast<int>(elim.size())) return false;
    std::vector<int> reach = elim;
    for (int b = next; b < n; ++b) reach.push_back(b);
    return numeric_rank(columns(Rn, reach)) == rank;
  };
  auto visit = [&](auto& self, int b) -> void {
    if (out.size() >= limit) return;
    if (b == n) {
      out.push_back(kept);
      return;
    }
    kept.push_back(b);
    if (static_cast<int>(kept.size()) <= k && completable(b + 1)) self(self, b + 1);
    kept.pop_back();
    elim.push_back(b);
    if (static_cast<int>(elim.size()) <= rank && completable(b + 1)) self(self, b + 1);
    elim.pop_back();
  };
  visit(visit, 0);
  return out;
}

}  // namespace pogear
