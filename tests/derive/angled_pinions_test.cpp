// Pinions that mesh at an angle: every mesh row against the row written in the frame where both of
// its axes are fixed, and the Ravigneaux set's ratios against the Willis equations written here.
#include <cmath>
#include <filesystem>
#include <numbers>

#include <Eigen/Dense>

#include "common/exact_algebra.hpp"
#include "test_support.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;

// The row of mesh `mi` in the frame F where both axes are fixed (the carrier of a planet, else the
// housing): each contact point moves at r (a omega - a_F omega_F) relative to F, tangentially; an
// external pair's points move oppositely when the spring is unstretched, an internal pair's alike.
// Written from the kinematics alone: no heights, no axis distances.
std::vector<ex> row_in_axes_frame(const Derivation& d, int mi) {
  const Topology& t = d.topology;
  const Mesh& m = t.meshes[mi];
  int frame = -1;
  for (int b : {m.first.body, m.second.body})
    if (body(t, b).axis == AxisKind::carried) frame = find_body(t, body(t, b).carrier);  // -1: a fixed carrier
  std::vector<ex> row(t.bodies.size(), ex(0));
  const bool internal = wheel(t, m.first).internal || wheel(t, m.second).internal;
  auto add = [&](WheelRef w, int sign) {
    // The wheel's radius in this mesh: its operating pitch radius with a centre distance.
    const ex r = parameter_symbol(d.symbols, contact_radius(t, m, w));
    if (!is_grounded(t, w.body)) row[w.body] += sign * r * t.bodies[w.body].arrow;  // a fixed body has no column
    if (frame >= 0) row[frame] -= sign * r * t.bodies[frame].arrow;
  };
  add(m.first, +1);
  add(m.second, internal ? -1 : +1);
  return row;
}

std::vector<std::string> model_files() {
  std::vector<std::string> files;
  for (const auto& e : std::filesystem::directory_iterator(source_path("models")))
    if (e.path().extension() == ".toml") files.push_back(e.path().string());
  files.push_back(source_path("tests/errors/gear.toml"));
  files.push_back(source_path("tests/vibration/pair.toml"));
  std::sort(files.begin(), files.end());
  return files;
}

TEST(AngledPinions, EveryRowOfEveryShippedModelIsItsRowInTheAxesFrame) {
  int meshes = 0;
  for (const std::string& file : model_files()) {
    SCOPED_TRACE(file);
    Derivation d = derive_model(file, std::nullopt, SourceLocation{file, 0, 0});
    for (unsigned mi = 0; mi < d.elastic.R.rows(); ++mi) {
      const auto expected = row_in_axes_frame(d, static_cast<int>(mi));
      // The sign of a row is the drawing's choice of F's positive direction; the kinematics is
      // the row up to that sign, equal under the layout's geometry relations.
      bool same = true, opposite = true;
      for (unsigned k = 0; k < d.elastic.R.cols(); ++k) {
        same = same && equal_under_geometry(d, d.elastic.R(mi, k), expected[k]);
        opposite = opposite && equal_under_geometry(d, d.elastic.R(mi, k), -expected[k]);
      }
      EXPECT_TRUE(same || opposite) << "mesh " << d.topology.meshes[mi].name;
      ++meshes;
    }
  }
  EXPECT_GE(meshes, 36);  // the eight shipped models and two test models, every mesh
}

// Teeth of models/ravigneaux.toml; its pitch radii are 1 mm per tooth (module 2 mm).
constexpr double Z_ss = 30, Z_sl = 36, Z_ps = 18, Z_pl = 20, Z_r = 76;

struct Ravigneaux {
  Derivation d;
  double ratio(const std::string& body, const std::string& driver) const {
    const int b = find_body(d.topology, body);
    int column = -1;
    for (std::size_t i = 0; i < d.rigid.kept.size(); ++i)
      if (d.topology.bodies[d.rigid.kept[i]].name == driver) column = static_cast<int>(i);
    return evaluate_matrix(d.rigid.Q1, d.values)(b, column);
  }
};

Ravigneaux ravigneaux(const std::vector<std::string>& keep) { return {derive_paper("ravigneaux", keep)}; }

TEST(AngledPinions, RavigneauxIsTheGearOfItsTeeth) {
  const Ravigneaux g = ravigneaux({});
  const std::map<std::string, double> teeth{{"r_ss", Z_ss}, {"r_sl", Z_sl}, {"r_ps", Z_ps}, {"r_pl", Z_pl}, {"r_r", Z_r}};
  for (const auto& [radius, z] : teeth) {
    EXPECT_DOUBLE_EQ(as_number(GiNaC::ex(sym(g.d, radius)).subs(g.d.values)).to_double(), z * 1e-3) << radius;
    const int body = find_body(g.d.topology, radius.substr(2));
    ASSERT_GE(body, 0) << radius;
    EXPECT_EQ(g.d.topology.bodies[body].wheels[0].teeth, z) << radius;
  }
}

// Willis in the carrier's frame, one equation per mesh: Z_i (w_i - w_c) = -+ Z_j (w_j - w_c).
// Unknowns (c, ps, pl, r, other sun); `held` is "sl" or "c", the small sun turns at 1.
Eigen::VectorXd willis(const std::string& held, const std::string& driver) {
  // Columns: ss, sl, c, ps, pl, r.
  Eigen::MatrixXd A = Eigen::MatrixXd::Zero(6, 6);
  Eigen::VectorXd b = Eigen::VectorXd::Zero(6);
  auto mesh = [&](int row, int i, double zi, int j, double zj, bool internal) {
    A(row, i) = zi;
    A(row, j) = internal ? -zj : zj;
    A(row, 2) = -zi - (internal ? -zj : zj);
  };
  mesh(0, 0, Z_ss, 3, Z_ps, false);
  mesh(1, 3, Z_ps, 4, Z_pl, false);
  mesh(2, 4, Z_pl, 1, Z_sl, false);
  mesh(3, 4, Z_pl, 5, Z_r, true);
  A(4, held == "sl" ? 1 : 2) = 1;       // the held member at rest
  A(5, driver == "ss" ? 0 : 1) = 1;     // the driver at 1
  b(5) = 1;
  return A.fullPivLu().solve(b);
}

TEST(AngledPinions, RavigneauxRatiosWithTheLargeSunHeldAreWillis) {
  const Ravigneaux g = ravigneaux({"ss", "sl"});
  // Ring over small sun, the fourth gear of a Ravigneaux automatic, as transmission texts write it.
  const double ring = Z_ss * (Z_r + Z_sl) / (Z_r * (Z_ss + Z_sl));
  // Q1 is exact (rational arithmetic) and evaluates to within one rounding of each entry.
  EXPECT_NEAR(g.ratio("r", "ss"), ring, 1e-15);
  const Eigen::VectorXd w = willis("sl", "ss");
  EXPECT_NEAR(g.ratio("r", "ss"), w(5), 1e-14);
  EXPECT_NEAR(g.ratio("c", "ss"), w(2), 1e-14);
  EXPECT_NEAR(g.ratio("ps", "ss"), w(3), 1e-14);
  EXPECT_NEAR(g.ratio("pl", "ss"), w(4), 1e-14);
  // The user's report: the short pinion turns at -0.45 per unit small-sun speed (-5/11 exactly).
  EXPECT_NEAR(g.ratio("ps", "ss"), -5.0 / 11.0, 1e-15);
}

TEST(AngledPinions, RavigneauxRatiosWithTheCarrierHeldAreWillis) {
  const Ravigneaux small = ravigneaux({"ss", "c"});
  EXPECT_NEAR(small.ratio("r", "ss"), Z_ss / Z_r, 1e-15);  // 30/76
  const Eigen::VectorXd w = willis("c", "ss");
  EXPECT_NEAR(small.ratio("ps", "ss"), w(3), 1e-14);
  EXPECT_NEAR(small.ratio("pl", "ss"), w(4), 1e-14);
  EXPECT_NEAR(small.ratio("ps", "ss"), -Z_ss / Z_ps, 1e-14);
  EXPECT_NEAR(small.ratio("pl", "ss"), Z_ss / Z_pl, 1e-14);
  const Ravigneaux large = ravigneaux({"sl", "c"});
  EXPECT_NEAR(large.ratio("r", "sl"), -Z_sl / Z_r, 1e-15);  // -36/76: reverse
  const Eigen::VectorXd v = willis("c", "sl");
  EXPECT_NEAR(large.ratio("ps", "sl"), v(3), 1e-14);
  EXPECT_NEAR(large.ratio("pl", "sl"), v(4), 1e-14);
  EXPECT_NEAR(large.ratio("ss", "sl"), v(0), 1e-14);
}

TEST(AngledPinions, RavigneauxReportsTheAngleOfItsTriangle) {
  const Ravigneaux g = ravigneaux({});
  ASSERT_EQ(g.d.radius.angled.size(), 1u);
  EXPECT_EQ(g.d.topology.meshes[g.d.radius.angled[0].mesh].name, "pspl");
  // Axes 48 mm and 56 mm out, 38 mm apart: the law of cosines.
  const double a = 48, b = 56, c = 38;
  EXPECT_NEAR(g.d.radius.angled[0].angle, std::acos((a * a + b * b - c * c) / (2 * a * b)), 1e-12);
  // Its closed forms are in wheel radii: the axis distances are written out.
  for (const char* distance : {"a_ps", "a_pl"}) {
    EXPECT_FALSE(g.d.elastic.R.has(sym(g.d, distance))) << distance;
    EXPECT_FALSE(g.d.rigid.L1.has(sym(g.d, distance))) << distance;
  }
}

TEST(AngledPinions, CollinearPinionsKeepThePapersRow) {
  // The paper's two-stage gear draws a and b on one line: r_ab,c = r_ca - r_cb (Sec. IV).
  Derivation d = derive_paper("paper_two_stage", {"s", "r"});
  EXPECT_TRUE(d.radius.angled.empty());
  EXPECT_TRUE((d.elastic.R(3, 1) - (sym(d, "r_ca") - sym(d, "r_cb"))).expand().is_zero());
}

}  // namespace
}  // namespace pogear::test
