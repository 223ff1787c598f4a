// One scene's generated systems as a GeneratedScene, from the header CMake generates for it;
// compiled once per scene, the function named by POGEAR_SCENE_FUNCTION.
#include "generated_scene.hpp"
#include "scene_under_test.hpp"

namespace pogear::test {

GeneratedScene POGEAR_SCENE_FUNCTION() {
  GeneratedScene s;
#if POGEAR_SCENE_HAS_ELASTIC
  s.main = generated_system<scene_under_test::Elastic>();
#if POGEAR_SCENE_HAS_RIGID
  s.rigid = generated_system<scene_under_test::Rigid>();
#endif
#else
  s.main = generated_system<scene_under_test::Rigid>();
#endif
  return s;
}

}  // namespace pogear::test
