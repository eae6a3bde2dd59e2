// SPDX-License-Identifier: Apache-2.0
// shadecore render — a scene through the lighting core (docs/scenes.md).
//
//   shadecore render SCENE --out DIR [--rtl] [--full-core] [--lanes K] [--share S] [--json FILE] [--size WxH]
//
// Derives the smallest feature set(s) that render the scene exactly (one core per specular unit in use),
// prints them, rasterises on the host (shadecore/render/raster.hpp: host software, not RTL), and writes into DIR:
//   cmodel.png       the image through the bit-accurate C model
//   exact.png        the same fragments through the double reference with exact cos^n
//   diff_exact.png   cmodel − exact, signed, log scale (red brighter, blue darker; render::diff_rgb8)
//   rtl.png          (--rtl) the image through the Verilated core, checked pixel by pixel against cmodel.png
//   diff_rtl.png     (--rtl) white where the RTL pixel differs from the C model's
//   contact_sheet.png  where the scene asks for one: shading modes × exact / unit / difference
//   .shadecore-render.json  the manifest: which files of DIR this render wrote (a later render into DIR removes
//                    the ones it does not write again, so DIR never mixes two runs)
// Every output is computed first and written at the end through io::OutputSet (docs/cli.md: checked before the
// run, staged, renamed into place together; a failure or an interrupt leaves nothing behind). No output may name
// an input (the scene, an OBJ file it loads). An RTL image that differs from the C model's is written and the exit
// status is 2.
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <memory>
#include <mutex>
#include <regex>
#include <string>
#include <thread>
#include <vector>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "shadecore/common/args.hpp"
#include "commands.hpp"
#include "shadecore/common/legend.hpp"
#include "output.hpp"
#include "shadecore/common/png.hpp"
#include "shadecore/render/mesh.hpp"
#include "shadecore/render/render.hpp"
#include "shadecore/render/scene.hpp"

#include "light_rtl.hpp"
#include "render_rtl.hpp"

namespace shadecore::cli {
namespace {
using namespace shadecore::canvas;

namespace fsys = std::filesystem;
using Clock = std::chrono::steady_clock;
using json = nlohmann::ordered_json;

struct RenderArgs {
  std::string scene, out, json_path, size;
  bool rtl = false, full_core = false, json_given = false, size_given = false;
  int lanes = 1;
  int share = 1;
};

double seconds_since(Clock::time_point t0) { return std::chrono::duration<double>(Clock::now() - t0).count(); }

// Progress for a step that may take more than a second: nothing if it ends sooner; otherwise a line on
// stderr (updated in place on a terminal, with the detail the step sets, e.g. "cell 3/12") and its time at
// the end.
class Step {
 public:
  explicit Step(std::string label) : label_(std::move(label)), t0_(Clock::now()), tty_(::isatty(STDERR_FILENO)) {
    if (delay().count() == 0 && !tty_) {  // no delay: shown at once, whatever the thread's start-up takes
      shown_ = true;
      std::fprintf(stderr, "render: %s ...\n", label_.c_str());
      std::fflush(stderr);
    }
    th_ = std::thread([this] { loop(); });
  }
  Step(const Step&) = delete;
  Step& operator=(const Step&) = delete;
  ~Step() { finish(); }
  void detail(std::string d) {
    std::lock_guard<std::mutex> lk(mu_);
    detail_ = std::move(d);
  }
  void finish() {
    if (!th_.joinable()) return;
    {
      std::lock_guard<std::mutex> lk(mu_);
      done_ = true;
    }
    cv_.notify_all();
    th_.join();
    if (shown_) {
      if (tty_) std::fputs("\r\033[K", stderr);
      io::set_progress_line(false);
      std::fprintf(stderr, "render: %s: %.1f s\n", label_.c_str(), seconds_since(t0_));
      std::fflush(stderr);
    }
  }

 private:
  // A step is shown after 1 s (SHADECORE_PROGRESS_DELAY_MS overrides it, for tests of the progress lines).
  static std::chrono::milliseconds delay() {
    const char* e = std::getenv("SHADECORE_PROGRESS_DELAY_MS");
    uint64_t ms = 1000;
    if (e && cliargs::parse_u64(e, ms)) return std::chrono::milliseconds(std::min<uint64_t>(ms, 3600000));
    return std::chrono::milliseconds(1000);
  }
  void loop() {
    std::unique_lock<std::mutex> lk(mu_);
    if (!shown_ && cv_.wait_for(lk, delay(), [this] { return done_; })) return;
    if (!tty_) {
      if (shown_) return;  // already announced
      shown_ = true;
      std::fprintf(stderr, "render: %s ...\n", label_.c_str());
      std::fflush(stderr);
      return;
    }
    shown_ = true;
    io::set_progress_line(true);
    do {
      std::fprintf(stderr, "\rrender: %s%s%s ... %.0f s\033[K", label_.c_str(), detail_.empty() ? "" : ": ",
                   detail_.c_str(), seconds_since(t0_));
      std::fflush(stderr);
    } while (!cv_.wait_for(lk, std::chrono::milliseconds(500), [this] { return done_; }));
  }
  std::string label_, detail_;
  Clock::time_point t0_;
  bool tty_;
  std::mutex mu_;
  std::condition_variable cv_;
  bool done_ = false, shown_ = false;
  std::thread th_;
};

// Wall time per phase of a render (the contact sheet's cells included), printed and in --json "phases".
struct Phases {
  double load = 0, tessellate = 0, rasterise = 0, light = 0, rtl = 0, write = 0;
  json to_json(double total) const {
    return {{"load_s", load},   {"tessellate_s", tessellate}, {"rasterise_s", rasterise}, {"light_s", light},
            {"rtl_s", rtl},     {"write_s", write},           {"total_s", total}};
  }
  std::string text(double total, bool rtl_run) const {
    return fmt::format("load {:.2f} s, tessellate {:.2f} s, rasterise {:.2f} s, light {:.2f} s{}, write {:.2f} s; total {:.2f} s",
                       load, tessellate, rasterise, light, rtl_run ? fmt::format(", RTL {:.2f} s", rtl) : std::string(),
                       write, total);
  }
};

std::string plural(uint64_t n, const char* one, const char* many) { return fmt::format("{} {}", n, n == 1 ? one : many); }

json stats_json(const render::ErrorStats& s) {
  json j;
  j["max_lsb"] = s.max_lsb;
  j["mean_lsb"] = s.mean_lsb;
  j["rms"] = s.rms;
  j["psnr_db"] = std::isfinite(s.psnr_db) ? json(s.psnr_db) : json(nullptr);
  j["identical"] = s.samples > 0 && s.max_lsb == 0;
  j["pixels"] = s.pixels;
  j["samples"] = s.samples;  // pixels × 3 channels
  if (s.max_x >= 0) j["max_at"] = {s.max_x, s.max_y};  // [x, y]: column from the left, row from the top
  return j;
}

std::string stats_text(const render::ErrorStats& s) {
  if (s.samples == 0) return "no covered pixels";
  return fmt::format("max {:.1f} LSB, mean {:.2f} LSB, PSNR {}", s.max_lsb, s.mean_lsb,
                     std::isfinite(s.psnr_db) ? fmt::format("{:.1f} dB", s.psnr_db) : std::string("inf (identical)"));
}

std::pair<int, int> parse_size(const std::string& s) {
  if (s.empty()) throw std::invalid_argument("--size: empty value (expected WxH, e.g. 64x64)");
  static const std::regex re(R"(^\s*(\d{1,5})\s*[xX]\s*(\d{1,5})\s*$)");
  std::smatch m;
  if (!std::regex_match(s, m, re)) throw std::invalid_argument("--size: malformed '" + s + "' (expected WxH, e.g. 64x64)");
  const int w = std::stoi(m[1].str()), h = std::stoi(m[2].str());
  if (w < 1 || h < 1 || w > 4096 || h > 4096) throw std::invalid_argument("--size: " + s + " out of range 1..4096");
  return {w, h};
}

std::string set_line(const FeatureSet& fs) { return fs.summary() + "  [key " + fs.key() + "]"; }

struct Rendered {
  render::Frame frame;
  render::Image image;
  render::RefImage exact, unit_double;
  double light_seconds = 0;
};

// Geometry and visibility (render::prepare), then the C model and both references over every fragment.
Rendered render_cmodel(const scene::Scene& sc, render::MeshSource& meshes, const render::Settings& st,
                       const std::string& what, Phases& ph, bool quiet = false) {
  Rendered r;
  {
    std::unique_ptr<Step> step;
    if (!quiet) step = std::make_unique<Step>(fmt::format("geometry and visibility, {}", what));
    r.frame = render::prepare(sc, meshes, st);
  }
  ph.tessellate += r.frame.tessellate_seconds;
  ph.rasterise += r.frame.rasterise_seconds;
  const auto t0 = Clock::now();
  size_t frags = 0;
  for (const auto& g : r.frame.groups) frags += g.dests.size();
  std::unique_ptr<Step> step;
  if (!quiet) step = std::make_unique<Step>(fmt::format("C model and references, {}: {} fragments", what, frags));
  std::vector<std::vector<Colour>> cols;
  std::vector<std::vector<render::RefColour>> ex, ud;
  for (const auto& g : r.frame.groups) {
    cols.push_back(render::run_cmodel(g));
    ex.push_back(render::run_reference(g, LightCore::SpecRef::Exact));
    ud.push_back(render::run_reference(g, LightCore::SpecRef::Variant));
  }
  r.image = render::resolve(r.frame, cols);
  r.exact = render::resolve_reference(r.frame, ex);
  r.unit_double = render::resolve_reference(r.frame, ud);
  r.light_seconds = seconds_since(t0);
  ph.light += r.light_seconds;
  return r;
}

// The manifest of a render directory: the files the last render into it wrote.
constexpr const char* kManifest = ".shadecore-render.json";
const std::vector<std::string> kRenderNames = {"cmodel.png", "exact.png",   "diff_exact.png",
                                               "rtl.png",    "diff_rtl.png", "contact_sheet.png"};

// Files an earlier render wrote into `dir` (from its manifest); empty if there is none or it is not ours.
std::vector<std::string> previous_render_files(const std::string& dir) {
  const std::string p = dir + "/" + kManifest;
  struct stat st {};
  if (::lstat(p.c_str(), &st) != 0 || !S_ISREG(st.st_mode) || st.st_size > (1 << 20)) return {};
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  std::vector<std::string> names;
  try {
    const json m = json::parse(ss.str());
    if (!m.is_object() || m.value("written_by", "") != "shadecore render" || !m.contains("files") || !m["files"].is_array())
      return {};
    for (const auto& f : m["files"]) {
      if (!f.is_string()) continue;
      const std::string n = f.get<std::string>();
      // Names directly inside DIR only (a manifest edited to point elsewhere removes nothing elsewhere).
      if (n.empty() || n == "." || n == ".." || n == kManifest || n.find('/') != std::string::npos ||
          n.find('\0') != std::string::npos)
        continue;
      names.push_back(n);
    }
  } catch (const json::exception&) {
    return {};
  }
  return names;
}

std::string unit_name(VariantId v) { return std::string(variant_name(v)); }

void run_render(const RenderArgs& a) {
  const auto t_start = Clock::now();
  Phases ph;
  scene::Scene sc;
  try {
    sc = scene::load_scene(a.scene);
  } catch (const scene::SceneError& e) {
    throw std::runtime_error(e.what());
  }
  ph.load = seconds_since(t_start);
  render::Settings st;
  st.full_core = a.full_core;
  st.lanes = a.lanes;
  st.share = a.share;
  if (a.size_given) std::tie(st.width, st.height) = parse_size(a.size);
  const bool sheet = sc.contact_sheet.has_value();
  std::vector<std::string> names = {"cmodel.png", "exact.png", "diff_exact.png"};
  if (a.rtl) {
    names.emplace_back("rtl.png");
    names.emplace_back("diff_rtl.png");
  }
  if (sheet) names.push_back("contact_sheet.png");
  // All outputs through io::OutputSet (docs/cli.md): checked now, written together at the end; a --json inside
  // --out is one more file of that directory.
  io::OutputSet outs;
  std::string json_member;
  if (a.json_given && !a.out.empty()) {
    const fsys::path jp = fsys::absolute(a.json_path).lexically_normal(), dp = fsys::absolute(a.out).lexically_normal();
    if (jp.parent_path() == dp) {
      json_member = jp.filename().string();
      if (std::find(names.begin(), names.end(), json_member) != names.end() || json_member == kManifest)
        throw std::invalid_argument("--json " + a.json_path + " is one of the images (or the manifest) written to --out");
    }
  }
  std::vector<std::string> dir_names = names;
  if (!json_member.empty()) dir_names.push_back(json_member);
  dir_names.push_back(kManifest);
  const int dir_out = outs.dir("--out", a.out, dir_names);
  const int json_out = !a.json_given || !json_member.empty() ? -1 : outs.file("--json", a.json_path);
  // No output may overwrite an input: the scene, or an OBJ file it loads.
  outs.check_input(a.scene, "the scene file");
  for (const auto& o : sc.objects)
    if (o.type == scene::ObjectType::Mesh) outs.check_input(o.file_path, "the OBJ file of " + o.where);
  // What an earlier render left in --out and this one does not write again is removed at the end (the
  // manifest says which files were a render's); without a manifest, files of ours are only pointed out.
  {
    const auto previous = previous_render_files(a.out);
    for (const auto& n : previous)
      if (std::find(dir_names.begin(), dir_names.end(), n) == dir_names.end()) outs.remove_at_commit(dir_out, n);
    struct stat mst {};
    if (previous.empty() && ::lstat((a.out + "/" + kManifest).c_str(), &mst) != 0)
      for (const auto& n : kRenderNames)
        if (std::find(names.begin(), names.end(), n) == names.end() && ::lstat((a.out + "/" + n).c_str(), &mst) == 0)
          fmt::print(stderr, "render: note: {}/{} is not from this run (no manifest says which render wrote it: left as it is)\n",
                     scene::printable(a.out, 0), n);
  }
  std::vector<std::pair<std::string, std::string>> files;  // name in --out, content

  render::MeshSource meshes(sc);
  Rendered main;
  try {
    main = render_cmodel(sc, meshes, st, "image", ph);
  } catch (const scene::SceneError& e) {
    throw std::runtime_error(e.what());
  }
  const render::Frame& fr = main.frame;

  // What the scene needs, and the core(s) it is rendered with.
  fmt::print("scene {}: {}x{}, {}, {}, {}\n", scene::printable(a.scene, 0), fr.width, fr.height, plural(sc.objects.size(), "object", "objects"),
             plural(sc.lights.size(), "light", "lights"), plural(sc.materials.size(), "material", "materials"));
  fmt::print("geometry: {} vertices, {} faces, {} triangles drawn; {} visible triangles kept\n", fr.drawn_vertices,
             fr.drawn_faces, fr.drawn_triangles, fr.tri_object.size());
  json features = json::array();
  uint64_t total_frags = 0;
  for (size_t g = 0; g < fr.groups.size(); ++g) {
    const auto& grp = fr.groups[g];
    std::string mats;
    json mj = json::array();
    for (int m : grp.materials) {
      mats += (mats.empty() ? "" : ", ") + scene::printable(sc.materials[m].name);
      mj.push_back(sc.materials[m].name);
    }
    fmt::print("core {}/{} (unit {}; {} {}):\n", g + 1, fr.groups.size(), grp.unit_label,
               grp.materials.size() == 1 ? "material" : "materials", mats);
    fmt::print("  feature set: {}\n", set_line(grp.specialised));
    if (a.full_core) {
      std::string subs;
      for (const auto& s : grp.full_substitutions) subs += (subs.empty() ? "" : ", ") + s;
      fmt::print("  rendered on the full core: {}{}\n", set_line(grp.fs),
                 subs.empty() ? std::string() : " — at the scene's width: " + subs);
    }
    fmt::print("  fragments: {} ({} per pixel, {} per vertex, {} per face), {}\n", grp.dests.size(), grp.pixels,
               grp.vertices, grp.faces, plural(grp.writes, "register write", "register writes"));
    const auto ge = render::error_vs(main.image, main.exact, static_cast<int>(g));
    const auto gu = render::error_vs(main.image, main.unit_double, static_cast<int>(g));
    fmt::print("  error over its pixels: vs exact cos^n: {}; vs the unit's own double formula: {}\n", stats_text(ge),
               stats_text(gu));
    total_frags += grp.dests.size();
    json fj;
    fj["core"] = g;
    fj["unit"] = grp.unit_label;
    fj["materials"] = mj;
    fj["name"] = grp.fs.name;
    fj["key"] = grp.fs.key();
    fj["summary"] = grp.fs.summary();
    fj["set"] = grp.fs.canonical();
    fj["verilog_params"] = grp.fs.verilog_params(32);
    fj["specialised"] = {{"key", grp.specialised.key()}, {"summary", grp.specialised.summary()}, {"set", grp.specialised.canonical()}};
    fj["full_substitutions"] = grp.full_substitutions;
    fj["fragments"] = {{"total", grp.dests.size()}, {"per_pixel", grp.pixels}, {"per_vertex", grp.vertices}, {"per_face", grp.faces}};
    fj["register_writes"] = grp.writes;
    fj["error_vs_exact"] = stats_json(ge);
    fj["error_vs_unit_double"] = stats_json(gu);
    features.push_back(fj);
  }
  const auto err_exact = render::error_vs(main.image, main.exact);
  const auto err_unit = render::error_vs(main.image, main.unit_double);
  fmt::print("C model, whole image: vs exact cos^n: {}; vs the unit's own double formula: {}\n", stats_text(err_exact),
             stats_text(err_unit));
  json images = json::array();
  images.push_back({{"name", "cmodel"}, {"file", "cmodel.png"}, {"error_vs_exact", stats_json(err_exact)},
                    {"error_vs_unit_double", stats_json(err_unit)}});
  const render::Image main_image = main.image;
  const render::RefImage main_exact = main.exact;
  const int img_w = fr.width, img_h = fr.height;

  // RTL.
  json rtl_json = nullptr;
  uint64_t bad_pixels = 0;
  bool rtl_ok = true;
  render::Image rimg;
  if (a.rtl) {
    const auto t_rtl = Clock::now();
    RtlTotals tot;
    const auto cols = run_rtl(fr, tot);
    rimg = render::resolve(fr, cols);
    bad_pixels = render::mismatching_pixels(main.image, rimg);
    rtl_ok = bad_pixels == 0 && tot.ok && tot.core_mismatches == 0;
    const auto err_rtl = render::error_vs(rimg, main.exact);
    fmt::print("RTL: {} fragments, {} cycles, {:.2f} s simulated{}; {} mismatching pixels vs the C model{}\n",
               total_frags, tot.cycles, tot.sim_seconds,
               tot.build_seconds > 0 ? fmt::format(" (+{:.1f} s core build)", tot.build_seconds) : std::string(),
               bad_pixels, tot.core_mismatches ? fmt::format(", {} core outputs differ from LightCore::eval", tot.core_mismatches) : std::string());
    rtl_json = {{"mismatching_pixels", bad_pixels},
                {"sim_seconds", tot.sim_seconds},
                {"cycles", tot.cycles},
                {"fragments", total_frags},
                {"core_mismatches", tot.core_mismatches},
                {"build_seconds", tot.build_seconds},
                {"ok", rtl_ok},
                {"cores", tot.cores}};
    images.push_back({{"name", "rtl"}, {"file", "rtl.png"}, {"error_vs_exact", stats_json(err_rtl)},
                      {"mismatching_pixels_vs_cmodel", bad_pixels}});
    ph.rtl = seconds_since(t_rtl);
  }
  main = Rendered();  // the frame's geometry is not needed any more (the images are kept)

  // Contact sheet: rows = shading modes, columns = exact cos^n, then per unit its image and |unit − exact|.
  json sheet_json = nullptr;
  Canvas sheet_canvas(1, 1, 0);
  if (sheet) {
    const auto& cs = *sc.contact_sheet;
    render::Settings cst;
    cst.width = cs.cell_width;
    cst.height = cs.cell_height;
    cst.camera = cs.camera;
    cst.objects = cs.objects;
    const int nrows = static_cast<int>(cs.modes.size());
    std::vector<std::string> col_names = {"exact cos^n"};
    for (auto u : cs.units) {
      col_names.push_back(unit_name(u));
      col_names.push_back(fmt::format("{} − exact", unit_name(u)));
    }
    std::vector<std::string> row_names;
    for (const auto& m : cs.modes) row_names.push_back(m ? scene::to_string(*m) : "scene");
    const SheetLayout L = layout_sheet(cs.cell_width, cs.cell_height, col_names, row_names, fr.F);
    Canvas cv = L.canvas();
    L.draw_labels(cv);
    L.draw_legend(cv);
    json rows = json::array();
    const int ncells = nrows * static_cast<int>(cs.units.size());
    Step step(fmt::format("contact sheet, {} cells of {}x{}", ncells, cs.cell_width, cs.cell_height));
    int done = 0;
    for (int r = 0; r < nrows; ++r) {
      cst.mode = cs.modes[r];
      const std::string& mode_name = row_names[r];
      json row;
      row["mode"] = mode_name;
      json cells = json::array();
      for (size_t u = 0; u < cs.units.size(); ++u) {
        step.detail(fmt::format("cell {}/{} ({} / {})", ++done, ncells, mode_name, unit_name(cs.units[u])));
        cst.unit = cs.units[u];
        Rendered cell;
        try {
          cell = render_cmodel(sc, meshes, cst, "contact sheet " + mode_name + "/" + unit_name(cs.units[u]), ph, true);
        } catch (const scene::SceneError& e) {
          throw std::runtime_error(e.what());
        }
        if (u == 0) L.place(cv, r, 0, render::to_rgb8(cell.exact));
        L.place(cv, r, 1 + 2 * static_cast<int>(u), render::to_rgb8(cell.image));
        L.place(cv, r, 2 + 2 * static_cast<int>(u), render::diff_rgb8(cell.image, cell.exact));
        const auto e = render::error_vs(cell.image, cell.exact);
        std::string units;
        for (const auto& g : cell.frame.groups) units += (units.empty() ? "" : "+") + g.unit_label;
        cells.push_back({{"unit", unit_name(cs.units[u])}, {"cores", units}, {"error_vs_exact", stats_json(e)}});
        images.push_back({{"name", "contact_sheet/" + mode_name + "/" + unit_name(cs.units[u])},
                          {"file", "contact_sheet.png"},
                          {"error_vs_exact", stats_json(e)}});
        fmt::print("contact sheet {:>8} / {:<12}: vs exact cos^n: {}\n", mode_name, unit_name(cs.units[u]), stats_text(e));
      }
      row["cells"] = cells;
      rows.push_back(row);
    }
    step.finish();
    sheet_canvas = std::move(cv);
    sheet_json = {{"file", "contact_sheet.png"}, {"columns", col_names}, {"rows", rows}, {"cell", {cs.cell_width, cs.cell_height}}, {"path", "C model"}};
  }

  // Write: encode every image, then commit everything together.
  const auto t_write = Clock::now();
  {
    Step step("writing the images");
    files.emplace_back("cmodel.png", encode_png(main_image.width, main_image.height, render::to_rgb8(main_image)));
    files.emplace_back("exact.png", encode_png(main_exact.width, main_exact.height, render::to_rgb8(main_exact)));
    // The difference with its colour bar below (the image at the top left: max_at's pixel is where it was).
    const Canvas d = with_diff_legend(main_image.width, main_image.height, render::diff_rgb8(main_image, main_exact),
                                      main_image.F);
    files.emplace_back("diff_exact.png", encode_png(d.width, d.height, d.rgb));
    if (a.rtl) {
      files.emplace_back("rtl.png", encode_png(rimg.width, rimg.height, render::to_rgb8(rimg)));
      // The mismatch map with its key below (the image at the top left, pixel coordinates unchanged).
      const Canvas k = with_key_legend(rimg.width, rimg.height, render::mismatch_rgb8(main_image, rimg),
                                       {{{255, 255, 255}, "RTL pixel differs from the C model's"},
                                        {{40, 40, 40}, "covered, RTL = C model"},
                                        {{0, 0, 0}, "background (no object), equal"}},
                                       "RTL vs C model, per pixel");
      files.emplace_back("diff_rtl.png", encode_png(k.width, k.height, k.rgb));
    }
    if (sheet) files.emplace_back("contact_sheet.png", encode_png(sheet_canvas.width, sheet_canvas.height, sheet_canvas.rgb));
  }
  ph.write = seconds_since(t_write);  // the commit below is a few renames
  const double total = seconds_since(t_start);
  if (a.json_given) {
    json j;
    j["scene"] = a.scene;
    j["command"] = command_line();
    j["width"] = img_w;
    j["height"] = img_h;
    j["full_core"] = a.full_core;
    j["lanes"] = a.lanes;
    j["share"] = a.share;
    j["features"] = features;
    j["fragments"] = total_frags;
    j["error_vs_exact"] = stats_json(err_exact);
    j["error_vs_unit_double"] = stats_json(err_unit);
    j["images"] = images;
    j["cmodel"] = {{"seconds", ph.light}};
    j["rtl"] = rtl_json;
    j["contact_sheet"] = sheet_json;
    j["phases"] = ph.to_json(total);
    j["seconds"] = total;
    if (json_out >= 0) outs.set(json_out, j.dump(2) + "\n");
    else files.emplace_back(json_member, j.dump(2) + "\n");
  }
  {
    json m;
    m["written_by"] = "shadecore render";
    m["scene"] = a.scene;
    m["command"] = command_line();
    json fl = json::array();
    for (const auto& f : files) fl.push_back(f.first);
    m["files"] = fl;
    files.emplace_back(kManifest, m.dump(2) + "\n");
  }
  const std::string stage = outs.stage(dir_out);
  for (const auto& [name, content] : files) write_staged(stage + "/" + name, content);
  outs.commit();
  fmt::print("time: {}\n", ph.text(total, a.rtl));
  fmt::print("wrote {}/{{{}}}{}\n", scene::printable(a.out, 0), [&] {
    std::string s;
    for (const auto& n : names) s += (s.empty() ? "" : ",") + n;
    return s;
  }(), a.json_given ? " and " + scene::printable(a.json_path, 0) : std::string());
  if (!rtl_ok)  // exit status 2: the check ran and failed; the images and the JSON are its record
    throw CheckFailed(fmt::format("RTL render FAILED: {} pixels differ from the C model (images written to {})",
                                  bad_pixels, a.out));
}

}  // namespace

void add_render(CLI::App& app) {
  auto args = std::make_shared<RenderArgs>();
  auto* sub = app.add_subcommand("render",
                                 "render a scene through the lighting core: C model, exact reference, and with --rtl the "
                                 "Verilated core specialised to the scene (docs/scenes.md)");
  sub->add_option("scene", args->scene, "scene file (JSON, docs/scenes.md)")->required()->check(cliargs::NonEmpty("scene path"));
  sub->add_option("--out", args->out, "output directory (created if needed)")->required()->check(cliargs::NonEmpty("path"));
  sub->add_flag("--rtl", args->rtl, "also render through the Verilated core and check it pixel by pixel");
  sub->add_flag("--full-core", args->full_core, "use the 'full' feature set instead of the derived one");
  sub->add_option("--lanes", args->lanes,
                  "lanes of every core (per-light datapaths; enabled lights take ceil(k/lanes) passes), clamped to "
                  "its light slots")
      ->check(CLI::Range(1, kMaxLights));
  auto* share_opt = sub->add_option("--share", args->share,
                                    "clocks per pass of every core (1..4: its normalisers and dot-product multipliers "
                                    "shared over that many clocks; > 1 needs --lanes 1)")
                        ->check(CLI::Range(1, kShareMax));
  auto* json_opt = sub->add_option("--json", args->json_path, "write a JSON report (atomically)")->check(cliargs::NonEmpty("path"));
  auto* size_opt = sub->add_option("--size", args->size, "render at WxH instead of the scene's image size (e.g. 64x64)")
                       ->check(cliargs::NonEmpty("size (expected WxH, e.g. 64x64)"));
  sub->callback([args, json_opt, size_opt, share_opt] {
    if (share_opt->count() > 0 && args->share > 1 && args->lanes > 1)
      throw std::invalid_argument("--share " + std::to_string(args->share) +
                                  " needs --lanes 1 (the shared normalisers serve one lane)");
    args->json_given = json_opt->count() > 0;
    args->size_given = size_opt->count() > 0;
    run_render(*args);
  });
}

}  // namespace shadecore::cli
