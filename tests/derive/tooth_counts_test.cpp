// Wheels given by tooth count and module: the same gear as by its pitch radii, and the reports'
// ratios in tooth counts against the Willis equations written here.
#include "../support/json.hpp"
#include "common/exact_algebra.hpp"
#include "report/report.hpp"
#include "test_support.hpp"

namespace pogear::test {
namespace {

using GiNaC::ex;

// tests/errors/gear.toml (radii 4.8 cm for the planet, 10 cm for the sun wheel s1) with both wheels
// given as 24 and 50 teeth of a 4 mm module, the module once on the planet and once on the mesh.
std::string gear_by_teeth() {
  std::string t = read_text(source_path("tests/errors/gear.toml"));
  auto replace = [&](const std::string& from, const std::string& to) {
    const auto pos = t.find(from);
    EXPECT_NE(pos, std::string::npos) << from;
    if (pos != std::string::npos) t.replace(pos, from.size(), to);
  };
  replace("distance = \"r_c\" }", "distance = \"r_c\" }\nteeth = 24\nmodule = \"4*mm\"");
  replace("{ name = \"s1\", radius = \"r_s1\" }", "{ name = \"s1\", teeth = 50 }");
  replace("first = \"p\"\nsecond = \"s1\"\n", "first = \"p\"\nsecond = \"s1\"\nmodule = \"4*mm\"\n");
  replace("r_s1 = \"10*cm\"\n", "");
  replace("r_p = \"4.8*cm\"\n", "");
  return t;
}

Derivation derive_text(const std::string& text) {
  return derive_topology(parse_topology_text(text, "gear.toml"), std::nullopt, SourceLocation{"gear.toml", 0, 0});
}

TEST(ToothCounts, GearByTeethIsTheGearOfItsPitchRadii) {
  Derivation radii = derive_text(read_text(source_path("tests/errors/gear.toml")));
  Derivation teeth = derive_text(gear_by_teeth());
  const Eigen::MatrixXd R0 = evaluate_matrix(radii.elastic.R, radii.values);
  const Eigen::MatrixXd R1 = evaluate_matrix(teeth.elastic.R, teeth.values);
  // 24 * 4 mm / 2 = 4.8 cm and 50 * 4 mm / 2 = 10 cm are the file's radii exactly (as decimals).
  EXPECT_EQ(R0, R1);
  EXPECT_EQ(evaluate_matrix(radii.rigid.Q1, radii.values), evaluate_matrix(teeth.rigid.Q1, teeth.values));
  EXPECT_EQ(evaluate_matrix(radii.rigid.L1, radii.values), evaluate_matrix(teeth.rigid.L1, teeth.values));
}

// The entry (i, j) of the report's Q1 as an expression in the given symbols.
ex printed_q1(const Derivation& d, unsigned i, unsigned j, const GiNaC::symtab& symbols) {
  const Json report = parse_json(report_json(d));
  GiNaC::parser reader(symbols, true);  // strict: no symbol outside `symbols`
  return reader(report["Q1"][i][j].str);
}

TEST(ToothCounts, ReportsWriteRatiosInToothCounts) {
  const Derivation d = derive_paper("ravigneaux", {"ss", "sl"});
  GiNaC::symtab z;
  for (const char* name : {"Z_ss", "Z_sl", "Z_ps", "Z_pl", "Z_r"}) z[name] = GiNaC::realsymbol(name);
  const ex Z_ss = z["Z_ss"], Z_sl = z["Z_sl"], Z_ps = z["Z_ps"], Z_pl = z["Z_pl"], Z_r = z["Z_r"];
  // Every entry is a ratio of tooth counts: the module and every length cancel (a strict parser
  // refuses any other symbol).
  for (unsigned i = 0; i < d.rigid.Q1.rows(); ++i)
    for (unsigned j = 0; j < d.rigid.Q1.cols(); ++j) EXPECT_NO_THROW(printed_q1(d, i, j, z)) << i << "," << j;
  // With the large sun held: ring / small sun as transmission texts write it, and the short pinion
  // from Willis in the carrier's frame, equal under the layout's tooth relation Z_r = 2 Z_pl + Z_sl.
  const GiNaC::exmap layout{{Z_r, 2 * Z_pl + Z_sl}};
  const ex ring = Z_ss * (Z_r + Z_sl) / (Z_r * (Z_ss + Z_sl));
  EXPECT_TRUE((printed_q1(d, 5, 0, z) - ring).subs(layout).normal().is_zero()) << printed_q1(d, 5, 0, z);
  // omega_c = Z_ss / (Z_ss + Z_sl) omega_ss; (omega_ps - omega_c) = -Z_ss / Z_ps (omega_ss - omega_c).
  const ex carrier = Z_ss / (Z_ss + Z_sl);
  EXPECT_TRUE((printed_q1(d, 2, 0, z) - carrier).normal().is_zero());
  EXPECT_TRUE((printed_q1(d, 3, 0, z) - (carrier - Z_ss / Z_ps * (1 - carrier))).normal().is_zero());
}

TEST(ToothCounts, ModelsWithoutTeethPrintTheirRadii) {
  const Derivation d = derive_paper("paper_one_stage", {"c", "r"});
  const Json report = parse_json(report_json(d));
  EXPECT_EQ(report["Q1"][1][0].str, "-r_c/r_p");  // the paper's T1 block, as printed there
}

}  // namespace
}  // namespace pogear::test
