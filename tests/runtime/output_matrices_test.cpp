// The generated output_matrices(p, C, D) against the generated outputs(p, x, u, y) of the
// checked-in paper simulators: y = C x + D u at random states and inputs.
#include <gtest/gtest.h>

#include "paper_one_stage.hpp"
#include "paper_two_stage.hpp"
#include "../support/output_matrices_check.hpp"

namespace {

template <class System>
double output_matrices_error() {
  return pogear::test::output_matrices_error<System>({});
}

// Outputs that are states: C selects them, exactly.
TEST(OutputMatrices, ElasticOutputsAreTheirStates) {
  namespace g = pogear_generated::paper_one_stage;
  g::Elastic::OutputMatrix C;
  g::Elastic::FeedthroughMatrix D;
  g::Elastic::output_matrices({}, C, D);
  EXPECT_EQ(C, g::Elastic::OutputMatrix::Identity());
  EXPECT_TRUE(D.isZero(0));
  EXPECT_EQ(output_matrices_error<g::Elastic>(), 0);
  EXPECT_EQ(output_matrices_error<pogear_generated::paper_two_stage::Elastic>(), 0);
}

// The rigid mesh forces of eq. (8): outputs() sums the derivatives' terms through rhs, C and D
// hold the exact coefficients rounded once. Rounding only, but of outputs() terms larger than those
// of C x + D u (the two-stage force rows cancel): measured 4e-16 and 3e-15 of the largest term of
// C x + D u; 2e-14 leaves room, and a wrong or missing coefficient is of order 1e-2 or more.
TEST(OutputMatrices, RigidOutputsMatchAtRandomPoints) {
  EXPECT_LT(output_matrices_error<pogear_generated::paper_one_stage::Rigid>(), 2e-14);
  EXPECT_LT(output_matrices_error<pogear_generated::paper_two_stage::Rigid>(), 2e-14);
}

}  // namespace
