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

}  // namespace
}  // namespace pogear::test
