// Friction that varies with slip (friction_curve): a curve of ratio 1 throughout reproduces the run
// without one bit for bit, and a linear curve on one rigid body follows its closed form with every
// method that runs it, compiled and interpreted.
#include <cmath>
#include <filesystem>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/braked_wheels.hpp"
#include "../support/commands.hpp"
#include "../support/csv.hpp"
#include "../support/files.hpp"

namespace pogear::test {
namespace {

namespace fs = std::filesystem;

// Runs dir/scene.toml with `args`; its output directory.
fs::path simulate_curve_scene(const fs::path& dir, const std::string& args) {
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " simulate " + (dir / "scene.toml").string() + " " +
                                args + " -o " + (dir / "out").string());
  EXPECT_EQ(c.status, 0) << c.err;
  return dir / "out";
}

// The shipped Simpson 1-2 upshift, its three elements given a friction curve of ratio 1 at every
// slip: every file the run writes is the run without curves, byte for byte. (A constant curve is a
// constant ratio: it folds into the capacity, here times 1, and the element stays linear.)
TEST(FrictionCurve, RatioOneThroughoutReproducesTheRunBitForBit) {
  const std::string model = read_text(source_path("models/simpson_3speed.toml"));
  const std::string one = "friction_curve = [[\"0*rad/s\", 1], [\"20*rad/s\", 1], [\"500*rpm\", 1]]\n";
  std::string curved = model;
  for (const std::string bodies : {"bodies = [\"i\", \"r1\"]\n", "body = \"s\"\n", "body = \"c2\"\n"})  // C1, B1, B2
    curved = with_edits(curved, {{bodies, bodies + one}});
  ASSERT_NE(curved, model);
  const std::string scene = with_edits(read_text(source_path("models/scenes/simpson_1_2_upshift.toml")),
                                       {{"\"../simpson_3speed.toml\"", "\"simpson_3speed.toml\""},
                                        {"\"simpson_B2_release.csv\"", "\"" + source_path("models/scenes/simpson_B2_release.csv") + "\""},
                                        {"\"simpson_B1_apply.csv\"", "\"" + source_path("models/scenes/simpson_B1_apply.csv") + "\""}});
  std::vector<fs::path> outs;
  for (const std::string* m : std::vector<const std::string*>{&model, &curved}) {
    const fs::path dir = temp_dir(m == &model ? "curve_none" : "curve_one");
    fs::create_directories(dir);
    write_text(dir / "simpson_3speed.toml", *m);
    write_text(dir / "scene.toml", scene);
    outs.push_back(simulate_curve_scene(dir, "--interpreted"));
  }
  int compared = 0;
  for (const auto& f : fs::directory_iterator(outs[0])) {
    const fs::path other = outs[1] / f.path().filename();
    ASSERT_TRUE(fs::exists(other)) << other;
    EXPECT_EQ(read_text(f.path()), read_text(other)) << f.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 4);  // the elastic and rigid CSV, the events and the shift metrics at least
}

// The converter's lock-up clutch of the shipped ZF 6HP26 launch with a constant curve of ratio 0.5
// is one of half the capacity and twice the static ratio (the same static capacity): every file the
// runs write is the same, byte for byte. Its run with a varying curve differs.
TEST(FrictionCurve, LockUpClutchTakesACurve) {
  const std::string scene = with_edits(read_text(source_path("models/scenes/zf6hp26_launch.toml")),
                                       {{"\"../zf6hp26.toml\"", "\"" + source_path("models/zf6hp26.toml") + "\""}});
  for (const std::string table : {"zf6hp26_launch_C_apply.csv", "zf6hp26_launch_D_release.csv", "zf6hp26_launch_lockup.csv"})
    ASSERT_NE(scene.find("\"" + table + "\""), std::string::npos) << table;
  auto variant = [&](const std::string& name, const std::string& lockup) {
    std::string text = with_edits(scene, {{"lockup = { capacity = \"700*N*m\", static_ratio = 1.2 }", lockup}});
    for (const std::string table : {"zf6hp26_launch_C_apply.csv", "zf6hp26_launch_D_release.csv", "zf6hp26_launch_lockup.csv"})
      text = with_edits(text, {{"\"" + table + "\"", "\"" + source_path("models/scenes/" + table) + "\""}});
    const fs::path dir = temp_dir(name);
    fs::create_directories(dir);
    write_text(dir / "scene.toml", text);
    return simulate_curve_scene(dir, "--interpreted");
  };
  const fs::path curved = variant("lockup_half_curve", "lockup = { capacity = \"700*N*m\", static_ratio = 1.2, friction_curve = "
                                                       "[[\"0*rad/s\", 0.5], [\"100*rad/s\", 0.5]] }");
  const fs::path halved = variant("lockup_half_capacity", "lockup = { capacity = \"350*N*m\", static_ratio = 2.4 }");
  const fs::path varying = variant("lockup_varying", "lockup = { capacity = \"700*N*m\", static_ratio = 1.2, friction_curve = "
                                                     "[[\"0*rad/s\", 1], [\"20*rad/s\", 0.8]] }");
  int compared = 0;
  for (const auto& f : fs::directory_iterator(halved)) {
    EXPECT_EQ(read_text(f.path()), read_text(curved / f.path().filename())) << f.path().filename();
    ++compared;
  }
  EXPECT_GE(compared, 3);  // the CSV, the events and the shift metrics at least
  EXPECT_NE(read_text(varying / "zf6hp26_launch.events.csv"), read_text(halved / "zf6hp26_launch.events.csv"));
}

// Two rigid wheels meshing, b on a fixed axis (J = J_a + J_b (r_a / r_b)^2 = 0.5 kg m^2 at a, no bearing friction), a
// at w0 = +-150 rad/s against brake B of capacity c = 20 N m fully applied, whose friction curve
// rises linearly from 0.5 at zero slip to 1.5 at 100 rad/s and holds 1.5 beyond: the kinetic torque
// is c f(|w|) = 10 + 0.2 |w| N m. (A curve whose f(0) is not 1 catches a ratio applied twice: in the
// capacity and again along the curve.) Above 100 rad/s the speed falls linearly, |w| = 150 - 60 t,
// until t1 = 5/6 s; then J |w|' = -(10 + 0.2 |w|): |w| + 50 = 150 e^(-0.4 (t - t1)), the brake
// locking at t1 + 2.5 ln 3. All the kinetic energy J w0^2 / 2 = 5625 J becomes the brake's heat.
std::string two_wheels_model() {
  return with_edits(braked_wheels_model(),
                    {{"static_ratio = 1.2\n", "static_ratio = 1.2\nfriction_curve = [[\"0*rad/s\", 0.5], [\"100*rad/s\", 1.5]]\n"}});
}

double closed_form_speed(double t) {
  const double t1 = 5.0 / 6.0;
  if (t <= t1) return 150 - 60 * t;
  return std::max(150 * std::exp(-0.4 * (t - t1)) - 50, 0.0);
}

// The two wheels spun at +-150 rad/s with `solver`, run `path` ("" compiled, "--interpreted"),
// against the closed form: speed, heat and lock time.
void expect_linear_curve_closed_form(const std::string& solver, const std::string& path, double sign) {
  const double t_lock = 5.0 / 6.0 + 2.5 * std::log(3.0);
  SCOPED_TRACE(solver + " " + path + (sign > 0 ? " forward" : " backward"));
  const fs::path dir = temp_dir("curve_" + solver + (path.empty() ? "_compiled" : "_interpreted") +
                                (sign > 0 ? "_fwd" : "_back"));
  fs::create_directories(dir);
  write_text(dir / "two_wheels.toml", two_wheels_model());
  write_text(dir / "scene.toml",
             "name = \"spin\"\nmodel = \"two_wheels.toml\"\neffects = []\n[initial]\nomega_a = \"" +
                 std::to_string(static_cast<int>(150 * sign)) + "*rad/s\"\n[engagement]\nB = \"1\"\n"
                 "[simulation]\nhorizon = \"4*s\"\nsample = \"1*ms\"\nsolver = \"" + solver +
                 "\"\ntolerance = 1e-10\n");
  const fs::path out = simulate_curve_scene(dir, path);
  const Csv csv = read_csv((out / "spin.csv").string());
  const std::size_t t = csv.column("t"), w = csv.column("omega_a"), E = csv.column("E_B");
  ASSERT_LT(E, csv.header.size());
  ASSERT_EQ(csv.rows.size(), 4001u);
  double worst = 0;
  for (const auto& row : csv.rows) worst = std::max(worst, std::abs(sign * row[w] - closed_form_speed(row[t])));
  // At a tolerance of 1e-10 (relative: 1e-8 rad/s per step at 100 rad/s) dopri5 ends 3.1e-8
  // rad/s off, the steps after the curve's corner at 100 rad/s, where it ends a step (without
  // that, 1.6e-7); TR-BDF2, of order 2, accumulates 2.0e-6 over its 1456 steps. The heat is
  // off by J w dw of that (1.6e-6 J, 1.0e-4 J); the lock time by the speed's error over its
  // final rate |w'| = 2 rad/s^2 (5.4e-10 s, 8.5e-8 s). Each bound is 3 to 5 times the measured.
  const bool dopri5 = solver == "dopri5";
  EXPECT_LT(worst, dopri5 ? 1.5e-7 : 1e-5);
  EXPECT_NEAR(csv.rows.back()[E], 0.5 * 0.5 * 150 * 150, dopri5 ? 1e-5 : 5e-4);
  // The lock: the events file's B slipping -> stuck.
  const std::string events = read_text(out / "spin.events.csv");
  const auto at = events.find(",B,slipping,stuck");
  ASSERT_NE(at, std::string::npos) << events;
  const double t_event = std::stod(events.substr(events.rfind('\n', at) + 1));
  EXPECT_NEAR(t_event, t_lock, dopri5 ? 3e-9 : 4e-7);
}

// Both directions, with both methods that run a curve.
TEST(FrictionCurve, LinearCurveOnOneBodyFollowsTheClosedForm) {
  for (const std::string solver : {"dopri5", "implicit"})
    for (const double sign : {1.0, -1.0}) expect_linear_curve_closed_form(solver, "--interpreted", sign);
}

// Compiled, one direction: the simulator runs the same engine on the generated matrices (what the
// compiled run adds, the curve as generated data, has no sign).
TEST(FrictionCurve, CompiledLinearCurveFollowsTheClosedForm) {
  for (const std::string solver : {"dopri5", "implicit"}) expect_linear_curve_closed_form(solver, "", 1.0);
}

// The static capacity is static_ratio c (here 1.2 x 20 N m = 24 N m), whatever the curve, varying or
// constant (0.5 throughout, folded into the kinetic capacity only): from rest, 23 N m on a leaves it
// stuck, 25 N m breaks it away at once, a then slipping under c f(|w|).
TEST(FrictionCurve, StaticCapacityIsTheStaticRatioTimesTheCapacity) {
  for (const bool varies : {true, false})
    for (const int torque : {23, 25}) {
      SCOPED_TRACE(std::to_string(torque) + (varies ? " varying" : " constant"));
      const fs::path dir = temp_dir("curve_static_" + std::to_string(torque) + (varies ? "_varying" : "_constant"));
      fs::create_directories(dir);
      write_text(dir / "two_wheels.toml",
                 varies ? two_wheels_model()
                        : with_edits(two_wheels_model(), {{"[\"100*rad/s\", 1.5]", "[\"100*rad/s\", 0.5]"}}));
      write_text(dir / "scene.toml", "name = \"hold\"\nmodel = \"two_wheels.toml\"\neffects = []\n[inputs]\ntau_a = \"" +
                                         std::to_string(torque) + "*N*m\"\n[initial]\nomega_a = \"0*rad/s\"\n"
                                         "[engagement]\nB = \"1\"\n[simulation]\nhorizon = \"0.5*s\"\nsample = \"10*ms\"\n");
      const fs::path out = simulate_curve_scene(dir, "--interpreted");
      const Csv csv = read_csv((out / "hold.csv").string());
      const std::size_t w = csv.column("omega_a");
      ASSERT_LT(w, csv.header.size());
      // Stuck, a's speed is exactly zero (the stuck mode has no speed of a). Slipping with the curve,
      // J w' = 25 - (10 + 0.2 w): w = 75 (1 - e^(-0.4 t)), 13.6 rad/s at 0.5 s, to dopri5's default
      // tolerance; with 0.5 throughout, J w' = 25 - 10: 15 rad/s at 0.5 s, exact stepping's rounding.
      if (torque == 23)
        EXPECT_EQ(csv.rows.back()[w], 0.0);
      else
        EXPECT_NEAR(csv.rows.back()[w], varies ? 75 * (1 - std::exp(-0.2)) : 15.0, 1e-6);
    }
}

}  // namespace
}  // namespace pogear::test
