// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — on-demand builds of the lighting core per feature set, and runs of a command stream
// through it (cli/light_rtl.hpp). The build is the CMake project sim/light_core (verilate() with the
// project's warning rules), configured and built per FeatureSet::key() into <cache>/<key>/; it is
// stamped with a hash of every source it is made of (RTL, testbench, C model headers, generated
// headers, the project), so an edited source rebuilds it; a lock file serialises concurrent builds of
// the same key (ctest -j). Every child runs through handoff::run_proc (fork/execvp, no shell).
#include "light_rtl.hpp"

#include <fcntl.h>
#include <sys/file.h>
#include <sys/stat.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <thread>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "coverage.hpp"
#include "handoff_bundle.hpp"
#include "output.hpp"
#include "shadecore/common/rtl_files.hpp"

namespace shadecore::cli {
namespace fs = std::filesystem;
namespace {

std::string read_all(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// Everything a simulator executable of `project` (sim/light_core, sim/unit_core) is built from: the project, the
// RTL, the headers, and the harness sources it compiles.
std::string sources_hash(const std::string& project, const std::vector<std::string>& harness_sources) {
  const fs::path src = SHADECORE_SOURCE_DIR, gen = SHADECORE_GENERATED_DIR;
  std::vector<fs::path> files = {src / project / "CMakeLists.txt", src / "rtl/lint/verilator_waiver.vlt"};
  auto add = [&files, &harness_sources](const fs::path& p) {
    const auto ext = p.extension();
    if (ext == ".v" || ext == ".vh" || ext == ".hpp" ||
        std::find(harness_sources.begin(), harness_sources.end(), p.filename().string()) != harness_sources.end())
      files.push_back(p);
  };
  for (const auto& dir : {src / "rtl", src / "sim", gen / "shadecore"})
    for (const auto& e : fs::directory_iterator(dir)) add(e.path());
  for (const auto& inc : {src / "cmodel/include", src / "stimulus/include", src / "common/include"})
    for (const auto& e : fs::recursive_directory_iterator(inc)) add(e.path());
  std::sort(files.begin(), files.end());
  uint64_t h = 1469598103934665603ull;
  auto mix = [&h](const std::string& s) {
    for (unsigned char c : s) {
      h ^= c;
      h *= 1099511628211ull;
    }
  };
  for (const auto& f : files) {
    mix(f.lexically_relative(f.parent_path().parent_path()).generic_string());
    mix(read_all(f));
  }
  return fmt::format("{:016x}", h);
}

// Elapsed-time ticker on stderr while a long step runs (only on a terminal).
class Ticker {
 public:
  explicit Ticker(std::string what, bool quiet) : what_(std::move(what)), on_(!quiet && isatty(2)) {
    if (!quiet) fmt::print(stderr, "shadecore: {} ...\n", what_);
    if (on_)
      th_ = std::thread([this] {
        const auto t0 = std::chrono::steady_clock::now();
        while (!stop_) {
          std::this_thread::sleep_for(std::chrono::milliseconds(250));
          const double s = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
          fmt::print(stderr, "\r  {} ... {:.0f} s", what_, s);
        }
        fmt::print(stderr, "\r\033[K");
      });
  }
  ~Ticker() {
    stop_ = true;
    if (th_.joinable()) th_.join();
  }

 private:
  std::string what_;
  bool on_;
  std::atomic<bool> stop_{false};
  std::thread th_;
};

struct Lock {
  int fd;
  explicit Lock(const fs::path& p) : fd(::open(p.c_str(), O_CREAT | O_RDWR, 0644)) {
    if (fd < 0 || ::flock(fd, LOCK_EX) != 0) throw std::runtime_error("cannot lock " + p.string());
  }
  ~Lock() {
    if (fd >= 0) ::close(fd);
  }
};

}  // namespace

Harness parse_harness(const std::string& name) {
  if (name == "systemc") return Harness::SystemC;
  if (name == "bare") return Harness::Bare;
  if (name == "axi") return Harness::Axi;
  throw std::invalid_argument("unknown harness '" + name + "' (known: systemc, bare, axi)");
}
const char* harness_name(Harness h) { return h == Harness::Bare ? "bare" : h == Harness::Axi ? "axi" : "systemc"; }

CoreBuild ensure_build(const ProjectBuild& pb, bool quiet) {
  const char* env = std::getenv("SHADECORE_CORE_CACHE");
  const fs::path cache = env && *env ? fs::path(env) : fs::path(SHADECORE_BINARY_DIR) / "cores";
  const fs::path dir = cache / pb.key;
  std::error_code ec;
  fs::create_directories(dir, ec);
  if (ec) throw std::runtime_error("cannot create the core cache " + dir.string() + ": " + ec.message());
  Lock lock(dir / ".lock");
  CoreBuild b;
  b.dir = dir.string();
  b.exe = (dir / pb.target).string();
  // One stamp per target: each is built when first asked for, against the sources of its time.
  const fs::path stamp_file = dir / pb.stamp;
  const std::string stamp = sources_hash(pb.project, pb.harness_sources);
  if (fs::exists(b.exe) && read_all(stamp_file) == stamp) return b;

  // Build: the generated files, then the CMake project (configure + build in the cache directory).
  const fs::path src = SHADECORE_SOURCE_DIR;
  if (pb.prepare) pb.prepare(dir);
  std::vector<std::string> configure = {
      SHADECORE_CMAKE_COMMAND, "-S", (src / pb.project).string(), "-B", dir.string(),
      "-G", SHADECORE_CMAKE_GENERATOR, "-DCMAKE_MAKE_PROGRAM=" SHADECORE_CMAKE_MAKE_PROGRAM,
      "-DCMAKE_CXX_COMPILER=" SHADECORE_CMAKE_CXX_COMPILER, "-DCMAKE_BUILD_TYPE=Release",
      "-DSHADECORE_SOURCE_DIR=" + src.string(), "-DSHADECORE_GENERATED_DIR=" SHADECORE_GENERATED_DIR};
  configure.insert(configure.end(), pb.defines.begin(), pb.defines.end());
  const std::vector<std::string> build = {SHADECORE_CMAKE_COMMAND, "--build", dir.string(), "--target", pb.target, "-j", "2"};
  const fs::path log = dir / pb.log;
  fs::remove(stamp_file, ec);
  // A cache shared between source trees ($SHADECORE_CORE_CACHE): CMake refuses a binary directory
  // configured from another source directory, so such a configuration starts afresh.
  if (fs::exists(dir / "CMakeCache.txt") &&
      read_all(dir / "CMakeCache.txt").find("CMAKE_HOME_DIRECTORY:INTERNAL=" + (src / pb.project).string() + "\n") ==
          std::string::npos) {
    fs::remove(dir / "CMakeCache.txt", ec);
    fs::remove_all(dir / "CMakeFiles", ec);
  }
  // Say why a build starts, where it goes and how long the last one took (issue 38: a new scene's first RTL
  // pixel waits for it; the time comes from <cache>/.last_build_seconds, written by every successful build).
  const fs::path last_file = cache / ".last_build_seconds";
  if (!quiet) {
    std::string last = read_all(last_file);
    if (last.empty() || last.size() > 8 || last.find_first_not_of("0123456789") != std::string::npos) last.clear();
    const std::string why = fs::exists(b.exe) ? "its RTL or testbench sources changed since it was built" : pb.first_use;
    fmt::print(stderr, "shadecore: {}: building its {} into {} (cached there for later runs){}\n", why, pb.noun, dir.string(),
               last.empty() ? "" : "; the last core build here took " + last + " s");
  }
  const auto t0 = std::chrono::steady_clock::now();
  int rc;
  std::string out;
  {
    Ticker t(pb.what, quiet);
    handoff::ProcOptions po;
    po.own_group = false;  // a terminal's ^C stops cmake, ninja, Verilator and the compiler too
    handoff::Proc p = handoff::run_proc(configure, fs::current_path(), po);
    out = "$ " + handoff::shell_join(configure) + "\n" + p.out;
    rc = p.status;
    if (rc == 0) {
      p = handoff::run_proc(build, fs::current_path(), po);
      out += "$ " + handoff::shell_join(build) + "\n" + p.out;
      rc = p.status;
    }
  }
  std::ofstream(log, std::ios::binary | std::ios::trunc) << out;
  b.build_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  if (rc != 0 || !fs::exists(b.exe))
    throw std::runtime_error("building the " + pb.noun + " failed (log: " + log.string() + ")");
  std::ofstream(stamp_file) << stamp;
  std::ofstream(last_file, std::ios::trunc) << fmt::format("{:.0f}", b.build_seconds);
  b.built_now = true;
  if (!quiet) fmt::print(stderr, "shadecore: built in {:.1f} s: {}\n", b.build_seconds, b.exe);
  return b;
}

CoreBuild ensure_core(const FeatureSet& feat, bool quiet, Harness harness, bool coverage, bool trace) {
  if (coverage && trace) throw std::invalid_argument("a core is built with coverage or with waveforms, not both");
  auto cmake_list = [](const std::vector<std::string>& v) {
    std::string s;
    for (const auto& e : v) s += (s.empty() ? "" : ";") + e;
    return s;
  };
  ProjectBuild pb;
  // The coverage and trace builds are directories of their own: the speed build of the set stays as it is.
  pb.key = feat.key() + (coverage ? "-cov" : "") + (trace ? "-trace" : "");
  pb.project = "sim/light_core";
  pb.harness_sources = {"light_main.cpp", "light_bare_main.cpp", "tb_light_run.cpp"};
  pb.target = harness == Harness::Bare  ? "shadecore_light_bare"
              : harness == Harness::Axi ? "shadecore_light_axi"
                                        : "shadecore_light_sim";
  pb.stamp = std::string("stamp") + (harness == Harness::SystemC ? "" : std::string(".") + harness_name(harness));
  pb.log = std::string("build") + (harness == Harness::SystemC ? "" : std::string(".") + harness_name(harness)) + ".log";
  // the AXI wrapper's own files (before the core's in light_axi_files): passed to every configuration of the set,
  // so the three targets share one CMake cache
  const std::vector<std::string> core_files = rtl::light_files(feat);
  std::vector<std::string> axi_files;
  for (const auto& f : rtl::light_axi_files(feat))
    if (std::find(core_files.begin(), core_files.end(), f) == core_files.end()) axi_files.push_back(f);
  pb.defines = {"-DSHADECORE_LIGHT_HARNESS_LIB=" SHADECORE_LIGHT_HARNESS_LIB,
                "-DSHADECORE_LIGHT_PARAMS=" + cmake_list(feat.verilog_params(32)),
                "-DSHADECORE_LIGHT_RTL=" + cmake_list(core_files),
                "-DSHADECORE_LIGHT_AXI_RTL=" + cmake_list(axi_files),
                std::string("-DSHADECORE_COVERAGE=") + (coverage ? "ON" : "OFF"),
                std::string("-DSHADECORE_TRACE=") + (trace ? "ON" : "OFF")};
  pb.noun = coverage ? "coverage core" : trace ? "trace core" : "core";
  pb.first_use = coverage ? "first coverage run of this feature set"
                 : trace  ? "first waveform of this feature set"
                          : "first use of this feature set";
  pb.what = fmt::format("building the lighting core '{}' [{}] ({} harness{}) for {}", feat.name, feat.key(),
                        harness_name(harness), coverage ? ", coverage build" : trace ? ", trace build" : "",
                        feat.summary());
  // The feature set's canonical JSON as a header (light_features.hpp) and as a file.
  pb.prepare = [&feat](const fs::path& dir) {
    std::ofstream h(dir / "light_features.hpp");
    h << "// generated by shadecore (cli/light_rtl.cpp) for one feature set — do not edit\n#pragma once\n"
      << "inline constexpr const char* kLightFeaturesJson = R\"sc_json(" << feat.canonical().dump(1)
      << ")sc_json\";\n";
    std::ofstream j(dir / "features.json");
    j << feat.canonical().dump(2) << "\n";
  };
  return ensure_build(pb, quiet);
}

RtlRunResult run_core_rtl(const FeatureSet& feat, const std::vector<sim::CoreCommand>& cmds, const RtlRunOptions& o) {
  RtlRunResult r;
  r.build = ensure_core(feat, o.quiet);
  char tmpl[] = "/tmp/shadecore_rtl_XXXXXX";
  if (!::mkdtemp(tmpl)) throw std::runtime_error("cannot create a temporary directory");
  const fs::path tmp = tmpl;
  struct Cleanup {
    fs::path p;
    ~Cleanup() {
      std::error_code ec;
      fs::remove_all(p, ec);
    }
  } cleanup{tmp};
  sim::write_commands((tmp / "cmds.bin").string(), cmds);
  const std::vector<std::string> argv = {
      r.build.exe, "--mode", "stream", "--quiet", "--label", feat.name, "--in", (tmp / "cmds.bin").string(),
      "--out", (tmp / "out.bin").string(), "--in-stall", fmt::format("{}", o.in_stall), "--out-stall",
      fmt::format("{}", o.out_stall), "--seed", std::to_string(o.seed)};
  ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  int rc;
  std::string log;
  {
    size_t frags = 0;
    for (const auto& c : cmds) frags += c.is_write ? 0 : 1;
    Ticker t(fmt::format("simulating {} fragments through the RTL core", frags), o.quiet);
    handoff::ProcOptions po;
    po.own_group = false;
    handoff::Proc p = handoff::run_proc(argv, fs::current_path(), po);
    rc = p.status;
    log = std::move(p.out);
  }
  const auto pos = log.find("COSIM-RESULT ");
  if (pos == std::string::npos) {
    std::string last = log.substr(0, log.find('\n'));
    throw std::runtime_error("the RTL simulation did not finish (exit " + std::to_string(rc) + "): " + last);
  }
  const auto j = nlohmann::json::parse(log.substr(pos + 13, log.find('\n', pos) - pos - 13));
  r.mismatches = j.at("mismatches").get<uint64_t>();
  r.cycles = j.at("cycles").get<uint64_t>();
  r.sim_seconds = j.at("wall_s").get<double>();
  r.ok = j.at("ok").get<bool>();
  const auto line = log.find("cosim: ");
  r.summary = line == std::string::npos ? "" : log.substr(line, log.find('\n', line) - line);
  if (fs::exists(tmp / "out.bin"))
    for (const auto& rec : sim::read_results((tmp / "out.bin").string())) r.colours.push_back(rec.c);
  return r;
}

}  // namespace shadecore::cli

namespace shadecore::cli {

int lighting_cosim(const LightCosimArgs& a) {
  if (a.mode != "random" && a.mode != "directed")
    throw std::invalid_argument("--core lighting: unknown mode '" + a.mode + "' (known: random, directed)");
  // Outputs (docs/cli.md): checked now, written together at the end — the waveform through a temporary file
  // the simulator writes; a FAIL keeps both, an error leaves neither.
  io::OutputSet outs;
  const int json_out = a.json_path.empty() ? -1 : outs.file("--json", a.json_path);
  const int trace_out = a.trace_path.empty() ? -1 : outs.file("--trace", a.trace_path, /*allow_stream=*/false);
  if (a.trace_all && trace_out < 0) throw std::invalid_argument("--trace-all needs --trace FILE");
  if (a.trace_all && !a.coverage_dir.empty())
    throw std::invalid_argument("--trace-all runs the trace build and --coverage the coverage build: not both (the "
                                "windowed --trace works with --coverage: only a failed run is run again for its waveform)");
  if (a.trace_window < 1 || a.trace_window > 1000000) throw std::invalid_argument("--trace-window: 1..1000000 cycles");
  const FeatureSet feat = feature_set_named_or_file(a.features);
  uint64_t seed = a.seed;
  if (seed == 0) {
    seed = std::chrono::steady_clock::now().time_since_epoch().count() ^ (uint64_t(::getpid()) << 32);
    if (seed == 0) seed = 1;
  }
  const Harness harness = parse_harness(a.harness);
  if (harness == Harness::Axi && !a.coverage_dir.empty())
    throw std::invalid_argument("--coverage is not built for the AXI harness yet (the wrapper's coverage map): use "
                                "--harness bare or systemc for the core's coverage");
  if (a.first != 0 && a.mode != "random") throw std::invalid_argument("--first applies to --mode random only");
  if (!a.coverage_dir.empty()) coverage::check_output_dir(a.coverage_dir, "--coverage");
  const CoreBuild b = ensure_core(feat, a.quiet, harness, !a.coverage_dir.empty(), a.trace_all);
  std::vector<std::string> argv = {
      b.exe, "--mode", a.mode, "--label", feat.name, "--count", std::to_string(a.count), "--seed",
      std::to_string(seed), "--in-stall", fmt::format("{}", a.in_stall), "--out-stall", fmt::format("{}", a.out_stall)};
  if (a.first != 0) argv.insert(argv.end(), {"--first", std::to_string(a.first)});
  if (a.write_rate >= 0) argv.insert(argv.end(), {"--write-rate", fmt::format("{}", a.write_rate)});
  if (a.reset_at != -2) argv.insert(argv.end(), {"--reset-at", std::to_string(a.reset_at)});
  if (!a.inject.empty()) argv.insert(argv.end(), {"--inject", a.inject});
  if (a.inject_at != 0) argv.insert(argv.end(), {"--inject-at", std::to_string(a.inject_at)});
  const std::vector<std::string> run_argv = argv;  // what a re-run for the waveform repeats
  if (a.trace_all) argv.insert(argv.end(), {"--trace", outs.produce_path(trace_out, {".hier"})});
  // --coverage DIR: the simulator writes its database into a scratch file under DIR, merged there at the end.
  const std::string cov_tmp =
      a.coverage_dir.empty() ? "" : (fs::path(a.coverage_dir) / fmt::format(".run.{}.dat", ::getpid())).string();
  if (!cov_tmp.empty()) {
    std::error_code ec;
    fs::create_directories(a.coverage_dir, ec);
    if (ec) throw std::runtime_error("--coverage: cannot create " + a.coverage_dir + ": " + ec.message());
    argv.insert(argv.end(), {"--coverage", cov_tmp});
  }
  struct Cleanup {
    std::string f;
    ~Cleanup() {
      std::error_code ec;
      if (!f.empty()) fs::remove(f, ec);
    }
  } cleanup{cov_tmp};
  ::setenv("SYSTEMC_DISABLE_COPYRIGHT_MESSAGE", "1", 1);
  // One simulator run: its COSIM-RESULT, its other lines shown (all, only the failure's when quiet, none when
  // silent: the re-run for a waveform, whose failure was shown already).
  const auto simulate = [](const std::vector<std::string>& args, bool quiet, bool silent = false) {
    nlohmann::json result;
    handoff::ProcOptions po;
    po.own_group = false;
    po.on_line = [&](const std::string& line) {
      if (line.rfind("COSIM-RESULT ", 0) == 0) result = nlohmann::json::parse(line.substr(13));
      else if (silent || line.rfind("cosim: waveform written to", 0) == 0) return;  // its temporary name: ours below
      else if (!quiet || line.rfind("cosim: FAIL", 0) == 0 || line.rfind("MISMATCH", 0) == 0 ||
               line.rfind("ERROR", 0) == 0 || line.rfind("cosim: reproduce", 0) == 0) {
        std::fputs(line.c_str(), stdout);
        std::fflush(stdout);
      }
    };
    const handoff::Proc p = handoff::run_proc(args, fs::current_path(), po);
    if (result.is_null()) {
      // The simulator refused its arguments or crashed: pass its words on, one line.
      std::string said = p.out;
      const auto at = said.find("error: ");
      said = at == std::string::npos ? "" : said.substr(at + 7, said.find('\n', at) - at - 7);
      throw std::runtime_error("the lighting-core simulator ended without a result (exit " + std::to_string(p.status) +
                               ")" + (said.empty() ? "" : ": " + said));
    }
    return result;
  };
  nlohmann::json result = simulate(argv, a.quiet);
  if (trace_out >= 0 && !a.trace_all) {
    if (result.at("ok").get<bool>()) {
      if (!a.quiet)
        fmt::print("cosim: PASS: no waveform written to {} (--trace keeps the cycles around the first failure; "
                   "--trace-all the whole run)\n", a.trace_path);
    } else {
      // The failure again on the trace build, dumping the window around its first error. The same options
      // give the same stimulus and the same timing (the stall generators are seeded), so the same first error.
      const uint64_t cycles = result.value("cycles", uint64_t{0});
      const uint64_t at = result["first_error_cycle"].is_number() ? result["first_error_cycle"].get<uint64_t>() : cycles;
      const uint64_t from = at > a.trace_window ? at - a.trace_window : 1, to = at + a.trace_window;
      if (!a.quiet)
        fmt::print("cosim: running the failure again on the trace build for its waveform (cycles {}..{}, first error at "
                   "cycle {})\n", from, to, at);
      std::fflush(stdout);
      const CoreBuild tb = ensure_core(feat, a.quiet, harness, false, /*trace=*/true);
      std::vector<std::string> again = run_argv;
      again[0] = tb.exe;
      again.insert(again.end(), {"--quiet", "--trace", outs.produce_path(trace_out, {".hier"}), "--trace-from",
                                 std::to_string(from), "--trace-to", std::to_string(to)});
      const nlohmann::json r2 = simulate(again, /*quiet=*/true, /*silent=*/true);
      for (const char* k : {"ok", "first_error_cycle", "vectors", "mismatches", "lost", "duplicated_or_reordered",
                            "latency_errors", "protocol_errors", "cycles"})
        if (r2.value(k, nlohmann::json()) != result.value(k, nlohmann::json()))
          throw std::runtime_error(fmt::format("--trace: the trace build's run did not repeat the failure ({} {} there, "
                                               "{} here): no waveform written",
                                               k, r2.value(k, nlohmann::json()).dump(), result.value(k, nlohmann::json()).dump()));
      result["trace"] = {{"file", a.trace_path}, {"from_cycle", from}, {"to_cycle", to}, {"build_dir", tb.dir}};
    }
  } else if (a.trace_all) {
    result["trace"] = {{"file", a.trace_path}, {"from_cycle", 1}, {"to_cycle", result.value("cycles", uint64_t{0})}};
  }
  result["build_dir"] = b.dir;
  result["built_now"] = b.built_now;
  result["build_s"] = b.build_seconds;
  if (!cov_tmp.empty()) coverage::canonicalise_from_build(cov_tmp, b.dir);  // parameterisations named (docs/coverage.md)
  if (!cov_tmp.empty())
    result["coverage"] = nlohmann::json::parse(
        coverage::report({cov_tmp}, a.coverage_dir, a.coverage_report ? coverage::waivers_in_use() : "", a.coverage_report,
                         a.quiet || !a.coverage_report, /*summary_file=*/a.coverage_report)["totals"]
            .dump());
  if (json_out >= 0) outs.set(json_out, result.dump(2) + "\n");
  outs.commit();  // a FAIL is a completed run: its JSON and waveform are its record
  if (result.contains("trace")) fmt::print("cosim: waveform written to {}\n", a.trace_path);
  std::fflush(stdout);
  return result.at("ok").get<bool>() ? 0 : kExitCheckFailed;
}

}  // namespace shadecore::cli
