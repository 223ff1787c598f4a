// libFuzzer target for scene files, on a fixed valid model (the paper's one-stage gear): any scene
// text must end in generated sources or an InputError. Any other exception, a crash, a leak,
// undefined behaviour or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <string>

#include "codegen/codegen.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  // The model line comes first and is fixed, so the fuzzer spends its time on the scene's own keys
  // rather than on model paths (a second `model` key is a TOML error). The scene "stands" in
  // fuzz/scene_dir, so `{ table = "torque.csv" }` finds the tables there.
  const std::string text = "model = \"../../models/paper_one_stage.toml\"\n" +
                           std::string(reinterpret_cast<const char*>(data), size);
  try {
    const pogear::Scene scene = pogear::parse_scene_text(text, POGEAR_SOURCE_DIR "/fuzz/scene_dir/fuzz.toml");
    // Overrides, keep and effects are checked against the derivation only here.
    const pogear::SpecializedScene model = pogear::specialize(scene);
    const pogear::GeneratedSources sources = pogear::generate_sources(model);
    if (sources.header.empty() || sources.main.empty()) __builtin_trap();
  } catch (const pogear::InputError&) {
    // The expected answer to bad input.
  }
  return 0;
}
