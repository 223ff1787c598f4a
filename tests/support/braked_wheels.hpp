// A model the shift tests share: one rigid body braked, whose motion they solve in closed form.
#pragma once

#include <string>

namespace pogear::test {

// Two rigid wheels meshing, b on a fixed axis: J = J_a + J_b (r_a / r_b)^2 = 0.5 kg m^2 at a, no
// bearing friction; brake B of capacity c = 20 N m and static ratio 1.2 on a.
inline std::string braked_wheels_model() {
  return R"(name = "braked_wheels"
keep = ["a"]

[[body]]
name = "a"

[[body]]
name = "b"
axis = { fixed = "below" }

[[mesh]]
first = "a"
second = "b"

[[brake]]
name = "B"
body = "a"
static_ratio = 1.2

[parameters]
r_a = "5*cm"
r_b = "10*cm"
J_a = "0.3*kg*m^2"
J_b = "0.8*kg*m^2"
b_a = "0*N*m*s"
b_b = "0*N*m*s"
K_ab = "1e6*N/m"
b_ab = "10*N*s/m"
Tcap_B = "20*N*m"
)";
}

}  // namespace pogear::test
