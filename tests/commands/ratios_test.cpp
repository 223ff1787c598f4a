// `pogear ratios --format json`: every engagement with its status, closed form and value, as the
// library computes them (the library against Willis' equations: tests/engagement/ratios_test.cpp).
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "../engagement/engagement_support.hpp"
#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "../support/json.hpp"
#include "derive/engagement.hpp"
#include "engage/gear_ratios.hpp"

namespace pogear::test {
namespace {

TEST(Ratios, JsonListsEveryEngagementWithStatusClosedFormAndValue) {
  const std::filesystem::path dir = test_dir("ratios_json");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " ratios " + source_path("models/simpson_3speed.toml") +
                                " --input i --output o --format json", dir);
  ASSERT_EQ(c.status, 0) << c.err;
  const Json j = parse_json(c.out);
  EXPECT_EQ(j["model"].str, "simpson_3speed");
  EXPECT_EQ(j["input"].str, "i");
  EXPECT_EQ(j["output"].str, "o");
  const Derivation d = derive_file("simpson_3speed");
  const GearRatios g = gear_ratios(d, "i", "o", SourceLocation{"test", 0, 0});
  ASSERT_EQ(j["engagements"].size(), g.engagements.size());
  for (std::size_t i = 0; i < g.engagements.size(); ++i) {
    const Json& e = j["engagements"][i];
    const EngagementRatio& x = g.engagements[i];
    ASSERT_EQ(e["engaged"].size(), x.engaged.size());
    for (std::size_t k = 0; k < x.engaged.size(); ++k)
      EXPECT_EQ(e["engaged"][k].str, d.topology.friction_elements[x.engaged[k]].name);
    EXPECT_EQ(e["status"].str, status_name(x.status));
    if (x.ratio) {
      EXPECT_EQ(e["value"].num, x.value);  // shortest round-trip form: the same double
      // The closed form reads back to the same value.
      GiNaC::symtab table;
      for (const auto& p : d.topology.parameters) table[p.name] = parameter_symbol(d.symbols, p.name);
      GiNaC::parser reader(table, true);
      const GiNaC::ex closed = reader(e["ratio"].str);
      EXPECT_TRUE((closed - *x.ratio).normal().is_zero()) << e["ratio"].str;
    } else {
      EXPECT_TRUE(e["ratio"].kind == Json::null);
      EXPECT_TRUE(e["value"].kind == Json::null);
    }
  }
}

// A model with [gears]: text lists the named gears with i, steps and spread, and the other
// engagements only with --all; JSON holds both, the gears as the library computes them.
TEST(Ratios, NamedGearsComeFirstAndTheRestWithAll) {
  const std::filesystem::path dir = test_dir("ratios_gears");
  const std::string command = std::string(POGEAR_EXECUTABLE) + " ratios " + source_path("models/simpson_3speed.toml") +
                              " --input i --output o";
  const Command text = run_command(command, dir), all = run_command(command + " --all", dir);
  ASSERT_EQ(text.status, 0) << text.err;
  ASSERT_EQ(all.status, 0) << all.err;
  const std::string gears_header = "  gear  engaged  i", engagements_header = "  engaged   status";
  EXPECT_NE(text.out.find(gears_header), std::string::npos) << text.out;
  EXPECT_NE(text.out.find("Spread (largest over smallest forward i): 2.41667."), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find(engagements_header), std::string::npos) << text.out;
  EXPECT_EQ(text.out.find("locked"), std::string::npos) << text.out;
  EXPECT_LT(all.out.find(gears_header), all.out.find(engagements_header)) << all.out;
  EXPECT_NE(all.out.find("locked"), std::string::npos) << all.out;

  const Command json = run_command(command + " --format json", dir);
  ASSERT_EQ(json.status, 0) << json.err;
  const Json j = parse_json(json.out);
  const Derivation d = derive_file("simpson_3speed");
  const GearRatios g = gear_ratios(d, "i", "o", SourceLocation{"test", 0, 0});
  EXPECT_EQ(j["engagements"].size(), g.engagements.size());
  ASSERT_EQ(j["gears"].size(), g.gears.size());
  for (std::size_t k = 0; k < g.gears.size(); ++k) {
    const Json& e = j["gears"][k];
    EXPECT_EQ(e["name"].str, g.gears[k].name);
    EXPECT_EQ(e["value"].num, g.gears[k].value);  // shortest round-trip form: the same double
    if (g.gears[k].step) EXPECT_EQ(e["step"].num, *g.gears[k].step);
    else EXPECT_TRUE(e["step"].kind == Json::null);
    ASSERT_EQ(e["engaged"].size(), g.gears[k].engaged.size());
    for (std::size_t n = 0; n < g.gears[k].engaged.size(); ++n)
      EXPECT_EQ(e["engaged"][n].str, d.topology.friction_elements[g.gears[k].engaged[n]].name);
  }
  ASSERT_TRUE(g.spread);
  EXPECT_EQ(j["spread"].num, *g.spread);
}

}  // namespace
}  // namespace pogear::test
