// Vibration modes with brakes and clutches stuck against references built here apart from pogear's
// grouping of bodies: the constrained eigenproblem on a dense null-space basis of the engagement
// rows, and the closed form of one oscillator. `pogear modes --engaged` and a scene's brakes and
// clutches on the command line: tests/commands/engaged_modes_test.cpp.
#include <algorithm>
#include <cmath>
#include <numbers>
#include <stdexcept>

#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "../derive/test_support.hpp"
#include "derive/engagement.hpp"
#include "common/exact_algebra.hpp"
#include "common/numeric_rank.hpp"
#include "vibrate/vibration_modes.hpp"

namespace pogear::test {
namespace {

// The engagement rows written from the topology here: a stuck element keeps its slip
// a_first omega_first - a_second omega_second at 0 (a brake: a_first omega_first).
Eigen::MatrixXd slip_rows(const Topology& t, const std::vector<int>& engaged) {
  Eigen::MatrixXd E = Eigen::MatrixXd::Zero(static_cast<Eigen::Index>(engaged.size()), t.bodies.size());
  for (std::size_t r = 0; r < engaged.size(); ++r) {
    const FrictionElement& f = t.friction_elements[engaged[r]];
    E(r, f.first) = t.bodies[f.first].arrow;
    if (!f.is_brake()) E(r, f.second) = -t.bodies[f.second].arrow;
  }
  return E;
}

struct Reference {
  std::vector<double> frequencies;  // ascending, rigid ones included (0)
  int rigid = 0;
};

// R^T K R phi = lambda J phi on omega = N q, N a basis of ker E from a full-pivoting LU (not
// orthonormal, not grouped): the generalized symmetric problem N^T R^T K R N, N^T J N.
Reference constrained_reference(const Derivation& d, const std::vector<int>& engaged) {
  const Eigen::MatrixXd J = evaluate_matrix(d.elastic.J, d.values), K = evaluate_matrix(d.elastic.K, d.values);
  const Eigen::MatrixXd R = evaluate_matrix(d.elastic.R, d.values);
  const Eigen::MatrixXd E = slip_rows(d.topology, engaged);
  const Eigen::MatrixXd N = engaged.empty() ? Eigen::MatrixXd::Identity(J.rows(), J.rows())
                                            : Eigen::MatrixXd(Eigen::FullPivLU<Eigen::MatrixXd>(E).kernel());
  const Eigen::MatrixXd A = N.transpose() * R.transpose() * K * R * N, B = N.transpose() * J * N;
  const Eigen::GeneralizedSelfAdjointEigenSolver<Eigen::MatrixXd> es(A, B);
  Reference ref;
  ref.rigid = static_cast<int>(N.cols()) - numeric_rank(R * N);
  for (Eigen::Index k = 0; k < es.eigenvalues().size(); ++k)
    ref.frequencies.push_back(k < ref.rigid ? 0.0 : std::sqrt(es.eigenvalues()(k)) / (2 * std::numbers::pi));
  return ref;
}

// The Simpson set as shipped (every arrow right) and with the front ring and the sun drawn with
// arrows left, so that the clutches C1 (i, r1) and C2 (i, s) tie bodies of opposite arrows.
std::vector<Derivation> simpson_variants() {
  std::string text = read_text(source_path("models/simpson_3speed.toml"));
  std::vector<Derivation> out{derive_file("simpson_3speed")};
  for (const char* body : {"name = \"r1\"", "name = \"s\""}) {
    const auto at = text.find(body);
    if (at == std::string::npos) ADD_FAILURE() << body;
    else text.insert(text.find('\n', at), "\narrow = \"left\"");
  }
  out.push_back(derive_topology(parse_topology_text(text, "simpson_left.toml"), std::nullopt,
                                SourceLocation{"simpson_left.toml", 0, 0}));
  return out;
}

// Every set of the Simpson set's four elements: the frequencies of the engaged gear, the count of
// rigid modes, and shapes that keep every stuck element's slip at 0.
TEST(EngagedModes, EverySetOfTheSimpsonElementsMatchesTheConstrainedEigenproblem) {
  for (const Derivation& d : simpson_variants()) {
    const int elements = static_cast<int>(d.topology.friction_elements.size());
    ASSERT_EQ(elements, 4);
    for (int set = 0; set < (1 << elements); ++set) {
      std::vector<int> engaged;
      for (int k = 0; k < elements; ++k)
        if (set & (1 << k)) engaged.push_back(k);
      const std::string names = engaged_names(d.topology, engaged, ",");
      const VibrationModes m = vibration_modes(d, d.values, "none", engaged);
      const Reference ref = constrained_reference(d, engaged);
      ASSERT_EQ(m.modes.size(), ref.frequencies.size()) << names;
      int rigid = 0;
      const Eigen::MatrixXd E = slip_rows(d.topology, engaged);
      for (std::size_t i = 0; i < m.modes.size(); ++i) {
        const VibrationMode& mode = m.modes[i];
        rigid += mode.kind == ModeKind::rigid;
        // Two symmetric eigensolvers on problems of condition ~1e4 (lambda_max / lambda_min): the
        // frequencies agree to ~1e-12 relative; 1e-9 leaves room and still tells one mode from another.
        EXPECT_NEAR(mode.frequency_hz, ref.frequencies[i], 1e-9 * ref.frequencies.back()) << names << " mode " << i;
        if (!engaged.empty()) {
          // Shapes are scaled to a largest entry of 1, so the slips are relative: exact up to rounding.
          EXPECT_LT((E * mode.shape).cwiseAbs().maxCoeff(), 1e-12) << names << " mode " << i;
        }
        EXPECT_NEAR(mode.kinetic_energy.sum(), 1, 1e-12);
      }
      EXPECT_EQ(rigid, ref.rigid) << names;
      EXPECT_EQ(m.engaged.size(), engaged.size());
    }
  }
}

// One mesh between two wheels, the first held by its brake Ba: the second is a single oscillator on
// the mesh stiffness, f = sqrt(K r_b^2 / J_b) / 2 pi, and the held wheel's shape entry is 0.
TEST(EngagedModes, AWheelMeshingAHeldWheelIsOneOscillator) {
  const std::string path = source_path("tests/vibration/pair.toml");
  const Derivation d = derive_topology(parse_topology(path), std::nullopt, SourceLocation{path, 0, 0});
  const VibrationModes m = vibration_modes(d, d.values, "none", {0});
  ASSERT_EQ(m.modes.size(), 1u);
  const double K = 500e3, r_b = 0.25, J_b = 0.3;
  // A 1x1 eigenproblem: a few ulps.
  EXPECT_NEAR(m.modes[0].frequency_hz / (std::sqrt(K * r_b * r_b / J_b) / (2 * std::numbers::pi)), 1, 1e-14);
  EXPECT_EQ(m.modes[0].kind, ModeKind::elastic);
  EXPECT_EQ(m.modes[0].shape(0), 0);
  EXPECT_EQ(m.modes[0].shape(1), 1);
  EXPECT_EQ(m.modes[0].strain_energy(0), 1);
  // The symbolic characteristic polynomial is of the engaged model: lambda = K r_b^2 / J_b.
  ASSERT_EQ(m.closed_form.size(), 1u);
  const auto sym = [&](const std::string& n) { return parameter_symbol(d.symbols, n); };
  EXPECT_TRUE((m.closed_form[0] - sym("K_ab") * GiNaC::pow(sym("r_b"), 2) / sym("J_b")).normal().is_zero())
      << m.closed_form[0];
  EXPECT_THROW(vibration_modes(d, d.values, "none", {0, 1}), std::domain_error);
}

}  // namespace
}  // namespace pogear::test
