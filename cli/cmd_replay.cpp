// SPDX-License-Identifier: Apache-2.0
// shadecore replay — a real GL program's frame through the lighting core: an apitrace capture read by
// shadecore_trace, its calls executed by the GL 1.x front end (shadecore_glfront) and the frame drawn by the same
// back end as `shadecore render` (render::prepare, the C model, the exact reference, the RTL), compared with Mesa's
// image of the same frame (docs/replay.md).
//
//   shadecore replay TRACE (--frame K | --call N) [--rtl] [--full-core] [--out DIR] [--json FILE]
//                          [--mesa | --reference PNG] [--tolerance LSB]
//
// Into DIR (staged and committed together, docs/cli.md): cmodel.png (C model), exact.png (LightCore::eval_double
// with exact cos^n), rtl.png (--rtl: bit-identical to cmodel.png, or the run fails), mesa.png and diff.png (--mesa:
// glretrace's snapshot of the frame under xvfb-run; --reference PNG: the given image, and diff.png), pair.png (exact
// and the reference side by side, the footer naming the command, the machine and the date).
// The comparison is gl-compare's (glref::compare) over the exact image: Mesa's snapshot has no object ids, so a
// pixel of it is covered where it differs from the frame's clear colour (8-bit), and shows the object the exact
// image shows there; the objects drawn with a capability the core lacks (texturing, blending, fog, …) are not
// comparable. PASS (exit 0): p99 <= --tolerance and max <= 2·tolerance LSB over the compared pixels with no coverage
// difference; else exit 2 with every output written.
#include <png.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <map>
#include <string>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "dir_with_json.hpp"
#include "handoff_bundle.hpp"
#include "light_rtl.hpp"
#include "output.hpp"
#include "render_rtl.hpp"
#include "shadecore/common/args.hpp"
#include "shadecore/common/legend.hpp"
#include "shadecore/common/png.hpp"
#include "shadecore/common/subprocess.hpp"
#include "shadecore/glfront/frontend.hpp"
#include "shadecore/glfront/trace.hpp"
#include "shadecore/render/glref.hpp"
#include "shadecore/render/render.hpp"

namespace shadecore::cli {
namespace {

namespace fsys = std::filesystem;
using json = nlohmann::ordered_json;
using Clock = std::chrono::steady_clock;

struct ReplayArgs {
  std::string trace, out_dir, json_path, reference;
  uint64_t frame = 0, call = 0;
  bool rtl = false, full_core = false, mesa = false;
  int tolerance = 2;
};

struct Png {
  int width = 0, height = 0;
  std::vector<uint8_t> rgb;
};

Png read_png(const std::string& path, const std::string& what) {
  png_image im{};
  im.version = PNG_IMAGE_VERSION;
  if (!png_image_begin_read_from_file(&im, path.c_str()))
    throw std::runtime_error(what + " " + path + ": not a readable PNG (" + im.message + ")");
  im.format = PNG_FORMAT_RGB;
  Png p;
  p.width = static_cast<int>(im.width), p.height = static_cast<int>(im.height);
  p.rgb.resize(PNG_IMAGE_SIZE(im));
  if (!png_image_finish_read(&im, nullptr, p.rgb.data(), 0, nullptr)) {
    const std::string m = im.message;
    png_image_free(&im);
    throw std::runtime_error(what + " " + path + ": " + m);
  }
  return p;
}

// glretrace (eglretrace for EGL captures) under xvfb-run: the snapshot after call N.
Png mesa_snapshot(const std::string& trace, const std::string& api, uint64_t call, int w, int h) {
  const char* tools[] = {"xvfb-run", api == "egl" ? "eglretrace" : "glretrace"};
  for (const char* t : tools)
    if (proc::run({"sh", "-c", std::string("command -v ") + t}).status != 0)
      throw std::runtime_error(std::string("--mesa needs ") + t +
                               " (Debian packages apitrace and xvfb; scripts/setup.sh installs them)");
  const fsys::path dir = fsys::temp_directory_path() / fmt::format("shadecore-replay-{}", ::getpid());
  fsys::remove_all(dir);
  fsys::create_directories(dir);
  proc::Options o;
  o.env = {{"LIBGL_ALWAYS_SOFTWARE", "1"}};
  const std::string screen = fmt::format("-screen 0 {}x{}x24", std::max(w, 640), std::max(h, 480));
  const proc::Result r = proc::run({"xvfb-run", "-a", "-s", screen, tools[1], "-S", std::to_string(call), "-s",
                                    dir.string() + "/", trace},
                                   o);
  const fsys::path png = dir / fmt::format("{:010d}.png", call);
  if (!fsys::exists(png)) {
    std::string err = r.err.empty() ? r.out : r.err;
    std::replace(err.begin(), err.end(), '\n', ' ');
    if (err.size() > 200) err = err.substr(0, 200) + "…";
    fsys::remove_all(dir);
    throw std::runtime_error(fmt::format("{} wrote no snapshot of call {} (exit {}): {}", tools[1], call, r.status, err));
  }
  Png p = read_png(png.string(), std::string(tools[1]) + "'s snapshot");
  fsys::remove_all(dir);
  return p;
}

// "AMD EPYC 7B13, 2 cores" from /proc/cpuinfo (the figures' footers name the machine).
std::string machine() {
  std::ifstream in("/proc/cpuinfo");
  std::string line, model;
  int cpus = 0;
  while (std::getline(in, line)) {
    if (line.rfind("model name", 0) == 0 && model.empty()) model = line.substr(line.find(':') + 2);
    if (line.rfind("processor", 0) == 0) ++cpus;
  }
  return (model.empty() ? std::string("unknown CPU") : model) + ", " + std::to_string(cpus) + " cores";
}

// exact.png and the reference side by side with their names and a footer naming the command, machine and date.
canvas::Canvas pair_figure(int w, int h, const std::vector<uint8_t>& exact, const std::vector<uint8_t>& ref,
                           const std::string& ref_name, const std::string& verdict) {
  const int gap = 8, pad = 4, line = canvas::Canvas::kTextRows + 3;
  const int W = 2 * w + gap;
  std::vector<std::string> foot;
  for (const std::string& t : {"shadecore replay: exact cos^n through the core's GL front end (left) and " + ref_name +
                                   " (right); " + verdict,
                               command_line(), machine() + ", " + utc_now()})
    for (const auto& l : canvas::wrap_text(t, W - 2 * pad, 1)) foot.push_back(l);
  canvas::Canvas cv(W, line + h + pad + static_cast<int>(foot.size()) * line + pad, 24);
  cv.text(pad, 2, "exact (shadecore)", 230, 230, 230);
  cv.text(w + gap + pad, 2, ref_name, 230, 230, 230);
  cv.blit(0, line, w, h, exact);
  cv.blit(w + gap, line, w, h, ref);
  for (size_t i = 0; i < foot.size(); ++i)
    cv.text(pad, line + h + pad + static_cast<int>(i) * line, foot[i], 200, 200, 200);
  return cv;
}

// ---- the measured clock (docs/timing.json) --------------------------------------------------------------------

// How two feature sets differ, one short item per capability (empty: the same core).
std::vector<std::string> fs_differences(const FeatureSet& a, const FeatureSet& b) {
  std::vector<std::string> d;
  if (a.slots.size() != b.slots.size())
    d.push_back(fmt::format("{} light slots vs {}", a.slots.size(), b.slots.size()));
  for (size_t j = 0; j < std::min(a.slots.size(), b.slots.size()); ++j)
    if (a.slots[j] != b.slots[j])
      d.push_back(fmt::format("slot {} {} vs {}", j, kinds_name(a.slots[j]), kinds_name(b.slots[j])));
  auto flag = [&d](bool x, bool y, const char* what) {
    if (x != y) d.push_back(std::string(x ? "with " : "without ") + what);
  };
  flag(a.ambient, b.ambient, "ambient");
  flag(a.diffuse, b.diffuse, "diffuse");
  flag(a.specular, b.specular, "specular");
  if (a.specular && b.specular && a.units() != b.units()) {
    auto names = [](const FeatureSet& f) {
      std::string u;
      for (auto v : f.units()) u += (u.empty() ? "" : "|") + std::string(variant_name(v));
      return u;
    };
    d.push_back("units " + names(a) + " vs " + names(b));
  }
  if (a.specular && b.specular && a.cutoff != b.cutoff) d.push_back("another cut-off");
  flag(a.norm, b.norm, "energy normalisation");
  flag(a.blinn, b.blinn, "Blinn");
  flag(a.phong, b.phong, "Phong");
  flag(a.local_viewer, b.local_viewer, "local viewer");
  flag(a.normalize, b.normalize, "normalize");
  flag(a.low_shininess, b.low_shininess, "low shininess");
  flag(a.two_side, b.two_side, "two-sided");
  flag(a.separate_specular, b.separate_specular, "separate specular");
  flag(a.colour_material, b.colour_material, "colour material");
  if (a.channels != b.channels) d.push_back(a.channels == 1 ? "mono vs RGB" : "RGB vs mono");
  if (a.lanes != b.lanes) d.push_back(fmt::format("{} lanes vs {}", a.lanes, b.lanes));
  if (a.share != b.share) d.push_back(fmt::format("share {} vs {}", a.share, b.share));
  if (a.config != b.config) d.push_back("config " + a.config + " vs " + b.config);
  if (a.spec_guard != b.spec_guard) d.push_back("another spec_guard");
  return d;
}

// The lighting sets docs/timing.json measured (rows of kind "lighting" with a closing period), read at run time;
// empty with `why` set when the file is absent or unreadable (never an error: the report says "no measured clock").
struct MeasuredSet {
  std::string name;
  FeatureSet fs;
  double period_ns = 0, fmax_mhz = 0;
  bool met = false;
};
std::vector<MeasuredSet> measured_sets(std::string& path, std::string& why) {
  path = (fsys::path(handoff::root_dir()) / "docs" / "timing.json").string();
  std::vector<MeasuredSet> out;
  std::string text, fail;
  if (!scene::read_regular_file(path, std::uint64_t{16} << 20, text, fail)) {  // never blocks (a FIFO is refused)
    why = "no measured clock (" + path + ": " + fail + ")";
    return out;
  }
  try {
    const json t = json::parse(text);
    for (const auto& r : t.at("rows")) {
      if (r.value("kind", "") != "lighting" || !r.contains("period_ns") || !r["period_ns"].is_number()) continue;
      MeasuredSet m;
      m.name = r.at("name").get<std::string>();
      m.period_ns = r["period_ns"].get<double>();
      m.fmax_mhz = r.value("fmax_mhz", 0.0);
      m.met = r.value("met", false);
      try {
        m.fs = feature_set_named_or_file(m.name);
      } catch (const std::exception&) {
        continue;  // a row naming no feature set of config/configs.json
      }
      if (m.period_ns > 0) out.push_back(std::move(m));
    }
  } catch (const std::exception& e) {
    why = std::string("no measured clock (") + path + " unreadable: " + scene::printable(e.what(), 80) + ")";
    return {};
  }
  if (out.empty()) why = "no measured clock (" + path + " has no measured lighting set)";
  return out;
}

json stats_json(const glref::DiffStats& s) {
  json j;
  j["pixels"] = s.pixels;
  j["p50_lsb"] = s.p50;
  j["p99_lsb"] = s.p99;
  j["max_lsb"] = s.max;
  j["mean_lsb"] = s.mean;
  j["above_tolerance"] = s.above;  // pixels above the p99 tolerance
  if (s.max_x >= 0) j["max_at"] = {s.max_x, s.max_y};
  return j;
}

void run_replay(const ReplayArgs& a, bool frame_given, bool call_given, bool json_given, bool ref_given) {
  const auto t0 = Clock::now();
  if (frame_given == call_given) throw std::invalid_argument("give one of --frame K and --call N");
  if (a.mesa && ref_given) throw std::invalid_argument("--mesa and --reference exclude each other");

  // Outputs: checked now, written together at the end. --json may lie inside --out.
  io::OutputSet outs;
  std::vector<std::string> names = {"cmodel.png", "exact.png"};
  if (a.rtl) names.push_back("rtl.png");
  if (a.mesa || ref_given) names.insert(names.end(), {"mesa.png", "diff.png", "pair.png"});
  const DirWithJson plan = plan_dir_with_json(outs, "--out", a.out_dir, names, json_given, a.json_path);
  const int dir_out = plan.dir, json_out = plan.json;
  const std::string& json_member = plan.json_member;
  outs.check_input(a.trace, "the capture");
  if (ref_given) outs.check_input(a.reference, "the reference image");

  // The front end: the capture up to the frame, GL's state, the frame's triangles.
  glfront::Handover h;
  uint64_t chunks = 0;
  unsigned version = 0;
  try {
    trace::Reader reader(a.trace);
    chunks = reader.chunks();
    version = reader.version();
    glfront::ReplayOptions ro;
    if (frame_given) ro.frame = a.frame;
    else ro.call = a.call;
    h = glfront::replay_frame(reader, ro, a.trace);
  } catch (const trace::TraceError& e) {  // names from the capture may hold any bytes: escaped, one line
    throw std::runtime_error(scene::printable(e.what(), 0));
  } catch (const glfront::ReplayError& e) {
    throw std::runtime_error(scene::printable(e.what(), 0));
  }
  const double t_front = std::chrono::duration<double>(Clock::now() - t0).count();

  // The back end: render's.
  h.settings.full_core = a.full_core;
  render::Frame fr;
  try {
    fr = render::prepare(h.scene, h.meshes, h.settings);
  } catch (const scene::SceneError& e) {
    throw std::runtime_error(e.what());
  }
  std::vector<std::vector<Colour>> cm;
  std::vector<std::vector<render::RefColour>> ex;
  uint64_t writes = 0, vertex_frags = 0, face_frags = 0, pixel_frags = 0, state_changes = 0, state_writes = 0;
  json cores = json::array();
  for (const auto& g : fr.groups) {
    cm.push_back(render::run_cmodel(g));
    ex.push_back(render::run_reference(g, LightCore::SpecRef::Exact));
    writes += g.writes, vertex_frags += g.vertices, face_frags += g.faces, pixel_frags += g.pixels;
    state_changes += g.state_changes, state_writes += g.state_writes;
    cores.push_back({{"key", g.fs.key()}, {"summary", g.fs.summary()}, {"register_writes", g.writes},
                     {"lighting_state_changes", g.state_changes}, {"state_change_register_writes", g.state_writes},
                     {"fragments", g.dests.size()}});
  }
  const render::Image img = render::resolve(fr, cm);
  const render::RefImage exact = render::resolve_reference(fr, ex);
  const std::vector<uint8_t> exact_rgb = render::to_rgb8(exact);
  const auto err_exact = render::error_vs(img, exact);

  const auto& st = h.stats;
  fmt::print("capture {}: trace version {}, {} chunks; {} calls read, frame {} = calls {}..{} ({} calls, {} executed with display lists)\n",
             scene::printable(a.trace, 0), version, chunks, st.calls_read, h.frame, h.first_call, h.snapshot_call,
             st.calls_in_frame, st.calls_executed);
  fmt::print("front end: {} primitives, {} vertices, {} triangles ({} culled); {} objects, {} materials, {} lights{}; {}x{}\n",
             st.primitives, st.vertices, st.triangles, st.culled, h.scene.objects.size(), h.scene.materials.size(),
             h.scene.lights.size(), h.scene.lighting_sets.empty() ? "" : " in the first lighting state", fr.width,
             fr.height);
  std::string unsup;
  for (const auto& [n, k] : st.unsupported)
    unsup += fmt::format("{}{} ×{}", unsup.empty() ? "" : ", ", scene::printable(n, 0), k);
  fmt::print("unsupported calls: {}\n", unsup.empty() ? "none" : unsup);
  for (const auto& [n, k] : st.notes) fmt::print("note: {} (×{})\n", scene::printable(n, 0), k);
  if (h.non_unit_normals)
    fmt::print("note: {} vertices have normals of length ≠ 1 that GL uses as they are (no GL_NORMALIZE); the core "
               "normalises them (worst length {:.6f})\n", h.non_unit_normals, h.worst_normal_length);
  if (h.eye_scale != 1)
    fmt::print("note: {} triangle vertices outside the core's eye-space range [-128, 128) (worst |coordinate| {:.6g}): "
               "the frame's eye space scaled by {} (clip coordinates unchanged, attenuation scaled to match)\n",
               h.eye_out_of_range, h.eye_worst, h.eye_scale);
  const size_t n_states = h.scene.lighting_states().size();
  if (n_states > 1)
    fmt::print("lighting: {} states in drawing order; the core reprogrammed {} times between batches ({} register writes)\n",
               n_states, state_changes, state_writes);
  for (const auto& g : fr.groups)
    fmt::print("core {}: {} register writes, {} vertex fragments  [key {}]\n", g.fs.summary(), g.writes, g.vertices, g.fs.key());
  fmt::print("C model vs exact cos^n: max {:.2f} LSB over {} px\n", err_exact.max_lsb, err_exact.pixels);

  // RTL.
  json rtl_json = nullptr;
  bool rtl_ok = true;
  render::Image rimg;
  if (a.rtl) {
    RtlTotals tot;
    const auto cols = run_rtl(fr, tot);
    rimg = render::resolve(fr, cols);
    const uint64_t bad = render::mismatching_pixels(img, rimg);
    rtl_ok = bad == 0 && tot.ok && tot.core_mismatches == 0;
    // The state changes' share: each core's register writes through the same core followed by its first fragment
    // alone (the simulator needs one): the writes, the drains before them and one trip through the pipeline; the
    // rest of the frame's cycles are the other vertices' lighting and the drains between material batches.
    uint64_t write_cycles = 0;
    for (const auto& g : fr.groups) {
      std::vector<sim::CoreCommand> ws;
      const render::CoreCmd* first_frag = nullptr;
      for (const auto& c : g.cmds) {
        if (!c.is_write) {
          if (!first_frag) first_frag = &c;
          continue;
        }
        sim::CoreCommand k;
        k.is_write = true;
        k.w = c.w;
        ws.push_back(k);
      }
      if (!first_frag) continue;
      sim::CoreCommand f;
      f.f = first_frag->f;
      ws.push_back(f);
      RtlRunOptions o;
      o.quiet = true;
      write_cycles += run_core_rtl(g.fs, ws, o).cycles;
    }
    // What the changes between batches cost (material and lighting-state writes after the first fragment, and the
    // drains before them): the frame's cycles less those of the same stream without them (the first programming,
    // then every fragment).
    uint64_t no_between_cycles = 0;
    for (const auto& g : fr.groups) {
      std::vector<sim::CoreCommand> ks;
      bool frag_seen = false;
      for (const auto& c : g.cmds) {
        if (c.is_write && frag_seen) continue;
        frag_seen = frag_seen || !c.is_write;
        sim::CoreCommand k;
        k.is_write = c.is_write;
        k.w = c.w;
        k.f = c.f;
        ks.push_back(k);
      }
      RtlRunOptions o;
      o.quiet = true;
      no_between_cycles += run_core_rtl(g.fs, ks, o).cycles;
    }
    const uint64_t between_cycles = tot.cycles >= no_between_cycles ? tot.cycles - no_between_cycles : 0;
    fmt::print("RTL: {} cycles (the register writes and one vertex alone: {}; the writes between batches and their "
               "drains: {}), {:.2f} s simulated; {} mismatching pixels vs the C model\n",
               tot.cycles, write_cycles, between_cycles, tot.sim_seconds, bad);
    rtl_json = {{"mismatching_pixels", bad}, {"cycles", tot.cycles}, {"register_writes_and_one_vertex_cycles", write_cycles},
                {"between_batches_cycles", between_cycles},
                {"lighting_cycles", tot.cycles >= write_cycles ? tot.cycles - write_cycles : 0},
                {"sim_seconds", tot.sim_seconds}, {"core_mismatches", tot.core_mismatches}, {"ok", rtl_ok},
                {"cores", tot.cores}};
  }

  // The frame's time at the measured clock: per core the lighting set of docs/timing.json it is (or the nearest one:
  // the same specular unit (or none) first — the unit is the longest path —, then the fewest differing capabilities,
  // then the longer period), its closing period × the core's cycles (--rtl).
  json clock_json;
  {
    std::string path, why;
    const std::vector<MeasuredSet> ms = measured_sets(path, why);
    if (ms.empty()) {
      clock_json = {{"measured", false}, {"why", why}};
      fmt::print("clock: {}\n", why);
    } else {
      json cj = json::array();
      double total_us = 0;
      bool all_cycles = a.rtl;
      for (size_t gi = 0; gi < fr.groups.size(); ++gi) {
        const FeatureSet& fs = fr.groups[gi].fs;
        const MeasuredSet* best = nullptr;
        std::vector<std::string> best_d;
        auto unit_differs = [&fs](const FeatureSet& m) { return fs.specular != m.specular || fs.units() != m.units(); };
        for (const auto& m : ms) {
          const auto dd = fs_differences(fs, m.fs);
          const auto score = std::make_tuple(unit_differs(m.fs), dd.size(), -m.period_ns);
          if (!best || score < std::make_tuple(unit_differs(best->fs), best_d.size(), -best->period_ns))
            best = &m, best_d = dd;
        }
        json c = {{"key", fs.key()}, {"measured_set", best->name}, {"exact", best_d.empty()},
                  {"differences", best_d}, {"period_ns", best->period_ns}, {"fmax_mhz", best->fmax_mhz},
                  {"met", best->met}};
        if (a.rtl && gi < rtl_json["cores"].size()) {
          const uint64_t cyc = rtl_json["cores"][gi]["cycles"].get<uint64_t>();
          const double us = static_cast<double>(cyc) * best->period_ns / 1000.0;
          c["cycles"] = cyc;
          c["time_us"] = us;
          total_us += us;
        } else {
          all_cycles = false;
        }
        std::string diffs;
        for (const auto& x : best_d) diffs += (diffs.empty() ? "" : ", ") + x;
        fmt::print("clock: core {} is {} {} (closes at {} ns){}\n", gi,
                   best_d.empty() ? "the measured lighting set" : "nearest the measured lighting set", best->name,
                   best->period_ns, diffs.empty() ? std::string() : "; it differs: " + diffs);
        cj.push_back(c);
      }
      clock_json = {{"measured", true}, {"source", path}, {"cores", cj},
                    {"frame_time_us", all_cycles ? json(total_us) : json(nullptr)}};
      if (all_cycles) fmt::print("frame time at the measured clock: {:.2f} µs (core cycles × the period)\n", total_us);
    }
  }

  // The reference: Mesa's snapshot of the same frame, or a given image.
  json cmp_json = nullptr;
  bool cmp_pass = true;
  std::vector<uint8_t> diff_rgb;
  Png ref;
  int diff_w = 0, diff_h = 0;
  std::string verdict;
  if (a.mesa || ref_given) {
    ref = a.mesa ? mesa_snapshot(a.trace, h.api, h.snapshot_call, fr.width, fr.height)
                 : read_png(a.reference, "--reference");
    if (ref.width != fr.width || ref.height != fr.height)
      throw std::runtime_error(fmt::format("the reference image is {}x{}, the frame {}x{}", ref.width, ref.height,
                                           fr.width, fr.height));
    const std::vector<int32_t> exact_obj = glref::object_map(fr);
    glref::GlImage gl;
    gl.width = ref.width, gl.height = ref.height, gl.rgb = ref.rgb;
    std::array<uint8_t, 3> bg{};
    for (int c = 0; c < 3; ++c) bg[c] = static_cast<uint8_t>(std::lround(h.scene.background[c] * 255));
    uint64_t covered_in_clear_colour = 0;  // geometry lit to exactly the clear colour in both images (glref.hpp)
    gl.object = glref::snapshot_objects(ref.rgb, bg, exact_obj, exact_rgb, covered_in_clear_colour);
    auto checks = glref::check_objects(h.scene, fr.object_shading);
    for (size_t o = 0; o < checks.size(); ++o)
      if (!h.object_excluded[o].empty()) {
        checks[o].comparable = false;
        for (const auto& r : h.object_excluded[o]) checks[o].reasons.push_back(r + " on");
      }
    glref::Comparison cmp = glref::compare(fr.width, fr.height, exact_rgb, exact_obj, gl, checks, a.tolerance, false);
    cmp_pass = cmp.pass && cmp.comparable.max <= 2 * a.tolerance;
    // Pixels above the max tolerance whose centre lies within glref::Comparison::kSnapPx of an edge of the triangle
    // the exact image shows there: Mesa transforms in float and snaps to its own sub-pixel grid, so such a centre
    // may fall to the neighbouring triangle (a rasterisation difference, not a lighting one). Counted apart; the
    // verdict stays the strict one.
    // The same for pixels covered in one image only (a silhouette centre Mesa's snapping puts on the other side):
    // the distance to the nearest edge of any triangle drawn near it.
    const auto& tris = fr.raster.tris();
    auto edge_px = [&](const auto& t, int x, int y) {  // centre of pixel (x, y) to the triangle's nearest edge
      const double cx = (x + 0.5) * 256.0, cy = (y + 0.5) * 256.0;  // 1/256 pixel units, as ScreenVertex
      double best = 1e30;
      for (int k = 0; k < 3; ++k) {
        const auto& a0 = t.v[k];
        const auto& a1 = t.v[(k + 1) % 3];
        const double ex = double(a1.X - a0.X), ey = double(a1.Y - a0.Y), l2 = ex * ex + ey * ey;
        const double u = l2 > 0 ? std::clamp(((cx - a0.X) * ex + (cy - a0.Y) * ey) / l2, 0.0, 1.0) : 0.0;
        best = std::min(best, std::hypot(cx - (a0.X + u * ex), cy - (a0.Y + u * ey)) / 256.0);
      }
      return best;
    };
    uint64_t above_max = 0, above_max_at_edge = 0, coverage_at_edge = 0;
    for (int y = 0; y < fr.height; ++y)
      for (int x = 0; x < fr.width; ++x) {
        const size_t p = static_cast<size_t>(y) * fr.width + x;
        const int32_t id = fr.raster.at(x, y);
        if ((exact_obj[p] < 0) != (gl.object[p] < 0)) {
          double best = 1e30;
          if (id >= 0) best = edge_px(tris[static_cast<size_t>(id)], x, y);
          else
            for (const auto& t : tris) best = std::min(best, edge_px(t, x, y));
          if (best <= glref::Comparison::kSnapPx) ++coverage_at_edge;
          continue;
        }
        if (id < 0 || !checks[static_cast<size_t>(exact_obj[p])].comparable) continue;
        int d = 0;
        for (int c = 0; c < 3; ++c) d = std::max(d, std::abs(int{exact_rgb[3 * p + c]} - int{ref.rgb[3 * p + c]}));
        if (d <= 2 * a.tolerance) continue;
        ++above_max;
        if (edge_px(tris[static_cast<size_t>(id)], x, y) <= glref::Comparison::kSnapPx) ++above_max_at_edge;
      }
    diff_rgb = cmp.diff_rgb;
    diff_w = fr.width, diff_h = fr.height;
    verdict = fmt::format("{}: p50 {} / p99 {} / max {} LSB (tolerance p99 {}, max {}) over {} compared pixels; covered: "
                          "exact {}, reference {}, by one only {}; {} px above {} LSB",
                          cmp_pass ? "PASS" : "FAIL", cmp.comparable.p50, cmp.comparable.p99, cmp.comparable.max,
                          a.tolerance, 2 * a.tolerance, cmp.comparable.pixels, cmp.covered_exact, cmp.covered_gl,
                          cmp.coverage_mismatch, cmp.comparable.above, a.tolerance);
    if (cmp.coverage_mismatch)
      verdict += fmt::format(" ({} of the {} covered by one only with the centre within 1/256 px of a triangle edge)",
                             coverage_at_edge, cmp.coverage_mismatch);
    if (above_max)
      verdict += fmt::format(", {} above {} LSB ({} with the centre within 1/256 px of a triangle edge)", above_max,
                             2 * a.tolerance, above_max_at_edge);
    if (covered_in_clear_colour)
      verdict += fmt::format("; {} px drawn in the clear colour in both (covered, not told from the background)",
                             covered_in_clear_colour);
    cmp_json = {{"reference", a.mesa ? (h.api == "egl" ? "eglretrace" : "glretrace") : a.reference},
                {"snapshot_call", h.snapshot_call},
                {"tolerance_p99_lsb", a.tolerance},
                {"tolerance_max_lsb", 2 * a.tolerance},
                {"p50_lsb", cmp.comparable.p50},
                {"p99_lsb", cmp.comparable.p99},
                {"max_lsb", cmp.comparable.max},
                {"mean_lsb", cmp.comparable.mean},
                {"compared_pixels", cmp.comparable.pixels},
                {"covered_exact", cmp.covered_exact},
                {"covered_reference", cmp.covered_gl},
                {"covered_both", cmp.covered_both},
                {"coverage_mismatch", cmp.coverage_mismatch},
                {"covered_in_clear_colour", covered_in_clear_colour},
                {"above_max_tolerance", above_max},
                {"above_max_tolerance_at_edge", above_max_at_edge},
                {"pass", cmp_pass},
                {"coverage_mismatch_at_edge", coverage_at_edge},
                {"pass_within_snapping", cmp.comparable.pixels > 0 && cmp.comparable.p99 <= a.tolerance &&
                                             cmp.object_mismatch == 0 && above_max == above_max_at_edge &&
                                             cmp.coverage_mismatch == coverage_at_edge},
                {"comparable", stats_json(cmp.comparable)},
                {"all", stats_json(cmp.all)}};
  }

  std::vector<std::pair<std::string, std::string>> files;
  if (dir_out >= 0) {
    files.emplace_back("cmodel.png", canvas::encode_png(img.width, img.height, render::to_rgb8(img)));
    files.emplace_back("exact.png", canvas::encode_png(fr.width, fr.height, exact_rgb));
    if (a.rtl) files.emplace_back("rtl.png", canvas::encode_png(rimg.width, rimg.height, render::to_rgb8(rimg)));
    if (a.mesa || ref_given) {
      files.emplace_back("mesa.png", canvas::encode_png(ref.width, ref.height, ref.rgb));
      const std::string tol = std::to_string(a.tolerance);
      const canvas::Canvas d = canvas::with_key_legend(
          diff_w, diff_h, diff_rgb,
          {{{0, 0, 0}, "equal (or background)"},
           {{120, 120, 120}, "1.." + tol + " LSB (grey, 60 per LSB)"},
           {{208, 0, 0}, "exact brighter than the reference by more than " + tol + " LSB"},
           {{0, 0, 208}, "the reference brighter than exact by more than " + tol + " LSB"},
           {{255, 255, 0}, "covered in one image only"},
           {{60, 50, 40}, "not compared: the exact image at 1/4"}},
          "exact vs the reference, 8-bit LSB, largest channel");
      files.emplace_back("diff.png", canvas::encode_png(d.width, d.height, d.rgb));
      const canvas::Canvas pr = pair_figure(fr.width, fr.height, exact_rgb, ref.rgb,
                                            a.mesa ? "Mesa (" + std::string(h.api == "egl" ? "eglretrace" : "glretrace") + ")"
                                                   : "the reference",
                                            verdict);
      files.emplace_back("pair.png", canvas::encode_png(pr.width, pr.height, pr.rgb));
    }
  }
  if (json_given) {
    json j;
    j["capture"] = a.trace;
    j["command"] = command_line();
    j["date"] = utc_now();
    j["trace_version"] = version;
    j["api"] = h.api;
    j["frame"] = h.frame;
    j["first_call"] = h.first_call;
    j["snapshot_call"] = h.snapshot_call;
    j["width"] = fr.width;
    j["height"] = fr.height;
    j["calls_read"] = st.calls_read;
    j["calls_in_frame"] = st.calls_in_frame;
    j["calls_executed"] = st.calls_executed;
    j["primitives"] = st.primitives;
    j["vertices"] = st.vertices;
    j["triangles"] = st.triangles;
    j["culled"] = st.culled;
    j["vertices_lit"] = vertex_frags;
    j["faces_lit"] = face_frags;
    j["register_writes"] = writes;
    j["lighting_states"] = n_states;                // runs of draws with one lighting state, in drawing order
    j["lighting_state_changes"] = state_changes;    // reprogrammings of the core between batches (all cores)
    j["state_change_register_writes"] = state_writes;  // their writes (of register_writes): changed registers only
    j["core_cycles"] = a.rtl ? rtl_json["cycles"] : json(nullptr);
    // the frame's time at the measured closing clock of its lighting set (docs/timing.json), or "no measured clock"
    j["clock"] = clock_json;
    json keys = json::array();
    for (const auto& g : fr.groups) keys.push_back(g.fs.key());
    j["feature_set_keys"] = keys;
    j["cores"] = cores;
    j["unsupported_calls"] = st.unsupported;
    j["ignored_calls"] = st.ignored;
    j["notes"] = st.notes;
    j["non_unit_normals"] = {{"count", h.non_unit_normals}, {"worst_length", h.worst_normal_length}};
    j["eye_space_out_of_range"] = {{"count", h.eye_out_of_range}, {"worst_coordinate", h.eye_worst},
                                   {"scale", h.eye_scale}};
    json objs = json::array();
    for (size_t o = 0; o < h.scene.objects.size(); ++o)
      objs.push_back({{"name", h.scene.objects[o].name}, {"where", h.scene.objects[o].where},
                      {"shading", scene::to_string(fr.object_shading[o])}, {"excluded", h.object_excluded[o]}});
    j["objects"] = objs;
    j["cmodel_vs_exact_max_lsb16"] = err_exact.max_lsb;
    j["rtl"] = rtl_json;
    j["comparison"] = cmp_json;
    j["seconds"] = {{"front_end", t_front}, {"total", std::chrono::duration<double>(Clock::now() - t0).count()}};
    if (json_out >= 0) outs.set(json_out, j.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
    else files.emplace_back(json_member, j.dump(2, ' ', false, json::error_handler_t::replace) + "\n");
  }
  if (dir_out >= 0) {
    const std::string stage = outs.stage(dir_out);
    for (const auto& [name, content] : files) write_staged(stage + "/" + name, content);
  }
  outs.commit();
  std::fflush(stdout);
  if (!rtl_ok) throw CheckFailed("replay: the RTL image differs from the C model's");
  if (!verdict.empty()) {
    if (!cmp_pass) throw CheckFailed("replay " + verdict);
    fmt::print("replay {}\n", verdict);
  }
}

}  // namespace

void add_replay(CLI::App& app) {
  auto args = std::make_shared<ReplayArgs>();
  auto* sub = app.add_subcommand("replay",
                                 "play one frame of an apitrace capture of an OpenGL 1.x program through the GL front end "
                                 "and the lighting core, against Mesa's image of it (docs/replay.md)");
  sub->add_option("trace", args->trace, "apitrace capture (.trace)")->required()->check(cliargs::NonEmpty("capture path"));
  auto* frame_opt = sub->add_option("--frame", args->frame, "frame K (from 1): the calls between the (K-1)-th and the K-th swap")
                        ->check(CLI::Range(uint64_t{1}, uint64_t{1} << 40));
  auto* call_opt = sub->add_option("--call", args->call, "the image after call N (the frame from the last swap before it)");
  sub->add_flag("--rtl", args->rtl, "also light every vertex with the Verilated core (bit-identical to the C model, or fail)");
  sub->add_flag("--full-core", args->full_core, "program the full core instead of the derived smallest one");
  sub->add_option("--out", args->out_dir, "write cmodel.png, exact.png (rtl.png, mesa.png, diff.png, pair.png) here")
      ->check(cliargs::NonEmpty("path"));
  auto* json_opt = sub->add_option("--json", args->json_path, "write a JSON report (atomically)")->check(cliargs::NonEmpty("path"));
  sub->add_flag("--mesa", args->mesa, "compare with Mesa: glretrace's snapshot of the frame under xvfb-run");
  auto* ref_opt = sub->add_option("--reference", args->reference, "compare with this PNG of the frame")
                      ->check(cliargs::NonEmpty("path"));
  sub->add_option("--tolerance", args->tolerance, "8-bit LSBs allowed at the 99th percentile (twice that at the max; default 2)")
      ->check(CLI::Range(0, 127));
  sub->callback([args, frame_opt, call_opt, json_opt, ref_opt] {
    run_replay(*args, frame_opt->count() > 0, call_opt->count() > 0, json_opt->count() > 0, ref_opt->count() > 0);
  });
}

}  // namespace shadecore::cli
