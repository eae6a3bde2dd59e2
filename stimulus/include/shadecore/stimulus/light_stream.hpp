// SPDX-License-Identifier: Apache-2.0
// shadecore — the command stream between the host (render, cosim front end) and the lighting-core
// simulator (sim/light_main.cpp): register writes and fragments in order, and the colours that come
// back. Binary, little-endian, no SystemC here (the CLI includes it too).
//
//   commands file: "SCLCMD01", then records: u8 kind; kind 0 (write): u32 addr, u32 data;
//                  kind 1 (fragment) / kind 2 (back-facing fragment, in_back_i = 1): i64 n[3], i64 p[3]
//                  kind 3 / kind 4: a front / back fragment with a colour (colour_material, in_cr_i..):
//                  i64 n[3], i64 p[3], u32 col[3] (written only for a non-zero colour, so streams without
//                  colours are unchanged); the fragment's tag is its index, 0, 1, ...
//   results file:  "SCLOUT02", then per fragment in tag order: u32 tag, u32 c[3], u32 s[3] (the secondary colour)
#pragma once

#include <cstdint>
#include <cstdio>
#include <stdexcept>
#include <string>
#include <vector>

#include "shadecore/light.hpp"

namespace shadecore::sim {

struct CoreCommand {
  bool is_write = false;
  RegWrite w{0, 0};
  Fragment f{};
};

inline constexpr char kCmdMagic[9] = "SCLCMD01";
inline constexpr char kOutMagic[9] = "SCLOUT02";  // 02: the secondary colour after the primary

inline void write_commands(const std::string& path, const std::vector<CoreCommand>& cmds) {
  std::FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) throw std::runtime_error("cannot write " + path);
  std::fwrite(kCmdMagic, 1, 8, fp);
  for (const auto& c : cmds) {
    const bool col = (c.f.col[0] | c.f.col[1] | c.f.col[2]) != 0;
    const uint8_t k = c.is_write ? 0 : static_cast<uint8_t>((c.f.back ? 2 : 1) + (col ? 2 : 0));
    std::fwrite(&k, 1, 1, fp);
    if (c.is_write) {
      std::fwrite(&c.w.addr, 4, 1, fp);
      std::fwrite(&c.w.data, 4, 1, fp);
    } else {
      std::fwrite(c.f.n, 8, 3, fp);
      std::fwrite(c.f.p, 8, 3, fp);
      if (col) std::fwrite(c.f.col, 4, 3, fp);
    }
  }
  if (std::fclose(fp) != 0) throw std::runtime_error("cannot write " + path);
}

inline std::vector<CoreCommand> read_commands(const std::string& path) {
  std::FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) throw std::runtime_error("cannot read " + path);
  char magic[8];
  if (std::fread(magic, 1, 8, fp) != 8 || std::string(magic, 8) != kCmdMagic) {
    std::fclose(fp);
    throw std::runtime_error(path + ": not a shadecore command stream");
  }
  std::vector<CoreCommand> out;
  uint8_t k;
  while (std::fread(&k, 1, 1, fp) == 1) {
    CoreCommand c;
    bool ok;
    if (k == 0) {
      c.is_write = true;
      ok = std::fread(&c.w.addr, 4, 1, fp) == 1 && std::fread(&c.w.data, 4, 1, fp) == 1;
    } else if (k >= 1 && k <= 4) {
      c.f.back = k == 2 || k == 4;
      ok = std::fread(c.f.n, 8, 3, fp) == 3 && std::fread(c.f.p, 8, 3, fp) == 3 &&
           (k <= 2 || std::fread(c.f.col, 4, 3, fp) == 3);
    } else {
      ok = false;
    }
    if (!ok) {
      std::fclose(fp);
      throw std::runtime_error(path + ": truncated or corrupt command stream");
    }
    out.push_back(c);
  }
  std::fclose(fp);
  return out;
}

struct ResultRecord {
  uint32_t tag;
  Colour c;
};

inline void write_results(const std::string& path, const std::vector<ResultRecord>& res) {
  std::FILE* fp = std::fopen(path.c_str(), "wb");
  if (!fp) throw std::runtime_error("cannot write " + path);
  std::fwrite(kOutMagic, 1, 8, fp);
  for (const auto& r : res) {
    std::fwrite(&r.tag, 4, 1, fp);
    std::fwrite(r.c.c, 4, 3, fp);
    std::fwrite(r.c.s, 4, 3, fp);  // the secondary colour (separate_specular; else 0)
  }
  if (std::fclose(fp) != 0) throw std::runtime_error("cannot write " + path);
}

inline std::vector<ResultRecord> read_results(const std::string& path) {
  std::FILE* fp = std::fopen(path.c_str(), "rb");
  if (!fp) throw std::runtime_error("cannot read " + path);
  char magic[8];
  if (std::fread(magic, 1, 8, fp) != 8 || std::string(magic, 8) != kOutMagic) {
    std::fclose(fp);
    throw std::runtime_error(path + ": not a shadecore result stream");
  }
  std::vector<ResultRecord> out;
  ResultRecord r;
  while (std::fread(&r.tag, 4, 1, fp) == 1) {
    if (std::fread(r.c.c, 4, 3, fp) != 3 || std::fread(r.c.s, 4, 3, fp) != 3) {
      std::fclose(fp);
      throw std::runtime_error(path + ": truncated result stream");
    }
    out.push_back(r);
  }
  std::fclose(fp);
  return out;
}

}  // namespace shadecore::sim
