// SPDX-License-Identifier: Apache-2.0
// shadecore gl-compare — shadecore's exact reference image against a GL implementation's fixed-function
// lighting (Mesa's OSMesa, llvmpipe) on the same scene (docs/gl_compare.md).
//
//   shadecore gl-compare SCENE [--json FILE] [--out-dir DIR] [--size WxH] [--mode flat|gouraud|phong]
//                              [--tolerance LSB] [--all-objects]
//
// The exact image is `shadecore render`'s exact.png: the scene's fragments through LightCore::eval_double with
// exact cos^n, resolved by the project's rasteriser. The GL image is the same scene, parsed and tessellated by the
// same code, drawn by OSMesa (shadecore/render/glref.hpp). Per covered pixel the difference is the max over R, G, B
// of |exact 8-bit − GL 8-bit|; the verdict (PASS: exit 0, FAIL: exit 2 with every output written) is
// p99 <= --tolerance (2) over the pixels of comparable objects, none covered by one image only, none shown by
// different objects, and at least one comparable pixel. Objects GL cannot show (Phong shading, R·V reflection,
// shininess > 128, energy normalisation, flat shading of position-dependent lighting under the scene's flat_rule
// centroid; flat_rule provoking_vertex is GL_FLAT's rule and compares) are reported and left out
// of the verdict unless --all-objects. Into DIR (all outputs staged and committed together, docs/cli.md):
//   mesa.png    GL's image;   exact.png   shadecore's exact image;
//   diff.png    amplified difference (glref::Comparison::diff_rgb: grey <= tolerance, red exact brighter, blue GL
//               brighter, yellow coverage mismatch, magenta object mismatch, dimmed = not comparable).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <regex>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "dir_with_json.hpp"
#include "output.hpp"
#include "shadecore/common/args.hpp"
#include "shadecore/common/legend.hpp"
#include "shadecore/common/png.hpp"
#include "shadecore/render/glref.hpp"
#include "shadecore/render/render.hpp"
#include "shadecore/render/scene.hpp"

namespace shadecore::cli {
namespace {

namespace fsys = std::filesystem;
using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

struct GlCompareArgs {
  std::string scene, json_path, out_dir, size, mode;
  int tolerance = 2;
  bool all_objects = false;
};

const std::vector<std::string> kNames = {"mesa.png", "exact.png", "diff.png"};

std::pair<int, int> parse_size(const std::string& s) {
  static const std::regex re(R"(^\s*(\d{1,5})\s*[xX]\s*(\d{1,5})\s*$)");
  std::smatch m;
  if (!std::regex_match(s, m, re)) throw std::invalid_argument("--size: malformed '" + s + "' (expected WxH, e.g. 64x64)");
  const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
  if (w < 1 || h < 1 || w > 4096 || h > 4096) throw std::invalid_argument("--size: " + s + " out of range 1..4096");
  return {w, h};
}

json stats_json(const glref::DiffStats& s) {
  json j;
  j["pixels"] = s.pixels;
  j["p50_lsb"] = s.p50;
  j["p99_lsb"] = s.p99;
  j["max_lsb"] = s.max;
  j["mean_lsb"] = s.mean;
  j["above_tolerance"] = s.above;
  if (s.max_x >= 0) j["max_at"] = {s.max_x, s.max_y};  // [x, y]: column from the left, row from the top
  return j;
}

std::string stats_text(const glref::DiffStats& s) {
  if (s.pixels == 0) return "no pixels";
  return fmt::format("{} px, p50 {} / p99 {} / max {} LSB", s.pixels, s.p50, s.p99, s.max);
}

void run_gl_compare(const GlCompareArgs& a, bool json_given, bool size_given, bool mode_given) {
  const auto t0 = Clock::now();
  scene::Scene sc;
  try {
    sc = scene::load_scene(a.scene);
  } catch (const scene::SceneError& e) {
    throw std::runtime_error(e.what());
  }
  render::Settings st;
  if (size_given) std::tie(st.width, st.height) = parse_size(a.size);
  if (mode_given) st.mode = scene::parse_shading(a.mode);

  // Outputs: checked now, written together at the end (io::OutputSet). --json may lie inside --out-dir.
  io::OutputSet outs;
  const DirWithJson plan = plan_dir_with_json(outs, "--out-dir", a.out_dir, kNames, json_given, a.json_path);
  const int dir_out = plan.dir, json_out = plan.json;
  const std::string& json_member = plan.json_member;
  outs.check_input(a.scene, "the scene file");
  for (const auto& o : sc.objects)
    if (o.type == scene::ObjectType::Mesh) outs.check_input(o.file_path, "the OBJ file of " + o.where);

  // shadecore's exact image (as `shadecore render`'s exact.png).
  render::MeshSource meshes(sc);
  render::Frame fr;
  try {
    fr = render::prepare(sc, meshes, st);
  } catch (const scene::SceneError& e) {
    throw std::runtime_error(e.what());
  }
  std::vector<std::vector<render::RefColour>> ex;
  for (const auto& g : fr.groups) ex.push_back(render::run_reference(g, LightCore::SpecRef::Exact));
  const render::RefImage exact = render::resolve_reference(fr, ex);
  const std::vector<uint8_t> exact_rgb = render::to_rgb8(exact);
  const std::vector<int32_t> exact_obj = glref::object_map(fr);
  const auto checks = glref::check_objects(sc, fr.object_shading);
  const double t_exact = std::chrono::duration<double>(Clock::now() - t0).count();

  // GL's image.
  const auto t1 = Clock::now();
  glref::GlSettings gs;
  gs.width = fr.width, gs.height = fr.height, gs.mode = st.mode;
  const glref::GlImage gl = glref::render_gl(sc, meshes, gs);
  const double t_gl = std::chrono::duration<double>(Clock::now() - t1).count();
  if (gl.renderer.rfind("llvmpipe", 0) != 0)
    fmt::print(stderr, "gl-compare: note: the GL image is {}'s, not llvmpipe's (GALLIUM_DRIVER); the measured reference is llvmpipe\n",
               gl.renderer);

  glref::Comparison cmp = glref::compare(fr.width, fr.height, exact_rgb, exact_obj, gl, checks, a.tolerance, a.all_objects);
  glref::explain_mismatches(sc, meshes, gl, cmp);

  fmt::print("scene {}: {}x{}, {} objects; GL: {} ({})\n", scene::printable(a.scene, 0), fr.width, fr.height,
             sc.objects.size(), gl.renderer, gl.version);
  json objs = json::array();
  for (size_t oi = 0; oi < sc.objects.size(); ++oi) {
    const auto& o = sc.objects[oi];
    const auto& c = checks[oi];
    const auto& s = cmp.per_object[oi];
    std::string why;
    for (const auto& r : c.reasons) why += (why.empty() ? "" : "; ") + r;
    fmt::print("  {:<16} {:<8} {}: {}{}\n", scene::printable(o.name, 16), scene::to_string(fr.object_shading[oi]),
               c.comparable ? "comparable" : "NOT comparable", stats_text(s), why.empty() ? "" : " — " + why);
    objs.push_back({{"name", o.name},
                    {"shading", scene::to_string(fr.object_shading[oi])},
                    {"material", sc.materials[static_cast<size_t>(o.material)].name},
                    {"comparable", c.comparable},
                    {"reasons", c.reasons},
                    {"notes", c.notes},
                    {"stats", stats_json(s)}});
  }
  fmt::print("coverage: exact {} px, GL {} px, both {} px; covered by one only: {}; shown by different objects: {}\n",
             cmp.covered_exact, cmp.covered_gl, cmp.covered_both, cmp.coverage_mismatch, cmp.object_mismatch);
  if (!cmp.mismatches.empty())
    fmt::print("mismatches within {:.4f} px of a triangle edge (sub-pixel vertex snapping, float vs double): {} of {}{}\n",
               glref::Comparison::kSnapPx, cmp.mismatch_near_edge, cmp.coverage_mismatch + cmp.object_mismatch,
               cmp.mismatches_explained ? " (all)" : "");
  for (size_t i = 0; i < cmp.mismatches.size() && i < 8; ++i) {
    const auto& m = cmp.mismatches[i];
    fmt::print("  at ({}, {}): exact shows {}, GL {}; nearest edge {}\n", m.x, m.y, m.exact_object, m.gl_object,
               m.edge_px < 0 ? std::string("none near") : fmt::format("{:.6f} px", m.edge_px));
  }
  fmt::print("comparable pixels: {}; all pixels of one object in both: {}\n", stats_text(cmp.comparable), stats_text(cmp.all));
  const std::string verdict = fmt::format("{}: p99 {} LSB (tolerance {}), max {} LSB over {} comparable pixels; coverage mismatch {}, object mismatch {}",
                                          cmp.pass ? "PASS" : "FAIL", cmp.comparable.p99, a.tolerance, cmp.comparable.max,
                                          cmp.comparable.pixels, cmp.coverage_mismatch, cmp.object_mismatch);

  std::vector<std::pair<std::string, std::string>> files;
  if (dir_out >= 0) {
    files.emplace_back("mesa.png", canvas::encode_png(gl.width, gl.height, gl.rgb));
    files.emplace_back("exact.png", canvas::encode_png(fr.width, fr.height, exact_rgb));
    // The amplified difference with its key below (glref.hpp, Comparison::diff_rgb; the image at the top left).
    const std::string tol = std::to_string(a.tolerance);
    const canvas::Canvas d = canvas::with_key_legend(
        fr.width, fr.height, cmp.diff_rgb,
        {{{0, 0, 0}, "equal (or background)"},
         {{120, 120, 120}, "1.." + tol + " LSB (grey, 60 per LSB)"},
         {{208, 0, 0}, "exact brighter than GL by more than " + tol + " LSB"},
         {{0, 0, 208}, "GL brighter than exact by more than " + tol + " LSB"},
         {{255, 255, 0}, "covered in one image only"},
         {{255, 0, 255}, "a different object in each"},
         {{60, 50, 40}, "not comparable: the exact image at 1/4"}},
        "exact vs Mesa GL, 8-bit LSB, largest channel");
    files.emplace_back("diff.png", canvas::encode_png(d.width, d.height, d.rgb));
  }
  if (json_given) {
    json j;
    j["scene"] = a.scene;
    j["command"] = command_line();
    j["date"] = utc_now();
    j["width"] = fr.width;
    j["height"] = fr.height;
    j["mode"] = mode_given ? json(a.mode) : json(nullptr);
    json g;
    g["gl_renderer"] = gl.renderer;
    g["gl_version"] = gl.version;
    g["tolerance_lsb"] = a.tolerance;
    g["all_objects"] = a.all_objects;
    g["p50_lsb"] = cmp.comparable.p50;
    g["p99_lsb"] = cmp.comparable.p99;
    g["max_lsb"] = cmp.comparable.max;
    g["mean_lsb"] = cmp.comparable.mean;
    g["comparable_pixels"] = cmp.comparable.pixels;
    g["covered_pixels"] = cmp.covered_both;
    g["covered_exact"] = cmp.covered_exact;
    g["covered_gl"] = cmp.covered_gl;
    g["coverage_mismatch"] = cmp.coverage_mismatch;
    g["object_mismatch"] = cmp.object_mismatch;
    json mm = json::array();
    for (const auto& m : cmp.mismatches)
      mm.push_back({{"at", {m.x, m.y}}, {"exact_object", m.exact_object}, {"gl_object", m.gl_object},
                    {"edge_px", m.edge_px < 0 ? json(nullptr) : json(m.edge_px)}});
    g["mismatches"] = mm;  // [x, y] from the top left; object index (−1 background); distance to the nearest edge
    g["mismatch_near_edge"] = cmp.mismatch_near_edge;
    g["mismatches_explained_by_snapping"] = cmp.mismatches_explained;
    g["pass_within_snapping"] = cmp.comparable.pixels > 0 && cmp.comparable.p99 <= a.tolerance && cmp.mismatches_explained;
    g["pass"] = cmp.pass;
    g["comparable"] = stats_json(cmp.comparable);
    g["all"] = stats_json(cmp.all);
    g["objects"] = objs;
    g["seconds"] = {{"exact", t_exact}, {"gl", t_gl}};
    j["gl_compare"] = g;
    if (json_out >= 0) outs.set(json_out, j.dump(2) + "\n");
    else files.emplace_back(json_member, j.dump(2) + "\n");
  }
  if (dir_out >= 0) {
    const std::string stage = outs.stage(dir_out);
    for (const auto& [name, content] : files) write_staged(stage + "/" + name, content);
  }
  outs.commit();
  std::fflush(stdout);  // the report before the one-line verdict on stderr
  if (!cmp.pass) throw CheckFailed("gl-compare " + verdict);
  fmt::print("gl-compare {}\n", verdict);
}

}  // namespace

void add_gl_compare(CLI::App& app) {
  auto args = std::make_shared<GlCompareArgs>();
  auto* sub = app.add_subcommand("gl-compare",
                                 "compare the scene's exact reference image with Mesa's fixed-function OpenGL "
                                 "(OSMesa, llvmpipe): p99 of the per-pixel 8-bit difference and coverage (docs/gl_compare.md)");
  sub->add_option("scene", args->scene, "scene file (JSON, docs/scenes.md)")->required()->check(cliargs::NonEmpty("scene path"));
  auto* json_opt = sub->add_option("--json", args->json_path, "write a JSON report (atomically)")->check(cliargs::NonEmpty("path"));
  sub->add_option("--out-dir", args->out_dir, "write mesa.png, exact.png and diff.png here (created if needed)")
      ->check(cliargs::NonEmpty("path"));
  auto* size_opt = sub->add_option("--size", args->size, "render at WxH instead of the scene's image size (e.g. 64x64)")
                       ->check(cliargs::NonEmpty("size (expected WxH, e.g. 64x64)"));
  auto* mode_opt = sub->add_option("--mode", args->mode, "every object in this shading mode in both images")
                       ->check(CLI::IsMember({"flat", "gouraud", "phong"}));
  sub->add_option("--tolerance", args->tolerance, "LSBs of 8 bits allowed at the 99th percentile (default 2)")
      ->check(CLI::Range(0, 255));
  sub->add_flag("--all-objects", args->all_objects, "count every object towards the verdict, comparable or not");
  sub->callback([args, json_opt, size_opt, mode_opt] {
    run_gl_compare(*args, json_opt->count() > 0, size_opt->count() > 0, mode_opt->count() > 0);
  });
}

}  // namespace shadecore::cli
