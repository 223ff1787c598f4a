// Properties every derivation must have, checked on the paper's models: R Q1 = 0, the paper's
// sign rules 2 and 3, L1 positive definite, and forces that balance the rigid model.
#include <Eigen/Dense>

#include "../support/commands.hpp"
#include "test_support.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;

const GiNaC::exmap& values_of(const Derivation& d) { return d.values; }

class BothPaperModels : public ::testing::TestWithParam<std::string> {};

TEST_P(BothPaperModels, KernelHoldsForEveryValidKeptSet) {
  Derivation d0 = derive_paper(GetParam(), {});
  const Eigen::MatrixXd Rn = evaluate_matrix(d0.elastic.R, values_of(d0));
  const auto sets = valid_keep_sets(Rn, 100);
  ASSERT_GE(sets.size(), 5u);
  for (const auto& set : sets) {
    std::vector<std::string> keep;
    for (int b : set) keep.push_back(d0.topology.bodies[b].name);
    Derivation d = derive_paper(GetParam(), keep);
    const GiNaC::matrix RQ = d.elastic.R.mul(d.rigid.Q1);
    for (unsigned i = 0; i < RQ.rows(); ++i)
      for (unsigned j = 0; j < RQ.cols(); ++j)
        EXPECT_TRUE(equal_under_geometry(d, RQ(i, j), 0)) << "keep " << keep[0] << "," << keep[1];
  }
}

TEST_P(BothPaperModels, ReversingAnArrowFlipsItsColumn) {
  const Derivation base = derive_paper(GetParam(), {});
  for (std::size_t k = 0; k < base.topology.bodies.size(); ++k) {
    Topology t = base.topology;
    t.bodies[k].arrow = -t.bodies[k].arrow;
    Derivation d = derive_topology(t, base.keep, {});
    for (unsigned i = 0; i < d.elastic.R.rows(); ++i)
      for (unsigned j = 0; j < d.elastic.R.cols(); ++j) {
        // The two derivations have their own symbols: compare printed forms.
        const ex expected = (j == k ? -1 : 1) * base.elastic.R(i, j);
        EXPECT_EQ(print_expression(d.elastic.R(i, j), Notation::ginac), print_expression(expected, Notation::ginac))
            << "body " << k << " entry " << i << "," << j;
      }
  }
}

TEST_P(BothPaperModels, SwappingAMeshsTerminalsFlipsItsRow) {
  const Derivation base = derive_paper(GetParam(), {});
  for (std::size_t m = 0; m < base.topology.meshes.size(); ++m) {
    Topology t = base.topology;
    std::swap(t.meshes[m].first, t.meshes[m].second);
    Derivation d = derive_topology(t, base.keep, {});
    for (unsigned i = 0; i < d.elastic.R.rows(); ++i)
      for (unsigned j = 0; j < d.elastic.R.cols(); ++j) {
        const ex expected = (i == m ? -1 : 1) * base.elastic.R(i, j);
        EXPECT_EQ(print_expression(d.elastic.R(i, j), Notation::ginac), print_expression(expected, Notation::ginac));
      }
  }
}

TEST_P(BothPaperModels, ReducedInertiaIsSymmetricPositiveDefinite) {
  Derivation d = derive_paper(GetParam(), {});
  const Eigen::MatrixXd L1 = evaluate_matrix(d.rigid.L1, values_of(d));
  // Entries are sums of a few products of O(1) numbers: symmetric to the last bits.
  EXPECT_LT((L1 - L1.transpose()).norm(), 1e-14 * L1.norm());
  Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(L1);
  EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0);
  // And it is Q1^T J Q1 formed numerically, an independent computation.
  const Eigen::MatrixXd Q1 = evaluate_matrix(d.rigid.Q1, values_of(d));
  const Eigen::MatrixXd J = evaluate_matrix(d.elastic.J, values_of(d));
  EXPECT_LT((Q1.transpose() * J * Q1 - L1).norm(), 1e-12 * L1.norm());
}

TEST_P(BothPaperModels, RecoveredForcesBalanceTheRigidModelAndEqualEquation8) {
  Derivation d = derive_paper(GetParam(), {});
  GiNaC::exmap at = values_of(d);
  const Eigen::MatrixXd R = evaluate_matrix(d.elastic.R, at);
  const Eigen::MatrixXd Q1 = evaluate_matrix(d.rigid.Q1, at);
  const Eigen::MatrixXd J = evaluate_matrix(d.elastic.J, at);
  const Eigen::MatrixXd BJ = evaluate_matrix(d.elastic.B_J, at);
  const Eigen::MatrixXd L1 = evaluate_matrix(d.rigid.L1, at);
  const Eigen::MatrixXd A1 = evaluate_matrix(d.rigid.A1, at);
  const auto n = R.cols();
  const auto k = Q1.cols();
  for (int trial = 0; trial < 5; ++trial) {
    Eigen::VectorXd tau = 100.0 * Eigen::VectorXd::Random(n);
    Eigen::VectorXd x1 = 50.0 * Eigen::VectorXd::Random(k);
    // The rigid model fixes dx1/dt; on it g lies in range(R^T).
    const Eigen::VectorXd dx1 = L1.ldlt().solve(A1 * x1 + Q1.transpose() * tau);
    const Eigen::VectorXd g = tau - J * Q1 * dx1 - BJ * Q1 * x1;
    GiNaC::exmap point = at;
    for (Eigen::Index b = 0; b < n; ++b) point[variable_symbol(d.symbols, {VariableKind::torque, static_cast<int>(b)})] = tau(b);
    for (Eigen::Index j = 0; j < k; ++j) {
      point[variable_symbol(d.symbols, {VariableKind::velocity, d.rigid.kept[j]})] = x1(j);
      point[variable_symbol(d.symbols, {VariableKind::acceleration, d.rigid.kept[j]})] = dx1(j);
    }
    Eigen::VectorXd F(R.rows());
    for (Eigen::Index i = 0; i < R.rows(); ++i) F(i) = to_double(d.rigid.force_recovery[i].subs(point));
    const Eigen::VectorXd eq8 = (R * R.transpose()).ldlt().solve(R * g);
    // cond(R R^T) is about 1e2 here and the entries are O(1e2) N: ~1e-12 relative is rounding.
    EXPECT_LT((R.transpose() * F - g).norm(), 1e-10 * g.norm());
    EXPECT_LT((F - eq8).norm(), 1e-10 * eq8.norm());
  }
}

INSTANTIATE_TEST_SUITE_P(Paper, BothPaperModels, ::testing::Values("paper_one_stage", "paper_two_stage"));

TEST(Degrees, PaperModelsHaveTwoDegreesOfFreedom) {
  for (const char* m : {"paper_one_stage", "paper_two_stage"}) {
    Derivation d = derive_paper(m, {});
    EXPECT_EQ(d.topology.bodies.size() - d.rigid.rank, 2u) << m;
  }
}

// exact_rigid_response (the sparse saddle-point solve behind generated rigid simulators) against
// L1^-1 Q1^T T by dense elimination of L1, exactly, for every valid kept set of the paper's
// models, the redundant meshes of three_planets and a synthetic chain of 5 stages.
void expect_rigid_response_is_dense_solve(Derivation& d, const std::string& what) {
  const GiNaC::exmap at = values_of(d);
  const RigidValues v = exact_rigid_values(d.rigid, d.elastic, at);
  const unsigned n = v.Q1.rows(), k = v.Q1.cols();
  GiNaC::matrix T(n, k + n);  // -B_J Q1 and every unit torque
  for (unsigned b = 0; b < n; ++b) {
    for (unsigned j = 0; j < k; ++j) T(b, j) = -exact_value(d.elastic.B_J(b, b), at) * v.Q1(b, j);
    T(b, k + b) = 1;
  }
  const GiNaC::matrix sparse = exact_rigid_response(d.rigid, d.elastic, at, T);
  const GiNaC::matrix dense = exact_solve(v.L1, exact_product(v.Q1.transpose(), exact_matrix(T, {})));
  ASSERT_EQ(sparse.rows(), dense.rows());
  for (unsigned i = 0; i < dense.rows(); ++i)
    for (unsigned j = 0; j < dense.cols(); ++j)
      EXPECT_TRUE((sparse(i, j) - dense(i, j)).is_zero()) << what << " (" << i << ", " << j << ")";
}

TEST(RigidResponse, EqualsTheDenseSolveThroughL1) {
  for (const char* m : {"paper_one_stage", "paper_two_stage"}) {
    Derivation d0 = derive_paper(m, {});
    for (const auto& set : valid_keep_sets(evaluate_matrix(d0.elastic.R, values_of(d0)), 100)) {
      std::vector<std::string> keep;
      for (int b : set) keep.push_back(d0.topology.bodies[b].name);
      Derivation d = derive_paper(m, keep);
      expect_rigid_response_is_dense_solve(d, std::string(m) + " keep " + keep[0] + "," + keep[1]);
    }
  }
  Derivation redundant = derive_paper("three_planets", {});
  ASSERT_TRUE(redundant.rigid.redundant_meshes);
  expect_rigid_response_is_dense_solve(redundant, "three_planets");
  const std::string chain = ::testing::TempDir() + "/chain_5.toml";
  const Command chain_model = run_command("bash " + source_path("scripts/make_chain.sh") + " 5");
  ASSERT_EQ(chain_model.status, 0) << chain_model.err;
  write_text(chain, chain_model.out);
  Derivation d = derive_model(chain, std::nullopt, SourceLocation{"--keep", 0, 0});
  expect_rigid_response_is_dense_solve(d, "chain of 5 stages");
}

// Another set of constraints is one more reduce_to_rigid on the same elastic model and symbol
// table: the result prints exactly as a derivation made from scratch for that set, and the first
// derivation's rigid model is left as it was.
TEST(Reduction, AnotherKeptSetReusesTheElasticModel) {
  for (const char* m : {"paper_one_stage", "paper_two_stage"}) {
    const Derivation d = derive_paper(m, {});
    const std::string before = print_expression(d.rigid.L1(0, 0), Notation::ginac);
    for (const auto& set : valid_keep_sets(evaluate_matrix(d.elastic.R, values_of(d)), 100)) {
      std::vector<std::string> keep;
      for (int b : set) keep.push_back(d.topology.bodies[b].name);
      const RigidModel again = reduce_to_rigid(d.topology, d.elastic, d.values, keep, SourceLocation{"--keep", 0, 0}, d.symbols);
      const Derivation fresh = derive_paper(m, keep);
      const std::string what = std::string(m) + " keep " + keep[0] + "," + keep[1];
      EXPECT_EQ(again.kept, fresh.rigid.kept) << what;
      for (const auto& [a, b] : {std::pair{&again.Q1, &fresh.rigid.Q1}, {&again.L1, &fresh.rigid.L1}, {&again.A1, &fresh.rigid.A1}}) {
        ASSERT_EQ(a->rows(), b->rows()) << what;
        for (unsigned i = 0; i < a->rows(); ++i)
          for (unsigned j = 0; j < a->cols(); ++j)
            EXPECT_EQ(print_expression((*a)(i, j), Notation::ginac), print_expression((*b)(i, j), Notation::ginac)) << what;
      }
      ASSERT_EQ(again.force_recovery.size(), fresh.rigid.force_recovery.size());
      for (std::size_t i = 0; i < again.force_recovery.size(); ++i)
        EXPECT_EQ(print_expression(again.force_recovery[i], Notation::ginac),
                  print_expression(fresh.rigid.force_recovery[i], Notation::ginac)) << what;
    }
    EXPECT_EQ(print_expression(d.rigid.L1(0, 0), Notation::ginac), before);
  }
}

}  // namespace
}  // namespace pogear::test
