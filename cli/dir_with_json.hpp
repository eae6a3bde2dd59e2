// SPDX-License-Identifier: Apache-2.0
// cli/dir_with_json.hpp — the outputs of a command that writes a set of named images into a directory and a JSON
// report that may lie inside that directory (gl-compare --out-dir, replay --out): both checked now and written
// together at the end through one io::OutputSet (docs/cli.md's output rules).
#pragma once

#include <algorithm>
#include <filesystem>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/common/output_files.hpp"

namespace shadecore::cli {

struct DirWithJson {
  int dir = -1;             // the directory's output (-1: no directory given)
  int json = -1;            // the JSON as a file of its own (-1: none, or it is json_member of the directory)
  std::string json_member;  // the JSON's name inside the directory, when --json points there
};

// `names` are the images the directory will hold; a --json inside the directory joins them unless it would
// overwrite one of them (std::invalid_argument, one line naming dir_opt).
inline DirWithJson plan_dir_with_json(io::OutputSet& outs, const std::string& dir_opt, const std::string& dir,
                                      std::vector<std::string> names, bool json_given, const std::string& json_path) {
  namespace fsys = std::filesystem;
  DirWithJson r;
  if (json_given && !dir.empty()) {
    const fsys::path jp = fsys::absolute(json_path).lexically_normal(), dp = fsys::absolute(dir).lexically_normal();
    if (jp.parent_path() == dp) {
      r.json_member = jp.filename().string();
      if (std::find(names.begin(), names.end(), r.json_member) != names.end())
        throw std::invalid_argument("--json " + json_path + " is one of the images written to " + dir_opt);
    }
  }
  if (!dir.empty()) {
    if (!r.json_member.empty()) names.push_back(r.json_member);
    r.dir = outs.dir(dir_opt, dir, names);
  }
  r.json = !json_given || !r.json_member.empty() ? -1 : outs.file("--json", json_path);
  return r;
}

}  // namespace shadecore::cli
