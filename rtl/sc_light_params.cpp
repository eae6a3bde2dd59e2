// SPDX-License-Identifier: Apache-2.0
// sc_light_params — the parameters of rtl/sc_light.v for a feature set, exactly as
// FeatureSet::verilog_params() (cmodel/include/shadecore/features.hpp) gives them: the one source
// for the RTL checks of rtl/CMakeLists.txt (no copied parameter lists).
//
//   sc_light_params SET [--tagw N]                 print -GNAME=VALUE ... (one line)
//   sc_light_params SET [--tagw N] -- TOOL ARG...  run TOOL; an argument @G@ becomes -GNAME=VALUE ...
//                                                  (Verilator), @P@ becomes -P NAME=VALUE ...
//                                                  (scripts/yosys_check.sh), @I@ becomes
//                                                  -Psc_light.NAME=VALUE ... (Icarus), @F@ becomes
//                                                  the set's RTL files (config/configs.json "rtl",
//                                                  common/include/shadecore/common/rtl_files.hpp) in --rtl-dir DIR
//   sc_light_params --random N [--seed S] [--tagw N] --rtl-dir DIR -- TOOL ARG...
//                                                  draw N feature sets (every capability: lights and
//                                                  kinds, terms, unit, cutoff, norm, reflection, local
//                                                  viewer, normalize, channels, width), seeded, and run
//                                                  TOOL for each; each set is printed; exit status 0
//                                                  when TOOL succeeded for every set, else 1
//
// SET is a name of config/configs.json "feature_sets" or a JSON file with one set. Errors: one line,
// exit status 2. With "--" the exit status is TOOL's.
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <cerrno>
#include <cstdint>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "shadecore/common/rtl_files.hpp"
#include "shadecore/features.hpp"
#include "shadecore/units/table.hpp"

namespace {

using shadecore::FeatureSet;

// SplitMix64: a fixed, documented sequence for a seed (the test prints its seed).
struct SplitMix {
  uint64_t s;
  uint64_t next() {
    uint64_t z = (s += 0x9e3779b97f4a7c15ull);
    z = (z ^ (z >> 30)) * 0xbf58476d1ce4e5b9ull;
    z = (z ^ (z >> 27)) * 0x94d049bb133111ebull;
    return z ^ (z >> 31);
  }
  int below(int n) { return static_cast<int>(next() % static_cast<uint64_t>(n)); }
  bool coin() { return (next() >> 63) != 0; }
};

// A random legal feature set: every field drawn, then validated by the same parser as a user's file
// (an illegal draw, e.g. no term enabled, is drawn again).
FeatureSet random_set(SplitMix& rng, int index) {
  for (;;) {
    FeatureSet fs;
    std::vector<std::string> cfgs;
    for (const auto& c : shadecore::kConfigs)
      if (c.format.frac <= shadecore::kLightFracMax) cfgs.emplace_back(c.name);
    fs.config = cfgs[static_cast<size_t>(rng.below(static_cast<int>(cfgs.size())))];
    fs.slots.clear();
    const int n = 1 + rng.below(shadecore::kMaxLights);
    for (int j = 0; j < n; ++j) fs.slots.push_back(static_cast<uint8_t>(1 + rng.below(15)));  // a non-empty kind set (spot: bit 3)
    fs.lanes = 1 + rng.below(n);
    fs.ambient = rng.coin();
    fs.diffuse = rng.coin();
    fs.specular = rng.coin();
    std::vector<shadecore::VariantId> units;
    for (const auto& v : shadecore::kVariants)
      if (!shadecore::is_table_variant(v.id)) units.push_back(v.id);
    fs.variant = units[static_cast<size_t>(rng.below(static_cast<int>(units.size())))];
    fs.more_units.clear();
    if (fs.variant != shadecore::VariantId::schlick_iter)
      for (auto u : units)  // further units the material can choose (schlick_iter only alone)
        if (u != fs.variant && u != shadecore::VariantId::schlick_iter && rng.below(4) == 0) fs.more_units.push_back(u);
    fs.cutoff = rng.coin() ? shadecore::Cutoff::SignClamp : shadecore::Cutoff::ThetaCr;
    if (!fs.specular || !fs.has_unit(shadecore::VariantId::cs16)) fs.cutoff = shadecore::Cutoff::ThetaCr;
    fs.norm = fs.specular && rng.coin();
    const int refl = rng.below(3);  // Blinn, Phong or both
    fs.blinn = refl != 1;
    fs.phong = refl != 0;
    fs.local_viewer = rng.coin();
    fs.normalize = rng.coin();
    fs.channels = rng.coin() ? 3 : 1;
    fs.share = fs.lanes == 1 ? 1 + rng.below(shadecore::kShareMax) : 1;  // drawn last: the earlier draws are as before
    try {
      FeatureSet checked = shadecore::feature_set_from_json(fs.canonical(), "random set");
      checked.name = "random" + std::to_string(index);
      return checked;
    } catch (const std::invalid_argument&) {
      continue;
    }
  }
}

std::vector<std::string> substitute(const FeatureSet& fs, int tagw, const std::string& rtl_dir,
                                    const std::vector<std::string>& tool) {
  const std::vector<std::string> params = fs.verilog_params(tagw);
  std::vector<std::string> args;
  for (const auto& a : tool) {
    if (a == "@G@") {
      for (const auto& p : params) args.push_back("-G" + p);
    } else if (a == "@P@") {
      for (const auto& p : params) args.insert(args.end(), {"-P", p});
    } else if (a == "@I@") {
      for (const auto& p : params) args.push_back("-Psc_light." + p);
    } else if (a == "@F@") {
      if (rtl_dir.empty()) throw std::invalid_argument("@F@ needs --rtl-dir DIR");
      for (const auto& f : shadecore::rtl::light_files(fs)) args.push_back(rtl_dir + "/" + f);
    } else {
      args.push_back(a);
    }
  }
  if (args.empty()) throw std::invalid_argument("no tool after --");
  return args;
}

int run_and_wait(std::vector<std::string> args) {
  std::vector<char*> cargs;
  for (auto& a : args) cargs.push_back(a.data());
  cargs.push_back(nullptr);
  std::fflush(stdout);
  const pid_t pid = ::fork();
  if (pid < 0) throw std::runtime_error("fork failed");
  if (pid == 0) {
    ::execvp(cargs[0], cargs.data());
    std::fprintf(stderr, "sc_light_params: error: cannot run '%s'\n", cargs[0]);
    ::_exit(127);
  }
  int st = 0;
  while (::waitpid(pid, &st, 0) < 0 && errno == EINTR) {
  }
  return WIFEXITED(st) ? WEXITSTATUS(st) : 128;
}

}  // namespace

// What --help prints (and the usage line of a call without arguments).
constexpr const char* kUsage = "usage: sc_light_params SET|--random N [--seed S] [--tagw N] [--rtl-dir DIR] [-- TOOL ARG...]";
constexpr const char* kHelp =
    "sc_light_params — the Verilog parameters of rtl/sc_light.v for a lighting feature set\n"
    "\n"
    "  sc_light_params SET [--tagw N]                  print -GNAME=VALUE ... (one line)\n"
    "  sc_light_params SET [--tagw N] [--rtl-dir DIR] -- TOOL ARG...\n"
    "                                                  run TOOL; in its arguments @G@ becomes -GNAME=VALUE ...\n"
    "                                                  (Verilator), @P@ -P NAME=VALUE ... (Yosys), @I@\n"
    "                                                  -Psc_light.NAME=VALUE ... (Icarus), @F@ the set's RTL files in DIR\n"
    "  sc_light_params --random N [--seed S] [--tagw N] --rtl-dir DIR -- TOOL ARG...\n"
    "                                                  draw N random feature sets (seeded) and run TOOL for each;\n"
    "                                                  exit 0 when TOOL succeeded for every set, else 1\n"
    "\n"
    "SET is a feature set named in config/configs.json \"feature_sets\" or a JSON file with one set\n"
    "(docs/lighting.md). Errors: one line on stderr, exit status 2; with -- the exit status is TOOL's.\n";

int main(int argc, char** argv) {
  try {
    for (int k = 1; k < argc && std::string(argv[k]) != "--"; ++k)
      if (std::string(argv[k]) == "--help" || std::string(argv[k]) == "-h") {
        std::printf("%s\n%s", kUsage, kHelp);
        return 0;
      }
    if (argc < 2) throw std::invalid_argument(std::string(kUsage) + " (--help: what each form does)");
    int tagw = 8;
    int random = 0;
    uint64_t seed = 1;
    std::string set, rtl_dir;
    int i = 1;
    for (; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--") break;
      if (a == "--tagw" && i + 1 < argc) tagw = std::atoi(argv[++i]);
      else if (a == "--random" && i + 1 < argc) random = std::atoi(argv[++i]);
      else if (a == "--seed" && i + 1 < argc) seed = std::strtoull(argv[++i], nullptr, 10);
      else if (a == "--rtl-dir" && i + 1 < argc) rtl_dir = argv[++i];
      else if (set.empty() && a.rfind("--", 0) != 0) set = a;
      else throw std::invalid_argument("unknown argument '" + a + "' (see sc_light_params --help)");
    }
    std::vector<std::string> tool(argv + std::min(i + 1, argc), argv + argc);
    if (random > 0) {
      if (i >= argc) throw std::invalid_argument("--random needs -- TOOL ARG...");
      std::printf("sc_light_params: %d random feature sets, seed %llu\n", random, static_cast<unsigned long long>(seed));
      SplitMix rng{seed};
      int failed = 0;
      for (int k = 0; k < random; ++k) {
        const FeatureSet fs = random_set(rng, k);
        std::printf("sc_light_params: set %d/%d: %s\n  %s\n", k + 1, random, fs.canonical().dump().c_str(),
                    fs.summary().c_str());
        const int rc = run_and_wait(substitute(fs, tagw, rtl_dir, tool));
        if (rc != 0) {
          ++failed;
          std::printf("sc_light_params: set %d/%d FAILED (exit %d)\n", k + 1, random, rc);
        }
      }
      std::printf("sc_light_params: %s: %d of %d random feature sets failed (seed %llu)\n", failed ? "FAIL" : "PASS",
                  failed, random, static_cast<unsigned long long>(seed));
      return failed ? 1 : 0;
    }
    if (set.empty()) throw std::invalid_argument("no feature set given");
    const FeatureSet fs = shadecore::feature_set_named_or_file(set);
    if (i >= argc) {
      const std::vector<std::string> params = fs.verilog_params(tagw);
      for (size_t k = 0; k < params.size(); ++k) std::printf("%s-G%s", k ? " " : "", params[k].c_str());
      std::printf("\n");
      return 0;
    }
    std::vector<std::string> args = substitute(fs, tagw, rtl_dir, tool);
    std::vector<char*> cargs;
    for (auto& a : args) cargs.push_back(a.data());
    cargs.push_back(nullptr);
    std::fflush(stdout);
    execvp(cargs[0], cargs.data());
    throw std::runtime_error("cannot run '" + args[0] + "'");
  } catch (const std::exception& e) {
    std::fprintf(stderr, "sc_light_params: error: %s\n", e.what());
    return 2;
  }
}
