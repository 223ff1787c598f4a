// DIR/<scene>.shift.json of `pogear simulate` against the shift metrics an independent script of the
// test's own (tests/scripts/shift_metrics_reference.py, no pogear code) computes from the run's CSV
// and events file by docs/friction-elements.md's definitions. The functions alone, on hand-made runs:
// tests/run/shift_metrics_test.cpp.
#include <cmath>
#include <filesystem>
#include <string>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "../support/files.hpp"
#include "../support/json.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

struct Measured {
  Json pogear, reference;
  std::string text, summary;
};

// `suffix` "" for the scene's model, ".rigid" for its rigid comparison run.
Measured measure(const std::string& scene, const std::string& options = "", const std::string& suffix = "") {
  const fs::path dir = temp_dir("shift_metrics_" + scene);
  const std::string toml = source_path("models/scenes/" + scene + ".toml");
  const Command run = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + toml + " " + options + " -o " + dir.string());
  EXPECT_EQ(run.status, 0) << run.err;
  const Command ref = run_command("python3 " + source_path("tests/scripts/shift_metrics_reference.py") + " " + toml + " " +
                                  dir.string() + (suffix.empty() ? "" : " " + suffix));
  EXPECT_EQ(ref.status, 0) << ref.err;
  Measured m;
  m.text = read_text(dir / (scene + suffix + ".shift.json"));
  m.summary = run.out;
  m.pogear = parse_json(m.text);
  m.reference = parse_json(ref.out);
  return m;
}

// Both read the same samples and the same event times (shortest round-trip decimals, read back to the
// same doubles) and apply the same definitions: times and slip times are the events' own, sums of a
// few of them differing in the order of their terms (a few ulps of 1 s); heat is a difference of two
// interpolated samples, powers and torques products of sampled values. So the two agree to rounding;
// 1e-12 (relative, absolute below 1) is a thousand times that and far below any definition's
// difference (the first against the last break-away of the Simpson B2 is 9.2e-4 s).
void expect_close(const Json& a, const Json& b, const std::string& what) {
  ASSERT_EQ(a.kind, Json::number) << what;
  ASSERT_EQ(b.kind, Json::number) << what;
  EXPECT_NEAR(a.num, b.num, 1e-12 * std::max(1.0, std::abs(b.num))) << what;
}

void expect_matches_reference(const Measured& m) {
  const Json& shifts = m.pogear["shifts"];
  const Json& ref = m.reference["shifts"];
  ASSERT_EQ(shifts.size(), ref.size());
  ASSERT_GT(shifts.size(), 0u);
  for (std::size_t i = 0; i < shifts.size(); ++i) {
    const Json &s = shifts[i], &r = ref[i];
    SCOPED_TRACE("shift " + std::to_string(i + 1));
    expect_close(s["start_s"], r["start_s"], "start");
    expect_close(s["end_s"], r["end_s"], "end");
    ASSERT_EQ(s["offgoing"].size(), r["offgoing"].size());
    for (std::size_t k = 0; k < s["offgoing"].size(); ++k) EXPECT_EQ(s["offgoing"][k].str, r["offgoing"][k].str);
    for (std::size_t k = 0; k < s["oncoming"].size(); ++k) EXPECT_EQ(s["oncoming"][k].str, r["oncoming"][k].str);
    expect_close(s["torque_phase"]["end_s"], r["torque_phase_end_s"], "torque phase end");
    expect_close(s["inertia_phase"]["duration_s"], r["inertia_phase_s"], "inertia phase");
    expect_close(s["lockup_s"], r["lockup_s"], "lock-up");
    expect_close(s["time_to_lockup_s"], r["time_to_lockup_s"], "time to lock-up");
    ASSERT_EQ(s["elements"].size(), r["elements"].size());
    for (const Json& e : s["elements"].items) {
      const std::string name = e["element"].str;
      const Json& re = r["elements"][name];
      expect_close(e["slip_time_s"], re["slip_time_s"], name + " slip time");
      expect_close(e["heat_J"], re["heat_J"], name + " heat");
      if (re["peak_slip_power_W"].kind == Json::null) EXPECT_EQ(e["peak_slip_power"].kind, Json::null) << name;
      else expect_close(e["peak_slip_power"]["value_W"], re["peak_slip_power_W"], name + " peak slip power");
    }
    if (r.fields.count("output_torque")) {
      const Json &o = s["output_torque"], &ro = r["output_torque"];
      expect_close(o["before_Nm"], ro["before_Nm"], "output torque before");
      expect_close(o["min"]["value_Nm"], ro["min_Nm"], "output torque min");
      expect_close(o["max"]["value_Nm"], ro["max_Nm"], "output torque max");
      expect_close(o["min_ratio"], ro["min_ratio"], "min ratio");
      expect_close(o["max_ratio"], ro["max_ratio"], "max ratio");
    } else {
      EXPECT_EQ(s["output_torque"].kind, Json::null);
    }
    if (r.fields.count("peak_jerk_m_per_s3")) expect_close(s["peak_jerk"]["value_m_per_s3"], r["peak_jerk_m_per_s3"], "jerk");
    else EXPECT_EQ(s["peak_jerk"].kind, Json::null);
  }
}

// The shipped clutch-to-clutch upshift: B2 out, B1 in over 150 ms from 1 s; elastic meshes ring B2
// through two re-sticks before it lets go for good at 1.07998 s, and B1 locks at 1.11122 s.
TEST(ShiftMetrics, SimpsonUpshiftAgainstAnIndependentReference) {
  const Measured m = measure("simpson_1_2_upshift");
  expect_matches_reference(m);
  const Json& s = m.pogear["shifts"][0];
  EXPECT_EQ(s["offgoing"][0].str, "B2");
  EXPECT_EQ(s["oncoming"][0].str, "B1");
  EXPECT_NEAR(s["lockup_s"].num, 1.1112, 1e-4);
  EXPECT_NEAR(s["torque_phase"]["end_s"].num, 1.0800, 1e-4);
  // The heat B1 takes is about its capacity's share times the slip it removes: kJ, not J or MJ.
  EXPECT_GT(s["elements"][1]["heat_J"].num, 1000);
  EXPECT_LT(s["elements"][1]["heat_J"].num, 5000);
  EXPECT_EQ(m.pogear["output_torque"].kind, Json::null);  // no torque of the output in its CSV: said, not guessed
  EXPECT_NE(m.summary.find("shift 1 at 1 s: B2 -> B1, torque phase 0.07998 s, inertia phase 0.03124 s, lock-up at 1.11122 s"),
            std::string::npos)
      << m.summary;
  // Keys in the documented order.
  std::size_t at = 0;
  for (const std::string key : {"\"scene\"", "\"output_torque\"", "\"jerk\"", "\"omitted\"", "\"shifts\"", "\"shift\"",
                                "\"start_s\"", "\"end_s\"", "\"commands_end_s\"", "\"offgoing\"", "\"oncoming\"",
                                "\"torque_phase\"", "\"inertia_phase\"", "\"lockup_s\"", "\"time_to_lockup_s\"",
                                "\"elements\"", "\"element\"", "\"slip_time_s\"", "\"heat_J\"", "\"peak_slip_power\"",
                                "\"events\"", "\"output_torque\"", "\"peak_jerk\"", "\"omitted\""}) {
    const std::size_t next = m.text.find(key, at);
    ASSERT_NE(next, std::string::npos) << key << " after " << at;
    at = next + key.size();
  }
}

// The same upshift's rigid comparison run has metrics of its own, DIR/<scene>.rigid.shift.json:
// without the meshes' ringing B2 breaks away once, and the summary prints its line after "rigid: ".
TEST(ShiftMetrics, RigidRunOfTheSimpsonUpshiftAgainstTheReference) {
  const Measured m = measure("simpson_1_2_upshift", "--interpreted", ".rigid");
  expect_matches_reference(m);
  const Json& s = m.pogear["shifts"][0];
  EXPECT_EQ(s["offgoing"][0].str, "B2");
  EXPECT_EQ(s["oncoming"][0].str, "B1");
  EXPECT_NEAR(s["lockup_s"].num, 1.1112, 1e-4);  // the rigid gear's lock-up, within 1e-5 s of the elastic one's
  EXPECT_NE(m.summary.find("rigid: shift 1 at 1 s: B2 -> B1"), std::string::npos) << m.summary;
}

// What the events give (phases, slip times) and the heat (E is constant where the ends fall) do not
// depend on the sample period; the sampled peaks do, and only by what the samples miss. The Simpson
// upshift at 0.1 ms against its 1 ms (measured): the events, located on other step sequences, 4.4e-14 s
// apart; the heat 2.5e-13 of itself apart; the peak slip powers higher by what the 1 ms samples miss
// (B1 0.087 %, B2 0.76 %; at 10 us 0.11 % and 0.76 %), never lower (the 1 ms samples are among the
// 0.1 ms ones). Hence 1e-9 for what does not depend on the samples, and 1 % for the peaks.
TEST(ShiftMetrics, SamplePeriodMovesOnlyTheSampledPeaks) {
  const fs::path dir = temp_dir("shift_metrics_sample");
  write_text(dir / "simpson_1_2_upshift.toml",
             with_edits(read_text(source_path("models/scenes/simpson_1_2_upshift.toml")),
                        {{"../simpson_3speed.toml", source_path("models/simpson_3speed.toml")},
                         {"simpson_B2_release.csv", source_path("models/scenes/simpson_B2_release.csv")},
                         {"simpson_B1_apply.csv", source_path("models/scenes/simpson_B1_apply.csv")},
                         {"horizon = \"2*s\"", "horizon = \"1.2*s\""},
                         {"sample = \"1*ms\"", "sample = \"0.1*ms\""}}));
  const Command fine = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "simpson_1_2_upshift.toml").string() +
                                   " -o " + (dir / "fine").string());
  ASSERT_EQ(fine.status, 0) << fine.err;
  const Json f = parse_json(read_text(dir / "fine" / "simpson_1_2_upshift.shift.json"))["shifts"][0];
  const Json c = measure("simpson_1_2_upshift").pogear["shifts"][0];
  for (const std::string key : {"lockup_s", "time_to_lockup_s"}) EXPECT_NEAR(f[key].num, c[key].num, 1e-9) << key;
  EXPECT_NEAR(f["torque_phase"]["end_s"].num, c["torque_phase"]["end_s"].num, 1e-9);
  for (std::size_t k = 0; k < c["elements"].size(); ++k) {
    const Json &fe = f["elements"][k], &ce = c["elements"][k];
    SCOPED_TRACE(ce["element"].str);
    EXPECT_NEAR(fe["slip_time_s"].num, ce["slip_time_s"].num, 1e-9);
    EXPECT_NEAR(fe["heat_J"].num, ce["heat_J"].num, 1e-9 * std::max(1.0, ce["heat_J"].num));
    const double pf = fe["peak_slip_power"]["value_W"].num, pc = ce["peak_slip_power"]["value_W"].num;
    EXPECT_GE(pf, pc * (1 - 1e-9));
    EXPECT_LE(pf, pc * 1.01 + 1e-6);  // C1 is stuck: 0 W at both
  }
}

// The same shift driving a car on compliant half-shafts (dopri5): the output torque is the
// half-shafts' and the jerk the car's, both columns of its CSV.
TEST(ShiftMetrics, VehicleUpshiftOutputTorqueAndJerkAgainstTheReference) {
  const Measured m = measure("simpson_vehicle_upshift");
  expect_matches_reference(m);
  EXPECT_EQ(m.pogear["output_torque"].str, "T_half_shafts");
  EXPECT_EQ(m.pogear["jerk"].str, "vehicle_jerk");
  EXPECT_NE(m.summary.find("output torque "), std::string::npos) << m.summary;
}

// Slips in rpm (speed_unit = "rpm"): the slip power is in W all the same; interpreted run.
TEST(ShiftMetrics, SixSpeedUpshiftInRpmAgainstTheReference) {
  const Measured m = measure("zf6hp26_1_2_upshift", "--interpreted");
  expect_matches_reference(m);
  const Json& c = m.pogear["shifts"][0]["elements"][1];
  ASSERT_EQ(c["element"].str, "C");
  // heat / slip time is the mean slip power; the peak is above it, and not 30/pi times it.
  const double mean = c["heat_J"].num / c["slip_time_s"].num;
  EXPECT_GT(c["peak_slip_power"]["value_W"].num, mean);
  EXPECT_LT(c["peak_slip_power"]["value_W"].num, 4 * mean);
}

}  // namespace
}  // namespace pogear::test
