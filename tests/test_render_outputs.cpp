// SPDX-License-Identifier: Apache-2.0
// shadecore — `shadecore render`'s outputs are the user's (issue 23, docs/scenes.md §2, docs/cli.md):
// no output may name an input, all-or-nothing even when a device in --out fails, a directory never mixes
// two runs (the manifest), a dangling --out symlink is followed, and the report says where the time went.
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <filesystem>
#include <fstream>
#include <set>
#include <string>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"

namespace {

namespace fs = std::filesystem;
using namespace shadecore::testing;  // tests/cli_run.hpp

const char* kScene = R"({
  "image": {"width": 24, "height": 18},
  "camera": {"eye": [0, 0, 6], "center": [0, 0, 0], "up": [0, 1, 0], "fovy": 40, "near": 1, "far": 20},
  "lights": [{"position": [0, 1, 1, 0], "specular": [1, 1, 1]}],
  "materials": {"m": {"diffuse": [0.8, 0.3, 0.2], "specular": [0.5, 0.5, 0.5], "shininess": 32}},
  "objects": [{"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8}]%SHEET%
})";

std::string scene_text(bool sheet) {
  std::string s = kScene;
  const std::string sheet_text = sheet ? R"(,
  "contact_sheet": {"modes": ["flat", "phong"], "units": ["cs16"], "cell": [16, 16]})"
                                       : "";
  s.replace(s.find("%SHEET%"), 7, sheet_text);
  return s;
}

std::string write(const TempDir& d, const std::string& name, const std::string& text) {
  std::ofstream(d / name) << text;
  return d / name;
}

std::set<std::string> entries(const fs::path& p) {
  std::set<std::string> s;
  for (const auto& e : fs::directory_iterator(p)) s.insert(e.path().filename().string());
  return s;
}

void expect_error(const shadecore::testing::CliRun& r, const std::string& needle) {
  EXPECT_EQ(r.status, 1) << r.out << r.err;
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_NE(r.err.find(needle), std::string::npos) << r.err;
}

// `render victim.json --json victim.json` used to replace the scene with the report.
TEST(RenderOutputs, NoOutputMayNameAnInput) {
  const TempDir d;
  const std::string text = scene_text(false);
  const std::string scene = write(d, "victim.json", text);
  fs::create_symlink(scene, d / "link.json");
  expect_error(run_cli("render " + scene + " --out " + (d / "o") + " --json " + scene), "is the scene file");
  expect_error(run_cli("render " + scene + " --out " + (d / "o") + " --json " + (d / "link.json")), "is the scene file");
  // The scene as one of the files written into --out.
  fs::create_directories(d.path() / "o2");
  const std::string inside = write(d, "o2/cmodel.png", text);
  expect_error(run_cli("render " + inside + " --out " + (d / "o2")), "is the scene file");
  // An OBJ file the scene loads.
  write(d, "tri.obj", "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  std::string with_mesh = text;
  const std::string sphere = R"({"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8})";
  with_mesh.replace(with_mesh.find(sphere), sphere.size(), R"({"type": "mesh", "file": "tri.obj", "material": "m"})");
  const std::string ms = write(d, "mesh.json", with_mesh);
  expect_error(run_cli("render " + ms + " --out " + (d / "o3") + " --json " + (d / "tri.obj")), "is the OBJ file of objects[0]");
  EXPECT_EQ(slurp(scene), text);
  EXPECT_EQ(slurp(inside), text);
  EXPECT_EQ(slurp(d / "tri.obj"), "v 0 0 0\nv 1 0 0\nv 0 1 0\nf 1 2 3\n");
  EXPECT_FALSE(fs::exists(d / "o"));
  EXPECT_FALSE(fs::exists(d / "o3"));
  EXPECT_EQ(entries(d.path() / "o2"), std::set<std::string>{"cmodel.png"});
}

// --out same --json same: refused before the run (it used to fail after it, leaving the images).
TEST(RenderOutputs, JsonNamingTheOutDirectoryIsRefusedUpFront) {
  const TempDir d;
  const std::string scene = write(d, "s.json", scene_text(false));
  expect_error(run_cli("render " + scene + " --out " + (d / "same") + " --json " + (d / "same")), "name the same file");
  EXPECT_FALSE(fs::exists(d / "same"));
  expect_error(run_cli("render " + scene + " --out " + (d / "x/y") + " --json " + (d / "./x")), "name the same file");
  EXPECT_FALSE(fs::exists(d / "x"));
}

// O/exact.png a symlink to /dev/full: the run fails and no regular output has been replaced.
TEST(RenderOutputs, FailingDeviceMemberCommitsNothing) {
  if (::access("/dev/full", W_OK) != 0) GTEST_SKIP() << "no /dev/full";
  const TempDir d;
  const std::string scene = write(d, "s.json", scene_text(false));
  fs::create_directories(d.path() / "O");
  write(d, "O/cmodel.png", "old");
  write(d, "O/diff_exact.png", "old");
  fs::create_symlink("/dev/full", d.path() / "O" / "exact.png");
  const auto r = run_cli("render " + scene + " --out " + (d / "O") + " --json " + (d / "r.json"));
  expect_error(r, "No space left on device");
  EXPECT_EQ(slurp(d / "O/cmodel.png"), "old");
  EXPECT_EQ(slurp(d / "O/diff_exact.png"), "old");
  EXPECT_TRUE(fs::is_symlink(d.path() / "O" / "exact.png"));
  EXPECT_EQ(entries(d.path() / "O"), (std::set<std::string>{"cmodel.png", "diff_exact.png", "exact.png"}));
  EXPECT_FALSE(fs::exists(d / "r.json"));
}

// Re-rendering into a directory removes what the earlier render wrote and this one does not (the
// manifest says which files those are); files shadecore did not write are left alone.
TEST(RenderOutputs, ManifestKeepsOneRunPerDirectory) {
  const TempDir d;
  const std::string with_sheet = write(d, "sheet.json", scene_text(true));
  const std::string plain = write(d, "plain.json", scene_text(false));
  const fs::path out = d.path() / "out";
  fs::create_directories(out);
  write(d, "out/notes.txt", "mine");
  auto r = run_cli("render " + with_sheet + " --out " + out.string() + " --json " + (out / "r.json").string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(entries(out), (std::set<std::string>{".shadecore-render.json", "cmodel.png", "contact_sheet.png",
                                                 "diff_exact.png", "exact.png", "notes.txt", "r.json"}));
  const auto m = nlohmann::json::parse(slurp((out / ".shadecore-render.json").string()));
  EXPECT_EQ(m["written_by"], "shadecore render");
  EXPECT_EQ(m["files"].size(), 5u);  // the four images and r.json
  r = run_cli("render " + plain + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(entries(out),
            (std::set<std::string>{".shadecore-render.json", "cmodel.png", "diff_exact.png", "exact.png", "notes.txt"}));
  EXPECT_EQ(slurp((out / "notes.txt").string()), "mine");
  // A failed run changes nothing, the manifest included.
  const std::string manifest = slurp((out / ".shadecore-render.json").string());
  r = run_cli("render " + with_sheet + " --out " + out.string() + " --size 0x1");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(slurp((out / ".shadecore-render.json").string()), manifest);
  EXPECT_FALSE(fs::exists(out / "contact_sheet.png"));
  // Without a manifest (a directory from elsewhere) a file with one of render's names is pointed out, not removed.
  fs::remove(out / ".shadecore-render.json");
  write(d, "out/contact_sheet.png", "someone's");
  r = run_cli("render " + plain + " --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.err.find("contact_sheet.png is not from this run"), std::string::npos) << r.err;
  EXPECT_EQ(slurp((out / "contact_sheet.png").string()), "someone's");
}

// --out a dangling symlink: followed, its target directory created (the link stays); a failed run
// creates nothing.
TEST(RenderOutputs, DanglingOutSymlinkIsFollowed) {
  const TempDir d;
  const std::string scene = write(d, "s.json", scene_text(false));
  fs::create_symlink(d.path() / "target", d.path() / "link");
  auto r = run_cli("render " + scene + " --out " + (d / "link"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_TRUE(fs::is_symlink(d.path() / "link"));
  EXPECT_TRUE(fs::is_regular_file(d.path() / "target" / "cmodel.png"));
  fs::remove_all(d.path() / "target");
  std::string bad = scene_text(false);
  const std::string sphere = R"({"type": "sphere", "material": "m", "shading": "phong", "slices": 12, "stacks": 8})";
  bad.replace(bad.find(sphere), sphere.size(), R"({"type": "mesh", "file": "missing.obj", "material": "m"})");
  const std::string bs = write(d, "bad.json", bad);
  r = run_cli("render " + bs + " --out " + (d / "link"));
  EXPECT_EQ(r.status, 1) << r.err;
  EXPECT_FALSE(fs::exists(d.path() / "target"));
  EXPECT_TRUE(fs::is_symlink(d.path() / "link"));
}

TEST(RenderOutputs, SayWhatIsWrongWithTheOutput) {
  const TempDir d;
  const std::string scene = write(d, "s.json", scene_text(false));
  expect_error(run_cli("render " + scene + " --out /proc/self"), "kernel file system");
  expect_error(run_cli("render " + scene + " --out /proc/self/newdir"), "kernel file system");
  expect_error(run_cli("render " + scene + " --out " + (d / "o") + " --json ''"), "--json");
  expect_error(run_cli("render " + scene + " --out " + (d / "o") + " --size ''"), "--size");
  expect_error(run_cli("render " + scene + " --out ''"), "--out");
  EXPECT_FALSE(fs::exists(d / "o"));
}

// The phases of the run on stdout and in --json; per-core errors on stdout; JSON pixels and samples.
TEST(RenderOutputs, ReportsPhasesAndPerCoreErrors) {
  const TempDir d;
  const std::string scene = write(d, "s.json", scene_text(true));
  const auto r = run_cli("render " + scene + " --out " + (d / "o") + " --json " + (d / "r.json"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_NE(r.out.find("1 object, 1 light, 1 material"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("time: load "), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("  error over its pixels: vs exact cos^n: max "), std::string::npos) << r.out;
  const auto j = nlohmann::json::parse(slurp(d / "r.json"));
  const auto& ph = j["phases"];
  double sum = 0;
  for (const char* k : {"load_s", "tessellate_s", "rasterise_s", "light_s", "rtl_s", "write_s"}) {
    ASSERT_TRUE(ph[k].is_number()) << k;
    EXPECT_GE(ph[k].get<double>(), 0.0) << k;
    sum += ph[k].get<double>();
  }
  EXPECT_LE(sum, ph["total_s"].get<double>() + 1e-3);
  EXPECT_EQ(ph["total_s"], j["seconds"]);
  const auto& e = j["error_vs_exact"];
  EXPECT_GT(e["pixels"].get<uint64_t>(), 0u);
  EXPECT_EQ(e["samples"].get<uint64_t>(), 3 * e["pixels"].get<uint64_t>());
  ASSERT_TRUE(e["max_at"].is_array());
  EXPECT_LT(e["max_at"][0].get<int>(), 24);  // [x, y]
  EXPECT_LT(e["max_at"][1].get<int>(), 18);
  EXPECT_EQ(j["features"][0]["error_vs_exact"]["pixels"], e["pixels"]);
}

// A material name or a path with control characters never reaches the terminal raw (stdout or stderr).
TEST(RenderOutputs, UserTextIsEscapedOnStdoutAndStderr) {
  const TempDir d;
  std::string text = scene_text(false);
  text.replace(text.find("\"m\": {\"diffuse\""), 4, "\"m\\u001b[2J\":");
  text.replace(text.find("\"material\": \"m\""), 15, "\"material\": \"m\\u001b[2J\"");
  const std::string scene = write(d, "esc.json", text);
  auto r = run_cli("render " + scene + " --out " + (d / "o"));
  ASSERT_EQ(r.status, 0) << r.err;
  EXPECT_EQ(r.out.find('\x1b'), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("m\\x1b[2J"), std::string::npos) << r.out;
  r = run_cli("render " + scene + " --out " + (d / "o") + " --json \"" + (d / "no\x1b[2Jdir/r.json") + "\"");
  EXPECT_EQ(r.status, 1);
  EXPECT_EQ(lines(r.err), 1) << r.err;
  EXPECT_EQ(r.err.find('\x1b'), std::string::npos) << r.err;
  EXPECT_NE(r.err.find("no\\x1b[2Jdir"), std::string::npos) << r.err;
}

// Every step longer than the progress delay (1 s; SHADECORE_PROGRESS_DELAY_MS=0 here) is shown on stderr,
// the contact sheet with its cell count, and its time at the end; stdout stays clean.
TEST(RenderOutputs, ProgressForEveryLongStep) {
  const TempDir d;
  const std::string scene = write(d, "s.json", scene_text(true));
  const auto r = shadecore::testing::run_shell("SHADECORE_PROGRESS_DELAY_MS=0 " + std::string(SHADECORE_CLI) + " render " +
                                               scene + " --out " + (d / "o"));
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* step : {"render: geometry and visibility, image", "render: C model and references, image",
                           "render: contact sheet, 2 cells of 16x16", "render: writing the images"})
    EXPECT_NE(r.err.find(step), std::string::npos) << step << "\n" << r.err;
  EXPECT_NE(r.err.find("render: contact sheet, 2 cells of 16x16: "), std::string::npos) << r.err;  // its time
  EXPECT_EQ(r.out.find("render: "), std::string::npos) << r.out;
}

}  // namespace
