// SPDX-License-Identifier: Apache-2.0
// shadecore — scene input hardening (issue 23) at the library level: parse_scene / printable directly.
// The CLI side (one line, exit 1, nothing written) is tests/test_render_cli.cpp's bad-scene table.
#include <gtest/gtest.h>

#include <array>
#include <string>
#include <vector>

#include "shadecore/render/scene.hpp"

namespace {

using namespace shadecore::scene;

const char* kBase = R"({
  "image": {"width": 40, "height": 30},
  "lights": [{"position": [0, 1, 1, 0]}],
  "materials": {"m": {"specular": [0.5, 0.5, 0.5], "shininess": 32}},
  "objects": [{"type": "sphere", "material": "m", "slices": 12, "stacks": 8},
              {"type": "torus", "material": "m", "sides": 6, "rings": 8},
              {"type": "plane", "material": "m", "subdivisions": 2}],
  "contact_sheet": {"units": ["cs16"], "cell": [32, 32], "objects": [1]}
})";

std::string edit(const std::string& from, const std::string& to) {
  std::string s = kBase;
  const auto i = s.find(from);
  if (i == std::string::npos) throw std::runtime_error("test bug: '" + from + "' not in the base scene");
  s.replace(i, from.size(), to);
  return s;
}

std::string error_of(const std::string& text) {
  try {
    (void)parse_scene(text, "s.json", ".");
  } catch (const SceneError& e) {
    return e.what();
  }
  return "";
}

TEST(SceneInput, PrintableEscapesControlsDelC1AndBadUtf8) {
  EXPECT_EQ(printable("a\x1b[2J\n\t\r\x7f"), "a\\x1b[2J\\n\\t\\r\\x7f");
  EXPECT_EQ(printable("\xff\xfe"), "\\xff\\xfe");
  EXPECT_EQ(printable("\xc2\x9b"), "\\u009b");                // C1 CSI, valid UTF-8
  EXPECT_EQ(printable("\xc0\xaf"), "\\xc0\\xaf");             // overlong
  EXPECT_EQ(printable("\xed\xa0\x80"), "\\xed\\xa0\\x80");    // a surrogate
  EXPECT_EQ(printable("caf\xc3\xa9 \xe2\x89\x88"), "caf\xc3\xa9 \xe2\x89\x88");  // valid UTF-8 stays
  EXPECT_EQ(printable(std::string(100, 'x')), std::string(60, 'x') + "\xe2\x80\xa6");
  EXPECT_EQ(printable(std::string(100, 'x'), 0), std::string(100, 'x'));
  const std::string once = printable("k\x1b\x01\xff");
  EXPECT_EQ(printable(once), once);  // escaping escaped text changes nothing
}

TEST(SceneInput, BaseSceneParses) {
  EXPECT_EQ(error_of(kBase), "");
}

// Every integer field takes an integral number (16.0, 1.6e1) and rejects a fraction.
TEST(SceneInput, IntegralNumbersForEveryIntegerField) {
  // (text in the base scene, the same with % for the number, the number)
  const std::vector<std::array<std::string, 3>> fields = {
      {"\"width\": 40", "\"width\": %", "40"},          {"\"height\": 30", "\"height\": %", "30"},
      {"\"shininess\": 32", "\"shininess\": %", "32"},  {"\"slices\": 12", "\"slices\": %", "12"},
      {"\"stacks\": 8", "\"stacks\": %", "8"},          {"\"sides\": 6", "\"sides\": %", "6"},
      {"\"rings\": 8", "\"rings\": %", "8"},            {"\"subdivisions\": 2", "\"subdivisions\": %", "2"},
      {"\"cell\": [32, 32]", "\"cell\": [32, %]", "32"}, {"\"objects\": [1]", "\"objects\": [%]", "1"},
  };
  for (const auto& [from, tmpl, num] : fields) {
    SCOPED_TRACE(from);
    auto with = [&, &tmpl = tmpl, &from = from](const std::string& n) {
      std::string t = tmpl;
      t.replace(t.find('%'), 1, n);
      return edit(from, t);
    };
    EXPECT_EQ(error_of(with(num + ".0")), "");
    EXPECT_EQ(error_of(with(num + "e0")), "");
    EXPECT_NE(error_of(with(num + ".5")).find("must be an integer"), std::string::npos);
  }
  const Scene sc = parse_scene(edit("\"shininess\": 32", "\"shininess\": 1.6e1"), "s.json", ".");
  EXPECT_EQ(sc.materials[0].shininess, 16);
}

// flat_rule (issue 19): centroid by default; centroid and provoking_vertex as written; anything else one line.
TEST(SceneInput, FlatRuleParses) {
  EXPECT_EQ(parse_scene(kBase, "s.json", ".").flat_rule, FlatRule::Centroid);
  EXPECT_EQ(parse_scene(edit("\"image\"", "\"flat_rule\": \"centroid\", \"image\""), "s.json", ".").flat_rule, FlatRule::Centroid);
  EXPECT_EQ(parse_scene(edit("\"image\"", "\"flat_rule\": \"provoking_vertex\", \"image\""), "s.json", ".").flat_rule,
            FlatRule::ProvokingVertex);
  EXPECT_STREQ(to_string(FlatRule::Centroid), "centroid");
  EXPECT_STREQ(to_string(FlatRule::ProvokingVertex), "provoking_vertex");
  EXPECT_EQ(error_of(edit("\"image\"", "\"flat_rule\": \"last\", \"image\"")),
            "s.json: flat_rule: unknown flat rule 'last' (known: centroid, provoking_vertex)");
  EXPECT_EQ(error_of(edit("\"image\"", "\"flat_rule\": true, \"image\"")), "s.json: flat_rule: must be a string");
  EXPECT_EQ(error_of(edit("\"image\"", "\"flat_rule\": \"Centroid\", \"image\"")),
            "s.json: flat_rule: unknown flat rule 'Centroid' (known: centroid, provoking_vertex)");
}

TEST(SceneInput, MissingCameraIsTheDefaultCamera) {
  const Scene sc = parse_scene(kBase, "s.json", ".");
  const Camera d;
  EXPECT_EQ(sc.camera.eye, d.eye);
  EXPECT_EQ(sc.camera.center, d.center);
  EXPECT_EQ(sc.camera.up, d.up);
  EXPECT_EQ(sc.camera.fovy, d.fovy);
  EXPECT_EQ(sc.camera.near, d.near);
  EXPECT_EQ(sc.camera.far, d.far);
}

// The deep value is refused before nlohmann builds it (its copy and destruction recurse: a stack overflow).
TEST(SceneInput, DeepNestingRefusedWithPosition) {
  const std::string deep = std::string(150000, '[') + std::string(150000, ']');
  EXPECT_EQ(error_of(edit("\"image\"", "\"_comment\": " + deep + ", \"image\"")),
            "s.json:2:78: nesting deeper than 64 levels");
  // 64 levels (the root object and 63 arrays) are fine
  EXPECT_EQ(error_of(edit("\"image\"", "\"_comment\": " + std::string(63, '[') + std::string(63, ']') + ", \"image\"")), "");
}

TEST(SceneInput, Cs16FormsAreUnitsTablesAreNot) {
  for (const char* u : {"cs16", "cs16_faithful", "cs16_compact", "schlick_div", "schlick_nr", "schlick_iter"}) {
    SCOPED_TRACE(u);
    EXPECT_EQ(error_of(edit("\"shininess\": 32", std::string("\"shininess\": 32, \"specular_unit\": \"") + u + "\"")), "");
    EXPECT_EQ(error_of(edit("\"units\": [\"cs16\"]", std::string("\"units\": [\"") + u + "\"]")), "");
  }
  for (const char* u : {"table256", "table1024"}) {
    SCOPED_TRACE(u);
    EXPECT_NE(error_of(edit("\"shininess\": 32", std::string("\"shininess\": 32, \"specular_unit\": \"") + u + "\""))
                  .find("is not a unit of the lighting core"),
              std::string::npos);
    EXPECT_NE(error_of(edit("\"units\": [\"cs16\"]", std::string("\"units\": [\"") + u + "\"]"))
                  .find("contact_sheet.units[0]: specular unit"),
              std::string::npos);
  }
}

// The attenuation bound follows the scene's config (F fraction bits): 2^-(F+1) is the smallest that is not 0.
TEST(SceneInput, AttenuationRoundsToZeroAtTheConfigsFormat) {
  auto att = [](const std::string& v) {
    return edit("[0, 1, 1, 0]", "[0, 1, 1, 1], \"constant_attenuation\": " + v + ", \"linear_attenuation\": 0");
  };
  EXPECT_NE(error_of(att("1e-9")).find("all round to 0 in the core's 16-bit fraction format"), std::string::npos);
  EXPECT_NE(error_of(att("0.0000076")).find("all round to 0"), std::string::npos);  // < 2^-17
  EXPECT_EQ(error_of(att("0.0000077")), "");                                          // >= 2^-17 rounds to 1 LSB
}

}  // namespace
