// SPDX-License-Identifier: Apache-2.0
// shadecore — `shadecore render` from the command line: bad scenes are one line on stderr, exit status 1
// and no output at all; a good scene writes its images and a JSON report with the documented fields.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
#include <sys/stat.h>
#include <unistd.h>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must point at the source tree"
#endif

namespace {

namespace fs = std::filesystem;
using shadecore::testing::run_cli;

const char* kGood = R"({
  "image": {"width": 40, "height": 30, "background": [0.1, 0.1, 0.1]},
  "camera": {"eye": [0, 0, 6], "center": [0, 0, 0], "up": [0, 1, 0], "fovy": 40, "near": 1, "far": 20},
  "light_model": {"ambient": [0.2, 0.2, 0.2]},
  "lights": [{"position": [0, 1, 1, 0], "specular": [1, 1, 1]}],
  "materials": {"m": {"diffuse": [0.8, 0.3, 0.2], "specular": [0.5, 0.5, 0.5], "shininess": 32}},
  "objects": [{"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8}]
})";

class RenderCli : public ::testing::Test {
 protected:
  void SetUp() override {
    dir_ = fs::temp_directory_path() / ("shadecore_render_cli_" + std::to_string(::getpid()) + "_" +
                                        ::testing::UnitTest::GetInstance()->current_test_info()->name());
    fs::remove_all(dir_);
    fs::create_directories(dir_);
  }
  void TearDown() override { fs::remove_all(dir_); }

  std::string write(const std::string& name, const std::string& text) {
    const fs::path p = dir_ / name;
    std::ofstream(p) << text;
    return p.string();
  }
  // `good` with `from` replaced by `to` (the text must contain `from`).
  static std::string edit(const std::string& from, const std::string& to) {
    std::string s = kGood;
    const auto i = s.find(from);
    if (i == std::string::npos) throw std::runtime_error("test bug: '" + from + "' not in the good scene");
    s.replace(i, from.size(), to);
    return s;
  }
  fs::path dir_;
};

struct Bad {
  const char* what;
  std::string scene;    // the scene text
  std::string needle;   // part of the one error line
};

TEST_F(RenderCli, BadScenesOneLineExit1NoOutput) {
  const std::string cube_bad_index = "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 7\n";
  const std::string collinear = "v 0 0 0\nv 1 0 0\nv 2 0 0\nv 0 1 0\nf 1 2 3\nf 1 2 4\n";
  write("bad_index.obj", cube_bad_index);
  write("collinear.obj", collinear);
  write("garbage.obj", "this is not an OBJ file\n");
  // issue 23: OBJ numbers and indices tinyobjloader maps silently (nan -> 0, wrapping indices), and paths
  // that are not regular files.
  const std::string tri = "v 0 0 0\nv 1 0 0\nv 0 1 0\n";
  write("nan.obj", "v nan nan nan\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("nan2.obj", "v NaN 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  write("inf.obj", tri + "v inf 0 0\nf 1 2 3\n");
  write("huge.obj", tri + "v 1e400 0 0\nf 1 2 3\n");
  write("vn_nan.obj", tri + "vn 0 0 nan\nf 1//1 2//1 3//1\n");
  write("wrap.obj", tri + "f 1 2 99999999999999999999\n");
  write("zero_index.obj", tri + "f 0 1 2\n");
  write("far_index.obj", tri + "f 1 2 4\n");
  write("neg_index.obj", tri + "f -1 -2 -4\n");
  write("not_int.obj", tri + "f 1 2 3.5\n");
  write("big_coord.obj", tri + "v 0 1e300 0\nf 1 2 3\n");
  write("face300.obj", tri + "f" + [] {  // tinyobjloader counts face vertices in an unsigned char
    std::string f;
    for (int i = 0; i < 300; ++i) f += " " + std::to_string(1 + i % 3);
    return f;
  }() + "\n");
  fs::create_directories(dir_ / "objdir.obj");
  const std::string fifo = (dir_ / "fifo.obj").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_symlink("loop_b.obj", dir_ / "loop_a.obj");
  fs::create_symlink("loop_a.obj", dir_ / "loop_b.obj");
  auto with_rot = [&](const std::string& t) { return edit("\"stacks\": 8}", "\"stacks\": 8, \"transform\": " + t + "}"); };
  const std::string deep = std::string(150000, '[') + std::string(150000, ']');
  const std::string mesh_obj = R"({"type": "mesh", "file": "%F", "material": "m"})";
  auto with_mesh = [&](const std::string& file) {
    std::string o = mesh_obj;
    o.replace(o.find("%F"), 2, file);
    return edit(R"({"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8})", o);
  };
  // a point light with the given spot keys
  auto spot_light = [&](const std::string& keys) {
    return edit(R"("position": [0, 1, 1, 0], "specular": [1, 1, 1]})",
                R"("position": [0, 1, 4, 1], "specular": [1, 1, 1], )" + keys + "}");
  };
  // light_model.two_side with the given value; the material's "back" object with the given value
  auto two_side = [&](const std::string& v) {
    return edit("\"ambient\": [0.2, 0.2, 0.2]}", "\"ambient\": [0.2, 0.2, 0.2], \"two_side\": " + v + "}");
  };
  auto back = [&](const std::string& v) { return edit("\"shininess\": 32}", "\"shininess\": 32, \"back\": " + v + "}"); };
  // GL_COLOR_MATERIAL (issue 19): the sphere's keys (objects[0].color_material, objects[0].color) and OBJ vertex colours
  auto sphere_keys = [&](const std::string& keys) { return edit("\"stacks\": 8}", "\"stacks\": 8, " + keys + "}"); };
  write("col_some.obj", "v 0 0 0 1 0 0\nv 1 0 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  write("col_first_missing.obj", "v 0 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  write("col_range.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1.5 0\nv 0 1 0 0 0 1\nf 1 2 3\n");
  write("col_negative.obj", "v 0 0 0 1 0 0\nv 1 0 0 0 1 0\nv 0 1 0 0 0 -0.25\nf 1 2 3\n");
  const std::vector<Bad> cases = {
      {"malformed JSON", edit("\"fovy\": 40,", "\"fovy\": 40,,"), ":3:"},
      {"malformed JSON line/column", std::string(kGood).substr(0, 120), "malformed JSON"},
      {"unknown top-level key", edit("\"image\"", "\"imagez\": 1, \"image\""), "imagez: unknown key"},
      {"unknown light key", edit("\"specular\": [1, 1, 1]}", "\"specular\": [1, 1, 1], \"spot_angle\": 30}"),
       "lights[0].spot_angle: unknown key"},
      // GL_SPOT_* (issue 19): every bad value of the new keys
      {"spot cutoff above 90", spot_light(R"("spot_cutoff": 91)"), "lights[0].spot_cutoff: 91 out of range 0..90 or 180"},
      {"spot cutoff negative", spot_light(R"("spot_cutoff": -1)"), "lights[0].spot_cutoff: -1 out of range 0..90 or 180"},
      {"spot cutoff 179", spot_light(R"("spot_cutoff": 179)"), "lights[0].spot_cutoff: 179 out of range 0..90 or 180"},
      {"spot cutoff not a number", spot_light(R"("spot_cutoff": "30")"), "lights[0].spot_cutoff: must be a number"},
      {"spot exponent above 128", spot_light(R"("spot_exponent": 129)"), "lights[0].spot_exponent: 129 out of range 0..128"},
      {"spot exponent negative", spot_light(R"("spot_exponent": -1)"), "lights[0].spot_exponent: -1 out of range 0..128"},
      {"spot exponent fractional", spot_light(R"("spot_exponent": 20.5)"), "lights[0].spot_exponent: must be an integer (20.5 is not)"},
      {"spot direction zero", spot_light(R"("spot_direction": [0, 0, 0])"), "lights[0].spot_direction: must be a non-zero direction"},
      {"spot direction two numbers", spot_light(R"("spot_direction": [1, 2])"), "lights[0].spot_direction: must be a list of 3 numbers"},
      {"spot on a directional light",
       edit("\"specular\": [1, 1, 1]}", "\"specular\": [1, 1, 1], \"spot_cutoff\": 30}"),
       "lights[0]: a spot light (spot_cutoff != 180) must be positional"},
      // flat_rule (issue 19): not a string, an unknown rule, user text escaped
      {"flat_rule not a string", edit("\"image\"", "\"flat_rule\": 1, \"image\""), "scene.json: flat_rule: must be a string"},
      {"flat_rule a list", edit("\"image\"", "\"flat_rule\": [\"centroid\"], \"image\""), "flat_rule: must be a string"},
      {"flat_rule unknown", edit("\"image\"", "\"flat_rule\": \"first_vertex\", \"image\""),
       "flat_rule: unknown flat rule 'first_vertex' (known: centroid, provoking_vertex)"},
      {"flat_rule empty", edit("\"image\"", "\"flat_rule\": \"\", \"image\""), "flat_rule: unknown flat rule '' (known: centroid"},
      {"flat_rule control character", edit("\"image\"", "\"flat_rule\": \"pv\\u001b[2J\", \"image\""),
       "flat_rule: unknown flat rule 'pv\\x1b[2J'"},
      {"unknown object key", edit("\"slices\": 12", "\"slices\": 12, \"colour\": 1"), "objects[0].colour: unknown key"},
      {"duplicate key", edit("\"fovy\": 40,", "\"fovy\": 40, \"fovy\": 50,"), "camera.fovy: duplicate key"},
      {"wrong type", edit("\"width\": 40", "\"width\": \"40\""), "image.width: must be an integer"},
      {"zero-size image", edit("\"width\": 40", "\"width\": 0"), "image.width: 0 out of range"},
      {"color_control unknown", edit("\"ambient\": [0.2, 0.2, 0.2]}", "\"ambient\": [0.2, 0.2, 0.2], \"color_control\": \"separate\"}"),
       "light_model.color_control: must be single or separate_specular"},
      {"color_control not a string", edit("\"ambient\": [0.2, 0.2, 0.2]}", "\"ambient\": [0.2, 0.2, 0.2], \"color_control\": 1}"),
       "light_model.color_control: must be a string"},
      {"shininess below 0", edit("\"shininess\": 32", "\"shininess\": -1"), "materials.m.shininess: -1 out of range 0..1024"},
      {"shininess above 1024", edit("\"shininess\": 32", "\"shininess\": 2000"), "out of range 0..1024"},
      {"normalization below 16", edit("\"shininess\": 32", "\"shininess\": 8, \"normalization\": {\"model\": \"phong\"}"),
       "materials.m.normalization: needs shininess 16..1024 (got 8; below 16 the power is not normalised)"},
      {"negative colour", edit("\"diffuse\": [0.8, 0.3, 0.2]", "\"diffuse\": [0.8, -0.3, 0.2]"),
       "materials.m.diffuse[1]: -0.3 out of range"},
      {"negative attenuation", edit("[0, 1, 1, 0], \"specular\"", "[0, 1, 1, 1], \"linear_attenuation\": -1, \"specular\""),
       "lights[0].linear_attenuation: -1 out of range"},
      {"all attenuation zero", edit("[0, 1, 1, 0], \"specular\"", "[0, 1, 1, 1], \"constant_attenuation\": 0, \"specular\""),
       "all round to 0 in the core's 16-bit fraction format"},
      {"too many lights",
       edit("\"lights\": [{\"position\": [0, 1, 1, 0], \"specular\": [1, 1, 1]}]",
            "\"lights\": [" + [] {
              std::string s;
              for (int i = 0; i < 9; ++i) s += std::string(i ? "," : "") + "{\"position\": [0, 1, 1, 0]}";
              return s;
            }() + "]"),
       "9 lights; the core supports at most 8"},
      {"degenerate camera", edit("\"eye\": [0, 0, 6]", "\"eye\": [0, 0, 0]"), "degenerate camera"},
      {"up parallel to view", edit("\"up\": [0, 1, 0]", "\"up\": [0, 0, 1]"), "parallel"},
      {"near >= far", edit("\"far\": 20", "\"far\": 0.5"), "camera.far: must be greater than near"},
      {"unknown material", edit("\"material\": \"m\"", "\"material\": \"steel\""), "unknown material 'steel'"},
      {"unknown shading", edit("\"shading\": \"phong\"", "\"shading\": \"toon\""), "unknown shading mode 'toon'"},
      {"unknown object type", edit("\"type\": \"sphere\"", "\"type\": \"teapot\""), "unknown object type 'teapot'"},
      {"unknown specular unit", edit("\"shininess\": 32", "\"shininess\": 32, \"specular_unit\": \"phong\""),
       "unknown variant 'phong'"},
      {"object out of the core's range", edit("\"stacks\": 8}", "\"stacks\": 8, \"transform\": {\"translate\": [0, 0, -200]}}"),
       "outside the core's position range"},
      {"missing OBJ file", with_mesh("nowhere.obj"), "no such OBJ file"},
      {"OBJ index out of range", with_mesh("bad_index.obj"), "bad_index.obj"},
      {"OBJ with no faces", with_mesh("garbage.obj"), "no faces"},
      {"degenerate triangle", with_mesh("collinear.obj"), "face 1 is degenerate"},
      // issue 23
      {"150000 nested [ in a _comment", edit("\"image\"", "\"_comment\": " + deep + ", \"image\""),
       "scene.json:2:78: nesting deeper than 64 levels"},
      {"65 nested arrays", edit("\"image\"", "\"_comment\": " + std::string(65, '[') + std::string(65, ']') + ", \"image\""),
       "nesting deeper than 64 levels"},
      {"OBJ is a directory", with_mesh("objdir.obj"), "objdir.obj: is a directory"},
      {"OBJ is /dev/null", with_mesh("/dev/null"), "/dev/null: is a character device, not a regular file"},
      {"OBJ is a FIFO", with_mesh("fifo.obj"), "fifo.obj: is a FIFO, not a regular file"},
      {"OBJ symlink loop", with_mesh("loop_a.obj"), "loop_a.obj: too many levels of symbolic links"},
      {"OBJ v nan", with_mesh("nan.obj"), "nan.obj:1: 'nan' is not a finite number"},
      {"OBJ v NaN", with_mesh("nan2.obj"), "nan2.obj:1: 'NaN' is not a finite number"},
      {"OBJ v inf", with_mesh("inf.obj"), "inf.obj:4: 'inf' is not a finite number"},
      {"OBJ v 1e400", with_mesh("huge.obj"), "huge.obj:4: '1e400' is not a finite number"},
      {"OBJ vn nan", with_mesh("vn_nan.obj"), "vn_nan.obj:4: 'nan' is not a finite number"},
      {"OBJ index overflows", with_mesh("wrap.obj"), "wrap.obj:4: vertex index 99999999999999999999 overflows"},
      {"OBJ index 0", with_mesh("zero_index.obj"), "zero_index.obj:4: vertex index 0"},
      {"OBJ index past the end", with_mesh("far_index.obj"), "far_index.obj:4: vertex index 4 out of range (3 in the file)"},
      {"OBJ relative index too far back", with_mesh("neg_index.obj"), "neg_index.obj:4: relative vertex index -4"},
      {"OBJ index not an integer", with_mesh("not_int.obj"), "not_int.obj:4: face index '3.5' is not an integer"},
      {"NUL in a file name", with_mesh("knot.obj\\u0000ignored"), "scene.json:7:49: \\u0000 (NUL) in a string"},
      {"NUL in a key", edit("\"image\"", "\"a\\u0000b\": 1, \"image\""), "\\u0000 (NUL) in a string"},
      {"NUL in a material name", edit("\"m\": {", "\"m\\u0000x\": {"), "scene.json:6:19: \\u0000 (NUL)"},
      {"NUL in an object name", edit("\"type\": \"sphere\"", "\"name\": \"a\\u0000\", \"type\": \"sphere\""),
       "\\u0000 (NUL) in a string"},
      {"valid JSON, a NUL byte, garbage", std::string(kGood) + std::string(1, '\0') + "garbage",
       "scene.json:8:2: NUL byte in the scene file"},
      {"ESC[2J in a key is escaped", edit("\"image\"", "\"\\u001b[2J\": 1, \"image\""), "scene.json: \\x1b[2J: unknown key"},
      {"newline, tab, DEL, C1 in a key", edit("\"image\"", "\"a\\nb\\tc\\u007fd\\u009be\": 1, \"image\""),
       "a\\nb\\tc\\x7fd\\u009be: unknown key"},
      {"control character in an unknown object type", edit("\"type\": \"sphere\"", "\"type\": \"sph\\u001b\""),
       "unknown object type 'sph\\x1b'"},
      {"long user text cut at 60 characters", edit("\"material\": \"m\"", "\"material\": \"" + std::string(500, 'x') + "\""),
       "unknown material '" + std::string(60, 'x') + "\u2026'"},
      {"1e999", edit("\"fovy\": 40", "\"fovy\": 1e999"), "scene.json:3:78: number out of range (overflows a double): 1e999"},
      {"a million-digit number", edit("\"fovy\": 40", "\"fovy\": " + std::string(1000000, '9')),
       "number out of range (overflows a double): " + std::string(60, '9') + "\u2026"},
      {"specular_unit table256", edit("\"shininess\": 32", "\"shininess\": 32, \"specular_unit\": \"table256\""),
       "materials.m.specular_unit: specular unit 'table256' is not a unit of the lighting core"},
      {"specular_unit table1024", edit("\"shininess\": 32", "\"shininess\": 32, \"specular_unit\": \"table1024\""),
       "the core takes cs16, schlick_div, schlick_nr, schlick_iter, cs16_faithful, cs16_compact"},
      {"contact_sheet unit table256", edit("\"objects\"", "\"contact_sheet\": {\"units\": [\"cs16\", \"table256\"]}, \"objects\""),
       "contact_sheet.units[1]: specular unit 'table256' is not a unit of the lighting core"},
      {"unknown unit lists only core units", edit("\"shininess\": 32", "\"shininess\": 32, \"specular_unit\": \"x\""),
       "unknown variant 'x' (known: cs16, schlick_div, schlick_nr, schlick_iter, cs16_faithful, cs16_compact)"},
      {"rotation axis 1e-300", with_rot("{\"rotate\": [30, 1e-300, 0, 0]}"),
       "objects[0].transform.rotate: rotation axis too short to normalise"},
      {"rotation axis 1e-300 in a list", with_rot("{\"rotate\": [[30, 0, 1, 0], [30, 0, 0, 1e-300]]}"),
       "objects[0].transform.rotate[1]: rotation axis too short to normalise"},
      {"rotation angle 1e300", with_rot("{\"rotate\": [1e300, 0, 1, 0]}"), "objects[0].transform.rotate[0]: 1e+300 out of range"},
      {"scale 1e-300", with_rot("{\"scale\": 1e-300}"), "objects[0].transform.scale: 1e-300 out of range: |scale| must be in [1e-6, 1e6]"},
      {"scale 1e300", with_rot("{\"scale\": [1, 1e300, 1]}"), "objects[0].transform.scale[1]: 1e+300 out of range"},
      {"translate 1e300", with_rot("{\"translate\": [1e300, 0, 0]}"), "objects[0].transform.translate[0]: 1e+300 out of range"},
      {"radius 1e-300", edit("\"slices\": 12", "\"radius\": 1e-300, \"slices\": 12"), "objects[0].radius: 1e-300 out of range [1e-6, 1e4]"},
      {"camera eye 1e300", edit("\"eye\": [0, 0, 6]", "\"eye\": [0, 0, 1e300]"), "camera.eye[2]: 1e+300 out of range"},
      {"camera up 1e-300", edit("\"up\": [0, 1, 0]", "\"up\": [0, 1e-300, 0]"), "camera.up: degenerate camera: up is the zero vector"},
      {"fovy 1e-300", edit("\"fovy\": 40", "\"fovy\": 1e-300"), "camera.fovy: 1e-300 out of range"},
      {"light position 1e300", edit("[0, 1, 1, 0]", "[0, 1e300, 1, 0]"), "lights[0].position[1]: 1e+300 out of range"},
      {"directional light 1e-300", edit("[0, 1, 1, 0]", "[0, 1e-300, 0, 0]"),
       "lights[0].position: the direction of a directional light (w = 0) is too short to normalise"},
      {"point light w 1e-300", edit("[0, 1, 1, 0]", "[0, 0, 0, 1e-300]"), "lights[0].position: w = 1e-300 is too close to 0"},
      {"attenuation 1e-9", edit("[0, 1, 1, 0], \"specular\"",
                                "[0, 1, 1, 1], \"constant_attenuation\": 1e-9, \"linear_attenuation\": 1e-9, "
                                "\"quadratic_attenuation\": 1e-9, \"specular\""),
       "lights[0]: constant, linear and quadratic attenuation all round to 0 in the core's 16-bit fraction format "
       "(smallest representable 2^-16 \u2248 1.52588e-05"},
      {"shininess 16.5", edit("\"shininess\": 32", "\"shininess\": 16.5"), "materials.m.shininess: must be an integer (16.5 is not)"},
      {"slices 12.5", edit("\"slices\": 12", "\"slices\": 12.5"), "objects[0].slices: must be an integer"},
      {"integral but out of range", edit("\"shininess\": 32", "\"shininess\": 2048.0"), "materials.m.shininess: 2048 out of range 0..1024"},
      {"huge unsigned integer", edit("\"width\": 40", "\"width\": 18446744073709551615"),
       "image.width: 18446744073709551615 out of range 1..4096"},
      {"more than 256 keys in one object (ordered_json's lookup is linear: a hang for a million)",
       edit("\"m\": {", [] {
         std::string k;
         for (int i = 0; i < 300; ++i) k += "\"k" + std::to_string(i) + "\": {}, ";
         return k;
       }() + "\"m\": {"),
       "scene.json: materials: more than 256 keys in one object"},
      {"OBJ face with 300 vertices", with_mesh("face300.obj"), "face300.obj:4: a face with 300 vertices; at most 255"},
      {"OBJ coordinate 1e300", with_mesh("big_coord.obj"), "big_coord.obj:4: '1e300' out of range [-1e6, 1e6]"},
      // GL_LIGHT_MODEL_TWO_SIDE and the back material (issue 19): every bad value of the new keys
      {"two_side a number", two_side("1"), "light_model.two_side: must be true or false"},
      {"two_side a string", two_side("\"true\""), "light_model.two_side: must be true or false"},
      {"two_side null", two_side("null"), "light_model.two_side: must be true or false"},
      {"back not an object", back("[0.1, 0.2, 0.3]"), "materials.m.back: must be a JSON object"},
      {"back a string", back("\"m\""), "materials.m.back: must be a JSON object"},
      {"back unknown key", back(R"({"colour": [0, 0, 0]})"),
       "materials.m.back.colour: unknown key (known here: emission, ambient, diffuse, specular, shininess)"},
      {"back nested back", back(R"({"back": {}})"), "materials.m.back.back: unknown key"},
      {"back specular_unit", back(R"({"specular_unit": "cs16"})"),
       "materials.m.back.specular_unit: applies to the front material only: the back face shares its specular unit, "
       "cut-off and normalisation (only the back shininess may differ)"},
      {"back cutoff", back(R"({"cutoff": "sign_clamp"})"), "materials.m.back.cutoff: applies to the front material only"},
      {"back normalization", back(R"({"normalization": {"model": "phong"}})"),
       "materials.m.back.normalization: applies to the front material only"},
      // a back shininess of its own is valid (a batch of its own, docs/scenes.md); under the front's normalisation
      // it has the front's range
      {"back shininess below 16, normalised", edit("\"shininess\": 32}", "\"shininess\": 32, \"normalization\": "
                                                  "{\"model\": \"blinn\"}, \"back\": {\"shininess\": 8}}"),
       "materials.m.back.shininess: needs 16..1024 with the front's normalization (got 8; below 16 the power is not "
       "normalised)"},
      {"back shininess negative", back(R"({"shininess": -1})"), "materials.m.back.shininess: -1 out of range 0..1024"},
      {"back shininess out of range", back(R"({"shininess": 2000})"), "materials.m.back.shininess: 2000 out of range 0..1024"},
      {"back shininess fractional", back(R"({"shininess": 32.5})"), "materials.m.back.shininess: must be an integer (32.5 is not)"},
      {"back negative colour", back(R"({"diffuse": [0.1, -0.2, 0.3]})"), "materials.m.back.diffuse[1]: -0.2 out of range"},
      {"back colour 2", back(R"({"emission": [2, 0, 0]})"), "materials.m.back.emission[0]: 2 out of range [0, 2)"},
      {"back colour two numbers", back(R"({"specular": [1, 1]})"), "materials.m.back.specular: must be a colour [r, g, b]"},
      {"back colour a number", back(R"({"ambient": 0.3})"), "materials.m.back.ambient: must be a colour [r, g, b]"},
      {"back colour not a number", back(R"({"ambient": [0.1, "a", 0.1]})"), "materials.m.back.ambient[1]: must be a number"},
      // GL_COLOR_MATERIAL (issue 19): every bad value of the new keys and of OBJ vertex colours
      {"color_material unknown", sphere_keys(R"("color_material": "glow")"),
       "objects[0].color_material: unknown color_material mode 'glow' (known: none, emission, ambient, diffuse, specular, "
       "ambient_and_diffuse)"},
      {"color_material GL name", sphere_keys(R"("color_material": "GL_DIFFUSE")"),
       "objects[0].color_material: unknown color_material mode 'GL_DIFFUSE'"},
      {"color_material a number", sphere_keys(R"("color_material": 2)"), "objects[0].color_material: must be a string"},
      {"color_material a bool", sphere_keys(R"("color_material": true)"), "objects[0].color_material: must be a string"},
      {"color above 1", sphere_keys(R"("color": [1, 1.5, 0])"), "objects[0].color[1]: 1.5 out of range [0, 1]"},
      {"color negative", sphere_keys(R"("color": [-0.1, 0, 0])"), "objects[0].color[0]: -0.1 out of range [0, 1]"},
      {"color two numbers", sphere_keys(R"("color": [1, 1])"), "objects[0].color: must be a colour [r, g, b]"},
      {"color four numbers", sphere_keys(R"("color": [1, 1, 1, 1])"), "objects[0].color: must be a colour [r, g, b]"},
      {"color a string", sphere_keys(R"("color": "red")"), "objects[0].color: must be a colour [r, g, b]"},
      {"color not a number", sphere_keys(R"("color": [0.1, "a", 0.1])"), "objects[0].color[1]: must be a number"},
      {"OBJ colours on some v lines", with_mesh("col_some.obj"),
       "col_some.obj:2: a vertex without a colour, but line 1 has one (vertex colours 'v x y z r g b' on every v line or on none)"},
      {"OBJ colour missing on the first v line", with_mesh("col_first_missing.obj"),
       "col_first_missing.obj:1: a vertex without a colour, but line 2 has one"},
      {"OBJ colour above 1", with_mesh("col_range.obj"), "col_range.obj:2: vertex colour '1.5' out of range [0, 1]"},
      {"OBJ colour negative", with_mesh("col_negative.obj"), "col_negative.obj:3: vertex colour '-0.25' out of range [0, 1]"},
  };
  for (const auto& c : cases) {
    SCOPED_TRACE(c.what);
    const std::string scene = write("scene.json", c.scene);
    const fs::path out = dir_ / "out", js = dir_ / "report.json";
    const auto r = run_cli("render " + scene + " --out " + out.string() + " --json " + js.string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(c.needle), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("scene.json"), std::string::npos) << r.err;  // names the file
    EXPECT_LT(r.err.size(), 600u) << "message too long";
    for (const char ch : r.err)  // user text is escaped: no control character but the final newline
      EXPECT_TRUE(ch == '\n' || (static_cast<unsigned char>(ch) >= 0x20 && ch != 0x7f)) << r.err;
    EXPECT_FALSE(fs::exists(out)) << "output directory left behind";
    EXPECT_FALSE(fs::exists(js)) << "JSON left behind";
  }
}

TEST_F(RenderCli, BadArgumentsOneLine) {
  const std::string scene = write("scene.json", kGood);
  for (const auto& [args, needle] : std::vector<std::pair<std::string, std::string>>{
           {"render " + (dir_ / "missing.json").string() + " --out " + (dir_ / "o").string(), "cannot read the scene file"},
           {"render " + scene + " --out " + (dir_ / "o").string() + " --size 0x10", "--size"},
           {"render " + scene + " --out " + (dir_ / "o").string() + " --size big", "--size"},
           {"render " + scene, "--out"},
           {"render " + scene + " --out " + scene, "not a directory"},
           {"render " + scene + " --out " + (dir_ / "o").string() + " --share 5", "--share"},
           {"render " + scene + " --out " + (dir_ / "o").string() + " --share 2 --lanes 2", "--share 2 needs --lanes 1"},
       }) {
    SCOPED_TRACE(args);
    const auto r = run_cli(args);
    EXPECT_EQ(r.status, 1);
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(dir_ / "o"));
  }
}

// A failure after --out exists (the OBJ is missing) leaves the directory as it was.
TEST_F(RenderCli, FailureLeavesExistingDirectoryUntouched) {
  fs::create_directories(dir_ / "out");
  std::ofstream(dir_ / "out" / "keep.txt") << "x";
  const std::string scene =
      write("scene.json", edit(R"({"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8})",
                               R"({"type": "mesh", "file": "none.obj", "material": "m"})"));
  const auto r = run_cli("render " + scene + " --out " + (dir_ / "out").string());
  EXPECT_EQ(r.status, 1) << r.err;
  std::vector<std::string> names;
  for (const auto& e : fs::directory_iterator(dir_ / "out")) names.push_back(e.path().filename().string());
  EXPECT_EQ(names, std::vector<std::string>{"keep.txt"});
}

TEST_F(RenderCli, WritesImagesAndJson) {
  const std::string scene = write("scene.json", kGood);
  const fs::path out = dir_ / "out" / "nested", js = dir_ / "r.json";
  const auto r = run_cli("render " + scene + " --out " + out.string() + " --json " + js.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("feature set: 1 slot (directional), 1 lane"), std::string::npos) << r.out;
  for (const char* f : {"cmodel.png", "exact.png", "diff_exact.png"}) {
    ASSERT_TRUE(fs::exists(out / f)) << f;
    std::ifstream in(out / f, std::ios::binary);
    char sig[8] = {};
    in.read(sig, 8);
    EXPECT_EQ(std::string(sig + 1, 3), "PNG");
  }
  EXPECT_FALSE(fs::exists(out / "rtl.png"));
  std::ifstream in(js);
  const auto j = nlohmann::json::parse(in);
  ASSERT_EQ(j["features"].size(), 1u);
  EXPECT_EQ(j["features"][0]["set"]["lights"][0], "directional");
  EXPECT_EQ(j["features"][0]["set"]["specular"], "cs16");
  EXPECT_TRUE(j["error_vs_exact"]["max_lsb"].is_number());
  EXPECT_TRUE(j["error_vs_exact"]["psnr_db"].is_number());
  EXPECT_EQ(j["images"][0]["name"], "cmodel");
  EXPECT_TRUE(j["images"][0]["error_vs_exact"]["max_lsb"].is_number());
  EXPECT_TRUE(j["rtl"].is_null());
  EXPECT_EQ(j["width"], 40);
}

// --json inside the --out directory the run creates: one more file of it; naming an image is an error.
TEST_F(RenderCli, JsonInsideOutDirectory) {
  const std::string scene = write("scene.json", kGood);
  const fs::path out = dir_ / "new";
  auto r = run_cli("render " + scene + " --out " + out.string() + " --json " + (out / "report.json").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "report.json"));
  EXPECT_TRUE(fs::exists(out / "cmodel.png"));
  fs::remove_all(out);
  r = run_cli("render " + scene + " --out " + out.string() + " --json " + (out / "exact.png").string());
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_NE(r.err.find("one of the images"), std::string::npos) << r.err;
  EXPECT_FALSE(fs::exists(out));
}

// The same scene on the full core: byte-identical C-model image.
TEST_F(RenderCli, FullCoreSameImage) {
  const std::string scene = std::string(SHADECORE_SOURCE_DIR) + "/scenes/diffuse.json";
  const auto a = run_cli("render " + scene + " --size 96x72 --out " + (dir_ / "a").string());
  const auto b = run_cli("render " + scene + " --size 96x72 --full-core --out " + (dir_ / "b").string());
  ASSERT_EQ(a.status, 0) << a.err;
  ASSERT_EQ(b.status, 0) << b.err;
  EXPECT_NE(b.out.find("rendered on the full core"), std::string::npos) << b.out;
  auto slurp = [](const fs::path& p) {
    std::ifstream in(p, std::ios::binary);
    std::stringstream ss;
    ss << in.rdbuf();
    return ss.str();
  };
  EXPECT_EQ(slurp(dir_ / "a" / "cmodel.png"), slurp(dir_ / "b" / "cmodel.png"));
}

// issue 23: the scene file itself must be a regular file of at most 16 MiB; nothing is read from a device and a
// FIFO is never opened (`timeout`: a blocking open would hang the test, not pass it).
TEST_F(RenderCli, SceneFileNotRegularOrTooLarge) {
  const std::string fifo = (dir_ / "fifo.json").string();
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  fs::create_directories(dir_ / "adir.json");
  const fs::path big = dir_ / "big.json";
  std::ofstream(big) << "{}";
  fs::resize_file(big, (16u << 20) + 1);
  fs::create_symlink("loop_b.json", dir_ / "loop_a.json");
  fs::create_symlink("loop_a.json", dir_ / "loop_b.json");
  for (const auto& [path, needle] : std::vector<std::pair<std::string, std::string>>{
           {"/dev/zero", "/dev/zero: is a character device, not a regular file"},
           {fifo, "fifo.json: is a FIFO, not a regular file"},
           {(dir_ / "adir.json").string(), "adir.json: is a directory, not a scene file"},
           {big.string(), "big.json: is 16777217 bytes; the limit is 16 MiB"},
           {(dir_ / "loop_a.json").string(), "too many levels of symbolic links"},
           {(dir_ / "none.json").string(), "none.json: cannot read the scene file (no such file)"},
       }) {
    SCOPED_TRACE(path);
    const fs::path out = dir_ / "out", js = dir_ / "r.json";
    const auto r = shadecore::testing::run_shell("timeout 20 " + std::string(SHADECORE_CLI) + " render " + path +
                                                 " --out " + out.string() + " --json " + js.string());
    EXPECT_EQ(r.status, 1) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
    EXPECT_FALSE(fs::exists(out));
    EXPECT_FALSE(fs::exists(js));
  }
}

std::string slurp_file(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Renders `scene` into dir/name and returns cmodel.png (empty on failure, with the error in the test log).
#define RENDER_PNG(scene_text, name)                                                               \
  [&]() {                                                                                          \
    const std::string sp = write(std::string(name) + ".json", scene_text);                         \
    const auto rr = run_cli("render " + sp + " --out " + (dir_ / (name)).string());               \
    EXPECT_EQ(rr.status, 0) << name << ": " << rr.err;                                            \
    return rr.status == 0 ? slurp_file(dir_ / (name) / "cmodel.png") : std::string();             \
  }()

// issue 23: an integral JSON number is an integer for every integer field (16.0, 1.6e1), and renders the same.
TEST_F(RenderCli, IntegralNumbersAreIntegers) {
  const std::string ref = RENDER_PNG(kGood, "ref");
  ASSERT_FALSE(ref.empty());
  std::string s = edit("\"shininess\": 32", "\"shininess\": 3.2e1");
  for (const auto& [from, to] : std::vector<std::pair<std::string, std::string>>{
           {"\"width\": 40", "\"width\": 40.0"}, {"\"height\": 30", "\"height\": 3e1"},
           {"\"slices\": 12", "\"slices\": 12.0"}, {"\"stacks\": 8", "\"stacks\": 0.8e1"}}) {
    s.replace(s.find(from), from.size(), to);
  }
  EXPECT_EQ(RENDER_PNG(s, "float_ints"), ref);
}

// issue 23: a scene without "camera" has the documented default camera (docs/scenes.md §3).
TEST_F(RenderCli, MissingCameraIsTheDefaultCamera) {
  const std::string cam = R"("camera": {"eye": [0, 0, 6], "center": [0, 0, 0], "up": [0, 1, 0], "fovy": 40, "near": 1, "far": 20},)";
  const std::string with_default = edit(cam, R"("camera": {"eye": [0, 0, 5], "center": [0, 0, 0], "up": [0, 1, 0], "fovy": 45, "near": 1, "far": 100},)");
  const std::string empty_camera = edit(cam, R"("camera": {},)");
  const std::string no_camera = edit(cam, "");
  const std::string a = RENDER_PNG(with_default, "explicit");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(RENDER_PNG(no_camera, "none"), a);
  EXPECT_EQ(RENDER_PNG(empty_camera, "empty"), a);
}

// issue 23: relative (negative) OBJ indices stay legal and give the same mesh as the absolute ones; the cs16 forms
// are accepted specular units.
TEST_F(RenderCli, ObjRelativeIndicesAndCs16Forms) {
  const std::string quad = "v -1 -1 0\nv 1 -1 0\nv 1 1 0\nv -1 1 0\nvn 0 0 1\n";
  write("abs.obj", quad + "f 1//1 2//1 3//1 4//1\n");
  write("rel.obj", quad + "f -4//-1 -3//-1 -2//-1 -1//-1\n");
  auto mesh = [&](const std::string& f) {
    return edit(R"({"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8})",
                R"({"type": "mesh", "file": ")" + f + R"(", "material": "m"})");
  };
  const std::string a = RENDER_PNG(mesh("abs.obj"), "abs");
  ASSERT_FALSE(a.empty());
  EXPECT_EQ(RENDER_PNG(mesh("rel.obj"), "rel"), a);
  for (const char* u : {"cs16_faithful", "cs16_compact", "schlick_iter"}) {
    SCOPED_TRACE(u);
    EXPECT_FALSE(RENDER_PNG(edit("\"shininess\": 32", std::string("\"shininess\": 32, \"specular_unit\": \"") + u + "\""), u).empty());
  }
}

}  // namespace
