// Extreme ratios: inertias over 1e-6 ... 1e6 and radius ratios over 1e-3 ... 1e3. The closed
// forms, evaluated exactly and rounded once, against Q1^T J Q1 formed in doubles.
#include <fmt/format.h>

#include "../simulate/sim_support.hpp"

namespace pogear::test {
namespace {

// The paper's one-stage gear with a wide spread of values; the dependent radii r_c and r_r1
// are left out so that pogear derives them from the geometry.
Derivation spread(double inertia_scale, double radius_scale) {
  std::string text = read_text(source_path("models/paper_one_stage.toml"));
  auto set = [&](const std::string& key, const std::string& value) {
    const auto pos = text.find(key + " = \"");
    ASSERT_NE(pos, std::string::npos) << key;
    const auto end = text.find('\n', pos);
    text.replace(pos, end - pos, key + " = \"" + value + "\"");
  };
  set("r_c", "");
  set("r_r1", "");
  text = std::regex_replace(text, std::regex("r_c = \"\"\n"), "");
  text = std::regex_replace(text, std::regex("r_r1 = \"\"\n"), "");
  set("J_c", fmt::format("{}*kg*meters^2", 0.17648 * inertia_scale));
  set("J_s", fmt::format("{}*kg*meters^2", 0.038617 / inertia_scale));
  set("J_g", fmt::format("{}*kg*meters^2", 0.48197 * inertia_scale));
  set("r_s1", fmt::format("{}*cm", 10 * radius_scale));
  set("r_p", fmt::format("{}*cm", 4.8 / radius_scale));
  set("r_g", fmt::format("{}*cm", 16 / radius_scale));
  return derive_topology(parse_topology_text(text, "spread.toml"), std::nullopt, {});
}

TEST(ExtremeRatios, ClosedFormsAgreeWithNumericQ1tJQ1WithinTheirCondition) {
  double worst = 0;
  for (double inertia : {1e-6, 1e-3, 1.0, 1e3, 1e6})
    for (double radius : {1e-3, 1e-1, 1.0, 1e1, 1e3}) {
      Derivation d = spread(inertia, std::sqrt(radius));  // r_s1/r_p = radius * 10/4.8
      const GiNaC::exmap exact = d.values;
      // The closed forms of L1 at exact rational values, rounded once: correctly rounded.
      const Eigen::MatrixXd closed = evaluate_matrix(d.rigid.L1, exact);
      // The same in doubles, as a numeric code would: Q1 and J rounded, then multiplied.
      const Eigen::MatrixXd Q = evaluate_matrix(d.rigid.Q1, exact), J = evaluate_matrix(d.elastic.J, exact);
      const Eigen::MatrixXd numeric = Q.transpose() * J * Q;
      // Sum of |terms| of each entry: the condition of the sum, which bounds the error of any
      // floating evaluation as (a few) eps * sum|terms| (Higham, Accuracy and Stability, 4.2).
      const Eigen::MatrixXd terms = Q.cwiseAbs().transpose() * J * Q.cwiseAbs();
      for (Eigen::Index i = 0; i < closed.rows(); ++i)
        for (Eigen::Index j = 0; j < closed.cols(); ++j) {
          const double bound = 8 * std::numeric_limits<double>::epsilon() * terms(i, j);
          const double err = std::abs(numeric(i, j) - closed(i, j));
          EXPECT_LE(err, bound) << "inertia x" << inertia << " radius x" << radius << " L1(" << i << "," << j << ")";
          worst = std::max(worst, err / std::abs(closed(i, j)));
        }
      EXPECT_TRUE(closed.allFinite());
      Eigen::SelfAdjointEigenSolver<Eigen::MatrixXd> eig(closed);
      EXPECT_GT(eig.eigenvalues().minCoeff(), 0.0) << "L1 stays positive definite";
    }
  // The exact evaluation is the more accurate one: it is correctly rounded, while the double
  // one carries the rounding of Q1's entries through the sums.
  RecordProperty("worst_relative_difference", fmt::format("{}", worst));
}

}  // namespace
}  // namespace pogear::test
