// SPDX-License-Identifier: Apache-2.0
// sc_light_params — the parameters of rtl/sc_light.v for a feature set, exactly as
// FeatureSet::verilog_params() (cmodel/include/shadecore/features.hpp) gives them: the one source
// for the RTL checks of rtl/CMakeLists.txt (no copied parameter lists).
//
//   sc_light_params SET [--tagw N]                 print -GNAME=VALUE ... (one line)
//   sc_light_params SET [--tagw N] -- TOOL ARG...  run TOOL; an argument @G@ becomes -GNAME=VALUE ...
//                                                  (Verilator), @P@ becomes -P NAME=VALUE ...
//                                                  (scripts/yosys_check.sh), @I@ becomes
//                                                  -Psc_light.NAME=VALUE ... (Icarus)
//
// SET is a name of config/configs.json "feature_sets" or a JSON file with one set. Errors: one line,
// exit status 2. With "--" the exit status is TOOL's.
#include <unistd.h>

#include <cstdio>
#include <cstdlib>
#include <exception>
#include <string>
#include <vector>

#include "shadecore/features.hpp"

int main(int argc, char** argv) {
  try {
    if (argc < 2) throw std::invalid_argument("usage: sc_light_params SET [--tagw N] [-- TOOL ARG...]");
    const shadecore::FeatureSet fs = shadecore::feature_set_named_or_file(argv[1]);
    int tagw = 8;
    int i = 2;
    for (; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "--") break;
      if (a == "--tagw" && i + 1 < argc) tagw = std::atoi(argv[++i]);
      else throw std::invalid_argument("unknown argument '" + a + "'");
    }
    const std::vector<std::string> params = fs.verilog_params(tagw);
    if (i >= argc) {
      for (size_t k = 0; k < params.size(); ++k) std::printf("%s-G%s", k ? " " : "", params[k].c_str());
      std::printf("\n");
      return 0;
    }
    std::vector<std::string> args;
    for (++i; i < argc; ++i) {
      const std::string a = argv[i];
      if (a == "@G@") {
        for (const auto& p : params) args.push_back("-G" + p);
      } else if (a == "@P@") {
        for (const auto& p : params) args.insert(args.end(), {"-P", p});
      } else if (a == "@I@") {
        for (const auto& p : params) args.push_back("-Psc_light." + p);
      } else {
        args.push_back(a);
      }
    }
    if (args.empty()) throw std::invalid_argument("no tool after --");
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
