// SPDX-License-Identifier: Apache-2.0
// shadecore handoff — small helpers of both bundles (cli/handoff_bundle.hpp): the source tree, files,
// tools on PATH, text, SHA-256, and the checks of the options both cores share.
#include <unistd.h>

#include <cstdlib>
#include <fstream>
#include <regex>
#include <sstream>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "handoff_bundle.hpp"
#include "shadecore/light_axi.hpp"
#include "unit_spec.hpp"

#ifndef SHADECORE_SOURCE_DIR
#error "SHADECORE_SOURCE_DIR must be defined by the build"
#endif

namespace shadecore::cli::handoff {

// ---------------------------------------------------------------------------- small helpers
std::string root_dir() {
  const char* env = std::getenv("SHADECORE_ROOT");
  return env && *env ? env : SHADECORE_SOURCE_DIR;
}

std::string read_text(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  if (!in) throw std::runtime_error("cannot read " + p.string());
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

void write_text(const fs::path& p, const std::string& s, bool exec) {
  fs::create_directories(p.parent_path());
  std::ofstream out(p, std::ios::binary | std::ios::trunc);
  out << s;
  out.close();
  if (!out) throw std::runtime_error("cannot write " + p.string());
  if (exec) fs::permissions(p, fs::perms::owner_exec | fs::perms::group_exec | fs::perms::others_exec, fs::perm_options::add);
}

bool on_path(const std::string& tool) {
  const char* path = std::getenv("PATH");
  std::stringstream ss(path ? path : "");
  std::string dir;
  while (std::getline(ss, dir, ':'))
    if (!dir.empty() && ::access((fs::path(dir) / tool).c_str(), X_OK) == 0) return true;
  return false;
}

std::string first_line(const std::string& s) { return s.substr(0, s.find('\n')); }

std::string last_line_with(const std::string& out, const std::string& needle) {
  std::stringstream ss(out);
  std::string line, found;
  while (std::getline(ss, line))
    if (line.find(needle) != std::string::npos) found = line;
  return found;
}

std::string shell_join(const std::vector<std::string>& argv) {
  std::string s;
  for (const auto& a : argv) {
    const bool plain = !a.empty() && a.find_first_not_of(
        "abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789_-+=./:,@%") == std::string::npos;
    s += (s.empty() ? "" : " ") + (plain ? a : "'" + a + "'");
  }
  return s;
}

// SHA-256 (FIPS 180-4), for MANIFEST.sha256 in `sha256sum` format.
std::string sha256_hex(const std::string& data) {
  static const uint32_t K[64] = {
      0x428a2f98, 0x71374491, 0xb5c0fbcf, 0xe9b5dba5, 0x3956c25b, 0x59f111f1, 0x923f82a4, 0xab1c5ed5, 0xd807aa98,
      0x12835b01, 0x243185be, 0x550c7dc3, 0x72be5d74, 0x80deb1fe, 0x9bdc06a7, 0xc19bf174, 0xe49b69c1, 0xefbe4786,
      0x0fc19dc6, 0x240ca1cc, 0x2de92c6f, 0x4a7484aa, 0x5cb0a9dc, 0x76f988da, 0x983e5152, 0xa831c66d, 0xb00327c8,
      0xbf597fc7, 0xc6e00bf3, 0xd5a79147, 0x06ca6351, 0x14292967, 0x27b70a85, 0x2e1b2138, 0x4d2c6dfc, 0x53380d13,
      0x650a7354, 0x766a0abb, 0x81c2c92e, 0x92722c85, 0xa2bfe8a1, 0xa81a664b, 0xc24b8b70, 0xc76c51a3, 0xd192e819,
      0xd6990624, 0xf40e3585, 0x106aa070, 0x19a4c116, 0x1e376c08, 0x2748774c, 0x34b0bcb5, 0x391c0cb3, 0x4ed8aa4a,
      0x5b9cca4f, 0x682e6ff3, 0x748f82ee, 0x78a5636f, 0x84c87814, 0x8cc70208, 0x90befffa, 0xa4506ceb, 0xbef9a3f7,
      0xc67178f2};
  uint32_t h[8] = {0x6a09e667, 0xbb67ae85, 0x3c6ef372, 0xa54ff53a, 0x510e527f, 0x9b05688c, 0x1f83d9ab, 0x5be0cd19};
  std::string m = data;
  const uint64_t bits = static_cast<uint64_t>(data.size()) * 8;
  m += static_cast<char>(0x80);
  while (m.size() % 64 != 56) m += '\0';
  for (int i = 7; i >= 0; --i) m += static_cast<char>((bits >> (8 * i)) & 0xff);
  auto rotr = [](uint32_t x, int r) { return (x >> r) | (x << (32 - r)); };
  for (size_t off = 0; off < m.size(); off += 64) {
    uint32_t w[64];
    for (int i = 0; i < 16; ++i)
      w[i] = (uint32_t(uint8_t(m[off + 4 * i])) << 24) | (uint32_t(uint8_t(m[off + 4 * i + 1])) << 16) |
             (uint32_t(uint8_t(m[off + 4 * i + 2])) << 8) | uint32_t(uint8_t(m[off + 4 * i + 3]));
    for (int i = 16; i < 64; ++i) {
      const uint32_t s0 = rotr(w[i - 15], 7) ^ rotr(w[i - 15], 18) ^ (w[i - 15] >> 3);
      const uint32_t s1 = rotr(w[i - 2], 17) ^ rotr(w[i - 2], 19) ^ (w[i - 2] >> 10);
      w[i] = w[i - 16] + s0 + w[i - 7] + s1;
    }
    uint32_t a = h[0], b = h[1], c = h[2], d = h[3], e = h[4], f = h[5], g = h[6], hh = h[7];
    for (int i = 0; i < 64; ++i) {
      const uint32_t t1 = hh + (rotr(e, 6) ^ rotr(e, 11) ^ rotr(e, 25)) + ((e & f) ^ (~e & g)) + K[i] + w[i];
      const uint32_t t2 = (rotr(a, 2) ^ rotr(a, 13) ^ rotr(a, 22)) + ((a & b) ^ (a & c) ^ (b & c));
      hh = g; g = f; f = e; e = d + t1; d = c; c = b; b = a; a = t1 + t2;
    }
    h[0] += a; h[1] += b; h[2] += c; h[3] += d; h[4] += e; h[5] += f; h[6] += g; h[7] += hh;
  }
  std::string out;
  for (uint32_t v : h) out += fmt::format("{:08x}", v);
  return out;
}

nlohmann::json interface_ports(const std::string& key) {
  const fs::path p = fs::path(root_dir()) / "config" / "interface.json";
  try {
    return nlohmann::json::parse(read_text(p)).at(key);
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error("malformed " + p.string() + ": " + e.what());
  }
}

int eval_width(const std::string& expr, const Widths& w) {
  if (expr == "F+1") return w.frac + 1;
  if (expr == "F+2") return w.frac + 2;
  if (expr == "F+8") return w.frac + 8;
  if (expr == "TAGW") return w.tagw;
  if (expr == "COEFW") return w.coefw;
  // the AXI wrapper's TDATA widths (config/configs.json light.axi, generated into light_axi_map.hpp)
  if (expr == "AXIS_IN") return axis_tdata_bits(kAXIS_IN_fields, w.frac);
  if (expr == "AXIS_OUT") return axis_tdata_bits(kAXIS_OUT_fields, w.frac);
  if (!expr.empty() && expr.find_first_not_of("0123456789") == std::string::npos) return std::stoi(expr);
  throw std::runtime_error("config/interface.json: unknown width '" + expr + "'");
}

SynthMode parse_synth(const std::string& text, SynthMode auto_mode) {
  if (text == "auto") return auto_mode;
  if (text == "flat") return SynthMode::Flat;
  if (text == "hier") return SynthMode::Hierarchical;
  if (text == "skip") return SynthMode::Skipped;
  throw std::invalid_argument("unknown --synth '" + text + "' (known: auto, flat, hier, skip)");
}

void check_top_name(const std::string& top, const std::string& tb) {
  static const std::regex ident(R"(^[A-Za-z_][A-Za-z0-9_]{0,62}$)");
  if (!std::regex_match(top, ident)) throw std::invalid_argument("--top '" + top + "' is not a Verilog identifier");
  if (top.rfind("sc_", 0) == 0 || top == tb)
    throw std::invalid_argument("--top '" + top + "' clashes with the bundle's module names (sc_*, " + tb + ")");
}

uint64_t checked_seed(uint64_t seed) {
  const uint64_t s = seed != 0 ? seed : pick_seed();
  if (s > 0x7fffffffull) throw std::invalid_argument("--seed must be in 1..2147483647 (the testbench's +seed= is 32-bit)");
  return s;
}

}  // namespace shadecore::cli::handoff
