// The shift metrics' functions (generator/src/run/shift_metrics) on hand-made runs whose metrics
// are known in closed form: the command windows, the phases from the events, slip times, heat,
// peak slip power (slips in rpm), the output torque's extrema and the peak jerk.
#include <cmath>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "run/shift_metrics.hpp"

namespace pogear {
namespace {

rt::Signal table(std::vector<double> t, std::vector<double> v) { return rt::Table{std::move(t), std::move(v)}; }

// Two ramps that overlap make one window; a step is a window of no length; a ramp that runs on to
// the horizon ends there; a constant makes none.
TEST(ShiftMetrics, CommandWindowsMergeWhereTheyOverlap) {
  const std::vector<ShiftElement> elements{{"A", table({0, 1, 2}, {1, 1, 0})},
                                           {"B", table({0, 1.5, 2.5}, {0, 0, 1})},
                                           {"C", rt::Step{0, 0.5, 4}},
                                           {"D", rt::Ramp{5, 0.1, 0}},
                                           {"E", rt::Constant{1}}};
  const std::vector<CommandWindow> w = command_windows(elements, 6);
  ASSERT_EQ(w.size(), 3u);
  EXPECT_EQ(w[0].start, 1);
  EXPECT_EQ(w[0].end, 2.5);
  EXPECT_EQ(w[1].start, 4);
  EXPECT_EQ(w[1].end, 4);
  EXPECT_EQ(w[2].start, 5);
  EXPECT_EQ(w[2].end, 6);
}

// X (off-going) releases from 1 to 2 s, Y (on-coming) applies from 1 to 2 s. X breaks away at 1.25 s,
// sticks again at 1.3 s and leaves for good at 1.35 s (ringing); Y locks at 1.75 s. Sampled every
// 0.05 s: E_Y = 100 (t - 1) J while Y slips, then 75 J; E_X = 40 (t - 1.35) J from 1.35 s to 2 s;
// Y carries 10 N m at a slip of 600 (1.75 - t) rpm, so |T slip| = 200 pi (1.75 - t) W, largest at 1 s.
TEST(ShiftMetrics, PhasesSlipTimesHeatAndPowersOfAHandMadeShift) {
  RunTable run;
  run.names = {"t", "T_half_shafts", "vehicle_jerk", "T_X", "T_Y", "slip_X", "slip_Y", "E_X", "E_Y", "mode"};
  run.units = {"s", "N m", "m/s^3", "N m", "N m", "rpm", "rpm", "J", "J", ""};
  for (int i = 0; i <= 60; ++i) {
    const double t = i / 20.0;  // correctly rounded, as the events' times are
    const bool y_slips = t >= 1 && t < 1.75, x_slips = t >= 1.35 && t < 2;
    const double torque = t < 1 ? 100 : i == 30 ? 50 : i == 36 ? 150 : 120;
    const double jerk = i == 32 ? -7 : i == 60 ? 100 : 1;  // the 100 after the shift is not its peak
    const double e_x = t < 1.35 ? 0 : 40 * (std::min(t, 2.0) - 1.35);
    const double e_y = t < 1 ? 0 : 100 * (std::min(t, 1.75) - 1);
    const int mode = (x_slips || t >= 2 ? 0 : 1) | (t >= 1.75 ? 2 : 0);
    run.rows.push_back({t, torque, jerk, x_slips ? 5.0 : 0.0, y_slips ? 10.0 : 0.0, x_slips ? 3.0 : 0.0,
                        y_slips ? 600 * (1.75 - t) : 0.0, e_x, e_y, static_cast<double>(mode)});
  }
  const std::vector<RunEvent> events{{1, "Y", "open", "slipping"},      {1.25, "X", "stuck", "slipping"},
                                     {1.3, "X", "slipping", "stuck"},   {1.35, "X", "stuck", "slipping"},
                                     {1.75, "Y", "slipping", "stuck"},  {2, "X", "slipping", "open"},
                                     {2.5, "limiter", "linear", "at_limit"}};  // a controller's: not an element
  const std::vector<ShiftElement> elements{{"X", table({0, 1, 2}, {1, 1, 0})}, {"Y", table({0, 1, 2}, {0, 0, 1})}};
  const ShiftMetrics m = measure_shifts(run, events, elements, 3);
  EXPECT_EQ(m.output_torque, "T_half_shafts");
  EXPECT_EQ(m.jerk, "vehicle_jerk");
  ASSERT_EQ(m.shifts.size(), 1u);
  const ShiftMeasure& s = m.shifts[0];
  EXPECT_EQ(s.start, 1);
  EXPECT_EQ(s.end, 2);
  EXPECT_EQ(s.offgoing, std::vector<std::string>{"X"});
  EXPECT_EQ(s.oncoming, std::vector<std::string>{"Y"});
  ASSERT_TRUE(s.torque_phase && s.inertia_phase && s.lockup);
  EXPECT_EQ(s.torque_phase->start, 1);
  EXPECT_EQ(s.torque_phase->end, 1.35);  // the last release, not the first break-away
  EXPECT_EQ(s.inertia_phase->start, 1.35);
  EXPECT_EQ(s.inertia_phase->end, 1.75);
  EXPECT_EQ(*s.lockup, 1.75);
  ASSERT_EQ(s.elements.size(), 2u);
  const ElementShift &x = s.elements[0], &y = s.elements[1];
  EXPECT_NEAR(x.slip_time, 0.05 + 0.65, 1e-15);
  EXPECT_NEAR(y.slip_time, 0.75, 1e-15);
  EXPECT_EQ(x.events, 4);
  EXPECT_EQ(y.events, 2);
  EXPECT_NEAR(x.heat, 26, 1e-12);
  EXPECT_NEAR(y.heat, 75, 1e-12);
  ASSERT_TRUE(y.peak_slip_power && x.peak_slip_power);
  EXPECT_NEAR(y.peak_slip_power->value, 200 * std::numbers::pi * 0.75, 1e-9);
  EXPECT_EQ(y.peak_slip_power->at, 1);
  EXPECT_NEAR(x.peak_slip_power->value, 15 * std::numbers::pi / 30, 1e-12);
  ASSERT_TRUE(s.output_torque && s.peak_jerk);
  EXPECT_EQ(s.output_torque->before, 100);
  EXPECT_EQ(s.output_torque->min.value, 50);
  EXPECT_NEAR(s.output_torque->min.at, 1.5, 1e-12);
  EXPECT_EQ(s.output_torque->max.value, 150);
  EXPECT_DOUBLE_EQ(*s.output_torque->min_ratio, 0.5);
  EXPECT_DOUBLE_EQ(*s.output_torque->max_ratio, 1.5);
  EXPECT_EQ(s.peak_jerk->value, -7);
  EXPECT_TRUE(s.omitted.empty());

  // Without an off-going element there is no torque phase, and JSON says why instead of a number.
  const std::vector<ShiftElement> apply_only{{"X", rt::Constant{1}}, {"Y", table({0, 1, 2}, {0, 0, 1})}};
  const ShiftMetrics a = measure_shifts(run, events, apply_only, 3);
  ASSERT_EQ(a.shifts.size(), 1u);
  EXPECT_FALSE(a.shifts[0].torque_phase);
  EXPECT_TRUE(a.shifts[0].lockup);
  const std::string json = shift_metrics_json(a);
  EXPECT_NE(json.find("\"torque_phase\": null"), std::string::npos) << json;
  EXPECT_NE(json.find("torque_phase: no element's command falls"), std::string::npos) << json;
}

}  // namespace
}  // namespace pogear
