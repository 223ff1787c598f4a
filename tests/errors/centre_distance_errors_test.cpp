// Operating centre distances (profile-shifted meshes) that cannot be: without teeth, not a length,
// beyond what a profile shift does, disagreeing with the layout, or with a radius given twice.
#include <gtest/gtest.h>

#include "error_support.hpp"

namespace pogear::test {
namespace {

// tests/errors/shifted.toml: a simple set by its teeth whose ring is one tooth too many for its planets.
const std::string& shifted_set() {
  static const std::string text = read_text(source_path("tests/errors/shifted.toml"));
  return text;
}

class CentreDistance : public ErrorTest {
 protected:
  void expect_shifted_error(const Edits& edits, const std::string& expected) {
    try {
      derive_topology(parse_topology_text(edited(shifted_set(), edits), "shifted.toml"), std::nullopt,
                      SourceLocation{"shifted.toml", 0, 0});
      ADD_FAILURE() << "no error";
    } catch (const InputError& e) {
      expect_documented(e.what(), expected);
    } catch (const GeometryConflict& e) {
      expect_documented(input_error_of(e).what(), expected);
    }
  }
};

TEST_F(CentreDistance, ShiftedSetIsAccepted) {
  const Derivation d = derive_topology(parse_topology_text(shifted_set(), "shifted.toml"), std::nullopt,
                                       SourceLocation{"shifted.toml", 0, 0});
  // The carrier turns at Z_s / (Z_s + Z_r) = 30/101 of the sun, at radii 50.5 mm * Z / 50 and / 51:
  // a ratio of doubles within a few ulps.
  EXPECT_NEAR(GiNaC::ex_to<GiNaC::numeric>(d.rigid_values.Q1(find_body(d.topology, "c"), 0).evalf()).to_double(),
              30.0 / 101, 4e-16);
}

TEST_F(CentreDistance, BeyondAProfileShift) {
  expect_shifted_error({{R"(centre_distance = "50.5*mm"

[parameters])", "centre_distance = \"54*mm\"\n\n[parameters]"}},
      R"~(shifted.toml:34:19: error: mesh pr: centre distance 54 mm is 3 mm from the reference centre distance of its teeth, m (71 - 20)/2 = 51 mm with module 2 mm; profile shifts move it by a fraction of the module: check the centre distance and the teeth)~");
}

TEST_F(CentreDistance, MeshesOfOnePlanetDisagree) {
  expect_shifted_error({{R"(centre_distance = "50.5*mm"

[parameters])", "centre_distance = \"50.7*mm\"\n\n[parameters]"}},
      R"~(shifted.toml:34:19: error: 'rw_r_pr' = (50.7*mm)*71/51 (0.0705824 m) contradicts the geometry: mesh pr (p with r) implies rw_r_pr = rw_p_pr+rw_p_ps+rw_s_ps = 0.0703824 m; correct the value, or the layout if the drawing differs)~");
}

// A scene's override of a parameter the centre distance names is checked as the model's value is.
TEST_F(CentreDistance, SceneOverrideBeyondAProfileShift) {
  const std::string model = edited(shifted_set(), {{R"(centre_distance = "50.5*mm"

[[mesh]])", "centre_distance = \"a_p\"\n\n[[mesh]]"},
                                                 {R"(centre_distance = "50.5*mm"

[parameters])", "centre_distance = \"a_p\"\n\n[parameters]\na_p = \"50.5*mm\""}});
  const std::string scene = "name = \"shifted\"\nmodel = \"gear.toml\"\n[parameters]\na_p = \"54*mm\"\n"
                            "[inputs]\ntau_s = \"10*Nm\"\n";
  expect_documented(scene_error(scene, model),
      R"~(gear.toml:28:19: error: mesh ps: centre distance 54 mm is 4 mm from the reference centre distance of its teeth, m (30 + 20)/2 = 50 mm with module 2 mm; profile shifts move it by a fraction of the module: check the centre distance and the teeth)~");
}

TEST_F(CentreDistance, NotAPositiveLength) {
  expect_shifted_error({{R"(centre_distance = "50.5*mm"

[parameters])", "centre_distance = \"50.5\"\n\n[parameters]"}},
      R"~(shifted.toml:34:19: error: the centre distance '50.5' of mesh pr is without a unit; it is a positive length, e.g. "60*mm")~");
  expect_shifted_error({{R"(centre_distance = "50.5*mm"

[parameters])", "centre_distance = true\n\n[parameters]"}},
      R"~(shifted.toml:34:19: error: a centre_distance is a length, e.g. centre_distance = "60*mm")~");
}

TEST_F(CentreDistance, OperatingRadiusGiven) {
  expect_shifted_error({{"b_pr = \"50*N*s/m\"", "b_pr = \"50*N*s/m\"\nrw_p_pr = \"20*mm\""}},
      R"~(shifted.toml:47:11: error: 'rw_p_pr' is the operating pitch radius of p in mesh pr, which its centre distance gives; leave it out of [parameters])~");
}

TEST_F(CentreDistance, WheelWithoutTeeth) {
  expect_model_error({{"first = \"p\"\nsecond = \"s1\"", "first = \"p\"\nsecond = \"s1\"\ncentre_distance = \"14.8*cm\""}},
      R"~(gear.toml:27:19: error: mesh ps: a centre distance sets the operating pitch radii from the teeth, but p is given by its radius; give its teeth and module)~");
}

}  // namespace
}  // namespace pogear::test
