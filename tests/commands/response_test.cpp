// `pogear response`: a CSV and a Bode figure per input and output, figures of long grids thinned,
// and a controller's torque as an output. The response itself against a time simulation:
// tests/vibration/response_test.cpp.
#include <algorithm>
#include <complex>
#include <cstdint>
#include <filesystem>
#include <numbers>
#include <string>
#include <vector>

#include <gtest/gtest.h>

#include "../support/commands.hpp"
#include "read/loads_and_controllers.hpp"
#include "../support/files.hpp"
#include "names/model_variables.hpp"
#include "vibrate/frequency_response.hpp"

namespace pogear::test {
namespace {

TEST(Response, CommandWritesACsvAndABodeFigurePerPair) {
  const auto dir = test_dir("response");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " response " +
                                source_path("models/scenes/paper_one_stage.toml") +
                                " --input tau_c --output omega_r,F_pr --from 10*Hz --to 2*kHz --points 200 -o " +
                                dir.string());
  ASSERT_EQ(c.status, 0) << c.err;
  for (const std::string pair : {"tau_c.omega_r", "tau_c.F_pr"}) {
    const std::string csv = read_text(dir / ("paper_one_stage.response." + pair + ".csv"));
    EXPECT_EQ(csv.substr(0, csv.find('\n')), pair == "tau_c.omega_r"
                                                 ? "f [Hz],magnitude [(rad/s)/(N m)],magnitude [dB],phase [deg]"
                                                 : "f [Hz],magnitude [N/(N m)],magnitude [dB],phase [deg]");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), 201);
    const std::string svg = read_text(dir / ("paper_one_stage.response." + pair + ".svg"));
    EXPECT_NE(svg.find("</svg>"), std::string::npos);
  }
  EXPECT_NE(c.out.find("resonance peak"), std::string::npos) << c.out;
}

// A figure shows about a thousand points across: 100,000 frequencies draw about as large a figure
// as 1,000, with the resonance peaks still in it; the CSV keeps them all.
TEST(Response, FiguresOfLongGridsAreThinnedToWhatTheyCanShow) {
  const auto dir = test_dir("response_thinned");
  std::uintmax_t svg_bytes[2] = {};
  for (int i = 0; i < 2; ++i) {
    const int points = i == 0 ? 1000 : 100000;
    const auto sub = dir / std::to_string(points);
    const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " response " +
                                  source_path("models/scenes/paper_one_stage.toml") +
                                  " --input tau_c --output omega_r --from 10*Hz --to 2*kHz --points " +
                                  std::to_string(points) + " -o " + sub.string());
    ASSERT_EQ(c.status, 0) << c.err;
    const std::string csv = read_text(sub / "paper_one_stage.response.tau_c.omega_r.csv");
    EXPECT_EQ(std::count(csv.begin(), csv.end(), '\n'), points + 1);
    svg_bytes[i] = std::filesystem::file_size(sub / "paper_one_stage.response.tau_c.omega_r.svg");
  }
  // Unthinned, the 100,000-point figure is some 60 times the 1,000-point one.
  EXPECT_LT(svg_bytes[1], 3 * svg_bytes[0]) << svg_bytes[0] << " and " << svg_bytes[1] << " bytes";
}

// A controller's torque is a response output (issue 31, item 14): the PI law's small-signal
// torque, Tc = -(kp + ki / (j w)) omega_a, against the response of omega_a itself.
TEST(Response, AControllersTorqueIsAnOutput) {
  const Scene scene = parse_scene_text("name = \"loop\"\nmodel = \"pair.toml\"\nkeep = [\"a\"]\n"
                                       "effects = [\"mesh_compliance\", \"mesh_damping\", \"bearing_friction\"]\n"
                                       "[controllers]\nspeed = { body = \"a\", set_point = \"100*rad/s\", "
                                       "kp = \"0.5*N*m*s/rad\", ki = \"20*N*m/rad\" }\n",
                                       source_path("tests/vibration/loop.toml"));
  const std::vector<Variable> inputs{*find_variable(scene.model, "tau_b")};
  const auto torque = find_scene_variable(scene, "Tc_speed", {VariableKind::controller_torque});
  ASSERT_TRUE(torque.has_value());
  const std::vector<Variable> outputs{*find_variable(scene.model, "omega_a"), *torque};
  const std::vector<TransferFunction> h = frequency_response(scene, inputs, outputs, FrequencyGrid{0.1, 1e3, 80});
  ASSERT_EQ(h.size(), 2u);
  EXPECT_EQ(h[1].output_name, "Tc_speed");
  std::size_t checked = 0;
  for (std::size_t k = 0; k < h[0].value.size(); ++k) {
    if (!h[0].accurate[k] || !h[1].accurate[k]) continue;
    ++checked;
    const std::complex<double> jw(0, 2 * std::numbers::pi * h[0].frequency_hz[k]);
    const std::complex<double> law = -(0.5 + 20.0 / jw) * h[0].value[k];
    // Two outputs of one solve, related by the controller's law: rounding, within the accuracy promised.
    EXPECT_LE(std::abs(h[1].value[k] - law), response_accuracy * std::abs(law)) << h[0].frequency_hz[k] << " Hz";
  }
  EXPECT_GT(checked, 70u);
  // And the command takes it (it was refused as "neither omega_<body> nor F_<mesh>").
  const auto dir = test_dir("response_controller");
  write_text(dir / "loop.toml", "name = \"loop\"\nmodel = \"" + source_path("tests/vibration/pair.toml") +
                                    "\"\nkeep = [\"a\"]\neffects = [\"mesh_compliance\", \"mesh_damping\", "
                                    "\"bearing_friction\"]\n[controllers]\nspeed = { body = \"a\", set_point = "
                                    "\"100*rad/s\", kp = \"0.5*N*m*s/rad\", ki = \"20*N*m/rad\" }\n");
  const Command c = run_command(std::string(POGEAR_EXECUTABLE) + " response " + (dir / "loop.toml").string() +
                                " --input tau_b --output Tc_speed --points 50 -o " + dir.string());
  ASSERT_EQ(c.status, 0) << c.err;
  const std::string csv = read_text(dir / "loop.response.tau_b.Tc_speed.csv");
  EXPECT_EQ(csv.substr(0, csv.find('\n')), "f [Hz],magnitude [(N m)/(N m)],magnitude [dB],phase [deg]");
}

}  // namespace
}  // namespace pogear::test
