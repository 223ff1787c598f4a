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

// Elastic outputs: the speeds, states that C selects exactly, and the force each mesh transmits,
// F + b_K R omega, with the damper's coefficients of the paper's one-stage gear (b_K = 40 N s/m).
TEST(OutputMatrices, ElasticOutputsAreStatesAndTransmittedForces) {
  namespace g = pogear_generated::paper_one_stage;
  g::Elastic::OutputMatrix C;
  g::Elastic::FeedthroughMatrix D;
  g::Elastic::output_matrices({}, C, D);
  g::Elastic::OutputMatrix expected = g::Elastic::OutputMatrix::Identity();
  // R's rows of meshes ps and rm (omega_c, omega_p, omega_s, omega_r, omega_g, omega_m), radii in m.
  const double b = 40.0;
  expected(6, 0) = b * 0.148, expected(6, 1) = -b * 0.048, expected(6, 2) = -b * 0.1;
  expected(7, 0) = b * 0.148, expected(7, 1) = b * 0.048, expected(7, 3) = -b * 0.196;
  expected(8, 2) = -b * 0.16, expected(8, 4) = -b * 0.16;
  expected(9, 3) = -b * 0.22, expected(9, 5) = -b * 0.12;
  // Each coefficient is b times a radius, rounded once (5.920000000000001 for 40 * 0.148): an ulp.
  EXPECT_TRUE(C.isApprox(expected, 1e-15)) << C;
  EXPECT_TRUE(D.isZero(0));
  // outputs() sums F + b v through the temporaries, C x in another order: a few eps (measured 1.8e-16).
  EXPECT_LT(output_matrices_error<g::Elastic>(), 1e-14);
  EXPECT_LT(output_matrices_error<pogear_generated::paper_two_stage::Elastic>(), 1e-14);
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
