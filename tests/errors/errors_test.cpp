// Every error pogear reports, with the exact text and position users see: each test is an entry
// of docs/errors.md, which shows the same text verbatim and names the test. The entries whose test
// runs the pogear executable stand in tests/commands/ (errors_test.cpp, cli_errors_test.cpp, ...).
#include <algorithm>
#include <cctype>

#include "pogear/signal_table.hpp"

#include "error_support.hpp"

namespace pogear::test {
namespace {

// ---------------------------------------------------------------- model files: reading

class ModelFiles : public ErrorTest {};

TEST_F(ModelFiles, CannotRead) {
  expect_documented(model_file_error("missing.toml"),
      R"~(missing.toml: error: cannot read the file (No such file or directory); check the path)~");
}

TEST_F(ModelFiles, Directory) {
  fs::create_directory("models");
  expect_documented(model_file_error("models"), R"~(models: error: this is a directory; give the file itself)~");
}

TEST_F(ModelFiles, TooLarge) {
  write_text("huge.toml", std::string((1 << 20) + 1, '#'));
  expect_documented(model_file_error("huge.toml"),
      R"~(huge.toml: error: the file is larger than 1048576 bytes; a model or scene file is a few kilobytes)~");
}

TEST_F(ModelFiles, NotARegularFile) {
  // A device or FIFO is refused before a byte is read: /dev/zero never ends, a FIFO may never write.
  expect_documented(model_file_error("/dev/zero"),
      R"~(/dev/zero: error: this is a character device, not a regular file; give the path of the file itself)~");
}

TEST_F(ModelFiles, ReadError) {
  // Reading /proc/self/mem from offset 0 fails with EIO: a file that opens but cannot be read.
  expect_documented(model_file_error("/proc/self/mem"),
      R"~(/proc/self/mem: error: cannot read the file: a read error; check the file)~");
}

TEST_F(ModelFiles, TomlSyntax) {
  expect_model_error({{R"(r_s1 = "10*cm")", R"(r_s1 = "10*cm)"}},
      R"~(gear.toml:37:14: error: Error while parsing string: unescaped control characters other than TAB (U+0009) are explicitly prohibited; fix the TOML syntax)~");
}

TEST_F(ModelFiles, UnknownTopLevelKey) {
  expect_model_error({{R"(keep = ["c", "r"])", "keep = [\"c\", \"r\"]\nstages = 2"}},
      R"~(gear.toml:4:1: error: unknown key 'stages' in the model file; the keys are name, title, keep, body, mesh, shaft, brake, clutch, gears, parameters)~");
}

// ---------------------------------------------------------------- model files: structure

class ModelStructure : public ErrorTest {};

TEST_F(ModelStructure, NotAName) {
  expect_model_error({{R"(name = "gear")", R"(name = "2gear")"}},
      R"~(gear.toml:2:8: error: the model name '2gear' is not a name; use letters, digits and '_', starting with a letter)~");
}

TEST_F(ModelStructure, NameTooLong) {
  expect_model_error({{R"(name = "c")", "name = \"" + std::string(65, 'c') + "\""}},
      R"~(gear.toml:6:8: error: a body name is 65 characters long; names have at most 64)~");
}

TEST_F(ModelStructure, NameNotAString) {
  expect_model_error({{R"(name = "c")", "name = 3"}},
      R"~(gear.toml:6:8: error: a body name must be a string in quotes)~");
}

TEST_F(ModelStructure, TitleNotAString) {
  expect_model_error({{R"(name = "gear")", "name = \"gear\"\ntitle = 5"}},
      R"~(gear.toml:3:9: error: title must be a string in quotes)~");
}

TEST_F(ModelStructure, TitleWithLineBreak) {
  expect_model_error({{R"(name = "gear")", "name = \"gear\"\ntitle = \"one\\ntwo\""}},
      R"~(gear.toml:3:9: error: the title is one line; remove the line break)~");
}

TEST_F(ModelStructure, NoBodies) {
  expect_documented(model_error("name = \"empty\"\n"),
      R"~(gear.toml: error: no [[body]] entries; add at least one, e.g. [[body]] name = "c")~");
}

TEST_F(ModelStructure, BodiesNotTables) {
  expect_documented(model_error("body = 3\n"), R"~(gear.toml:1:8: error: 'body' must be written as [[body]] tables)~");
}

TEST_F(ModelStructure, TooManyBodies) {
  std::string text = "# 129 bodies\n";
  for (int i = 0; i < 129; ++i) text += "[[body]]\nname = \"b" + std::to_string(i) + "\"\n";
  expect_documented(model_error(text),
      R"~(gear.toml:2:1: error: 129 bodies; pogear derives gears of at most 128 (the symbolic derivation grows steeply with the size); model a smaller part of the gear)~");
}

TEST_F(ModelStructure, BodyUnknownKey) {
  expect_model_error({{R"(axis = { fixed = "below" })", R"(axsi = { fixed = "below" })"}},
      R"~(gear.toml:22:1: error: unknown key 'axsi' in a [[body]]; the keys are name, axis, arrow, inertia, friction, wheels, teeth, module, count, fixed)~");
}

TEST_F(ModelStructure, BodyWithoutName) {
  expect_model_error({{"name = \"c\"\n", ""}}, R"~(gear.toml:5:1: error: a [[body]] needs a name, e.g. name = "c")~");
}

TEST_F(ModelStructure, UnknownAxis) {
  expect_model_error({{R"(name = "c")", "name = \"c\"\naxis = \"middle\""}},
      R"~(gear.toml:7:8: error: axis "middle" is not known; write "central", { fixed = "below" } or { carrier = "c", distance = "r_c" })~");
}

TEST_F(ModelStructure, AxisNotATable) {
  expect_model_error({{R"(axis = { fixed = "below" })", "axis = 3"}},
      R"~(gear.toml:22:8: error: axis must be a table { ... })~");
}

TEST_F(ModelStructure, AxisUnknownKey) {
  expect_model_error({{R"(distance = "r_c" })", R"(distance = "r_c", height = 1 })"}},
      R"~(gear.toml:10:43: error: unknown key 'height' in an axis; the keys are carrier, distance, side, fixed)~");
}

TEST_F(ModelStructure, FixedAndCarried) {
  expect_model_error({{R"(axis = { fixed = "below" })", R"(axis = { fixed = "below", carrier = "c" })"}},
      R"~(gear.toml:22:8: error: an axis is either fixed or carried, not both)~");
}

TEST_F(ModelStructure, FixedSide) {
  expect_model_error({{R"(axis = { fixed = "below" })", R"(axis = { fixed = "left" })"}},
      R"~(gear.toml:22:18: error: fixed must be "above" or "below": where the axis is drawn relative to the wheels it meshes with)~");
}

TEST_F(ModelStructure, CarriedIncomplete) {
  expect_model_error({{R"({ carrier = "c", distance = "r_c" })", R"({ carrier = "c" })"}},
      R"~(gear.toml:10:8: error: a carried axis needs carrier = "<body>" and distance = "<parameter>")~");
}

TEST_F(ModelStructure, CarriedSide) {
  expect_model_error({{R"(distance = "r_c" })", R"(distance = "r_c", side = "up" })"}},
      R"~(gear.toml:10:50: error: side must be "above" or "below")~");
}

TEST_F(ModelStructure, Arrow) {
  expect_model_error({{R"(name = "c")", "name = \"c\"\narrow = \"up\""}},
      R"~(gear.toml:7:9: error: arrow must be "right" or "left": the positive direction of omega as drawn)~");
}

TEST_F(ModelStructure, InertiaNotAName) {
  expect_model_error({{R"(name = "c")", "name = \"c\"\ninertia = \"J c\""}},
      R"~(gear.toml:7:11: error: inertia 'J c' is not a name; use letters, digits and '_', starting with a letter)~");
}

TEST_F(ModelStructure, WheelsNotAList) {
  expect_model_error({{R"(wheels = [ { name = "r1", radius = "r_r1", internal = true } ])", R"(wheels = "r1")"}},
                     R"~(gear.toml:18:10: error: wheels must be a list: [ { name = "s1", radius = "r_s1" } ])~");
}

TEST_F(ModelStructure, WheelNotATable) {
  expect_model_error({{R"(wheels = [ { name = "r1", radius = "r_r1", internal = true } ])", R"(wheels = [ "r1" ])"}},
                     R"~(gear.toml:18:12: error: a wheel must be a table { ... })~");
}

TEST_F(ModelStructure, WheelUnknownKey) {
  expect_model_error({{"internal = true }", "internal = true, pitch = 80 }"}},
      R"~(gear.toml:18:61: error: unknown key 'pitch' in a wheel; the keys are name, radius, internal, teeth, module)~");
}

TEST_F(ModelStructure, WheelWithoutName) {
  expect_model_error({{R"({ name = "r1", radius = "r_r1", internal = true })", R"({ radius = "r_r1", internal = true })"}},
                     R"~(gear.toml:18:12: error: a wheel needs a name, e.g. { name = "s1", radius = "r_s1" })~");
}

TEST_F(ModelStructure, InternalNotBoolean) {
  expect_model_error({{"internal = true", R"(internal = "yes")"}},
      R"~(gear.toml:18:55: error: internal must be true or false)~");
}

TEST_F(ModelStructure, EmptyWheelList) {
  expect_model_error({{R"(wheels = [ { name = "r1", radius = "r_r1", internal = true } ])", "wheels = []"}},
      R"~(gear.toml:18:10: error: an empty wheel list; leave 'wheels' out for a body without teeth)~");
}

TEST_F(ModelStructure, DuplicateBody) {
  expect_model_error({{R"(name = "g")", R"(name = "c")"}},
      R"~(gear.toml:21:8: error: duplicate name 'c' (body); it is already used at line 6)~");
}

TEST_F(ModelStructure, DuplicateWheel) {
  expect_model_error({{R"({ name = "s2", radius = "r_s2" })", R"({ name = "s1", radius = "r_s2" })"}},
      R"~(gear.toml:14:55: error: duplicate name 's1' (wheel); it is already used at line 14)~");
}

TEST_F(ModelStructure, CarrierNotABody) {
  expect_model_error({{R"(carrier = "c")", R"(carrier = "x")"}},
      R"~(gear.toml:9:8: error: body 'p' is carried by 'x', which is not a body of this model)~");
}

TEST_F(ModelStructure, CarrierLoop) {
  expect_model_error({{R"(name = "c")", "name = \"c\"\naxis = { carrier = \"p\", distance = \"r_c\" }"}},
      R"~(gear.toml:6:8: error: body 'c' is carried, through its carriers, by itself)~");
}

// The hint's example names the model's bodies (issue 31, item 14: it named p and s1, which the
// model did not have).
TEST_F(ModelStructure, NoMeshes) {
  expect_documented(model_error("[[body]]\nname = \"a\"\n\n[[body]]\nname = \"b\"\naxis = { fixed = \"below\" }\n"),
      R"~(gear.toml: error: no [[mesh]] entries; add at least one, e.g. [[mesh]] first = "a", second = "b")~");
}

TEST_F(ModelStructure, OneBodyNoMeshes) {
  expect_documented(model_error("[[body]]\nname = \"a\"\n"),
      R"~(gear.toml: error: no [[mesh]] entries, and one body: a gear is two or more bodies whose wheels mesh; add a second [[body]] and a [[mesh]] between them)~");
}

TEST_F(ModelStructure, TooManyMeshes) {
  std::string text = "# 257 meshes\n[[body]]\nname = \"a\"\n\n[[body]]\nname = \"b\"\naxis = { fixed = \"below\" }\n\n";
  for (int i = 0; i < 257; ++i) text += "[[mesh]]\nfirst = \"a\"\nsecond = \"b\"\nname = \"m" + std::to_string(i) + "\"\n";
  expect_documented(model_error(text),
      R"~(gear.toml:9:1: error: 257 meshes; pogear derives gears of at most 256 (the symbolic derivation grows steeply with the size); model a smaller part of the gear)~");
}

TEST_F(ModelStructure, MeshUnknownKey) {
  expect_model_error({{R"(second = "g")", "second = \"g\"\nratio = 2"}},
      R"~(gear.toml:35:1: error: unknown key 'ratio' in a [[mesh]]; the keys are first, second, name, stiffness, damping, module, centre_distance)~");
}

TEST_F(ModelStructure, MeshIncomplete) {
  expect_model_error({{"second = \"g\"\n", ""}},
      R"~(gear.toml:32:1: error: a [[mesh]] needs first = "<wheel>" and second = "<wheel>")~");
}

TEST_F(ModelStructure, UnknownWheel) {
  expect_model_error({{R"(second = "s1")", R"(second = "s9")"}},
      R"~(gear.toml:26:10: error: no wheel or body named 's9'; the wheels are c, p, s1, s2, r1, g)~");
}

TEST_F(ModelStructure, BodyWithSeveralWheels) {
  expect_model_error({{R"(second = "s1")", R"(second = "s")"}},
      R"~(gear.toml:26:10: error: body 's' has several wheels (s1, s2); name the one that meshes)~");
}

TEST_F(ModelStructure, AmbiguousWheel) {
  // Body g's only wheel is called c, and body c's default wheel is c too.
  expect_model_error({{"axis = { fixed = \"below\" }\n", "axis = { fixed = \"below\" }\nwheels = [ { name = \"c\", radius = \"r_g\" } ]\n"},
                      {R"(second = "g")", R"(second = "c")"}},
                     R"~(gear.toml:35:10: error: wheel name 'c' is ambiguous: a body of that name has it as its only wheel, and another body has a wheel of that name too; rename one of them)~");
}

TEST_F(ModelStructure, MeshWithItself) {
  expect_model_error({{R"(second = "g")", R"(second = "s1")"}},
      R"~(gear.toml:34:10: error: a body cannot mesh with itself)~");
}

TEST_F(ModelStructure, DuplicateMeshName) {
  expect_model_error({{R"(second = "g")", "second = \"g\"\nname = \"ps\""}},
      R"~(gear.toml:33:9: error: duplicate name 'ps' (mesh); it is already used at line 25)~");
}

TEST_F(ModelStructure, MeshNamedLikeABody) {
  expect_model_error({{R"(second = "g")", "second = \"g\"\nname = \"c\""}},
      R"~(gear.toml:33:9: error: mesh 'c' has the name of the body at line 6: the body's bearing friction and the mesh's damping would both be b_c; give the mesh another name)~");
}

TEST_F(ModelStructure, KeepNotAList) {
  expect_model_error({{R"(keep = ["c", "r"])", R"(keep = "c")"}},
      R"~(gear.toml:3:8: error: keep must be a list of body names, e.g. keep = ["c", "r"])~");
}

TEST_F(ModelStructure, KeepNotABody) {
  expect_model_error({{R"(keep = ["c", "r"])", R"(keep = ["c", "x"])"}},
      R"~(gear.toml:3:14: error: keep names 'x', which is not a body)~");
}

// ---------------------------------------------------------------- model files: brakes and clutches

class FrictionElements : public ErrorTest {
 protected:
  // gear.toml with `elements` written before [parameters] (line 36) and `parameters` after b_sg.
  void expect_error(const std::string& elements, const std::string& parameters, const std::string& expected) {
    Edits edits{{"[parameters]", elements + "\n[parameters]"}};
    if (!parameters.empty()) edits.push_back({R"(b_sg = "b_ps")", "b_sg = \"b_ps\"\n" + parameters});
    expect_model_error(edits, expected);
  }
};

TEST_F(FrictionElements, ClutchJoinsABodyToItself) {
  expect_error("[[clutch]]\nname = \"C1\"\nbodies = [\"s\", \"s\"]\n", "",
      R"~(gear.toml:38:16: error: clutch 'C1' joins body 's' to itself; name two bodies)~");
}

TEST_F(FrictionElements, UnknownBody) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"x\"\n", "",
      R"~(gear.toml:38:8: error: brake 'B1' names 'x', which is not a body; the bodies are c, p, s, r, g)~");
}

TEST_F(FrictionElements, SamePairTwice) {
  expect_error("[[clutch]]\nname = \"C1\"\nbodies = [\"s\", \"c\"]\n\n[[clutch]]\nname = \"C2\"\nbodies = [\"c\", \"s\"]\n",
               "Tcap_C1 = \"100*N*m\"\nTcap_C2 = \"100*N*m\"",
      R"~(gear.toml:41:8: error: 'C2' joins 'c' and 's' as 'C1' (line 37) does; one element per pair of bodies, or remove one)~");
}

TEST_F(FrictionElements, DuplicateName) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\n\n[[clutch]]\nname = \"B1\"\nbodies = [\"s\", \"c\"]\n", "",
      R"~(gear.toml:41:8: error: duplicate name 'B1' (brake or clutch); it is already used at line 37)~");
}

TEST_F(FrictionElements, ClutchAcrossAxes) {
  expect_error("[[clutch]]\nname = \"C1\"\nbodies = [\"s\", \"g\"]\n", "",
      R"~(gear.toml:38:16: error: clutch 'C1' joins 's' on the central axis and 'g' on a fixed axis; a clutch joins two bodies that turn about one axis)~");
}

// Two bodies on fixed axes that mesh with each other turn about two axes (issue 31, item 10).
TEST_F(FrictionElements, ClutchAcrossTwoFixedAxes) {
  expect_model_error(
      {{"[[mesh]]\nfirst = \"p\"\nsecond = \"s1\"",
        "[[body]]\nname = \"h\"\naxis = { fixed = \"below\" }\n\n[[mesh]]\nfirst = \"g\"\nsecond = \"h\"\n\n"
        "[[mesh]]\nfirst = \"p\"\nsecond = \"s1\""},
       {"[parameters]", "[[clutch]]\nname = \"C1\"\nbodies = [\"g\", \"h\"]\n\n[parameters]"}},
      R"~(gear.toml:46:16: error: clutch 'C1' joins 'g' and 'h', which turn about two different fixed axes: they mesh with each other (mesh gh); a clutch joins two bodies that turn about one axis)~");
}

// Two fixed-axis bodies below the central wheel they both mesh with, at radii that put their axes
// at different heights: neither meshes the other, and both are drawn on one side (issue 31, item 10).
TEST_F(FrictionElements, ClutchAcrossFixedAxesAtDifferentHeights) {
  auto edits = [](const std::string& r_h) {
    return Edits{{"[[mesh]]\nfirst = \"p\"\nsecond = \"s1\"",
                  "[[body]]\nname = \"h\"\naxis = { fixed = \"below\" }\n\n[[mesh]]\nfirst = \"s2\"\nsecond = \"h\"\n\n"
                  "[[mesh]]\nfirst = \"p\"\nsecond = \"s1\""},
                 {"[parameters]", "[[clutch]]\nname = \"C1\"\nbodies = [\"g\", \"h\"]\n\n[parameters]"},
                 {"r_g = \"16*cm\"", "r_g = \"16*cm\"\nr_h = \"" + r_h + "\"\nJ_h = \"0.1*kg*meters^2\"\nb_h = \"b_c\"\n"
                                     "K_sh = \"K_ps\"\nb_sh = \"b_ps\"\nTcap_C1 = \"100*N*m\""}};
  };
  // g's axis is at -(r_s2 + r_g) = -0.32 m, h's at -(r_s2 + r_h).
  expect_model_error(edits("12*cm"),
      R"~(gear.toml:46:16: error: clutch 'C1' joins 'g' and 'h', whose meshes place their fixed axes at heights -0.32 m and -0.28 m of the side view; a clutch joins two bodies that turn about one axis)~");
  // At r_h = r_g both axes are at -0.32 m: one axis, and the clutch is accepted.
  EXPECT_NO_THROW(derive_topology(parse_topology_text(edited(base_model(), edits("16*cm")), "gear.toml"),
                                  std::nullopt, SourceLocation{"gear.toml", 0, 0}));
}

TEST_F(FrictionElements, BrakeOnAPlanet) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"p\"\n", "",
      R"~(gear.toml:38:8: error: brake 'B1' holds 'p', a planet, whose axis moves with its carrier; a brake holds a body on the central axis or on a fixed axis)~");
}

TEST_F(FrictionElements, ClutchWithoutTwoBodies) {
  expect_error("[[clutch]]\nname = \"C1\"\nbodies = [\"s\"]\n", "",
      R"~(gear.toml:38:10: error: clutch 'C1' needs the two bodies it joins, e.g. bodies = ["s", "c"])~");
}

TEST_F(FrictionElements, BrakeWithoutBody) {
  expect_error("[[brake]]\nname = \"B1\"\n", "",
      R"~(gear.toml:36:1: error: brake 'B1' needs the body it holds, e.g. body = "r")~");
}

TEST_F(FrictionElements, WithoutName) {
  expect_error("[[brake]]\nbody = \"r\"\n", "", R"~(gear.toml:36:1: error: a [[brake]] needs a name, e.g. name = "B1")~");
}

TEST_F(FrictionElements, UnknownKey) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\ntorque = \"T\"\n", "",
      R"~(gear.toml:39:1: error: unknown key 'torque' in a [[brake]]; the keys are name, body, capacity, static_ratio, one_way, friction_curve)~");
}

TEST_F(FrictionElements, MissingCapacity) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\n", "",
      R"~(gear.toml:37:8: error: missing parameter 'Tcap_B1' (a brake's torque capacity); add it under [parameters], e.g. Tcap_B1 = "...")~");
}

TEST_F(FrictionElements, NegativeCapacity) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\n", "Tcap_B1 = \"-50*N*m\"",
      R"~(gear.toml:62:11: error: parameter 'Tcap_B1' is a brake's torque capacity and must be positive (it is -50))~");
}

TEST_F(FrictionElements, CapacityNotATorque) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\n", "Tcap_B1 = \"50*N\"",
      R"~(gear.toml:62:11: error: parameter 'Tcap_B1' is a brake's torque capacity but has unit kg*m/s^2; it needs kg*m^2/s^2)~");
}

TEST_F(FrictionElements, StaticRatioBelowOne) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\nstatic_ratio = \"0.8\"\n", "Tcap_B1 = \"50*N*m\"",
      R"~(gear.toml:39:16: error: static_ratio of 'B1' is 0.8; static over kinetic friction is from 1 to 10 (1 when they are equal))~");
}

TEST_F(FrictionElements, StaticRatioWithAUnit) {
  expect_error("[[brake]]\nname = \"B1\"\nbody = \"r\"\nstatic_ratio = \"2*m\"\n", "Tcap_B1 = \"50*N*m\"",
      R"~(gear.toml:39:16: error: static_ratio of 'B1' has unit m; it is a plain number, static over kinetic friction)~");
}

// ---------------------------------------------------------------- model files: parameters

class ModelParameters : public ErrorTest {};

TEST_F(ModelParameters, NotATable) {
  const std::string text = base_model().substr(0, base_model().find("[parameters]"));
  expect_documented(model_error(edited(text, {{R"(keep = ["c", "r"])", "keep = [\"c\", \"r\"]\nparameters = 3"}})),
                    R"~(gear.toml:4:14: error: [parameters] must be a table { ... })~");
}

TEST_F(ModelParameters, TooMany) {
  std::string text = edited(base_model(), {});
  for (int i = 0; i < 2049 - 21; ++i) text += "x" + std::to_string(i) + " = 1\n";
  expect_documented(model_error(text), R"~(gear.toml:36:1: error: 2049 parameters; a model has at most 2048)~");
}

TEST_F(ModelParameters, BadName) {
  expect_model_error({{R"(r_s1 = "10*cm")", R"("r s1" = "10*cm")"}},
      R"~(gear.toml:37:1: error: 'r s1' is not a parameter name; use letters, digits and '_', starting with a letter)~");
}

TEST_F(ModelParameters, NameTooLong) {
  expect_model_error({{R"(r_s1 = "10*cm")", "r_s1 = \"10*cm\"\n" + std::string(65, 'x') + " = 1"}},
      R"~(gear.toml:38:1: error: a parameter name is 65 characters long; names have at most 64)~");
}

TEST_F(ModelParameters, NameOfAUnit) {
  expect_model_error({{R"(r_s1 = "10*cm")", "r_s1 = \"10*cm\"\ncm = 2"}},
      R"~(gear.toml:38:1: error: parameter 'cm' has the name of a unit; rename it)~");
}

TEST_F(ModelParameters, NotFinite) {
  expect_model_error({{R"(r_s1 = "10*cm")", "r_s1 = nan"}},
      R"~(gear.toml:37:8: error: parameter 'r_s1' is not finite)~");
}

TEST_F(ModelParameters, WrongType) {
  expect_model_error({{R"(r_s1 = "10*cm")", "r_s1 = true"}},
      R"~(gear.toml:37:8: error: parameter 'r_s1' must be a number (SI) or a string such as "4.8*cm")~");
}

TEST_F(ModelParameters, DefinedThroughItself) {
  expect_model_error({{R"(b_c = "0.08*Nm/rpm")", R"(b_c = "b_p")"}},
      R"~(gear.toml:47:7: error: parameter 'b_c' is defined through itself)~");
}

TEST_F(ModelParameters, Missing) {
  expect_model_error({{"J_g = \"0.48197*kg*meters^2\"\n", ""}},
      R"~(gear.toml:21:8: error: missing parameter 'J_g' (an inertia); add it under [parameters], e.g. J_g = "...")~");
}

TEST_F(ModelParameters, WrongUnit) {
  expect_model_error({{R"(J_p = "0.009756*kg*meters^2")", R"(J_p = "0.009756*kg*meters")"}},
      R"~(gear.toml:43:7: error: parameter 'J_p' is an inertia but has unit kg*m; it needs kg*m^2)~");
}

TEST_F(ModelParameters, NotPositive) {
  expect_model_error({{R"(r_g = "16*cm")", R"(r_g = "0*cm")"}},
      R"~(gear.toml:40:7: error: parameter 'r_g' is a radius and must be positive (it is 0))~");
}

TEST_F(ModelParameters, Negative) {
  expect_model_error({{R"(b_c = "0.08*Nm/rpm")", R"(b_c = "-0.08*Nm/rpm")"}},
      R"~(gear.toml:47:7: error: parameter 'b_c' is a bearing friction coefficient and must be zero or positive (it is -0.7639437268410977))~");
}

TEST_F(ModelParameters, OutOfRange) {
  expect_model_error({{R"(J_c = "0.17648*kg*meters^2")", R"(J_c = "1e40*kg*meters^2")"}},
      R"~(gear.toml:42:7: error: parameter 'J_c' is an inertia of 1e+40 (SI), outside the range pogear computes with, 1e-30 to 1e+30; check the value and its unit)~");
}

// ---------------------------------------------------------------- parameter expressions

class Expressions : public ErrorTest {
 protected:
  // The model with r_p = "<text>".
  void expect_expression_error(const std::string& text, const std::string& expected) {
    expect_model_error({{R"(r_p = "4.8*cm")", "r_p = \"" + text + "\""}}, expected);
  }
};

TEST_F(Expressions, Empty) { expect_expression_error(" ",
    R"~(gear.toml:39:9: error: empty expression; write a number with its unit, e.g. 4.8*cm)~"); }
TEST_F(Expressions, MissingOperator) { expect_expression_error("4.8 cm",
    R"~(gear.toml:39:12: error: unexpected 'c'; join factors with '*', e.g. 4.8*cm)~"); }
TEST_F(Expressions, DoubleStar) { expect_expression_error("4.8**cm",
    R"~(gear.toml:39:12: error: '**' is not a power; write '^')~"); }
TEST_F(Expressions, TooDeep) {
  expect_expression_error(std::string(70, '(') + "4.8" + std::string(70, ')') + "*cm",
      R"~(gear.toml:39:21: error: expression nested deeper than 64 levels; simplify it)~");
}
TEST_F(Expressions, AddsDifferentUnits) { expect_expression_error("4.8*cm + 1*kg",
    R"~(gear.toml:39:15: error: adds kg to m; both sides of '+' need the same unit)~"); }
TEST_F(Expressions, DivisionByZero) { expect_expression_error("4.8*cm/0",
    R"~(gear.toml:39:14: error: division by zero: the divisor is 0; check the value or the parameter it names)~"); }
TEST_F(Expressions, ExponentWithUnit) { expect_expression_error("cm^(2*s)",
    R"~(gear.toml:39:11: error: an exponent must be a plain number)~"); }
TEST_F(Expressions, FractionalUnitPower) { expect_expression_error("cm^0.5",
    R"~(gear.toml:39:11: error: a unit can only be raised to a whole power between -16 and 16)~"); }
TEST_F(Expressions, EndsEarly) { expect_expression_error("4.8*",
    R"~(gear.toml:39:12: error: the expression ends too early; a number, unit or name is missing)~"); }
TEST_F(Expressions, UnclosedParenthesis) { expect_expression_error("(4.8*cm",
    R"~(gear.toml:39:8: error: this '(' is never closed)~"); }
TEST_F(Expressions, UnexpectedCharacter) { expect_expression_error("4.8*%",
    R"~(gear.toml:39:12: error: unexpected '%'; expected a number, a unit or a parameter name)~"); }
TEST_F(Expressions, NotANumber) { expect_expression_error("4.8.1*cm",
    R"~(gear.toml:39:8: error: '4.8.1' is not a number)~"); }
TEST_F(Expressions, UnknownName) { expect_expression_error("4.8*cn",
    R"~(gear.toml:39:12: error: unknown unit or parameter 'cn'; units are m, meter, meters, metre, cm, mm, kg, gram, s, ms, minute, Hz, kHz, N, Newton, kN, Nm, rad, deg, rev, rpm, pi, J, W, K, degC, or name a parameter of this model)~"); }
TEST_F(Expressions, TooLong) {
  std::string text = "4.8*cm";
  while (text.size() <= max_expression_length) text += "+0";
  expect_expression_error(text,
      R"~(gear.toml:39:7: error: expression longer than 4096 characters; split it into parameters that name each other)~");
}
TEST_F(Expressions, Overflow) { expect_expression_error("1e300*1e300*cm",
    R"~(gear.toml:39:13: error: the value here is not a finite number (an overflow, or a negative number to a fractional power); write numbers of a physical size)~"); }
TEST_F(Expressions, NegativeToFractionalPower) { expect_expression_error("(-4.8)^0.5*cm",
    R"~(gear.toml:39:14: error: the value here is not a finite number (an overflow, or a negative number to a fractional power); write numbers of a physical size)~"); }
TEST_F(Expressions, UnitPowerTooHigh) { expect_expression_error("((cm^16)^16)^16",
    R"~(gear.toml:39:16: error: the unit m^256 has a power above 64; no physical parameter has such a unit)~"); }

// ---------------------------------------------------------------- geometry and the rigid model

class Geometry : public ErrorTest {};

TEST_F(Geometry, TwoInternalWheels) {
  expect_model_error({{"axis = { fixed = \"below\" }\n", "axis = { fixed = \"below\" }\nwheels = [ { name = \"g\", radius = \"r_g\", internal = true } ]\n"},
                      {"first = \"s2\"\nsecond = \"g\"", "first = \"r1\"\nsecond = \"g\""},
                      {"[parameters]\n", "[parameters]\nK_rg = \"K_ps\"\nb_rg = 0\n"}},
                     R"~(gear.toml:34:9: error: mesh rg (r1 of body r with g): two internal wheels cannot mesh; one of r1 and g must have external teeth)~");
}

TEST_F(Geometry, FixedAxesFirst) {
  expect_model_error({{"axis = { fixed = \"below\" }\n", "axis = { fixed = \"below\" }\n\n[[body]]\nname = \"h\"\naxis = { fixed = \"below\" }\n"},
                      {"[[mesh]]\nfirst = \"p\"\nsecond = \"s1\"", "[[mesh]]\nfirst = \"g\"\nsecond = \"h\"\n\n[[mesh]]\nfirst = \"p\"\nsecond = \"s1\""},
                      {"[parameters]\n", "[parameters]\nr_h = \"5*cm\"\nJ_h = \"0.1*kg*m^2\"\nb_h = 0\nK_gh = \"K_ps\"\nb_gh = 0\n"}},
                     R"~(gear.toml:29:9: error: mesh gh (g with h): neither axis height is known yet; mesh a fixed-axis gear with a central or carried wheel first)~");
}

TEST_F(Geometry, CannotTellWhichAxisIsHigher) {
  // Planets p and q on carrier c, neither axis distance given: which one is drawn higher?
  expect_model_error({{"axis = { fixed = \"below\" }\n", "axis = { fixed = \"below\" }\n\n[[body]]\nname = \"q\"\naxis = { carrier = \"c\", distance = \"d_q\" }\n"},
                      {"[[mesh]]\nfirst = \"p\"\nsecond = \"s1\"", "[[mesh]]\nfirst = \"p\"\nsecond = \"q\"\n\n[[mesh]]\nfirst = \"p\"\nsecond = \"s1\""},
                      {"r_c = \"14.8*cm\"\n", "r_q = \"2*cm\"\nJ_q = \"0.01*kg*m^2\"\nb_q = 0\nK_pq = \"K_ps\"\nb_pq = 0\n"}},
                     R"~(gear.toml:29:9: error: mesh pq (p with q): cannot tell which axis is drawn higher; give the numeric values of the axis distances)~");
}

TEST_F(Geometry, SameAxis) {
  expect_model_error({{"first = \"s2\"\nsecond = \"g\"", "first = \"s2\"\nsecond = \"r1\""},
                      {"[parameters]\n", "[parameters]\nK_sr = \"K_ps\"\nb_sr = 0\n"}},
                     R"~(gear.toml:33:9: error: mesh sr (s2 of body s with r1 of body r): s2 of body s and r1 of body r turn about the same axis, so they cannot mesh; put one on a carrier or a fixed axis)~");
}

TEST_F(Geometry, MissingRadius) {
  expect_model_error({{"r_s2 = \"16*cm\"\n", ""}},
      R"~(gear.toml:33:9: error: missing parameter 'r_s2' (the radius of s2 of body s); add it under [parameters], e.g. r_s2 = "10*cm")~");
}

TEST_F(Geometry, MissingAxisDistance) {
  // A planet q that meshes nothing: no contact fixes its axis distance d_q.
  expect_model_error({{"axis = { fixed = \"below\" }\n", "axis = { fixed = \"below\" }\n\n[[body]]\nname = \"q\"\naxis = { carrier = \"c\", distance = \"d_q\" }\n"},
                      {"[parameters]\n", "[parameters]\nJ_q = \"0.01*kg*m^2\"\nb_q = 0\n"}},
                     R"~(gear.toml:25:8: error: missing parameter 'd_q' (the axis distance of q); add it under [parameters])~");
}

TEST_F(Geometry, DerivedLengthNotPositive) {
  // Planet p with inner teeth around the sun, without the ring: its axis distance would be
  // r_p - r_s1 < 0.
  expect_model_error({{"axis = { carrier = \"c\", distance = \"r_c\" }\n", "axis = { carrier = \"c\", distance = \"r_c\" }\nwheels = [ { name = \"p\", radius = \"r_p\", internal = true } ]\n"},
                      {"[[mesh]]\nfirst = \"p\"\nsecond = \"r1\"\n", ""},
                      {"r_c = \"14.8*cm\"\n", ""}},
                     R"~(gear.toml:26:9: error: mesh ps (p with s1 of body s) makes 'r_c' = -0.052 m, which is not positive; check the layout)~");
}

TEST_F(Geometry, Contradiction) {
  expect_model_error({{R"(r_c = "14.8*cm")", R"(r_c = "15*cm")"}},
      R"~(gear.toml:41:7: error: 'r_c' = 15*cm (0.15 m) contradicts the geometry: mesh ps (p with s1 of body s) implies r_c = r_p+r_s1 = 0.148 m; correct the value, or the layout if the drawing differs)~");
}

TEST_F(Geometry, PinionTriangleCannotClose) {
  // The Ravigneaux set with suns of 10 and 40 teeth and pinions of 5 (module 2 mm): the pinions'
  // axes are 15 mm and 45 mm out, too far apart for two 5 mm pinions to reach each other.
  const std::string model = edited(read_text(source_path("models/ravigneaux.toml")),
                                   {{"teeth = 30", "teeth = 10"}, {"teeth = 36", "teeth = 40"}, {"teeth = 18", "teeth = 5"},
                                    {"teeth = 20", "teeth = 5"}, {"teeth = 76", "teeth = 50"}});
  expect_documented(model_error(model),
      R"~(gear.toml:49:9: error: mesh pspl (ps with pl): pinions ps and pl of carrier c cannot mesh: their axes are a_ps = 0.015 m (from mesh ssps) and a_pl = 0.045 m (from mesh plsl) from the central axis, so the centre distance r_pl+r_ps = 0.01 m must lie between 0.03 m and 0.06 m; correct the radii or the axis distances)~");
}

// ---------------------------------------------------------------- tooth counts and modules

class Teeth : public ErrorTest {
 protected:
  static constexpr const char* planet = "name = \"p\"\naxis = { carrier = \"c\", distance = \"r_c\" }";
  static std::string planet_with(const std::string& keys) { return std::string(planet) + "\n" + keys; }
};

TEST_F(Teeth, WithoutModule) {
  expect_model_error({{planet, planet_with("teeth = 24")}, {"r_p = \"4.8*cm\"\n", ""}},
      R"~(gear.toml:11:9: error: p has 24 teeth but no module; give module = "2*mm" with its teeth or on one of its meshes)~");
}

TEST_F(Teeth, ModulesDiffer) {
  expect_model_error({{planet, planet_with("teeth = 24\nmodule = \"4*mm\"")}, {"r_p = \"4.8*cm\"\n", ""},
                      {R"({ name = "s1", radius = "r_s1" })", R"({ name = "s1", teeth = 50, module = "5*mm" })"},
                      {"r_s1 = \"10*cm\"\n", ""}},
      R"~(gear.toml:27:9: error: mesh ps: p has module 4 mm and s1 of body s module 5 mm; meshing wheels share one module)~");
}

TEST_F(Teeth, RadiusGivenTwice) {
  expect_model_error({{planet, planet_with("teeth = 24\nmodule = \"4*mm\"")}},
      R"~(gear.toml:41:7: error: 'r_p' is the pitch radius of p, which its 24 teeth give; leave it out of [parameters])~");
}

TEST_F(Teeth, RadiusAndTeeth) {
  expect_model_error({{R"({ name = "s1", radius = "r_s1" })", R"({ name = "s1", radius = "r_s1", teeth = 50 })"}},
      R"~(gear.toml:14:36: error: a wheel is given by its radius or by its teeth, not both; leave out the radius)~");
}

TEST_F(Teeth, ModuleWithoutUnit) {
  expect_model_error({{planet, planet_with("teeth = 24\nmodule = \"4\"")}, {"r_p = \"4.8*cm\"\n", ""}},
      R"~(gear.toml:12:10: error: the module '4' has no unit; a module is a length, e.g. "2*mm")~");
}

// ---------------------------------------------------------------- lumped planets

class Lumped : public ErrorTest {};

TEST_F(Lumped, CountOnACentralBody) {
  expect_model_error({{"[[body]]\nname = \"c\"\n", "[[body]]\nname = \"c\"\ncount = 3\n"}},
      R"~(gear.toml:7:9: error: count lumps identical planets; it goes on a body with a carried axis (a planet))~");
}

TEST_F(Lumped, CountIsNotAWholeNumber) {
  expect_model_error({{"distance = \"r_c\" }", "distance = \"r_c\" }\ncount = 2.5"}},
      R"~(gear.toml:11:9: error: count is the number of identical planets, a whole number from 1 to 64)~");
}

TEST_F(Lumped, MeshingPlanetsOfDifferentCounts) {
  const std::string model = edited(read_text(source_path("models/ravigneaux.toml")),
                                   {{"distance = \"a_ps\" }", "distance = \"a_ps\" }\ncount = 3"}});
  expect_documented(model_error(model),
      R"~(gear.toml:50:9: error: mesh 'pspl' joins planet 'ps' (count 3) and planet 'pl' (count 1); planets that mesh with each other are lumped in equal numbers)~");
}

class Reduction : public ErrorTest {};

TEST_F(Reduction, KeepUnknownBody) {
  expect_documented(model_error(base_model(), std::vector<std::string>{"c", "x"}),
      R"~(gear.toml: error: cannot keep 'x': there is no such body)~");
}

TEST_F(Reduction, KeptTwice) {
  expect_documented(model_error(base_model(), std::vector<std::string>{"c", "c"}),
      R"~(gear.toml: error: 'c' is kept twice)~");
}

TEST_F(Reduction, WrongNumberKept) {
  expect_documented(model_error(base_model(), std::vector<std::string>{"c", "r", "s"}),
      R"~(gear.toml: error: 3 velocities kept, but this gear has 2 degrees of freedom (5 bodies, rank of R 3); keep 2, e.g. c,p)~");
}

TEST_F(Reduction, TiedVelocities) {
  expect_documented(model_error(base_model(), std::vector<std::string>{"s", "g"}),
      R"~(gear.toml: error: the kept velocities s,g do not parametrize the rigid motions: s and g are tied: omega_g == -r_s2*omega_s/r_g in every rigid motion; valid choices are c,p; c,s; c,r; c,g; p,s; p,r; p,g; s,r; r,g)~");
}

TEST_F(Reduction, TiedVelocitiesFromTheModelFile) {
  expect_model_error({{R"(keep = ["c", "r"])", R"(keep = ["s", "g"])"}},
      R"~(gear.toml:3:8: error: the kept velocities s,g do not parametrize the rigid motions: s and g are tied: omega_g == -r_s2*omega_s/r_g in every rigid motion; valid choices are c,p; c,s; c,r; c,g; p,s; p,r; p,g; s,r; r,g)~");
}

// ---------------------------------------------------------------- scene files

class SceneFiles : public ErrorTest {};

TEST_F(SceneFiles, CannotRead) {
  try {
    parse_scene("missing.toml");
    ADD_FAILURE() << "no error";
  } catch (const InputError& e) {
    expect_documented(e.what(),
        R"~(missing.toml: error: cannot read the scene file (No such file or directory); check the path)~");
  }
}

TEST_F(SceneFiles, TooLarge) {
  expect_documented(scene_error(base_scene() + std::string(1 << 20, '#')),
      R"~(scene.toml: error: the scene file is larger than 1048576 bytes; a model or scene file is a few kilobytes)~");
}

TEST_F(SceneFiles, TomlSyntax) {
  expect_scene_error({{"horizon = \"0.1*s\"", "horizon = 0.1*s"}},
      R"~(scene.toml:15:14: error: Error while parsing floating-point: expected decimal digit, saw '*'; fix the TOML syntax)~");
}

TEST_F(SceneFiles, UnknownKey) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\nduration = 2"}},
      R"~(scene.toml:7:1: error: unknown key 'duration' in the scene file; the keys are name, model, effects, keep, compare_rigid, tunable, outputs, inputs, initial, parameters, simulation, engagement, speed_unit, loads, controllers, vehicle, engine, converter, thermal, actuators, slip_control)~");
}

TEST_F(SceneFiles, ModelError) {
  // Errors of the model are located in the model file.
  expect_documented(scene_error(base_scene(), edited(base_model(), {{R"(r_g = "16*cm")", R"(r_g = "0*cm")"}})),
                    R"~(gear.toml:40:7: error: parameter 'r_g' is a radius and must be positive (it is 0))~");
}

class Scenes : public ErrorTest {};

TEST_F(Scenes, NameNotAString) { expect_scene_error({{R"(name = "demo")", "name = 3"}},
    R"~(scene.toml:2:8: error: name must be a string in quotes)~"); }
TEST_F(Scenes, BadName) { expect_scene_error({{R"(name = "demo")", R"(name = "my demo")"}},
    R"~(scene.toml:2:8: error: scene name 'my demo' must be letters, digits and '_' (it names C++ code and files))~"); }
TEST_F(Scenes, NameTooLong) {
  expect_scene_error({{R"(name = "demo")", "name = \"" + std::string(65, 'd') + "\""}},
      R"~(scene.toml:2:8: error: the scene name is 65 characters long; names have at most 64)~");
}
TEST_F(Scenes, NameIsACppKeyword) {
  expect_scene_error({{R"(name = "demo")", R"(name = "long")"}},
      R"~(scene.toml:2:8: error: scene name 'long' is a C++ keyword or macro, which cannot name the generated code; choose another name)~");
}
TEST_F(Scenes, NoModel) { expect_scene_error({{"model = \"gear.toml\"\n", ""}},
    R"~(scene.toml: error: the scene names no model; add model = "path/to/model.toml")~"); }
TEST_F(Scenes, ModelPathWithLineBreak) {
  expect_scene_error({{R"(model = "gear.toml")", R"(model = "gear.toml\n")"}},
      R"~(scene.toml:3:9: error: the model path contains a line break; give the path of the model file)~");
}
TEST_F(Scenes, ModelDoesNotExist) {
  expect_scene_error({{R"(model = "gear.toml")", R"(model = "gears.toml")"}},
      R"~(scene.toml:3:9: error: model file 'gears.toml' does not exist; give its path relative to the scene file)~");
}
TEST_F(Scenes, EffectsNotAList) {
  expect_scene_error({{R"(effects = ["mesh_compliance", "mesh_damping", "bearing_friction", "mesh_forces"])",
                       R"(effects = "mesh_forces")"}},
                     R"~(scene.toml:4:11: error: effects must be a list of strings, e.g. ["a", "b"])~");
}
TEST_F(Scenes, EffectNotAString) {
  expect_scene_error({{R"("mesh_forces"])", R"("mesh_forces", 5])"}},
      R"~(scene.toml:4:82: error: effects must be a string in quotes)~");
}
TEST_F(Scenes, UnknownEffect) {
  expect_scene_error({{R"("mesh_forces"])", R"("mesh_forces", "backlash"])"}},
      R"~(scene.toml:4:11: error: unknown effect 'backlash'; the effects are mesh_compliance, shaft_compliance, mesh_damping, shaft_damping, bearing_friction, mesh_forces)~");
}
TEST_F(Scenes, DampingWithoutCompliance) {
  expect_scene_error({{R"("mesh_compliance", )", ""}, {"compare_rigid = true\n", ""}},
      R"~(scene.toml:4:11: error: mesh_damping needs mesh_compliance: a rigid mesh has no deflection to damp; add mesh_compliance or drop mesh_damping)~");
}
TEST_F(Scenes, KeepNotABody) { expect_scene_error({{R"(keep = ["c", "r"])", R"(keep = ["c", "x"])"}},
    R"~(scene.toml:5:8: error: keep names 'x', which is not a body of the model)~"); }
TEST_F(Scenes, KeepWrongNumber) {
  // The reduction's own messages, located at the scene's keep.
  expect_scene_error({{R"(keep = ["c", "r"])", R"(keep = ["c"])"}},
      R"~(scene.toml:5:8: error: 1 velocity kept, but this gear has 2 degrees of freedom (5 bodies, rank of R 3); keep 2, e.g. c,p)~");
}
TEST_F(Scenes, CompareRigidNotBoolean) {
  expect_scene_error({{"compare_rigid = true", R"(compare_rigid = "yes")"}},
      R"~(scene.toml:6:17: error: compare_rigid must be true or false)~");
}
TEST_F(Scenes, CompareRigidOfARigidScene) {
  expect_scene_error({{R"("mesh_compliance", "mesh_damping", )", ""}},
      R"~(scene.toml:6:17: error: compare_rigid compares the elastic model with the rigid one, but this scene is already rigid (no mesh_compliance); drop compare_rigid or add mesh_compliance)~");
}
TEST_F(Scenes, ParametersNotATable) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\nparameters = 3"}},
      R"~(scene.toml:7:14: error: [parameters] must be a table)~");
}
TEST_F(Scenes, OverrideOfNoParameter) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nK_xy = \"2000*Newton/mm\"\n"),
      R"~(scene.toml:22:1: error: 'K_xy' is not a parameter of the model gear)~");
}
TEST_F(Scenes, OverrideNotFinite) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nK_ps = inf\n"),
      R"~(scene.toml:22:8: error: parameter 'K_ps' is not finite)~");
}
TEST_F(Scenes, OverrideWrongType) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nK_ps = true\n"),
      R"~(scene.toml:22:8: error: a parameter override is a number (SI) or a string such as "2000*Newton/mm")~");
}
TEST_F(Scenes, OverrideExpression) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nK_ps = \"2000*Newton/mn\"\n"),
      R"~(scene.toml:22:21: error: unknown unit or parameter 'mn'; units are m, meter, meters, metre, cm, mm, kg, gram, s, ms, minute, Hz, kHz, N, Newton, kN, Nm, rad, deg, rev, rpm, pi, J, W, K, degC, or name a parameter of this model)~");
}
TEST_F(Scenes, OverrideWrongUnit) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nK_ps = \"2000*Newton\"\n"),
      R"~(scene.toml:22:8: error: parameter 'K_ps' is a mesh stiffness but has unit kg*m/s^2; it needs kg/s^2)~");
}
TEST_F(Scenes, OverrideNotPositive) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nJ_c = \"0*kg*m^2\"\n"),
      R"~(scene.toml:22:7: error: parameter 'J_c' is an inertia and must be positive (it is 0))~");
}
TEST_F(Scenes, OverrideBreaksTheGeometry) {
  expect_documented(scene_error(base_scene() + "\n[parameters]\nr_p = \"5*cm\"\n"),
      R"~(gear.toml:41:7: error: 'r_c' = 14.8*cm (0.148 m) contradicts the geometry: mesh ps (p with s1 of body s) implies r_c = r_p+r_s1 = 0.15 m; correct the value, or the layout if the drawing differs)~");
}
TEST_F(Scenes, TunableNotAParameter) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\ntunable = [\"K_xy\"]"}},
      R"~(scene.toml:7:11: error: tunable 'K_xy' is not a parameter of the model)~");
}
TEST_F(Scenes, TunableTwice) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\ntunable = [\"K_ps\", \"K_ps\"]"}},
      R"~(scene.toml:7:11: error: tunable 'K_ps' is listed twice)~");
}
TEST_F(Scenes, QuantityNamesATunable) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\ntunable = [\"J_c\"]"},
                      {R"(tau_c = { constant = "100*Nm" })", R"(tau_c = { constant = "J_c*500/s^2" })"}},
      R"~(scene.toml:10:22: error: constant names tunable 'J_c', but the simulator takes this value at the scene's value of it, whatever --param sets; write the value without 'J_c', or drop 'J_c' from tunable)~");
}
// Read before the tunables are listed in the file (a load, a controller, a vehicle), a value is
// refused all the same.
TEST_F(LoadsAndControllers, GainNamesATunable) {
  expect_error("[controllers]\nspeed = { body = \"c\", set_point = \"100*rpm\", kp = \"b_c*20\" }\n",
               R"~(scene.toml:23:51: error: kp names tunable 'b_c', but the simulator takes this value at the scene's value of it, whatever --param sets; write the value without 'b_c', or drop 'b_c' from tunable)~",
               {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"b_c\"]"}});
  expect_error("[loads]\nr = { linear = \"b_c\" }\n",
               R"~(scene.toml:23:16: error: linear names tunable 'b_c', but the simulator takes this value at the scene's value of it, whatever --param sets; write the value without 'b_c', or drop 'b_c' from tunable)~",
               {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"b_c\"]"}});
}
TEST_F(Scenes, TunableClashesWithGeneratedCode) {
  const std::string model = edited(base_model(), {{"[parameters]\n", "[parameters]\ndouble = 2\n"}});
  expect_documented(scene_error(edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"double\"]"}}), model),
                    R"~(scene.toml:7:11: error: tunable 'double' cannot be a variable of the generated C++ (a keyword, a macro or a name the code uses itself); rename the parameter in the model)~");
}
TEST_F(Scenes, ParameterNamedLikeAMeshVelocity) {
  const std::string model = edited(base_model(), {{"[parameters]\n", "[parameters]\nv_ps = 2\n"}});
  expect_documented(scene_error(base_scene(), model),
      R"~(gear.toml:37:8: error: the model has a parameter named 'v_ps', which pogear's generated code uses for a mesh velocity; rename the parameter)~");
}
TEST_F(Scenes, InputsNotATable) {
  expect_scene_error({{"[inputs]\ntau_c = { constant = \"100*Nm\" }", "inputs = 3"}},
      R"~(scene.toml:8:10: error: [inputs] must be a table of tau_<body> = signal)~");
}
TEST_F(Scenes, InputOfNoBody) { expect_scene_error({{"tau_c = {", "tau_x = {"}},
    R"~(scene.toml:9:1: error: input 'tau_x' names no body; inputs are tau_<body>, e.g. tau_c)~"); }

class Signals : public ErrorTest {
 protected:
  // The scene with tau_c = <signal>.
  void expect_signal_error(const std::string& signal, const std::string& expected) {
    expect_scene_error({{R"(tau_c = { constant = "100*Nm" })", "tau_c = " + signal}}, expected);
  }
};

TEST_F(Signals, WrongType) { expect_signal_error("true",
    R"~(scene.toml:9:9: error: an input torque must be a number (SI) or a string with a unit)~"); }
TEST_F(Signals, WrongUnit) { expect_signal_error(R"({ constant = "100*N" })",
    R"~(scene.toml:9:22: error: constant has unit kg*m/s^2; it needs kg*m^2/s^2)~"); }
TEST_F(Signals, NotFinite) { expect_signal_error("inf", R"~(scene.toml:9:9: error: an input torque is not finite)~"); }
TEST_F(Signals, TorqueWithoutAUnit) { expect_signal_error("{ constant = 100 }",
    R"~(scene.toml:9:22: error: constant has no unit (100); a torque needs one, e.g. "100*N*m")~"); }
TEST_F(Signals, UnknownKey) { expect_signal_error(R"({ constant = "100*Nm", at = "1*s" })",
    R"~(scene.toml:9:32: error: unknown key 'at' in a constant signal; the keys are constant)~"); }
TEST_F(Signals, StepWithoutTime) { expect_signal_error(R"({ step = "100*Nm" })",
    R"~(scene.toml:9:9: error: a step needs at = "<time>", e.g. at = "0.5*s")~"); }
TEST_F(Signals, RampSlopeUnit) { expect_signal_error(R"({ ramp = "50*Nm" })",
    R"~(scene.toml:9:18: error: ramp (a slope, e.g. "50*Nm/s") has unit kg*m^2/s^2; it needs kg*m^2/s^3)~"); }
TEST_F(Signals, SineWithoutFrequency) { expect_signal_error(R"({ sine = "10*Nm" })",
    R"~(scene.toml:9:9: error: a sine needs frequency = "<f>*Hz")~"); }
TEST_F(Signals, SineFrequencyInRpm) { expect_signal_error(R"({ sine = "10*Nm", frequency = "60*rpm" })",
    R"~(scene.toml:9:39: error: frequency is in cycles per second; give it in Hz or kHz, e.g. "50*Hz" (rpm would make it an angular speed, 2 pi times the frequency: 3000*rpm turns at 50*Hz))~"); }
TEST_F(Signals, SineFrequencyNotPositive) {
  expect_signal_error(R"({ sine = "10*Nm", frequency = "-5*Hz" })",
    R"~(scene.toml:9:39: error: frequency is -5 Hz; a sine's frequency is positive (a constant input is { constant = ... }, and the sign of a sine is its amplitude's or its phase's))~");
}
TEST_F(Signals, SineFrequencyBeyondAGearsDynamics) {
  expect_signal_error(R"({ sine = "10*Nm", frequency = "1e30*Hz" })",
    R"~(scene.toml:9:39: error: frequency is 1e+30 Hz, above 1e+06 Hz, far beyond a gear's dynamics and what its sine can be computed at in double precision; give the frequency in Hz)~");
}
TEST_F(Signals, UnknownForm) { expect_signal_error(R"({ pulse = "10*Nm" })",
    R"~(scene.toml:9:9: error: a signal is { constant = ... }, { step = ..., at = ... }, { ramp = ... }, { sine = ..., frequency = ... }, { table = "file.csv" } or { table = [[time, value], ...] })~"); }

class Tables : public ErrorTest {
 protected:
  // The scene with tau_c = { table = "torque.csv" } and torque.csv holding `csv`.
  void expect_table_error(const std::string& csv, const std::string& expected) {
    write_text("torque.csv", csv);
    expect_table_file_error("torque.csv", expected);
  }
  void expect_table_file_error(const std::string& file, const std::string& expected) {
    expect_scene_error({{R"(tau_c = { constant = "100*Nm" })", "tau_c = { table = \"" + file + "\" }"}}, expected);
  }
};

TEST_F(Tables, InlineRowNotAPair) {
  expect_scene_error({{R"(tau_c = { constant = "100*Nm" })", R"(tau_c = { table = [["0*s", "0*Nm"], "1"] })"}},
      R"~(scene.toml:9:37: error: a row of the table is [time, value], e.g. table = [["0*s", "0*Nm"], ["1*s", "100*Nm"]])~");
}
TEST_F(Tables, InlineTimeGoesBack) {
  expect_scene_error({{R"(tau_c = { constant = "100*Nm" })",
                       R"(tau_c = { table = [["0*s", "0*Nm"], ["1*s", "100*Nm"], ["0.5*s", "50*Nm"]] })"}},
      R"~(scene.toml:9:57: error: time 0.5 s is before the previous row's (1 s); the rows go forward in time)~");
}
TEST_F(Tables, InlineWithoutRows) {
  expect_scene_error({{R"(tau_c = { constant = "100*Nm" })", R"(tau_c = { table = [] })"}},
      R"~(scene.toml:9:19: error: the table has no rows; give rows [time, value], e.g. table = [["0*s", "0*Nm"], ["1*s", "100*Nm"]])~");
}
TEST_F(Tables, CannotOpen) { expect_table_file_error("torques.csv",
    R"~(scene.toml:9:19: error: table 'torques.csv': cannot open file (No such file or directory); give its path relative to the scene file)~"); }
TEST_F(Tables, ThreeColumns) { expect_table_error("t,tau\n0,0,1\n",
    R"~(torque.csv:2: error: expected 2 columns 't,value', found more; the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, OneColumn) { expect_table_error("t,tau\n0\n",
    R"~(torque.csv:2: error: expected 2 columns 't,value', found 1; the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, BadTime) { expect_table_error("t,tau\n0,0\nhalf,100\n",
    R"~(torque.csv:3: error: bad number 'half' in column 1 (time); the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, BadValue) { expect_table_error("t,tau\n0,0\n0.5,abc\n",
    R"~(torque.csv:3: error: bad number 'abc' in column 2 (value); the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, NotFinite) { expect_table_error("t,tau\n0,0\n0.5,inf\n",
    R"~(torque.csv:3: error: non-finite number; the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, TimeGoesBack) { expect_table_error("t,tau\n0,0\n0.5,100\n0.25,50\n",
    R"~(torque.csv:4: error: time 0.25 is before the previous row's; the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, NoRows) { expect_table_error("t,tau\n# nothing yet\n",
    R"~(scene.toml:9:19: error: table 'torque.csv': no data rows; the table needs two columns: time [s], torque [N m])~"); }
TEST_F(Tables, TooManyRows) {
  std::string csv = "t,tau\n";
  for (std::size_t i = 0; i <= rt::max_table_rows; ++i) csv += std::to_string(i) + ",1\n";
  expect_table_error(csv,
      R"~(torque.csv:100002: error: more than 100000 rows; resample the table more coarsely; the table needs two columns: time [s], torque [N m])~");
}
TEST_F(Tables, TooLarge) {
  // A sparse file of 16 MiB and one byte: reading stops one byte past the limit.
  write_text("zeros.csv", "");
  fs::resize_file("zeros.csv", (std::uintmax_t{16} << 20) + 1);
  expect_table_file_error("zeros.csv",
      R"~(scene.toml:9:19: error: table 'zeros.csv': larger than 16777216 bytes; a table has at most 100000 rows)~");
}
TEST_F(Tables, NotARegularFile) { expect_table_file_error("/dev/zero",
    R"~(scene.toml:9:19: error: table '/dev/zero': a character device, not a regular file)~"); }
TEST_F(Tables, ReadError) { expect_table_file_error("/proc/self/mem",
    R"~(scene.toml:9:19: error: table '/proc/self/mem': read error)~"); }

class Initial : public ErrorTest {};

TEST_F(Initial, NotATable) {
  expect_scene_error({{"[initial]\nomega_c = \"0*rpm\"\n", ""}, {"compare_rigid = true", "compare_rigid = true\ninitial = 0"}},
                     R"~(scene.toml:7:11: error: [initial] must be a table of omega_<body> and F_<mesh> values)~");
}
TEST_F(Initial, UnknownName) { expect_scene_error({{"omega_c = \"0*rpm\"", "omega_x = \"0*rpm\""}},
    R"~(scene.toml:12:1: error: 'omega_x' is neither omega_<body>, F_<mesh> nor Tc_<controller> of the scene; name a body's speed, a mesh's force or a controller's start torque)~"); }
TEST_F(Initial, ForceOfARigidScene) {
  expect_scene_error({{R"("mesh_compliance", "mesh_damping", )", ""}, {"compare_rigid = true\n", ""},
                      {"omega_c = \"0*rpm\"", "F_ps = \"10*N\""}},
                     R"~(scene.toml:11:1: error: initial force 'F_ps' needs mesh_compliance: the rigid model has no force states)~");
}
TEST_F(Initial, SpeedWithoutAUnit) { expect_scene_error({{"omega_c = \"0*rpm\"", "omega_c = \"1000\""}},
    R"~(scene.toml:12:11: error: omega_c has no unit (1000); a speed needs one, e.g. "1000*rpm" or "1000*rad/s")~"); }
// Carrier and ring at rest hold the sun: the paper's gear has two degrees of freedom.
TEST_F(Initial, SpeedsContradictTheGear) {
  expect_scene_error({{"omega_c = \"0*rpm\"", "omega_c = \"0*rpm\"\nomega_r = \"0*rpm\"\nomega_s = \"100*rpm\""}},
    R"~(scene.toml:11:1: error: the initial speeds omega_c, omega_s, omega_r contradict the gear's kinematics, which require -omega_c + 0.337838*omega_s + 0.662162*omega_r = 0 (with these speeds it is 3.53783 rad/s); give speeds that satisfy it, or name fewer bodies)~");
}
TEST_F(Initial, SpeedInHz) { expect_scene_error({{"omega_c = \"0*rpm\"", "omega_c = \"10*Hz\""}},
    R"~(scene.toml:12:11: error: omega_c is in Hz, which for a speed could mean rev/s or rad/s; give it in rpm or rad/s, e.g. "600*rpm")~"); }
TEST_F(Initial, SpeedUnitUnknown) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\nspeed_unit = \"rev/min\""}},
    R"~(scene.toml:7:14: error: speed_unit is "rad/s" (the default) or "rpm")~");
}
TEST_F(Initial, StartUnknown) { expect_scene_error({{"omega_c = \"0*rpm\"", "start = \"warm\""}},
    R"~(scene.toml:12:9: error: start "warm" is not known; write "given" (the default), "rigid" or "steady")~"); }
TEST_F(Initial, SteadyStartWithANamedSpeed) {
  expect_scene_error({{"omega_c = \"0*rpm\"", "omega_c = \"0*rpm\"\nstart = \"steady\""}},
    R"~(scene.toml:13:9: error: start = "steady" computes the whole state from the inputs at t = 0; remove omega_c from [initial])~");
}
TEST_F(Initial, SteadyStartWithoutEquilibrium) {
  expect_scene_error({{R"(, "bearing_friction")", ""}, {"omega_c = \"0*rpm\"", "start = \"steady\""}},
    R"~(scene.toml:12:9: error: start = "steady": the gear has no equilibrium (a rigid motion meets no bearing friction, so a constant torque accelerates it for ever); add bearing_friction to the effects, or start from given speeds)~");
}
TEST_F(Initial, StartWithTunables) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\ntunable = [\"J_c\"]"}, {"omega_c = \"0*rpm\"", "start = \"rigid\""}},
    R"~(scene.toml:13:9: error: start = "rigid" is computed at the scene's parameter values, which tunable parameters change at run time; set them in [parameters], or start from given speeds)~");
}
TEST_F(Initial, RigidStartWithAForce) {
  expect_scene_error({{"omega_c = \"0*rpm\"", "F_ps = \"10*N\"\nstart = \"rigid\""}},
    R"~(scene.toml:13:9: error: start = "rigid" takes the mesh forces from the rigid model; remove F_ps from [initial])~");
}
TEST_F(Initial, RigidStartOfARigidScene) {
  expect_scene_error({{R"("mesh_compliance", "mesh_damping", )", ""}, {"compare_rigid = true\n", ""},
                      {"omega_c = \"0*rpm\"", "start = \"rigid\""}},
    R"~(scene.toml:11:9: error: start = "rigid" starts the elastic model on the rigid model's trajectory; this scene simulates the rigid model (no mesh_compliance), which starts there already: remove start)~");
}
TEST_F(Initial, WrongUnit) { expect_scene_error({{"omega_c = \"0*rpm\"", "omega_c = \"10*rev\""}},
    R"~(scene.toml:12:11: error: omega_c has no unit (rad, deg, rev and pi are plain numbers); it needs 1/s)~"); }

class Outputs : public ErrorTest {};

TEST_F(Outputs, EmptyList) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\noutputs = []"}},
      R"~(scene.toml:7:11: error: outputs = [] names no output; name the speeds and forces to write, or leave outputs out for all of them)~");
}
TEST_F(Outputs, NotAList) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\noutputs = \"omega_c\""}},
      R"~(scene.toml:7:11: error: outputs must be a list of strings, e.g. ["a", "b"])~");
}
TEST_F(Outputs, Unknown) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\noutputs = [\"omega_x\"]"}},
      R"~(scene.toml:7:11: error: output 'omega_x' is none of omega_<body>, F_<mesh>, Fspring_<mesh>, Tc_<controller>)~");
}
TEST_F(Outputs, ForceWithoutMeshForces) {
  expect_scene_error({{R"(, "mesh_forces"])", "]"}, {"compare_rigid = true", "compare_rigid = true\noutputs = [\"F_ps\"]"}},
                     R"~(scene.toml:7:11: error: output 'F_ps' is a mesh force, but the scene does not ask for mesh_forces; add it to effects)~");
}
TEST_F(Outputs, ListedTwice) {
  expect_scene_error({{"compare_rigid = true", "compare_rigid = true\noutputs = [\"omega_c\", \"omega_c\"]"}},
      R"~(scene.toml:7:11: error: output 'omega_c' is listed twice)~");
}

class Simulation : public ErrorTest {};

TEST_F(Simulation, NotATable) {
  const std::string text = base_scene().substr(0, base_scene().find("[simulation]"));
  expect_documented(scene_error(edited(text, {{"compare_rigid = true", "compare_rigid = true\nsimulation = 1"}})),
                    R"~(scene.toml:7:14: error: [simulation] must be a table)~");
}
TEST_F(Simulation, UnknownKey) { expect_scene_error({{"solver = \"exact\"", "method = \"exact\""}},
    R"~(scene.toml:17:1: error: unknown key 'method' in [simulation]; the keys are horizon, sample, solver, tolerance, step, max_steps)~"); }
TEST_F(Simulation, MaxSteps) { expect_scene_error({{"solver = \"exact\"", "solver = \"exact\"\nmax_steps = 0"}},
    R"~(scene.toml:18:13: error: max_steps is a whole number from 1 to 1000000000000)~"); }
TEST_F(Simulation, ToleranceNotANumber) { expect_scene_error({{"tolerance = 1e-9", "tolerance = \"1e-9\""}},
    R"~(scene.toml:18:13: error: tolerance is a plain number, the relative tolerance, e.g. 1e-8)~"); }
TEST_F(Simulation, ToleranceOutOfRange) { expect_scene_error({{"tolerance = 1e-9", "tolerance = 2"}},
    R"~(scene.toml:18:13: error: tolerance must be from 1e-14 to 0.01 (a looser one lets an adaptive method diverge, a tighter one stalls it on rounding); give one in that range, e.g. 1e-8)~"); }
TEST_F(Simulation, SolverNotAString) { expect_scene_error({{"solver = \"exact\"", "solver = 4"}},
    R"~(scene.toml:17:10: error: solver must be a string in quotes)~"); }
TEST_F(Simulation, UnknownSolver) { expect_scene_error({{"solver = \"exact\"", "solver = \"euler\""}},
    R"~(scene.toml:17:10: error: unknown solver 'euler'; the solvers are exact, rk4, dopri5, implicit)~"); }
TEST_F(Simulation, HorizonUnit) { expect_scene_error({{"horizon = \"0.1*s\"", "horizon = \"0.1*m\""}},
    R"~(scene.toml:15:11: error: horizon has unit m; it needs s)~"); }
TEST_F(Simulation, HorizonNotPositive) { expect_scene_error({{"horizon = \"0.1*s\"", "horizon = \"0*s\""}},
    R"~(scene.toml:15:11: error: horizon must be positive; give the simulated time, e.g. horizon = "2*s")~"); }
TEST_F(Simulation, SampleAboveHorizon) { expect_scene_error({{"sample = \"1*ms\"", "sample = \"1*s\""}},
    R"~(scene.toml:16:10: error: sample must be positive and at most the horizon)~"); }
TEST_F(Simulation, StepNotPositive) { expect_scene_error({{"step = \"0.05*ms\"", "step = \"-1*ms\""}},
    R"~(scene.toml:19:8: error: step must be positive)~"); }
TEST_F(Simulation, TooManySamples) { expect_scene_error({{"horizon = \"0.1*s\"", "horizon = \"1000*minute\""}},
    R"~(scene.toml:14:1: error: 60000000 samples requested; at most 1e7 (raise sample or shorten the horizon))~"); }

TEST_F(Simulation, RedundantMeshesWithTunables) {
  // A third planet on the carrier: three meshes for two degrees of freedom between sun and ring.
  const std::string model = edited(base_model(),
      {{"axis = { fixed = \"below\" }\n", "axis = { fixed = \"below\" }\n\n[[body]]\nname = \"q\"\naxis = { carrier = \"c\", distance = \"r_c\", side = \"below\" }\ninertia = \"J_p\"\nfriction = \"b_p\"\nwheels = [ { name = \"q\", radius = \"r_p\" } ]\n"},
       {"[parameters]\n", "[[mesh]]\nfirst = \"q\"\nsecond = \"s1\"\nstiffness = \"K_ps\"\ndamping = \"b_ps\"\n\n[[mesh]]\nfirst = \"q\"\nsecond = \"r1\"\nstiffness = \"K_ps\"\ndamping = \"b_ps\"\n\n[parameters]\n"}});
  expect_documented(scene_error(edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"J_c\"]"}}), model),
                    R"~(scene.toml: error: this model has redundant meshes, whose rigid load split depends on every stiffness and radius; it is computed at fixed values, so it cannot be combined with tunable parameters: drop 'tunable' or 'mesh_forces')~");
}

}  // namespace
}  // namespace pogear::test

namespace pogear::test {
namespace {

// docs/errors.md itself: it lists the example files as they are, and each entry names a test
// that exists.
TEST(ErrorDocs, ShowTheExampleFilesVerbatim) {
  EXPECT_NE(docs().find("```toml\n" + base_model() + "```"), std::string::npos);
  EXPECT_NE(docs().find("```toml\n" + base_scene() + "```"), std::string::npos);
}

TEST(ErrorDocs, EveryEntryNamesItsTest) {
  std::size_t entries = 0;
  for (auto at = docs().find("\n### "); at != std::string::npos; at = docs().find("\n### ", at + 1)) {
    const auto next = docs().find("\n## ", at + 1) < docs().find("\n### ", at + 1) ? docs().find("\n## ", at + 1)
                                                                                   : docs().find("\n### ", at + 1);
    const std::string entry = docs().substr(at, next == std::string::npos ? std::string::npos : next - at);
    EXPECT_NE(entry.find(" Test: `"), std::string::npos) << entry;
    ++entries;
  }
  EXPECT_GT(entries, 150u);  // the page was found and has its entries
}

TEST(ErrorDocs, EveryNamedTestExists) {
  std::string sources;
  // The stability suite checks the messages of runs it refuses (ExactRange) where it runs them, the
  // runtime's suite those of the hybrid engine, tests/commands those of the command line.
  for (const char* dir : {"tests/errors", "tests/commands", "tests/stability", "tests/runtime"})
    for (const auto& e : fs::directory_iterator(source_path(dir)))
      if (e.path().extension() == ".cpp") sources += read_text(e.path());
  // Every `Suite.Name` in backquotes, both parts capitalized words (no std::regex: g++ 12 warns
  // falsely inside it under -fsanitize=address, and the suite builds with -Werror).
  auto word = [](const std::string& s) {
    return !s.empty() && std::isupper(static_cast<unsigned char>(s[0])) &&
           std::all_of(s.begin(), s.end(), [](char c) { return std::isalnum(static_cast<unsigned char>(c)); });
  };
  std::size_t checked = 0;
  for (auto open = docs().find('`'); open != std::string::npos; open = docs().find('`', open + 1)) {
    const auto close = docs().find('`', open + 1);
    if (close == std::string::npos) break;
    const std::string quoted = docs().substr(open + 1, close - open - 1);
    const auto dot = quoted.find('.');
    if (dot == std::string::npos || !word(quoted.substr(0, dot)) || !word(quoted.substr(dot + 1))) continue;
    open = close;  // the closing quote opens nothing
    const std::string suite = quoted.substr(0, dot), name = quoted.substr(dot + 1);
    EXPECT_TRUE(sources.find("TEST_F(" + suite + ", " + name + ")") != std::string::npos ||
                sources.find("TEST(" + suite + ", " + name + ")") != std::string::npos)
        << suite << "." << name << " is named in docs/errors.md but is no test";
    ++checked;
  }
  EXPECT_GT(checked, 150u);
}

TEST_F(EngagementCommands, UnknownElement) {
  expect_error("B9 = \"1\"\n",
               R"~(scene.toml:22:1: error: 'B9' is not a brake or clutch of the model; its elements are B1, C1)~");
}

TEST_F(EngagementCommands, CommandOutsideZeroToOne) {
  expect_error("B1 = { step = \"1.5\", at = \"0.05*s\" }\n",
               R"~(scene.toml:22:6: error: the command of B1 is 1.5 at t = 0.05 s; an engagement command is from 0 (open) to 1 (fully engaged) over the whole run)~");
}

TEST_F(EngagementCommands, NegativeRamp) {
  // A ramp that leaves [0, 1] before the horizon: its value at the horizon is below 0.
  expect_error("C1 = { ramp = \"-20/s\", initial = \"1\" }\n",
               R"~(scene.toml:22:6: error: the command of C1 is -1 at t = 0.1 s; an engagement command is from 0 (open) to 1 (fully engaged) over the whole run)~");
}

TEST_F(EngagementCommands, SineRefused) {
  expect_error("B1 = { sine = \"0.5\", frequency = \"1*Hz\", offset = \"0.5\" }\n",
               R"~(scene.toml:22:15: error: an engagement command is constant, a step, a ramp or a table (piecewise linear, so that events are located exactly); give the sine as a table)~");
}

TEST_F(EngagementCommands, ModelWithoutElements) {
  expect_documented(scene_error(base_scene() + "\n[engagement]\nB1 = \"1\"\n"),
                    R"~(scene.toml:21:1: error: [engagement] commands brakes and clutches, but the model gear has none; add [[brake]] or [[clutch]] to the model, or drop [engagement])~");
}

TEST_F(EngagementCommands, NotWithRk4) {
  expect_error("B1 = \"1\"\n",
               R"~(scene.toml:17:10: error: the scene engages brakes or clutches, which rk4 does not simulate (its fixed steps cannot locate their events); use solver = "exact", "dopri5" or "implicit")~",
               {{R"(solver = "exact")", R"(solver = "rk4")"}});
}

// A static ratio defined through a tunable would keep its number while --param moved the tunable:
// refused, naming it (capacities follow their tunables: SimulateCommand.ParamMovesCapacitiesThatFollowATunable).
TEST_F(EngagementCommands, StaticRatioThroughATunable) {
  const std::string model = edited(shift_model(), {{"body = \"r\"", "body = \"r\"\nstatic_ratio = \"mu_s\""},
                                                   {"Tcap_B1 = \"50*N*m\"", "Tcap_B1 = \"50*N*m\"\nmu_s = \"1.2\""}});
  expect_documented(
      scene_error(edited(base_scene(), {{"compare_rigid = true", "compare_rigid = true\ntunable = [\"mu_s\"]"}}) +
                      "\n[engagement]\nB1 = \"1\"\n",
                  model),
      R"~(scene.toml:7:11: error: the static_ratio of B1 (mu_s) depends on tunable 'mu_s', and a simulation takes static ratios at the scene's value; drop 'mu_s' from tunable)~");
}

TEST_F(LoadsAndControllers, LoadsNotATable) {
  expect_error("", R"~(scene.toml:7:9: error: [loads] must be a table of <body> = { constant = ..., linear = ..., quadratic = ... })~",
               {{"compare_rigid = true", "compare_rigid = true\nloads = 3"}});
}

TEST_F(LoadsAndControllers, LoadOnUnknownBody) {
  expect_error("[loads]\nx = { constant = \"1*N*m\" }\n",
               R"~(scene.toml:22:5: error: the load's body 'x' is not a body of the model; its bodies are c, p, s, r, g)~");
}

TEST_F(LoadsAndControllers, LoadNotATable) {
  expect_error("[loads]\nr = \"5*N*m\"\n",
               R"~(scene.toml:22:5: error: a load is a table { constant = "<torque>", linear = "<N*m*s/rad>", quadratic = "<N*m*s^2/rad^2>" }, each part optional)~");
}

TEST_F(LoadsAndControllers, NegativeLoad) {
  expect_error("[loads]\nr = { linear = \"-0.5*N*m*s\" }\n",
               R"~(scene.toml:22:16: error: linear is negative; a load takes power from the gear (a torque that drives it is an input in [inputs]))~");
}

TEST_F(LoadsAndControllers, LoadWithoutUnit) {
  expect_error("[loads]\nr = { constant = \"5\" }\n",
               R"~(scene.toml:22:18: error: constant has no unit (5); give it with its unit, e.g. "5*N*m")~");
}

TEST_F(LoadsAndControllers, ControllersNotATable) {
  expect_error("", R"~(scene.toml:7:15: error: [controllers] must be a table of <name> = { body = ..., set_point = ..., kp = ..., ki = ... })~",
               {{"compare_rigid = true", "compare_rigid = true\ncontrollers = \"mg1\""}});
}

TEST_F(LoadsAndControllers, ControllerNotATable) {
  expect_error("[controllers]\nmg1 = \"s\"\n",
               R"~(scene.toml:22:7: error: a controller is a table { body = "<body>", speed_of = "<body>", set_point = <speed signal>, kp = "<N*m*s/rad>", ki = "<N*m/rad>" })~");
}

TEST_F(LoadsAndControllers, BadControllerName) {
  expect_error("[controllers]\n\"my controller\" = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:19: error: controller name 'my controller' must be letters, digits and '_', from a letter, at most 64 characters (it names the controller's variables in the generated code))~");
}

TEST_F(LoadsAndControllers, ControllerNameTakenByAParameter) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:7: error: the model has a parameter named 'ref_mg1', which the generated code uses for controller 'mg1'; rename the controller)~",
               {}, edited(base_model(), {{R"(b_sg = "b_ps")", "b_sg = \"b_ps\"\nref_mg1 = \"1*rad/s\""}}));
}

TEST_F(LoadsAndControllers, ControllerWithoutBody) {
  expect_error("[controllers]\nmg1 = { set_point = \"100*rpm\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:7: error: the controller names no body; add body = "<body>", the body whose torque it sets)~");
}

TEST_F(LoadsAndControllers, ControllerOnUnknownBody) {
  expect_error("[controllers]\nmg1 = { body = \"s\", speed_of = \"e\", set_point = \"100*rpm\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:32: error: speed_of 'e' is not a body of the model; its bodies are c, p, s, r, g)~");
}

TEST_F(LoadsAndControllers, ControllerWithoutSetPoint) {
  expect_error("[controllers]\nmg1 = { body = \"s\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:7: error: the controller has no set_point; add set_point = "<speed>", e.g. "1500*rpm")~");
}

TEST_F(LoadsAndControllers, SetPointNotASpeed) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*N*m\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:33: error: a set-point has unit kg*m^2/s^2; it needs 1/s)~");
}

TEST_F(LoadsAndControllers, ControllerGains) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"-1*N*m*s\" }\n",
               R"~(scene.toml:22:49: error: a controller's gains kp and ki are non-negative and not both zero; give kp = "<N*m*s/rad>" and ki = "<N*m/rad>")~");
}

TEST_F(LoadsAndControllers, TorqueLimitsOutOfOrder) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\", torque_min = \"50*N*m\", torque_max = \"-50*N*m\" }\n",
               R"~(scene.toml:22:96: error: torque_max (-50 N m) is not above torque_min (50 N m); give the limits of the torque the controller can apply)~");
}

TEST_F(LoadsAndControllers, TrackingTimeWithoutLimits) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\", ki = \"1*N*m\", tracking_time = \"0.1*s\" }\n",
               R"~(scene.toml:22:90: error: tracking_time is the time constant with which the integral follows a torque limit; it needs torque_min or torque_max, and ki)~");
}

TEST_F(LoadsAndControllers, LimitedIntegralControllerNeedsTrackingTime) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", ki = \"1*N*m\", torque_max = \"50*N*m\" }\n",
               R"~(scene.toml:22:7: error: a controller with torque limits and no kp needs tracking_time, the time constant with which its integral follows a limit (kp / ki, the default, is zero))~");
}

TEST_F(LoadsAndControllers, CoefficientWithoutUnit) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"0.5\" }\n",
               R"~(scene.toml:22:49: error: kp has no unit (0.5); give it with its unit, e.g. "1.5*N*m*s/rad")~");
  expect_error("[loads]\nr = { linear = 0.5 }\n",
               R"~(scene.toml:22:16: error: linear has no unit (0.5); give it with its unit, e.g. "0.5*N*m*s/rad")~");
}

TEST_F(LoadsAndControllers, SpeedsInHz) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"10*Hz\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:22:33: error: a set-point is in Hz, which for a speed could mean rev/s or rad/s; give it in rpm or rad/s, e.g. "600*rpm")~");
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"10*rad/s\", kp = \"1*N*m/Hz\" }\n",
               R"~(scene.toml:22:50: error: kp is per Hz, which for a speed could mean per rev/s or per rad/s; give it per rad/s, e.g. "1.5*N*m*s/rad")~");
}

TEST_F(LoadsAndControllers, QuadraticLoadWithRk4) {
  expect_error("[loads]\nr = { quadratic = \"0.01*N*m*s^2\" }\n",
               R"~(scene.toml:17:10: error: a quadratic load makes the scene nonlinear, which rk4's fixed step cannot be checked against its stability limit; use solver = "dopri5" or "implicit", or a linear load)~",
               {{R"(solver = "exact")", R"(solver = "rk4")"}});
}

TEST_F(LoadsAndControllers, TooManyControllers) {
  std::string controllers = "[controllers]\n";
  for (int i = 0; i < 17; ++i) controllers += "c" + std::to_string(i) + " = { body = \"s\", set_point = \"1*rpm\", kp = \"1*N*m*s\" }\n";
  expect_error(controllers, R"~(scene.toml:21:1: error: 17 controllers; a scene has at most 16)~");
}

TEST_F(LoadsAndControllers, ParameterNamedLikeAQuadraticLoad) {
  expect_error("[loads]\nr = { quadratic = \"0.01*N*m*s^2\" }\n",
               R"~(gear.toml:37:8: error: the model has a parameter named 'TQ_r', which pogear's generated code uses for a quadratic load; rename the parameter)~",
               {{R"(solver = "exact")", R"(solver = "dopri5")"}},
               edited(base_model(), {{"[parameters]\n", "[parameters]\nTQ_r = 2\n"}}));
}

TEST_F(LoadsAndControllers, StartTorqueWithoutIntegral) {
  expect_error("[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\" }\n",
               R"~(scene.toml:12:10: error: controller 'mg1' has no integral (ki = 0) to start at a given torque; its torque at t = 0 is kp times the speed error: drop Tc_mg1)~",
               {{"omega_c = \"0*rpm\"", "Tc_mg1 = \"-5*N*m\""}});
}

TEST_F(LoadsAndControllers, StartTorqueOutsideTheLimits) {
  const std::string controller =
      "[controllers]\nmg1 = { body = \"s\", set_point = \"100*rpm\", kp = \"1*N*m*s\", ki = \"2*N*m\", "
      "torque_min = \"-20*N*m\", torque_max = \"50*N*m\" }\n";
  expect_error(controller,
               R"~(scene.toml:12:10: error: Tc_mg1 = 80 N m is above controller 'mg1''s torque_max, 50 N m; give a start torque within its limits)~",
               {{"omega_c = \"0*rpm\"", "Tc_mg1 = \"80*N*m\""}});
  expect_error(controller,
               R"~(scene.toml:12:10: error: Tc_mg1 = -25 N m is below controller 'mg1''s torque_min, -20 N m; give a start torque within its limits)~",
               {{"omega_c = \"0*rpm\"", "Tc_mg1 = \"-25*N*m\""}});
}

TEST_F(LoadsAndControllers, NotWithRigidStart) {
  expect_error("[controllers]\nspeed = { body = \"c\", set_point = \"100*rpm\", kp = \"1*N*m*s/rad\" }\n",
               R"~(scene.toml:12:9: error: start = "rigid" and "steady" are not available with [controllers]; give the initial speeds in [initial])~",
               {{"omega_c = \"0*rpm\"", "start = \"rigid\""}});
}

TEST_F(LoadsAndControllers, SteadyStartWithAQuadraticLoad) {
  expect_error("[loads]\nr = { quadratic = \"0.01*N*m*s^2\" }\n",
               R"~(scene.toml:12:9: error: start = "steady" solves a linear equilibrium, which a quadratic load does not have; start from given speeds, or with start = "rigid")~",
               {{"omega_c = \"0*rpm\"", "start = \"steady\""}, {R"(solver = "exact")", R"(solver = "dopri5")"}});
}

TEST_F(LoadsAndControllers, QuadraticLoadWithExactSolver) {
  expect_error("[loads]\nr = { quadratic = \"0.01*N*m*s^2\" }\n",
               R"~(scene.toml:17:10: error: a quadratic load makes the scene nonlinear, which exact stepping does not integrate; use solver = "dopri5" or "implicit", or a linear load)~");
}

TEST_F(LoadsAndControllers, QuadraticLoadWithBrakesAndExactSolver) {
  const std::string model = edited(base_model(), {{"[parameters]", "[[brake]]\nname = \"B1\"\nbody = \"r\"\n\n[parameters]"},
                                                  {R"(b_sg = "b_ps")", "b_sg = \"b_ps\"\nTcap_B1 = \"50*N*m\""}});
  expect_error("[engagement]\nB1 = \"1\"\n\n[loads]\nr = { quadratic = \"0.01*N*m*s^2\" }\n",
               R"~(scene.toml:17:10: error: a quadratic load makes the scene nonlinear, which exact stepping does not integrate; use solver = "dopri5" or "implicit", or a linear load)~",
               {}, model);
}

}  // namespace
}  // namespace pogear::test
