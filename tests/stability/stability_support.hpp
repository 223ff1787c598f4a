// Scenes of the stability suite that its library tests here and its end-to-end tests in
// tests/commands/ both run: the one-stage paper scene made stiff, or with other effects and steps.
#pragma once

#include <string>

#include "../simulate/sim_support.hpp"

namespace pogear::test {

// The one-stage paper scene with the given effects and [parameters], tau_c = 100 Nm from rest.
inline std::string range_scene(const std::string& effects, const std::string& parameters, const std::string& horizon,
                               const std::string& sample) {
  std::string text = with_effects(scene_text("paper_one_stage"), effects);
  text = with_line(text, "compare_rigid = true", "compare_rigid = false");
  text = with_line(text, "horizon = \"2*s\"", "horizon = \"" + horizon + "\"");
  text = with_line(text, "sample = \"1*ms\"", "sample = \"" + sample + "\"");
  return parameters.empty() ? text : with_parameters(text, parameters);
}

inline const char* const kUndamped = "\"mesh_compliance\"";

// The one-stage paper scene with K_ps = 1e12 N/m, no rigid model, and `simulation` for its solver line.
inline std::string stiff_scene(const std::string& simulation) {
  std::string text = with_line(scene_text("paper_one_stage"), "compare_rigid = true", "compare_rigid = false");
  text = with_line(text, "[simulation]", "[parameters]\nK_ps = \"1e12*Newton/m\"\n\n[simulation]");
  return with_line(text, "solver = \"exact\"", simulation);
}

}  // namespace pogear::test
