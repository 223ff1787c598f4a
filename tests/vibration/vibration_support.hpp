// Shared by the vibration tests here and their end-to-end half in tests/commands/: the Ravigneaux
// set of models/ravigneaux.toml, bodies by name, a simple planetary gear.
#pragma once

#include <string>

#include <gtest/gtest.h>

#include "../derive/test_support.hpp"

namespace pogear::test {

inline Derivation ravigneaux() { return derive_file("ravigneaux"); }

inline int body(const Derivation& d, const std::string& name) {
  const int b = find_body(d.topology, name);
  EXPECT_GE(b, 0) << name;
  return b;
}

// A simple planetary gear: sun, one planet, carrier and ring (r_c and r_r follow from the geometry).
inline const char* const simple_model = R"(name = "simple"
keep = ["c", "r"]
[[body]]
name = "c"
[[body]]
name = "p"
axis = { carrier = "c", distance = "r_c" }
[[body]]
name = "s"
[[body]]
name = "r"
wheels = [ { name = "r", radius = "r_r", internal = true } ]
[[mesh]]
first = "p"
second = "s"
[[mesh]]
first = "p"
second = "r"
[parameters]
r_s = "10*cm"
r_p = "4.8*cm"
J_c = "0.17648*kg*meters^2"
J_p = "0.009756*kg*meters^2"
J_s = "0.038617*kg*meters^2"
J_r = "0.54251*kg*meters^2"
b_c = "0.08*Nm/rpm"
b_p = "b_c"
b_s = "b_c"
b_r = "b_c"
K_ps = "1000*Newton/mm"
K_pr = "1300*Newton/mm"
b_ps = "0.4*Newton*s/cm"
b_pr = "b_ps"
)";

}  // namespace pogear::test
