// Which velocities a rigid model may keep: valid_keep_sets against sets worked out by hand and
// against a rank test of Eigen's own, and the typed error of a tied set against the rigid motions.
#include <algorithm>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "common/exact_algebra.hpp"
#include "derive/derivation_errors.hpp"
#include "derive/kept_velocities.hpp"
#include "test_support.hpp"

namespace pogear::test {
namespace {

using Sets = std::vector<std::vector<int>>;

TEST(KeptVelocities, ValidSetsOfSmallMatricesByHand) {
  // A chain of three bodies, each pair meshing: one freedom, any one body parametrizes it.
  Eigen::MatrixXd chain(2, 3);
  chain << 1, -1, 0, 0, 1, -1;
  EXPECT_EQ(valid_keep_sets(chain, 10), (Sets{{0}, {1}, {2}}));
  // Body 0 held: the two others are free, and only they can be kept.
  Eigen::MatrixXd held(1, 3);
  held << 1, 0, 0;
  EXPECT_EQ(valid_keep_sets(held, 10), (Sets{{1, 2}}));
  // Bodies 0 and 1 tied, body 2 held: keeping 2 would leave 0 and 1 both to solve from one row.
  Eigen::MatrixXd tied(2, 3);
  tied << 1, 1, 0, 0, 0, 1;
  EXPECT_EQ(valid_keep_sets(tied, 10), (Sets{{0}, {1}}));
  // The limit cuts the list, in order.
  EXPECT_EQ(valid_keep_sets(chain, 2), (Sets{{0}, {1}}));
}

// Every set of `dof` bodies whose complement's columns of Rn are independent (Eigen's
// column-pivoting QR with its default threshold), in lexicographic order.
Sets independent_complements(const Eigen::MatrixXd& Rn, int dof) {
  const int n = static_cast<int>(Rn.cols());
  Sets out;
  std::vector<bool> pick(static_cast<std::size_t>(n), false);
  std::fill(pick.begin(), pick.begin() + dof, true);
  do {
    std::vector<int> kept, elim;
    for (int b = 0; b < n; ++b) (pick[static_cast<std::size_t>(b)] ? kept : elim).push_back(b);
    Eigen::MatrixXd cols(Rn.rows(), static_cast<Eigen::Index>(elim.size()));
    for (std::size_t j = 0; j < elim.size(); ++j) cols.col(static_cast<Eigen::Index>(j)) = Rn.col(elim[j]);
    if (Eigen::ColPivHouseholderQR<Eigen::MatrixXd>(cols).rank() == static_cast<Eigen::Index>(elim.size()))
      out.push_back(kept);
  } while (std::prev_permutation(pick.begin(), pick.end()));
  return out;
}

TEST(KeptVelocities, ValidSetsOfThePaperGearsAgreeWithAnotherRankTest) {
  for (const char* model : {"paper_one_stage", "paper_two_stage", "ravigneaux"}) {
    const Derivation d = derive_file(model);
    const Eigen::MatrixXd Rn = evaluate_matrix(d.elastic.R, d.values);
    const int dof = static_cast<int>(Rn.cols()) - d.rigid.rank;
    EXPECT_EQ(valid_keep_sets(Rn, 1000), independent_complements(Rn, dof)) << model;
  }
}

TEST(KeptVelocities, TiedSetIsATypedErrorWhoseRelationHoldsOnEveryRigidMotion) {
  // paper_one_stage: s and g turn in a fixed ratio (g meshes s2 of body s on a fixed axis).
  const Derivation d = derive_paper("paper_one_stage", {"c", "r"});
  const Topology& t = d.topology;
  const Eigen::MatrixXd Rn = evaluate_matrix(d.elastic.R, d.values);
  const SourceLocation where{"keep.toml", 3, 8};
  try {
    choose_kept_velocities(t, d.elastic.R, Rn, d.rigid.rank, {"s", "g"}, where, d.values, d.symbols);
    FAIL() << "s and g were accepted";
  } catch (const TiedVelocities& e) {
    EXPECT_EQ(e.where().line, 3);
    EXPECT_EQ(e.where().column, 8);
    const TiedVelocities::Details& tied = e.details();
    EXPECT_EQ(tied.kept, (std::vector<std::string>{"s", "g"}));
    ASSERT_EQ(tied.tie, TiedVelocities::Tie::in_ratio);
    EXPECT_EQ(tied.first, "s");
    EXPECT_EQ(tied.second, "g");
    // omega_g == ratio * omega_s on omega = Q1 (omega_c, omega_r), for any omega_c, omega_r.
    GiNaC::exmap on_rigid_motion;
    for (int b = 0; b < static_cast<int>(t.bodies.size()); ++b) {
      GiNaC::ex omega = 0;
      for (std::size_t i = 0; i < d.rigid.kept.size(); ++i)
        omega += d.rigid.Q1(static_cast<unsigned>(b), static_cast<unsigned>(i)) *
                 variable_symbol(d.symbols, {VariableKind::velocity, d.rigid.kept[i]});
      on_rigid_motion[variable_symbol(d.symbols, {VariableKind::velocity, b})] = omega;
    }
    const GiNaC::ex gap = (tied.relation.lhs() - tied.relation.rhs()).subs(on_rigid_motion, GiNaC::subs_options::no_pattern);
    EXPECT_TRUE(gap.subs(d.values).normal().is_zero()) << tied.relation << " off the rigid motion: " << gap;
    // The valid sets it lists are valid_keep_sets', by name.
    std::vector<std::vector<std::string>> valid;
    for (const auto& set : valid_keep_sets(Rn, 12)) {
      valid.emplace_back();
      for (int b : set) valid.back().push_back(t.bodies[static_cast<std::size_t>(b)].name);
    }
    EXPECT_EQ(tied.valid, valid);
  }
}

TEST(KeptVelocities, WrongCountAndUnknownNamesAreInputErrors) {
  const Derivation d = derive_file("paper_one_stage");
  const Eigen::MatrixXd Rn = evaluate_matrix(d.elastic.R, d.values);
  auto choose = [&](const std::vector<std::string>& keep) {
    return choose_kept_velocities(d.topology, d.elastic.R, Rn, d.rigid.rank, keep, {"k", 0, 0}, d.values, d.symbols);
  };
  EXPECT_THROW(choose({"c"}), InputError);
  EXPECT_THROW(choose({"c", "x"}), InputError);
  EXPECT_THROW(choose({"c", "c"}), InputError);
  const KeptVelocities ok = choose({"r", "c"});
  EXPECT_EQ(ok.kept, (std::vector<int>{find_body(d.topology, "r"), find_body(d.topology, "c")}));
  EXPECT_EQ(ok.kept.size() + ok.eliminated.size(), d.topology.bodies.size());
  EXPECT_TRUE(std::is_sorted(ok.eliminated.begin(), ok.eliminated.end()));
}

}  // namespace
}  // namespace pogear::test
