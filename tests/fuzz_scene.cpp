// SPDX-License-Identifier: Apache-2.0
// shadecore — scene-input fuzzer for `shadecore render` (issue 23; docs/scenes.md "Limits", "Fuzzing").
//
// From a seed and for a bounded time (or number of iterations) it mutates the example scenes scenes/*.json and
// the OBJ files scenes/meshes/*.obj — JSON-tree mutations (nasty values: NaN, 1e999, -0, huge integers, 16.0,
// "", NUL, control characters, deep nesting; swapped types, removed keys, unknown and duplicated keys, special
// files as OBJ paths), byte-level mutations (flips, insertions, truncation, NULs) and OBJ line mutations — writes
// them into a temporary directory and runs the real CLI
//     shadecore render MUTATED --out DIR --json J --size 16x12
// as a subprocess, checking the rule of docs/cli.md:
//   * no crash: the exit status is 0 or 1 (never a signal, 134, 139), and no hang (killed after --timeout s);
//   * status 1: stderr is exactly one line "shadecore: error: …" without control characters; neither DIR nor J
//     exists and no ".shadecore.*" temporary file is left anywhere in the temporary directory;
//   * status 0: DIR/cmodel.png, exact.png, diff_exact.png and J exist.
// Tessellation counts are clamped in tree mutations (slices, stacks, sides, rings, subdivisions ≤ 64, contact-sheet
// cells ≤ 32) so that one render stays well under a second.
// A share of the iterations (--capture-share, 0.2) fuzzes `shadecore replay` instead (issue 37, docs/replay.md): an
// apitrace capture — the hand-built ones of tests/replay_capture.hpp, or the *.trace files of --captures DIR — has
// its decompressed stream mutated byte by byte, is recompressed into Snappy chunks of a random size and runs as
//     shadecore replay MUTATED.trace --frame K --out DIR --json J
// under the same rules (status 0: DIR/cmodel.png, exact.png and J exist).
// On a failure it prints the seed, the iteration and what failed, saves the input under --keep (default
// ./fuzz_scene_failures/seed<S>_it<I>/) and exits 1 (with --keep-going: after the run, if any failed).
//
//   shadecore_fuzz_scene [--seconds 60] [--iterations N] [--seed 1] [--timeout 30] [--keep DIR] [--keep-going]
//                        [--cli PATH] [--scenes DIR] [--captures DIR] [--capture-share F] [--verbose]
#include <fcntl.h>
#include <signal.h>
#include <sys/stat.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <functional>
#include <iostream>
#include <map>
#include <random>
#include <sstream>
#include <string>
#include <thread>
#include <vector>

#include <nlohmann/json.hpp>

#include "replay_capture.hpp"

#ifndef SHADECORE_CLI
#error "SHADECORE_CLI must point at the shadecore executable"
#endif
#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must point at the source tree"
#endif

namespace fs = std::filesystem;
using json = nlohmann::ordered_json;

namespace {

using Rng = std::mt19937_64;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}
void spit(const fs::path& p, const std::string& s) { std::ofstream(p, std::ios::binary) << s; }

size_t pick(Rng& r, size_t n) { return std::uniform_int_distribution<size_t>(0, n - 1)(r); }
bool chance(Rng& r, double p) { return std::uniform_real_distribution<double>(0, 1)(r) < p; }

std::string nest(size_t n) { return std::string(n, '[') + std::string(n, ']'); }

// Raw JSON texts put in place of a value.
const std::vector<std::string>& nasty_values() {
  static const std::vector<std::string> v = {
      "NaN", "nan", "Infinity", "-Infinity", "1e999", "-1e999", "1e308", "1e-300", "-1e-300", "1e300", "-0", "-0.0",
      "0", "1", "-1", "2", "3", "7", "16", "16.0", "1.6e1", "16.5", "0.5", "1e-9", "255", "256", "1023", "1024", "1025",
      "4096", "4097", "65536", "2147483647", "2147483648", "-2147483649", "9223372036854775807", "9223372036854775808",
      "18446744073709551615", "18446744073709551616", "99999999999999999999", "-9223372036854775809",
      std::string(400, '9'), "0." + std::string(400, '0') + "1", "1e", "--1", "01", ".5", "+1",
      "\"\"", "\"\\u0000\"", "\"a\\u0000b\"", "\"meshes/knot.obj\\u0000ignored\"", "\"\\u001b[2J\"", "\"\\n\"",
      "\"\\t\\r\\u007f\\u009b\"", "\"\\ud800\"", "\"\\udc00x\"", "\"" + std::string(300, 'x') + "\"", "\"table256\"",
      "\"table1024\"", "\"cs16\"", "\"cs16_faithful\"", "\"cs16_compact\"", "\"schlick_nr\"", "\"schlick_div\"",
      "\"schlick_iter\"", "\"flat\"", "\"gouraud\"", "\"phong\"", "\"scene\"", "\"sphere\"", "\"torus\"", "\"mesh\"",
      "\"plane\"", "\"quad\"", "\"narrow\"", "\"wide\"", "\"sign_clamp\"", "\"theta_cr\"", "\"blinn_ndf\"",
      "\"/dev/zero\"", "\"/dev/null\"", "\"meshes\"", "\"meshes/\"", "\"@FIFO@\"", "\"@LOOP@\"", "\"/\"",
      "null", "true", "false", "[]", "{}", "[0]", "[0, 0, 0]", "[1e-300, 0, 0]", "[0, 0, 1e-300, 0]",
      "[1e300, 1e300, 1e300]", "[0, 0, 0, 0]", "[30, 1e-300, 0, 0]", "[30, 0, 0, 0]", "[1e300, 0, 1, 0]", "[1, 1]",
      "[1e-300, 1e-300]", "[16, 16]", "[0, 0]", "[1, 2, 3, 4, 5]", "[\"flat\", \"flat\"]", "[\"table256\"]",
      "{\"_comment\": 1}", "{\"a\": 1}", nest(63), nest(64), nest(65), nest(2000), nest(150000), "[" + nest(62) + "]",
      "{\"model\": \"blinn\"}", "{\"model\": \"nope\", \"coefficient\": \"classical\"}",
      "{\"width\": 16.0, \"height\": 12.0}", "[0, 1, 1, 1e-300]",
  };
  return v;
}
const std::vector<std::string>& nasty_keys() {
  static const std::vector<std::string> v = {"\\u001b[2J", "a\\u0000b", "\\u0000", "", "_comment", "\\n", "\\u007f",
                                             "x\\u009by", std::string(200, 'k'), "image", "type", "file", "name",
                                             "slices", "camera", "lights", "materials", "objects", "\\ud800"};
  return v;
}

// Every value node of the tree (pre-order), with its parent and key/index, for mutation.
struct Node {
  json* v;
  json* parent;
  std::string key;  // when parent is an object
  size_t idx = 0;   // when parent is an array
};
void collect(json& j, json* parent, const std::string& key, size_t idx, std::vector<Node>& out) {
  out.push_back({&j, parent, key, idx});
  if (j.is_object())
    for (auto it = j.begin(); it != j.end(); ++it) collect(it.value(), &j, it.key(), 0, out);
  else if (j.is_array())
    for (size_t i = 0; i < j.size(); ++i) collect(j[i], &j, "", i, out);
}

// Caps the tessellation and sheet sizes (a valid render must stay fast).
void clamp_counts(json& j) {
  if (j.is_object()) {
    for (auto it = j.begin(); it != j.end(); ++it) {
      const std::string& k = it.key();
      json& v = it.value();
      const bool count = k == "slices" || k == "stacks" || k == "sides" || k == "rings" || k == "subdivisions";
      if (count && v.is_number() && v.get<double>() > 64 && v.get<double>() <= 1e6) v = 64;
      if (k == "cell" && v.is_array())
        for (auto& c : v)
          if (c.is_number() && c.get<double>() > 32 && c.get<double>() <= 1e6) c = 32;
      clamp_counts(v);
    }
  } else if (j.is_array()) {
    for (auto& e : j) clamp_counts(e);
  }
}

struct Mutated {
  std::string scene;
  std::map<std::string, std::string> meshes;  // name -> text
  std::string how;
};

std::string tree_mutation(const std::string& base, Rng& r, std::string& how) {
  json root = json::parse(base);
  std::map<std::string, std::string> raw;  // placeholder -> raw text
  int ph = 0;
  auto placeholder = [&](const std::string& text) {
    const std::string p = "@@P" + std::to_string(ph++) + "@@";
    raw["\"" + p + "\""] = text;
    return p;
  };
  const int n = 1 + static_cast<int>(pick(r, 4));
  for (int m = 0; m < n; ++m) {
    std::vector<Node> nodes;
    collect(root, nullptr, "", 0, nodes);
    Node& nd = nodes[pick(r, nodes.size())];
    const int op = static_cast<int>(pick(r, 7));
    if (op <= 2) {  // a nasty value
      const std::string& t = nasty_values()[pick(r, nasty_values().size())];
      *nd.v = placeholder(t);
      how += " value:" + t.substr(0, 24);
    } else if (op == 3 && nd.parent && nd.parent->is_object()) {  // remove the key
      nd.parent->erase(nd.key);
      how += " remove:" + nd.key;
    } else if (op == 3 && nd.parent && nd.parent->is_array() && !nd.parent->empty()) {
      nd.parent->erase(nd.idx);
      how += " remove:[" + std::to_string(nd.idx) + "]";
    } else if (op == 4 && nd.v->is_object()) {  // a nasty or duplicated key
      std::string k;
      if (!nd.v->empty() && chance(r, 0.5)) {
        auto it = nd.v->begin();
        std::advance(it, static_cast<long>(pick(r, nd.v->size())));
        k = it.key();
      } else {
        k = nasty_keys()[pick(r, nasty_keys().size())];
      }
      const std::string p = placeholder("");
      (*nd.v)[p] = placeholder(nasty_values()[pick(r, nasty_values().size())]);
      raw.erase("\"" + p + "\"");
      raw["\"" + p + "\""] = "\"" + k + "\"";  // the key text itself
      how += " key:" + k.substr(0, 24);
    } else if (op == 5) {  // swapped type
      json& v = *nd.v;
      if (v.is_number()) v = v.dump();
      else if (v.is_string()) v = json::array({v});
      else if (v.is_array()) v = v.empty() ? json(0) : v[0];
      else if (v.is_object()) v = json::array({v});
      else v = json::object();
      how += " swap";
    } else if (op == 6 && nd.v->is_array() && !nd.v->empty()) {  // duplicated element
      nd.v->push_back((*nd.v)[pick(r, nd.v->size())]);
      how += " dup-element";
    } else if (nd.v->is_number()) {  // a scaled number
      const double f[] = {0, -1, 1e-300, 1e300, 1.0000001, 16.0, 1e6, 1e-6, 0.5};
      *nd.v = nd.v->get<double>() * f[pick(r, 9)];
      how += " scale-number";
    }
  }
  clamp_counts(root);
  std::string text = root.dump(chance(r, 0.5) ? 2 : -1);
  for (const auto& [p, t] : raw) {
    for (size_t i; (i = text.find(p)) != std::string::npos;) text.replace(i, p.size(), t);
  }
  return text;
}

std::string byte_mutation(std::string s, Rng& r, std::string& how) {
  const int n = 1 + static_cast<int>(pick(r, 3));
  for (int m = 0; m < n && !s.empty(); ++m) {
    const int op = static_cast<int>(pick(r, 7));
    const size_t at = pick(r, s.size());
    switch (op) {
      case 0: s[at] = static_cast<char>(s[at] ^ (1 << pick(r, 8))); how += " flip"; break;
      case 1: s.insert(at, 1, static_cast<char>(pick(r, 256))); how += " insert-byte"; break;
      case 2: s.resize(at); how += " truncate"; break;
      case 3: s.insert(at, 1, '\0'); how += " NUL"; break;
      case 4: s.insert(at, nest(pick(r, 3) == 0 ? 100000 : 70)); how += " nest"; break;
      case 5: {  // duplicate a slice
        const size_t len = std::min(s.size() - at, pick(r, 80) + 1);
        s.insert(at, s.substr(at, len));
        how += " dup-slice";
        break;
      }
      default: {
        const char* toks[] = {"1e999", "\\u0000", "\\u001b", "-0", "16.0", ",", "\"", "NaN", "\xff", "\x7f"};
        s.insert(at, toks[pick(r, 10)]);
        how += " insert-token";
      }
    }
  }
  return s;
}

std::string obj_mutation(std::string s, Rng& r, std::string& how) {
  std::vector<std::string> lines;
  std::stringstream ss(s);
  for (std::string l; std::getline(ss, l);) lines.push_back(l);
  if (lines.empty()) lines.push_back("");
  const char* nums[] = {"nan", "NaN", "inf", "-inf", "1e400", "-0", "1e-400", "0x10", "", "abc", "1e308", "3.5"};
  const char* idx[] = {"0", "-1", "-99", "99999999999999999999", "2147483647", "2147483648", "-2147483648", "1/1/1",
                       "1//1", "1/", "/1", "1/2/3/4", "", "1.5", "+1", "-0"};
  const int n = 1 + static_cast<int>(pick(r, 3));
  for (int m = 0; m < n; ++m) {
    const size_t at = pick(r, lines.size());
    std::string& l = lines[at];
    const int op = static_cast<int>(pick(r, 7));
    if (op == 0 && l.rfind("v ", 0) == 0) {
      l = "v " + std::string(nums[pick(r, 12)]) + " 0 0";
      how += " obj-v";
    } else if (op == 1 && l.rfind("f ", 0) == 0) {
      l += " " + std::string(idx[pick(r, 16)]);
      how += " obj-f-index";
    } else if (op == 2) {
      lines.erase(lines.begin() + static_cast<long>(at));
      if (lines.empty()) lines.push_back("");
      how += " obj-drop-line";
    } else if (op == 3) {
      std::string f = "f";
      const size_t k = pick(r, 3) == 0 ? 300 : 1 + pick(r, 5);
      for (size_t i = 0; i < k; ++i) f += " " + std::to_string(1 + pick(r, 4));
      lines.push_back(f);
      how += " obj-face-" + std::to_string(k);
    } else if (op == 4) {
      lines.resize(at + 1);
      how += " obj-truncate";
    } else if (op == 5) {
      lines.insert(lines.begin() + static_cast<long>(at), "vn " + std::string(nums[pick(r, 12)]) + " 0 1");
      how += " obj-vn";
    } else {
      std::string t = byte_mutation(l, r, how);
      l = t;
    }
  }
  std::string out;
  for (const auto& l : lines) out += l + "\n";
  return out;
}

struct Run {
  int status = 0;  // exit status, 128 + signal, or -1 for a timeout
  std::string out, err;
};

Run run(const std::vector<std::string>& args, const fs::path& io, double timeout_s) {
  const std::string o = (io / "stdout").string(), e = (io / "stderr").string();
  const pid_t pid = ::fork();
  if (pid == 0) {
    const int fo = ::open(o.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fe = ::open(e.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
    const int fi = ::open("/dev/null", O_RDONLY);
    ::dup2(fo, 1), ::dup2(fe, 2), ::dup2(fi, 0);
    std::vector<char*> av;
    for (const auto& a : args) av.push_back(const_cast<char*>(a.c_str()));
    av.push_back(nullptr);
    ::execv(av[0], av.data());
    ::_exit(127);
  }
  Run r;
  const auto t0 = std::chrono::steady_clock::now();
  int ws = 0;
  for (;;) {
    const pid_t w = ::waitpid(pid, &ws, WNOHANG);
    if (w == pid) break;
    if (std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() > timeout_s) {
      ::kill(pid, SIGKILL);
      ::waitpid(pid, &ws, 0);
      r.status = -1;
      break;
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(5));
  }
  if (r.status != -1) r.status = WIFEXITED(ws) ? WEXITSTATUS(ws) : 128 + (WIFSIGNALED(ws) ? WTERMSIG(ws) : 0);
  r.out = slurp(o);
  r.err = slurp(e);
  return r;
}

bool has_temp_left(const fs::path& dir) {
  std::error_code ec;
  for (auto it = fs::recursive_directory_iterator(dir, fs::directory_options::skip_permission_denied, ec);
       it != fs::recursive_directory_iterator(); it.increment(ec)) {
    if (ec) break;
    if (it->path().filename().string().rfind(".shadecore.", 0) == 0) return true;
    if (it->is_symlink(ec) || it->is_fifo(ec)) it.disable_recursion_pending();
  }
  return false;
}

}  // namespace

int main(int argc, char** argv) {
  double seconds = 60, timeout_s = 30;
  long long iterations = -1;
  unsigned long long seed = 1;
  std::string cli = SHADECORE_CLI, scenes = std::string(SHADECORE_SOURCE_DIR) + "/scenes", keep = "fuzz_scene_failures";
  std::string captures_dir;
  double capture_share = 0.2;
  bool keep_going = false, verbose = false;
  for (int i = 1; i < argc; ++i) {
    const std::string a = argv[i];
    auto val = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::cerr << "shadecore_fuzz_scene: error: " << a << " needs a value\n";
        std::exit(2);
      }
      return argv[++i];
    };
    if (a == "--seconds") seconds = std::stod(val());
    else if (a == "--iterations") iterations = std::stoll(val());
    else if (a == "--seed") seed = std::stoull(val());
    else if (a == "--timeout") timeout_s = std::stod(val());
    else if (a == "--keep") keep = val();
    else if (a == "--cli") cli = val();
    else if (a == "--scenes") scenes = val();
    else if (a == "--captures") captures_dir = val();
    else if (a == "--capture-share") capture_share = std::stod(val());
    else if (a == "--keep-going") keep_going = true;
    else if (a == "--verbose") verbose = true;
    else {
      std::cerr << "shadecore_fuzz_scene: error: unknown argument " << a << "\n";
      return 2;
    }
  }
  std::vector<std::pair<std::string, std::string>> bases;  // name, text
  std::map<std::string, std::string> meshes;
  for (const auto& e : fs::directory_iterator(scenes))
    if (e.path().extension() == ".json") bases.emplace_back(e.path().filename().string(), slurp(e.path()));
  for (const auto& e : fs::directory_iterator(fs::path(scenes) / "meshes"))
    if (e.path().extension() == ".obj") meshes[e.path().filename().string()] = slurp(e.path());
  std::sort(bases.begin(), bases.end());
  if (bases.empty()) {
    std::cerr << "shadecore_fuzz_scene: error: no scenes in " << scenes << "\n";
    return 2;
  }
  // capture streams (decompressed): hand-built ones, and those of --captures DIR
  std::vector<std::pair<std::string, std::string>> streams = {
      {"tiny1", shadecore::test::tiny_stream(1)},
      {"tiny3_arrays", shadecore::test::tiny_stream(3, false, true)},
      {"core_profile", shadecore::test::tiny_stream(1, true)}};
  if (!captures_dir.empty())
    for (const auto& e : fs::directory_iterator(captures_dir))
      if (e.path().extension() == ".trace") {
        const std::string f = slurp(e.path());
        std::string out;
        bool ok = f.size() > 2 && f[0] == 'a' && f[1] == 't';
        for (size_t at = 2; ok && at + 4 <= f.size();) {
          const auto* b = reinterpret_cast<const unsigned char*>(f.data() + at);
          const size_t n = size_t{b[0]} | size_t{b[1]} << 8 | size_t{b[2]} << 16 | size_t{b[3]} << 24;
          std::string chunk;
          ok = at + 4 + n <= f.size() && snappy::Uncompress(f.data() + at + 4, n, &chunk);
          out += chunk;
          at += 4 + n;
        }
        if (ok) streams.emplace_back(e.path().filename().string(), out);
        else std::cerr << "shadecore_fuzz_scene: note: " << e.path().string() << " is not a Snappy capture, skipped\n";
      }
  long long replay_runs = 0;
  const fs::path work = fs::temp_directory_path() / ("shadecore_fuzz_" + std::to_string(::getpid()));
  fs::remove_all(work);
  Rng rng(seed);
  const auto t0 = std::chrono::steady_clock::now();
  long long it = 0, ok0 = 0, ok1 = 0, failures = 0;
  std::map<std::string, long long> first_words;  // what the errors were about (summary)
  for (; iterations < 0 ? std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count() < seconds
                        : it < iterations;
       ++it) {
    fs::remove_all(work);
    const fs::path dir = work / "in", io = work / "io";
    fs::create_directories(dir / "meshes");
    fs::create_directories(io);
    fs::create_directories(dir / "adir");
    ::mkfifo((dir / "fifo").c_str(), 0600);
    fs::create_symlink("loop2", dir / "loop1");
    fs::create_symlink("loop1", dir / "loop2");
    if (chance(rng, capture_share)) {  // a mutated capture through `shadecore replay`
      ++replay_runs;
      const auto& [cname, cstream] = streams[pick(rng, streams.size())];
      std::string how = cname + ":";
      const std::string mutated = byte_mutation(cstream, rng, how);
      const std::string file = shadecore::test::container(mutated, 1 + pick(rng, 4096));
      spit(dir / "in.trace", file);
      const std::string frame = std::to_string(1 + pick(rng, 3));
      const fs::path out = dir / "out", js = dir / "report.json";
      const Run r = run({cli, "replay", (dir / "in.trace").string(), "--frame", frame, "--out", out.string(), "--json",
                         js.string()},
                        io, timeout_s);
      std::string bad;
      if (r.status == -1) bad = "hang: killed after " + std::to_string(timeout_s) + " s";
      else if (r.status != 0 && r.status != 1) bad = "exit status " + std::to_string(r.status) + " (crash?)";
      else if (r.status == 1) {
        ++ok1;
        const long nl = std::count(r.err.begin(), r.err.end(), '\n');
        if (nl != 1 || r.err.back() != '\n') bad = "status 1 with " + std::to_string(nl) + " lines on stderr";
        else if (r.err.rfind("shadecore: error: ", 0) != 0) bad = "the error line does not start with 'shadecore: error: '";
        else if (std::any_of(r.err.begin(), r.err.end() - 1,
                             [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
          bad = "control character in the error line";
        else if (fs::exists(out) || fs::exists(js)) bad = "status 1 but an output exists";
      } else {
        ++ok0;
        for (const char* f : {"cmodel.png", "exact.png"})
          if (!fs::exists(out / f)) bad = std::string("status 0 but ") + f + " is missing";
        if (!fs::exists(js)) bad = "status 0 but the JSON is missing";
      }
      if (bad.empty() && has_temp_left(dir)) bad = "a .shadecore.* temporary file was left";
      if (verbose) std::cout << "it " << it << " replay status " << r.status << " " << how << "\n  " << r.err;
      if (!bad.empty()) {
        ++failures;
        const fs::path k = fs::path(keep) / ("seed" + std::to_string(seed) + "_it" + std::to_string(it));
        fs::create_directories(k);
        spit(k / "in.trace", file);
        spit(k / "stderr", r.err);
        std::cout << "FAIL seed " << seed << " iteration " << it << ": " << bad << "\n  mutation: " << how
                  << "\n  stderr: " << r.err.substr(0, 400) << "\n  input saved in " << k.string() << " (rerun: " << cli
                  << " replay " << (k / "in.trace").string() << " --frame " << frame << ")\n";
        if (!keep_going) break;
      }
      continue;
    }
    const auto& [bname, btext] = bases[pick(rng, bases.size())];
    Mutated m;
    m.how = bname + ":";
    m.meshes = meshes;
    const int kind = static_cast<int>(pick(rng, 10));
    if (kind < 6) m.scene = tree_mutation(btext, rng, m.how);
    else if (kind < 8) m.scene = byte_mutation(btext, rng, m.how);
    else {
      m.scene = chance(rng, 0.5) ? btext : tree_mutation(btext, rng, m.how);
      auto mit = m.meshes.begin();
      std::advance(mit, static_cast<long>(pick(rng, m.meshes.size())));
      m.how += " " + mit->first + ":";
      mit->second = obj_mutation(mit->second, rng, m.how);
    }
    for (const auto& [p, t] : std::map<std::string, std::string>{{"@FIFO@", "fifo"}, {"@LOOP@", "loop1"}})
      for (size_t i; (i = m.scene.find(p)) != std::string::npos;) m.scene.replace(i, p.size(), t);
    spit(dir / "scene.json", m.scene);
    for (const auto& [n, t] : m.meshes) spit(dir / "meshes" / n, t);
    const fs::path out = dir / "out", js = dir / "report.json";
    const Run r = run({cli, "render", (dir / "scene.json").string(), "--out", out.string(), "--json", js.string(),
                       "--size", "16x12"},
                      io, timeout_s);
    std::string bad;
    if (r.status == -1) bad = "hang: killed after " + std::to_string(timeout_s) + " s";
    else if (r.status != 0 && r.status != 1) bad = "exit status " + std::to_string(r.status) + " (crash?)";
    else if (r.status == 1) {
      ++ok1;
      const long nl = std::count(r.err.begin(), r.err.end(), '\n');
      if (nl != 1 || r.err.back() != '\n') bad = "status 1 with " + std::to_string(nl) + " lines on stderr";
      else if (r.err.rfind("shadecore: error: ", 0) != 0) bad = "the error line does not start with 'shadecore: error: '";
      else if (std::any_of(r.err.begin(), r.err.end() - 1,
                           [](char c) { return static_cast<unsigned char>(c) < 0x20 || c == 0x7f; }))
        bad = "control character in the error line";
      else if (fs::exists(out)) bad = "status 1 but the output directory exists";
      else if (fs::exists(js)) bad = "status 1 but the JSON exists";
      const std::string msg = r.err.substr(std::min<size_t>(r.err.size(), 18));
      const auto c = msg.find(": ", msg.find(dir.string()) == 0 ? dir.string().size() + 12 : 0);
      first_words[msg.substr(c == std::string::npos ? 0 : c + 2, 28)]++;
    } else {
      ++ok0;
      for (const char* f : {"cmodel.png", "exact.png", "diff_exact.png"})
        if (!fs::exists(out / f)) bad = std::string("status 0 but ") + f + " is missing";
      if (!fs::exists(js)) bad = "status 0 but the JSON is missing";
    }
    if (bad.empty() && has_temp_left(dir)) bad = "a .shadecore.* temporary file was left";
    if (verbose) std::cout << "it " << it << " status " << r.status << " " << m.how << "\n  " << r.err;
    if (!bad.empty()) {
      ++failures;
      const fs::path k = fs::path(keep) / ("seed" + std::to_string(seed) + "_it" + std::to_string(it));
      fs::create_directories(k / "meshes");
      spit(k / "scene.json", m.scene);
      for (const auto& [n, t] : m.meshes) spit(k / "meshes" / n, t);
      spit(k / "stderr", r.err);
      spit(k / "stdout", r.out);
      std::cout << "FAIL seed " << seed << " iteration " << it << ": " << bad << "\n  mutation: " << m.how
                << "\n  stderr: " << r.err.substr(0, 400) << (r.err.empty() || r.err.back() != '\n' ? "\n" : "")
                << "  input saved in " << k.string() << " (rerun: " << cli << " render " << (k / "scene.json").string()
                << " --out OUT --json J --size 16x12)\n";
      if (!keep_going) break;
    }
  }
  fs::remove_all(work);
  const double el = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();
  std::cout << "shadecore_fuzz_scene: seed " << seed << ", " << it << " iterations in " << el << " s: " << ok0
            << " rendered, " << ok1 << " rejected (one line), " << failures << " failures; " << replay_runs
            << " of the iterations were mutated captures through replay\n";
  if (verbose)
    for (const auto& [w, c] : first_words) std::cout << "  " << c << "  " << w << "\n";
  return failures ? 1 : 0;
}
