// Golden tests: pogear's R, Q1 and closed forms against the paper's printed formulas, written
// here by hand from the paper's text (with the corrections of docs/paper-errata.md, as noted).
#include "test_support.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;
using GiNaC::pow;

TEST(GoldenOneStage, RadiusMatrixIsEquation5) {
  Derivation d = derive_paper("paper_one_stage", {"c", "r"});
  auto r = [&](const char* n) { return sym(d, n); };
  // Eq. (5); columns (c, p, s, r, g, m), rows (ps, pr, sg, rm).
  const ex expected[4][6] = {
      {r("r_c"), -r("r_p"), -r("r_s1"), 0, 0, 0},
      {r("r_c"), r("r_p"), 0, -r("r_r1"), 0, 0},
      {0, 0, -r("r_s2"), 0, -r("r_g"), 0},
      {0, 0, 0, -r("r_r2"), 0, -r("r_m")},
  };
  ASSERT_EQ(d.elastic.R.rows(), 4u);
  ASSERT_EQ(d.elastic.R.cols(), 6u);
  for (unsigned i = 0; i < 4; ++i)
    for (unsigned j = 0; j < 6; ++j)
      EXPECT_TRUE((d.elastic.R(i, j) - expected[i][j]).expand().is_zero()) << "R(" << i << "," << j << ")";
}

TEST(GoldenOneStage, GeometryRelationsAreThePapers) {
  Derivation d = derive_paper("paper_one_stage", {"c", "r"});
  ASSERT_EQ(d.radius.relations.size(), 2u);
  // "r_c = r_p + r_s1 and r_r1 = 2 r_p + r_s1" (Sec. III, after eq. 5).
  EXPECT_EQ(d.radius.relations[0].parameter, "r_c");
  EXPECT_TRUE((d.radius.relations[0].rhs - sym(d, "r_p") - sym(d, "r_s1")).expand().is_zero());
  EXPECT_EQ(d.radius.relations[1].parameter, "r_r1");
  EXPECT_TRUE((d.radius.relations[1].rhs - 2 * sym(d, "r_p") - sym(d, "r_s1")).expand().is_zero());
}

TEST(GoldenOneStage, Q1IsTheT1Block) {
  Derivation d = derive_paper("paper_one_stage", {"c", "r"});
  auto r = [&](const char* n) { return sym(d, n); };
  // T1 of Sec. III-B for x1 = (omega_c, omega_r); "2 r_c / r_s" is r_s1 (docs/paper-errata.md E8).
  const ex expected[6][2] = {
      {1, 0},
      {-r("r_c") / r("r_p"), r("r_r1") / r("r_p")},
      {2 * r("r_c") / r("r_s1"), -r("r_r1") / r("r_s1")},
      {0, 1},
      {-2 * r("r_c") * r("r_s2") / (r("r_g") * r("r_s1")), r("r_r1") * r("r_s2") / (r("r_g") * r("r_s1"))},
      {0, -r("r_r2") / r("r_m")},
  };
  for (unsigned i = 0; i < 6; ++i)
    for (unsigned j = 0; j < 2; ++j)
      EXPECT_TRUE(equal_under_geometry(d, d.rigid.Q1(i, j), expected[i][j])) << "Q1(" << i << "," << j << ")";
}

TEST(GoldenOneStage, ClosedFormsArePrinted) {
  Derivation d = derive_paper("paper_one_stage", {"c", "r"});
  auto s = [&](const char* n) { return sym(d, n); };
  const ex rc = s("r_c"), rp = s("r_p"), rs1 = s("r_s1"), rs2 = s("r_s2"), rg = s("r_g"), rm = s("r_m"),
           rr1 = s("r_r1"), rr2 = s("r_r2");
  // Sec. III-B, J1, J3, J2 and b1, b3, b2 as printed.
  const ex J1 = s("J_c") + s("J_p") * pow(rc, 2) / pow(rp, 2) + 4 * s("J_s") * pow(rc, 2) / pow(rs1, 2) +
                4 * s("J_g") * pow(rc, 2) * pow(rs2, 2) / (pow(rg, 2) * pow(rs1, 2));
  const ex J3 = -s("J_p") * rc * rr1 / pow(rp, 2) - 2 * s("J_s") * rc * rr1 / pow(rs1, 2) -
                2 * s("J_g") * rc * rr1 * pow(rs2, 2) / (pow(rg, 2) * pow(rs1, 2));
  const ex J2 = s("J_r") + s("J_m") * pow(rr2, 2) / pow(rm, 2) + s("J_p") * pow(rr1, 2) / pow(rp, 2) +
                s("J_s") * pow(rr1, 2) / pow(rs1, 2) + s("J_g") * pow(rr1, 2) * pow(rs2, 2) / (pow(rg, 2) * pow(rs1, 2));
  const ex b1 = -s("b_c") - s("b_p") * pow(rc, 2) / pow(rp, 2) - 4 * s("b_s") * pow(rc, 2) / pow(rs1, 2) -
                4 * s("b_g") * pow(rc, 2) * pow(rs2, 2) / (pow(rg, 2) * pow(rs1, 2));
  const ex b3 = s("b_p") * rc * rr1 / pow(rp, 2) + 2 * s("b_s") * rc * rr1 / pow(rs1, 2) +
                2 * s("b_g") * rc * rr1 * pow(rs2, 2) / (pow(rg, 2) * pow(rs1, 2));
  const ex b2 = -s("b_r") - s("b_m") * pow(rr2, 2) / pow(rm, 2) - s("b_p") * pow(rr1, 2) / pow(rp, 2) -
                s("b_s") * pow(rr1, 2) / pow(rs1, 2) - s("b_g") * pow(rr1, 2) * pow(rs2, 2) / (pow(rg, 2) * pow(rs1, 2));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.L1(0, 0), J1));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.L1(0, 1), J3));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.L1(1, 0), J3));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.L1(1, 1), J2));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.A1(0, 0), b1));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.A1(0, 1), b3));
  EXPECT_TRUE(equal_under_geometry(d, d.rigid.A1(1, 1), b2));
  // The closed forms hold even without the geometry relations: they are the same expressions.
  EXPECT_TRUE((d.rigid.L1(0, 0) - J1).normal().is_zero());
  EXPECT_TRUE((d.rigid.A1(1, 1) - b2).normal().is_zero());
}

TEST(GoldenTwoStage, RadiusMatrixIsEquation10WithRq) {
  Derivation d = derive_paper("paper_two_stage", {"s", "r"});
  auto r = [&](const char* n) { return sym(d, n); };
  // Eq. (10), columns (s, c, p, a, r, b, q), rows (sp, sa, pr, ab, bq); last entry -r_q (docs/paper-errata.md E9).
  const ex expected[5][7] = {
      {r("r_s1"), -r("r_cp"), r("r_p"), 0, 0, 0, 0},
      {r("r_s2"), -r("r_ca"), 0, r("r_a"), 0, 0, 0},
      {0, r("r_cp"), r("r_p"), 0, -r("r_r"), 0, 0},
      {0, r("r_ca") - r("r_cb"), 0, r("r_a"), 0, r("r_b"), 0},
      {0, r("r_cb"), 0, 0, 0, r("r_b"), -r("r_q")},
  };
  for (unsigned i = 0; i < 5; ++i)
    for (unsigned j = 0; j < 7; ++j)
      EXPECT_TRUE((d.elastic.R(i, j) - expected[i][j]).expand().is_zero()) << "R(" << i << "," << j << ")";
}

TEST(GoldenTwoStage, GeometryRelationsAreThePapers) {
  Derivation d = derive_paper("paper_two_stage", {"s", "r"});
  auto r = [&](const char* n) { return sym(d, n); };
  // Sec. IV after eq. (10), and r_r = 2 r_p + r_s1 (docs/paper-errata.md E10).
  const std::map<std::string, ex> expected{
      {"r_cp", r("r_p") + r("r_s1")},
      {"r_ca", r("r_a") + r("r_s2")},
      {"r_cb", 2 * r("r_a") + r("r_b") + r("r_s2")},
      {"r_q", 2 * r("r_a") + 2 * r("r_b") + r("r_s2")},
      {"r_r", 2 * r("r_p") + r("r_s1")},
  };
  ASSERT_EQ(d.radius.relations.size(), expected.size());
  for (const auto& g : d.radius.relations) {
    ASSERT_TRUE(expected.count(g.parameter)) << g.parameter;
    EXPECT_TRUE((g.rhs - expected.at(g.parameter)).expand().is_zero()) << g.parameter;
  }
}

TEST(GoldenTwoStage, Q1IsThePrintedMatrixAsCorrected) {
  Derivation d = derive_paper("paper_two_stage", {"s", "r"});
  auto r = [&](const char* n) { return sym(d, n); };
  const ex rs1 = r("r_s1"), rs2 = r("r_s2"), rcp = r("r_cp"), rca = r("r_ca"), rcb = r("r_cb"), rr = r("r_r"),
           rp = r("r_p"), ra = r("r_a"), rb = r("r_b"), rq = r("r_q");
  // Rows s, c, p, a, r, b, q of Q1 for x1 = (omega_s, omega_r), as given in docs/paper-errata.md E13.
  const ex expected[7][2] = {
      {1, 0},
      {rs1 / (2 * rcp), rr / (2 * rcp)},
      {-rs1 / (2 * rp), rr / (2 * rp)},
      {(rca * rs1 - 2 * rcp * rs2) / (2 * ra * rcp), rca * rr / (2 * ra * rcp)},
      {0, 1},
      {(rcb * rs1 - 2 * rca * rs1 + 2 * rcp * rs2) / (2 * rb * rcp), -(2 * rca * rr - rcb * rr) / (2 * rb * rcp)},
      {(rcb * rs1 - rca * rs1 + rcp * rs2) / (rcp * rq), -(rca * rr - rcb * rr) / (rcp * rq)},
  };
  for (unsigned i = 0; i < 7; ++i)
    for (unsigned j = 0; j < 2; ++j)
      EXPECT_TRUE(equal_under_geometry(d, d.rigid.Q1(i, j), expected[i][j])) << "Q1(" << i << "," << j << ")";
}

}  // namespace
}  // namespace pogear::test
