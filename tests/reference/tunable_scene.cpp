// The systems generated from tunable_one_stage.toml at Params other than the scene's:
// K_ps = 2000 N/mm and J_c = 0.3 kg m^2 (reference_test.cpp builds its reference with the same
// values as [parameters] overrides).
#include "generated_scene.hpp"
#include "scene_under_test.hpp"

namespace pogear::test {
namespace {

// The system's Params with each tunable it has (the rigid system has no stiffness) at its other value.
template <class Params>
Params other_values() {
  Params p;
  if constexpr (requires { p.K_ps; }) p.K_ps = 2e6;
  if constexpr (requires { p.J_c; }) p.J_c = 0.3;
  return p;
}

}  // namespace

GeneratedScene generated_tunable_one_stage() {
  GeneratedScene s;
  s.main = generated_system<scene_under_test::Elastic>(other_values<scene_under_test::Elastic::Params>());
  s.rigid = generated_system<scene_under_test::Rigid>(other_values<scene_under_test::Rigid::Params>());
  return s;
}

}  // namespace pogear::test
