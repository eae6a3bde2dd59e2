// shadecore — `shadecore render` from the command line: bad scenes are one line on stderr, exit status 1
// and no output at all; a good scene writes its images and a JSON report with the documented fields.
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>
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
  const std::string mesh_obj = R"({"type": "mesh", "file": "%F", "material": "m"})";
  auto with_mesh = [&](const std::string& file) {
    std::string o = mesh_obj;
    o.replace(o.find("%F"), 2, file);
    return edit(R"({"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8})", o);
  };
  const std::vector<Bad> cases = {
      {"malformed JSON", edit("\"fovy\": 40,", "\"fovy\": 40,,"), ":3:"},
      {"malformed JSON line/column", std::string(kGood).substr(0, 120), "malformed JSON"},
      {"unknown top-level key", edit("\"image\"", "\"imagez\": 1, \"image\""), "imagez: unknown key"},
      {"unknown light key", edit("\"specular\": [1, 1, 1]}", "\"specular\": [1, 1, 1], \"spot_cutoff\": 30}"),
       "lights[0].spot_cutoff: unknown key"},
      {"unknown object key", edit("\"slices\": 12", "\"slices\": 12, \"colour\": 1"), "objects[0].colour: unknown key"},
      {"duplicate key", edit("\"fovy\": 40,", "\"fovy\": 40, \"fovy\": 50,"), "camera.fovy: duplicate key"},
      {"wrong type", edit("\"width\": 40", "\"width\": \"40\""), "image.width: must be an integer"},
      {"zero-size image", edit("\"width\": 40", "\"width\": 0"), "image.width: 0 out of range"},
      {"shininess below 16", edit("\"shininess\": 32", "\"shininess\": 8"), "materials.m.shininess: 8 out of range 16..1024"},
      {"shininess above 1024", edit("\"shininess\": 32", "\"shininess\": 2000"), "out of range 16..1024"},
      {"negative colour", edit("\"diffuse\": [0.8, 0.3, 0.2]", "\"diffuse\": [0.8, -0.3, 0.2]"),
       "materials.m.diffuse[1]: -0.3 out of range"},
      {"negative attenuation", edit("[0, 1, 1, 0], \"specular\"", "[0, 1, 1, 1], \"linear_attenuation\": -1, \"specular\""),
       "lights[0].linear_attenuation: -1 out of range"},
      {"all attenuation zero", edit("[0, 1, 1, 0], \"specular\"", "[0, 1, 1, 1], \"constant_attenuation\": 0, \"specular\""),
       "all 0"},
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
  EXPECT_NE(r.out.find("feature set: 1 light (directional)"), std::string::npos) << r.out;
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

}  // namespace
