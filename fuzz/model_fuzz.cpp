// libFuzzer target for model files: any bytes must end in a derivation or an InputError. Any other
// exception, a crash, a leak, undefined behaviour or a hang is a finding.
#include <cstddef>
#include <cstdint>
#include <optional>
#include <string>

#include "derive/derivation.hpp"
#include "report/report.hpp"

extern "C" int LLVMFuzzerTestOneInput(const std::uint8_t* data, std::size_t size) {
  const std::string text(reinterpret_cast<const char*>(data), size);
  try {
    pogear::Topology t = pogear::parse_topology_text(text, "fuzz.toml");
    // Past the parser, the geometry, rank and symbolic stages see the accepted model, and the
    // JSON report prints every expression and number they made.
    const pogear::Derivation d = pogear::derive_topology(std::move(t), std::nullopt, {"fuzz.toml", 0, 0});
    const std::string report = pogear::report_json(d);
    if (report.empty()) __builtin_trap();  // a derivation always has something to say
  } catch (const pogear::InputError&) {
    // The expected answer to bad input.
  }
  return 0;
}
