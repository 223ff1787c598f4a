// The generated rhs(), outputs() and matrices() of every scene in models/scenes/, and of the
// tunable path at other values than the scene's, against the reference numeric model
// (numeric_system) built from the same scene file, at random states and inputs. CMake generates
// each scene's header at build time and lists the scenes of models/scenes/ in scenes.inc.
#include <random>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "../support/gaps.hpp"
#include "generated_scene.hpp"
#include "specialize/reference_model.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {

#define POGEAR_SCENE(id, file) GeneratedScene generated_##id();
#include "scenes.inc"
#undef POGEAR_SCENE
GeneratedScene generated_tunable_one_stage();  // tunable_scene.cpp

namespace {

struct SceneUnderTest {
  std::string id, file;
  GeneratedScene (*generated)();
  std::string parameters;  // [parameters] overrides of the reference, the values the generated Params hold
};

void PrintTo(const SceneUnderTest& scene, std::ostream* out) { *out << scene.id; }

std::vector<SceneUnderTest> scenes() {
  return {
#define POGEAR_SCENE(id, file) SceneUnderTest{#id, file, &generated_##id, ""},
#include "scenes.inc"
#undef POGEAR_SCENE
      // The tunable path (the rigid system solved from Params) at other values than the scene's.
      SceneUnderTest{"tunable_one_stage", POGEAR_TUNABLE_SCENE, &generated_tunable_one_stage,
                     "K_ps = \"2000*Newton/mm\"\nJ_c = 0.3"},
  };
}

// Both sides are the doubles of the same exact expressions: the generated code evaluates the
// specialized expressions (coefficients rounded once, temporaries shared between rows; for the
// tunable rigid system a Cholesky solve of L1 from Params), the reference rounds the exactly solved
// M, N, C, D, E once and multiplies in doubles. Each side is within a few ulps of the exact value
// times the condition of the sum, so the gap is measured relative to the sum of the absolute values
// of the terms. Measured: at most 6.5e-16 for rhs, 2.1e-15 for outputs (paper_two_stage, whose
// rigid forces go through dx/dt), 0 for the matrices of the scenes without tunables (the exact
// entries rounded once) and 7.5e-16 for the tunable one (the solve). 1e-14 leaves a factor of 5;
// a wrong sign gives a gap of order 1, and J_c off by 1e-12 of itself already 1e-13.
constexpr double kTolerance = 1e-14;

struct Systems {
  const GeneratedSystem& generated;
  const SpecializedSystem& specialized;
  NumericSystem reference;
};

// The quadratic loads' torques -c s |s| at x, one per load, and their sizes for the scales.
Eigen::VectorXd quadratic_torques(const NumericSystem& r, const Eigen::VectorXd& x) {
  Eigen::VectorXd q(static_cast<Eigen::Index>(r.quadratic.size()));
  for (std::size_t i = 0; i < r.quadratic.size(); ++i) {
    const double s = r.quadratic[i].speed_row.dot(x);
    q(static_cast<Eigen::Index>(i)) = -r.quadratic[i].coefficient * s * std::abs(s);
  }
  return q;
}

// The reference's dx/dt = M x + N u + sum g q, and the scale of its terms.
Eigen::VectorXd reference_rhs(const NumericSystem& r, const Eigen::VectorXd& x, const Eigen::VectorXd& u,
                              Eigen::VectorXd* scale = nullptr) {
  const Eigen::VectorXd q = quadratic_torques(r, x);
  Eigen::VectorXd dx = r.M * x + r.N * u;
  if (scale) *scale = r.M.cwiseAbs() * x.cwiseAbs() + r.N.cwiseAbs() * u.cwiseAbs();
  for (std::size_t i = 0; i < r.quadratic.size(); ++i) {
    dx += q(static_cast<Eigen::Index>(i)) * r.quadratic[i].state_column;
    if (scale) *scale += std::abs(q(static_cast<Eigen::Index>(i))) * r.quadratic[i].state_column.cwiseAbs();
  }
  return dx;
}

class GeneratedSystems : public ::testing::TestWithParam<SceneUnderTest> {
 protected:
  void SetUp() override {
    generated_ = GetParam().generated();
    const SceneUnderTest& scene = GetParam();
    model_ = specialize(scene.parameters.empty()
                            ? parse_scene(scene.file)
                            : parse_scene_text(read_text(scene.file) + "\n[parameters]\n" + scene.parameters + "\n", scene.file));
    systems_.push_back({generated_.main, model_.main, numeric_system(model_, model_.main)});
    ASSERT_EQ(generated_.rigid.has_value(), model_.rigid.has_value());
    if (model_.rigid) systems_.push_back({*generated_.rigid, *model_.rigid, numeric_system(model_, *model_.rigid)});
    for (const Systems& s : systems_) {
      ASSERT_EQ(s.generated.states, port_names(model_.derivation.symbols, state_variables(s.specialized)))
          << s.specialized.kind;
      ASSERT_EQ(s.generated.outputs, port_names(model_.derivation.symbols, output_variables(s.specialized)))
          << s.specialized.kind;
    }
  }

  // 20 states and inputs with every entry uniform in [-1, 1] (reproducible: a fixed seed).
  template <class Check>
  void at_random_points(const Systems& s, Check check) {
    std::mt19937 random(20261123);
    std::uniform_real_distribution<double> uniform(-1.0, 1.0);
    const Eigen::Index nx = s.reference.M.rows(), nu = s.reference.N.cols();
    for (int sample = 0; sample < 20; ++sample) {
      Eigen::VectorXd x(nx), u(nu);
      for (Eigen::Index i = 0; i < nx; ++i) x(i) = uniform(random);
      for (Eigen::Index i = 0; i < nu; ++i) u(i) = uniform(random);
      check(x, u);
    }
  }

  GeneratedScene generated_;
  SpecializedScene model_;
  std::vector<Systems> systems_;
};

TEST_P(GeneratedSystems, RhsMatchesTheReferenceAtRandomStatesAndInputs) {
  for (const Systems& s : systems_) {
    const NumericSystem& r = s.reference;
    at_random_points(s, [&](const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
      Eigen::VectorXd scale;
      const Eigen::VectorXd dx = reference_rhs(r, x, u, &scale);
      EXPECT_LT(largest_scaled_gap(s.generated.rhs(x, u), dx, scale), kTolerance)
          << s.specialized.kind << " at x = " << x.transpose() << ", u = " << u.transpose() << ":\n"
          << s.generated.rhs(x, u).transpose() << "\nvs the reference\n" << dx.transpose();
    });
  }
}

// y = C x + D u + E dx/dt (+ the quadratic loads' terms and their rates'), dx/dt from the reference.
TEST_P(GeneratedSystems, OutputsMatchTheReferenceAtRandomStatesAndInputs) {
  for (const Systems& s : systems_) {
    const NumericSystem& r = s.reference;
    at_random_points(s, [&](const Eigen::VectorXd& x, const Eigen::VectorXd& u) {
      Eigen::VectorXd dx_scale;
      const Eigen::VectorXd dx = reference_rhs(r, x, u, &dx_scale);
      const Eigen::VectorXd q = quadratic_torques(r, x);
      Eigen::VectorXd y = r.C * x + r.D * u + r.E * dx;
      Eigen::VectorXd scale = r.C.cwiseAbs() * x.cwiseAbs() + r.D.cwiseAbs() * u.cwiseAbs() + r.E.cwiseAbs() * dx_scale;
      for (std::size_t i = 0; i < r.quadratic.size(); ++i) {
        const QuadraticLoad& l = r.quadratic[i];
        y += q(static_cast<Eigen::Index>(i)) * l.output_column;
        scale += std::abs(q(static_cast<Eigen::Index>(i))) * l.output_column.cwiseAbs();
        // The torque's rate, -2 c |s| ds/dt (vehicle_jerk).
        const double rate = 2 * l.coefficient * std::abs(l.speed_row.dot(x)) * l.speed_row.dot(dx);
        y -= rate * l.rate_output_column;
        scale += std::abs(rate) * l.rate_output_column.cwiseAbs();
      }
      EXPECT_LT(largest_scaled_gap(s.generated.output_values(x, u), y, scale), kTolerance)
          << s.specialized.kind << " at x = " << x.transpose() << ", u = " << u.transpose() << ":\n"
          << s.generated.output_values(x, u).transpose() << "\nvs the reference\n" << y.transpose();
    });
  }
}

// Entry by entry, each relative to itself: an exact zero of the reference must be a zero.
TEST_P(GeneratedSystems, MatricesMatchTheReference) {
  for (const Systems& s : systems_) {
    Eigen::MatrixXd M, N;
    s.generated.matrices(M, N);
    const NumericSystem& r = s.reference;
    ASSERT_EQ(M.rows(), r.M.rows());
    ASSERT_EQ(M.cols(), r.M.cols());
    ASSERT_EQ(N.cols(), r.N.cols());
    for (Eigen::Index i = 0; i < M.rows(); ++i) {
      EXPECT_LT(largest_scaled_gap(M.row(i).transpose(), r.M.row(i).transpose(), r.M.row(i).cwiseAbs().transpose()), kTolerance)
          << s.specialized.kind << " row " << i << " of M:\n" << M.row(i) << "\nvs the reference\n" << r.M.row(i);
      EXPECT_LT(largest_scaled_gap(N.row(i).transpose(), r.N.row(i).transpose(), r.N.row(i).cwiseAbs().transpose()), kTolerance)
          << s.specialized.kind << " row " << i << " of N:\n" << N.row(i) << "\nvs the reference\n" << r.N.row(i);
    }
  }
}

// The quadratic loads as the hybrid runs take them (columns of dx/dt, speeds, coefficients), entry by
// entry as the matrices, in every nonlinear system and only there.
TEST_P(GeneratedSystems, QuadraticLoadsMatchTheReference) {
  for (const Systems& s : systems_) {
    const NumericSystem& r = s.reference;
    ASSERT_EQ(static_cast<bool>(s.generated.quadratic_loads), !r.quadratic.empty()) << s.specialized.kind;
    if (r.quadratic.empty()) continue;
    Eigen::MatrixXd columns, speeds;
    Eigen::VectorXd c;
    s.generated.quadratic_loads(columns, speeds, c);
    ASSERT_EQ(c.size(), static_cast<Eigen::Index>(r.quadratic.size()));
    ASSERT_EQ(columns.rows(), r.M.rows());
    ASSERT_EQ(speeds.cols(), r.M.rows());
    for (std::size_t i = 0; i < r.quadratic.size(); ++i) {
      const QuadraticLoad& q = r.quadratic[i];
      const auto I = static_cast<Eigen::Index>(i);
      EXPECT_LT(largest_scaled_gap(columns.col(I), q.state_column, q.state_column.cwiseAbs()), kTolerance) << i;
      EXPECT_LT(largest_scaled_gap(speeds.row(I).transpose(), q.speed_row, q.speed_row.cwiseAbs()), kTolerance) << i;
      EXPECT_EQ(c(I), q.coefficient) << i;
    }
  }
}

// The engine's and converter's data as the hybrid runs take them: the generated tables equal the
// scene's to the last bit (printed with 17 digits), the bodies' speeds the reference's.
TEST_P(GeneratedSystems, DrivelineMatchesTheReference) {
  for (const Systems& s : systems_) {
    ASSERT_EQ(static_cast<bool>(s.generated.driveline), !s.specialized.driveline.empty()) << s.specialized.kind;
    if (s.specialized.driveline.empty()) continue;
    const rt::DrivelineData g = s.generated.driveline();
    const rt::DrivelineData r = driveline_data(model_.scene, s.specialized, s.reference.driveline_speeds);
    ASSERT_EQ(g.engine.has_value(), r.engine.has_value());
    ASSERT_EQ(g.converter.has_value(), r.converter.has_value());
    if (r.engine) {
      EXPECT_EQ(g.engine->speeds, r.engine->speeds);
      EXPECT_EQ(g.engine->throttles, r.engine->throttles);
      EXPECT_EQ(g.engine->torque, r.engine->torque);
      for (const double t : {0.0, 0.1999, 0.2, 0.2001, 1.0})
        EXPECT_EQ(rt::value(g.throttle, t), rt::value(r.throttle, t)) << t;
      EXPECT_LT(largest_scaled_gap(g.engine_speed.transpose(), r.engine_speed.transpose(), r.engine_speed.cwiseAbs().transpose()), kTolerance);
    }
    if (r.converter) {
      EXPECT_EQ(g.converter->capacity.x, r.converter->capacity.x);
      EXPECT_EQ(g.converter->capacity.y, r.converter->capacity.y);
      EXPECT_EQ(g.converter->torque_ratio.y, r.converter->torque_ratio.y);
      EXPECT_LT(largest_scaled_gap(g.pump_speed.transpose(), r.pump_speed.transpose(), r.pump_speed.cwiseAbs().transpose()), kTolerance);
      EXPECT_LT(largest_scaled_gap(g.turbine_speed.transpose(), r.turbine_speed.transpose(), r.turbine_speed.cwiseAbs().transpose()), kTolerance);
    }
  }
}

INSTANTIATE_TEST_SUITE_P(Scenes, GeneratedSystems, ::testing::ValuesIn(scenes()),
                         [](const ::testing::TestParamInfo<SceneUnderTest>& info) { return info.param.id; });

}  // namespace
}  // namespace pogear::test
