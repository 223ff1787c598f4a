// Gear ratios of every engagement against an independent reference: Willis' equation per
// planetary set, written in the test from tooth counts, solved with the engaged elements' equations.
// `pogear ratios --format json`: tests/commands/ratios_test.cpp.
#include <cmath>
#include <filesystem>
#include <map>
#include <set>

#include <Eigen/Dense>
#include <gtest/gtest.h>

#include "../support/files.hpp"
#include "common/exact_algebra.hpp"
#include "derive/engagement.hpp"
#include "engage/gear_ratios.hpp"
#include "read/tooth_counts.hpp"
#include "engagement_support.hpp"
#include "pogear/hybrid.hpp"
#include "specialize/reference_model.hpp"
#include "read/scene.hpp"
#include "specialize/specialization.hpp"

namespace pogear::test {
namespace {

// A planetary set of the reference: sun, carrier and ring as indices of the central members, and
// its basic ratio k = z_ring / z_sun. Willis: (w_s - w_c) = -k (w_r - w_c).
struct WillisSet {
  int sun, carrier, ring;
  double k;
};

// One reference engagement: what an element equates, over the central members (-1: the housing).
struct Joint {
  std::string name;
  int a, b;
};

struct Reference {
  std::string status;
  double ratio = 0;  // w_out / w_in when status is "ratio" or "output held"
  int freedoms = 0;
};

// The central members' motion with `engaged` stuck, solved in doubles from Willis' equations.
Reference willis_reference(int members, const std::vector<WillisSet>& sets, const std::vector<Joint>& joints,
                           const std::set<std::string>& engaged, int in, int out) {
  std::vector<Eigen::RowVectorXd> rows;
  for (const WillisSet& s : sets) {
    Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(members);
    r(s.sun) += 1;
    r(s.carrier) += -1 - s.k;
    r(s.ring) += s.k;
    rows.push_back(r);
  }
  for (const Joint& j : joints)
    if (engaged.count(j.name)) {
      Eigen::RowVectorXd r = Eigen::RowVectorXd::Zero(members);
      r(j.a) = 1;
      if (j.b >= 0) r(j.b) = -1;
      rows.push_back(r);
    }
  Eigen::MatrixXd W(rows.size(), members);
  for (std::size_t i = 0; i < rows.size(); ++i) W.row(i) = rows[i];
  Eigen::FullPivLU<Eigen::MatrixXd> lu(W);
  lu.setThreshold(1e-10);
  Reference ref;
  ref.freedoms = members - static_cast<int>(lu.rank());
  if (ref.freedoms == 0) ref.status = "locked";
  else if (ref.freedoms > 1) ref.status = "free";
  else {
    const Eigen::VectorXd v = lu.kernel().col(0);
    const double scale = v.cwiseAbs().maxCoeff();
    if (std::abs(v(in)) < 1e-12 * scale) ref.status = "input held";
    else {
      ref.ratio = v(out) / v(in);
      ref.status = std::abs(ref.ratio) < 1e-12 ? "output held" : "ratio";
    }
  }
  return ref;
}

// Both sets of the Simpson gear: sun 30, planets 21, ring 72 teeth (models/simpson_3speed.toml).
TEST(Ratios, SimpsonSetMatchesWillisEquationsForEveryEngagement) {
  const Derivation d = derive_file("simpson_3speed");
  const GearRatios g = gear_ratios(d, "i", "o", SourceLocation{"test", 0, 0});
  // Central members: 0 i, 1 r1, 2 s, 3 o (front carrier and rear ring), 4 c2.
  const double k = 72.0 / 30.0;
  const std::vector<WillisSet> sets{{2, 3, 1, k}, {2, 4, 3, k}};
  const std::vector<Joint> joints{{"C1", 0, 1}, {"C2", 0, 2}, {"B1", 2, -1}, {"B2", 4, -1}};
  EXPECT_EQ(g.gear_freedoms, 3);

  std::set<std::set<std::string>> listed;
  for (const EngagementRatio& e : g.engagements) {
    std::set<std::string> names;
    for (int i : e.engaged) names.insert(d.topology.friction_elements[i].name);
    listed.insert(names);
    const Reference ref = willis_reference(5, sets, joints, names, 0, 3);
    SCOPED_TRACE(engaged_names(d.topology, e.engaged, ","));
    EXPECT_EQ(status_name(e.status), ref.status);
    EXPECT_EQ(e.freedoms, ref.freedoms);
    // pogear's value is its exact closed form correctly rounded; the reference's LU solve of a 5x5
    // system of small integers and k: a few ulps.
    if (ref.status == "ratio") {
      EXPECT_NEAR(e.value, ref.ratio, 1e-14);
    }
    if (ref.status == "output held") {
      EXPECT_EQ(e.value, 0.0);
    }
  }
  // Every set is listed but the one of all four elements: any three lock the gear already.
  EXPECT_EQ(listed.size(), 15u);
  EXPECT_EQ(g.redundant_sets, 1);

  // The textbook ratios of the Simpson set, output over input: 1st k/(2k+1), 2nd k/(k+1), 3rd 1,
  // reverse -1/k.
  const std::map<std::set<std::string>, double> textbook{
      {{"C1", "B2"}, k / (2 * k + 1)}, {{"C1", "B1"}, k / (k + 1)}, {{"C1", "C2"}, 1.0}, {{"C2", "B2"}, -1 / k}};
  int found = 0;
  for (const EngagementRatio& e : g.engagements) {
    std::set<std::string> names;
    for (int i : e.engaged) names.insert(d.topology.friction_elements[i].name);
    if (auto it = textbook.find(names); it != textbook.end()) {
      ++found;
      EXPECT_EQ(e.status, EngagementStatus::ratio);
      EXPECT_NEAR(e.value, it->second, 1e-15) << "engaged " << engaged_names(d.topology, e.engaged, ",");
    }
  }
  EXPECT_EQ(found, 4);
}

TEST(Ratios, ClosedFormOfFirstGearIsTheTextbookFormulaInTheRadii) {
  const Derivation d = derive_file("simpson_3speed");
  const GearRatios g = gear_ratios(d, "i", "o", SourceLocation{"test", 0, 0});
  const auto r = [&](const std::string& name) { return parameter_symbol(d.symbols, name); };
  // k = r_ring / r_sun with the ring's radius from the geometry, r_s + 2 r_p.
  const GiNaC::ex k = (r("r_s") + 2 * r("r_p")) / r("r_s");
  for (const EngagementRatio& e : g.engagements)
    if (engaged_names(d.topology, e.engaged, ",") == "C1,B2") {
      ASSERT_TRUE(e.ratio);
      EXPECT_TRUE((*e.ratio - k / (2 * k + 1)).normal().is_zero()) << *e.ratio;
      return;
    }
  ADD_FAILURE() << "C1,B2 is not listed";
}

// Modelica's SimpleGearShift situation: the engine on the sun, the load on the carrier; the ring
// braked gives the reduction 1/(1 + z_r/z_s), the ring clutched to the sun direct drive.
TEST(Ratios, GearshiftPlanetaryIsAReductionWithTheBrakeAndDirectWithTheClutch) {
  const Derivation d = derive_file("gearshift_planetary");
  const GearRatios g = gear_ratios(d, "s", "c", SourceLocation{"test", 0, 0});
  std::map<std::string, const EngagementRatio*> by_name;
  for (const EngagementRatio& e : g.engagements) by_name[engaged_names(d.topology, e.engaged, ",")] = &e;
  ASSERT_TRUE(by_name.count("") && by_name.count("brake") && by_name.count("clutch") && by_name.count("brake,clutch"));
  const double zs = 100, zr = 150;  // the model's tooth counts (pitch radii in mm at module 1)
  EXPECT_EQ(by_name["brake"]->status, EngagementStatus::ratio);
  EXPECT_NEAR(by_name["brake"]->value, 1 / (1 + zr / zs), 1e-16);  // 0.4, correctly rounded: within an ulp
  EXPECT_EQ(by_name["clutch"]->status, EngagementStatus::ratio);
  EXPECT_EQ(by_name["clutch"]->value, 1.0);
  EXPECT_EQ(by_name["brake,clutch"]->status, EngagementStatus::locked);
  EXPECT_EQ(by_name[""]->status, EngagementStatus::free);
}

// A model given by tooth counts gets its ratios in tooth counts, as its reports write the rigid
// model: the gear shift's set with a 100-tooth sun, 25-tooth planets and a 150-tooth ring.
TEST(Ratios, AModelGivenByTeethHasItsRatiosInToothCounts) {
  std::string text = read_text(source_path("models/gearshift_planetary.toml"));
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"name = \"s\"                        # sun, with the engine's inertia\naxis = \"central\"",
                                            "name = \"s\"\naxis = \"central\"\nteeth = 100\nmodule = \"1*mm\""},
        {"axis = { carrier = \"c\", distance = \"r_c\" }", "axis = { carrier = \"c\", distance = \"r_c\" }\nteeth = 25\nmodule = \"1*mm\""},
        {"wheels = [ { name = \"r\", radius = \"r_r\", internal = true } ]",
         "wheels = [ { name = \"r\", teeth = 150, module = \"1*mm\", internal = true } ]"},
        {"r_s = \"50*mm\"", ""}, {"r_p = \"12.5*mm\"", ""}, {"r_r = \"75*mm\"", ""}}) {
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const Derivation d = derive_topology(parse_topology_text(text, "teeth.toml"), std::nullopt, SourceLocation{"teeth.toml", 0, 0});
  const GearRatios g = gear_ratios(d, "s", "c", SourceLocation{"test", 0, 0});
  const double zs = 100, zp = 25;
  bool brake_seen = false;
  for (const EngagementRatio& e : g.engagements) {
    if (engaged_names(d.topology, e.engaged, ",") != "brake") continue;
    brake_seen = true;
    ASSERT_TRUE(e.ratio);
    // Z_s / (2 (Z_p + Z_s)) = 1 / (1 + Z_r / Z_s) with Z_r = Z_s + 2 Z_p: 0.4. The tooth counts are
    // symbols of their own (not parameters): found in the form by name.
    GiNaC::exmap counts;
    std::set<std::string> names;
    for (GiNaC::const_preorder_iterator it = e.ratio->preorder_begin(); it != e.ratio->preorder_end(); ++it)
      if (GiNaC::is_a<GiNaC::symbol>(*it)) {
        const std::string name = GiNaC::ex_to<GiNaC::symbol>(*it).get_name();
        names.insert(name);
        counts[*it] = name == "Z_s" ? zs : name == "Z_p" ? zp : 0;
      }
    EXPECT_EQ(names, (std::set<std::string>{"Z_p", "Z_s"})) << *e.ratio;
    EXPECT_DOUBLE_EQ(GiNaC::ex_to<GiNaC::numeric>(GiNaC::evalf(e.ratio->subs(counts))).to_double(), zs / (2 * (zp + zs)));
    EXPECT_NEAR(e.value, zs / (2 * (zp + zs)), 1e-16);
  }
  EXPECT_TRUE(brake_seen);
}

// The value of a ratio in tooth counts is the tooth fraction correctly rounded, not its value at
// the pitch radii m Z / 2, which are doubles: with a module of 0.7 mm (no binary fraction) those
// radii are rounded, and so would the ratio be, by an ulp.
TEST(Ratios, AToothRatioIsTheCorrectlyRoundedFraction) {
  std::string text = read_text(source_path("models/gearshift_planetary.toml"));
  for (const auto& [from, to] :
       {std::pair<std::string, std::string>{"name = \"s\"                        # sun, with the engine's inertia\naxis = \"central\"",
                                            "name = \"s\"\naxis = \"central\"\nteeth = 37\nmodule = \"0.7*mm\""},
        {"axis = { carrier = \"c\", distance = \"r_c\" }", "axis = { carrier = \"c\", distance = \"r_c\" }\nteeth = 17\nmodule = \"0.7*mm\""},
        {"wheels = [ { name = \"r\", radius = \"r_r\", internal = true } ]",
         "wheels = [ { name = \"r\", teeth = 71, module = \"0.7*mm\", internal = true } ]"},
        {"r_s = \"50*mm\"", ""}, {"r_p = \"12.5*mm\"", ""}, {"r_r = \"75*mm\"", ""},
        {"r_c = \"62.5*mm\"", "r_c = \"18.9*mm\""}}) {  // (37 + 17) 0.7 mm / 2
    const std::size_t at = text.find(from);
    ASSERT_NE(at, std::string::npos) << from;
    text.replace(at, from.size(), to);
  }
  const Derivation d = derive_topology(parse_topology_text(text, "teeth.toml"), std::nullopt, SourceLocation{"teeth.toml", 0, 0});
  int ratios = 0;
  for (const auto& [in, out] : {std::pair<std::string, std::string>{"s", "c"}, {"c", "s"}, {"r", "s"}, {"s", "r"}}) {
    const GearRatios g = gear_ratios(d, in, out, SourceLocation{"test", 0, 0});
    for (const EngagementRatio& e : g.engagements) {
      if (e.status != EngagementStatus::ratio) continue;
      ASSERT_TRUE(e.ratio);
      GiNaC::exmap counts;
      for (GiNaC::const_preorder_iterator it = e.ratio->preorder_begin(); it != e.ratio->preorder_end(); ++it)
        if (GiNaC::is_a<GiNaC::symbol>(*it)) {
          const std::string name = GiNaC::ex_to<GiNaC::symbol>(*it).get_name();
          ASSERT_TRUE(name == "Z_s" || name == "Z_p" || name == "Z_r") << *e.ratio;
          counts[*it] = name == "Z_s" ? 37 : name == "Z_p" ? 17 : 71;
        }
      const GiNaC::ex fraction = e.ratio->subs(counts);
      ASSERT_TRUE(GiNaC::is_a<GiNaC::numeric>(fraction) && GiNaC::ex_to<GiNaC::numeric>(fraction).is_rational());
      // CLN rounds a rational to the nearest double.
      EXPECT_EQ(e.value, GiNaC::ex_to<GiNaC::numeric>(fraction).to_double())
          << in << " to " << out << " with " << engaged_names(d.topology, e.engaged, ",") << ": " << *e.ratio;
      ++ratios;
    }
  }
  EXPECT_GE(ratios, 4);
}

// With B2 a one-way brake (a low sprag on the rear carrier, holding it against turning back), the
// Simpson gear's 1st (C1 B2) holds in drive and freewheels in coast, the textbook "no engine
// braking in 1st"; its reverse (C2 B2) would need the sprag to hold the other way: no drive, which
// is why reverse takes a band. The hybrid engine agrees: under a driving torque on i against a load
// on o, B2 stays stuck with C1 and slips with C2.
TEST(Ratios, OneWayElementsHoldInDriveOrInCoast) {
  std::string text = read_text(source_path("models/simpson_3speed.toml"));
  const std::string b2 = "body = \"c2\"\nstatic_ratio = \"1.2\"";
  ASSERT_NE(text.find(b2), std::string::npos);
  text.replace(text.find(b2), b2.size(), "body = \"c2\"\nstatic_ratio = \"1.2\"\none_way = true");
  const std::filesystem::path dir = test_dir("ratios_one_way");
  write_text(dir / "sprag.toml", text);
  const Derivation d = derive_topology(parse_topology((dir / "sprag.toml").string()), std::nullopt, SourceLocation{});
  const GearRatios g = gear_ratios(d, "i", "o", SourceLocation{"test", 0, 0});
  std::map<std::string, const EngagementRatio*> by_name;
  for (const EngagementRatio& e : g.engagements) by_name[engaged_names(d.topology, e.engaged, ",")] = &e;
  ASSERT_TRUE(by_name.count("C1,B2") && by_name.count("C2,B2") && by_name.count("C1,B1"));
  ASSERT_EQ(by_name["C1,B2"]->one_way.size(), 1u);
  EXPECT_TRUE(by_name["C1,B2"]->one_way[0].drive);
  EXPECT_FALSE(by_name["C1,B2"]->one_way[0].coast);
  ASSERT_EQ(by_name["C2,B2"]->one_way.size(), 1u);
  EXPECT_FALSE(by_name["C2,B2"]->one_way[0].drive);
  EXPECT_TRUE(by_name["C2,B2"]->one_way[0].coast);
  EXPECT_TRUE(by_name["C1,B1"]->one_way.empty());

  for (const std::string clutch : {"C1", "C2"}) {
    SCOPED_TRACE(clutch);
    const SpecializedScene m = specialize(parse_scene_text(
        "name = \"sprag\"\nmodel = \"sprag.toml\"\neffects = [\"bearing_friction\"]\n"
        "[inputs]\ntau_i = \"50*N*m\"\ntau_o = \"-20*N*m\"\n[engagement]\n" + clutch + " = \"1\"\nB2 = \"1\"\n"
        "[simulation]\nhorizon = \"0.2*s\"\nsample = \"1*ms\"\n",
        (dir / "sprag_scene.toml").string()));
    const NumericSystem ns = numeric_system(m, m.main);
    const rt::HybridSystem hs = hybrid_system(m, m.main, ns);  // the engine keeps a reference
    rt::HybridEngine engine(hs, m.scene.horizon, rt::HybridMethod{});
    std::uint32_t mode = 0;
    const rt::RunStatus st = engine.run(
        ns.x0, m.scene.sample, [&](double, const rt::HybridSample& sample) { mode = sample.mode; return true; },
        [](const rt::HybridEvent&) {});
    ASSERT_TRUE(st.ok) << st.message;
    // Elements in the scene's order: the clutch (bit 0), then B2 (bit 1).
    EXPECT_EQ((mode >> 1) & 1u, clutch == "C1" ? 1u : 0u) << "mode " << mode;
  }
}

// The Simpson set's named gears as a transmission engineer quotes them (models/simpson_3speed.toml
// names 1 = C1 B2, 2 = C1 B1, 3 = C1 C2, R = C2 B2), against Willis' equation of each set with
// k = z_ring / z_sun = 72/30: 1st (rear carrier held) i = (2k + 1)/k, 2nd (sun held) (k + 1)/k,
// 3rd (front set locked) 1, reverse (input on the sun, rear carrier held) -k.
TEST(Ratios, NamedGearsAsTheEngineerQuotesThem) {
  const Derivation d = derive_file("simpson_3speed");
  const GearRatios g = gear_ratios(d, "i", "o", SourceLocation{"simpson_3speed.toml", 0, 0});
  const GiNaC::numeric k(72, 30);
  const std::vector<GiNaC::numeric> i{(2 * k + 1) / k, (k + 1) / k, 1, -k};
  const std::vector<std::string> names{"1", "2", "3", "R"};
  // The closed forms are ratios of radii: at the tooth counts (the radii in mm) they are Willis'
  // fractions exactly.
  GiNaC::exmap teeth;
  for (const auto& [name, z] : {std::pair{"r_s", 30}, {"r_p", 21}, {"r_r", 72}, {"r_c", 51}})
    teeth[parameter_symbol(d.symbols, name)] = z;
  // The values are at the model's radii, "30*mm" and so on as doubles (0.03 is not exact): the
  // exact ratio at those radii, correctly rounded, is within a few ulps of the fraction's.
  auto near = [](double value, const GiNaC::numeric& exact) {
    return std::abs(value - exact.to_double()) <= 4e-16 * std::abs(exact.to_double());
  };
  ASSERT_EQ(g.gears.size(), 4u);
  for (std::size_t n = 0; n < 4; ++n) {
    EXPECT_EQ(g.gears[n].name, names[n]);
    EXPECT_TRUE((g.gears[n].i.subs(teeth) - i[n]).normal().is_zero()) << names[n] << ": " << g.gears[n].i;
    EXPECT_TRUE(near(g.gears[n].value, i[n])) << names[n] << ": " << g.gears[n].value;
  }
  ASSERT_TRUE(g.gears[0].step && g.gears[1].step);
  EXPECT_TRUE(near(*g.gears[0].step, i[0] / i[1])) << *g.gears[0].step;
  EXPECT_TRUE(near(*g.gears[1].step, i[1] / i[2])) << *g.gears[1].step;
  EXPECT_FALSE(g.gears[2].step);  // the next gear is reverse
  EXPECT_FALSE(g.gears[3].step);  // the last
  ASSERT_TRUE(g.spread);
  EXPECT_TRUE(near(*g.spread, i[0] / i[2])) << *g.spread;
}

// The 6HP26's seven gears from the Willis equations of its two sets, in exact rationals: the front
// set's sun (37) held, ring (71) the input; the Ravigneaux set's small sun (31) through two pinions
// and its large sun (38) through one to the ring (85). Written here from the teeth alone.
GiNaC::numeric willis_6hp26(const std::vector<std::string>& engaged) {
  const GiNaC::symbol c1("c1"), s2("s2"), s3("s3"), c2("c2"), out("out");
  const GiNaC::ex in = 1;
  GiNaC::lst equations{
      (0 - c1) * 37 == -(in - c1) * 71,    // front: (w_s - w_c) Z_s = -(w_r - w_c) Z_r
      (s2 - c2) * 31 == (out - c2) * 85,   // small sun, two pinions: the ring turns with it
      (s3 - c2) * 38 == -(out - c2) * 85}; // large sun, one pinion: against it
  for (const std::string& e : engaged) {
    if (e == "A") equations.append(s2 == c1);
    if (e == "B") equations.append(s3 == c1);
    if (e == "C") equations.append(s3 == 0);
    if (e == "D") equations.append(c2 == 0);
    if (e == "E") equations.append(c2 == in);
  }
  const GiNaC::ex solution = GiNaC::lsolve(equations, GiNaC::lst{c1, s2, s3, c2, out});
  for (const GiNaC::ex& eq : solution)
    if (eq.lhs().is_equal(out)) return GiNaC::ex_to<GiNaC::numeric>(1 / eq.rhs());
  ADD_FAILURE() << "no solution for the output";
  return 0;
}

TEST(Ratios, ZF6HP26GearsAreTheWillisFractionsOfItsTeeth) {
  const Derivation d = derive_file("zf6hp26");
  const GearRatios g = gear_ratios(d, "in", "out", SourceLocation{"zf6hp26.toml", 0, 0});
  const std::vector<std::pair<std::string, std::vector<std::string>>> gears{
      {"1", {"A", "D"}}, {"2", {"A", "C"}}, {"3", {"A", "B"}}, {"4", {"A", "E"}},
      {"5", {"B", "E"}}, {"6", {"C", "E"}}, {"R", {"B", "D"}}};
  // As published, to the three decimals quoted.
  const std::vector<double> published{4.171, 2.340, 1.521, 1.143, 0.867, 0.691, -3.403};
  ASSERT_EQ(g.gears.size(), gears.size());
  for (std::size_t n = 0; n < gears.size(); ++n) {
    SCOPED_TRACE(gears[n].first);
    EXPECT_EQ(g.gears[n].name, gears[n].first);
    const GiNaC::numeric exact = willis_6hp26(gears[n].second);
    // The closed form is in tooth counts only (the long pinion's operating centre distance
    // cancels), and at the counts it is Willis' fraction exactly.
    const auto in_numbers = in_tooth_numbers(g.gears[n].i, d.topology);
    ASSERT_TRUE(in_numbers) << g.gears[n].i;
    EXPECT_TRUE((*in_numbers - exact).is_zero()) << *in_numbers << " vs " << exact;
    // The value is at the operating radii a Z / (Z_2 +- Z_1) and the pitch radii m Z / 2, doubles:
    // within a few ulps of the fraction.
    EXPECT_NEAR(g.gears[n].value, exact.to_double(), 4e-16 * std::abs(exact.to_double()));
    EXPECT_NEAR(g.gears[n].value, published[n], 5e-4);
  }
}

// A planet whose sun mesh is shifted to the ring mesh's reference centre distance (sun 30, planet 20,
// ring 71, module 2 mm: 51 mm, the sun's reference being 50 mm): the carrier's ratio is Willis'
// Z_s / (Z_s + Z_r) in tooth counts, the unshifted mesh's module cancelling the centre distance.
TEST(Ratios, OneShiftedMeshOfAPlanetKeepsTheRatioInTeeth) {
  // tests/errors/shifted.toml with its ring mesh at its reference and its sun mesh shifted to it.
  std::string model = read_text(source_path("tests/errors/shifted.toml"));
  const std::string shifted = "centre_distance = \"50.5*mm\"\n";
  model.replace(model.find(shifted), shifted.size(), "centre_distance = \"51*mm\"\n");
  model.erase(model.find(shifted), shifted.size());
  const Derivation d = derive_topology(parse_topology_text(model, "shifted.toml"), std::nullopt, SourceLocation{});
  const GearRatios g = gear_ratios(d, "s", "c", SourceLocation{"shifted.toml", 0, 0});
  ASSERT_EQ(g.engagements.size(), 1u);  // nothing to engage: the ring is fixed
  ASSERT_TRUE(g.engagements[0].ratio);
  const auto in_numbers = in_tooth_numbers(*g.engagements[0].ratio, d.topology);
  ASSERT_TRUE(in_numbers) << *g.engagements[0].ratio;  // tooth counts only
  EXPECT_TRUE((*in_numbers - GiNaC::numeric(30, 101)).is_zero()) << *in_numbers;
}

}  // namespace
}  // namespace pogear::test
