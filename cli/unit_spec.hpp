// SPDX-License-Identifier: Apache-2.0
// shadecore CLI — what `eval`, `vectors` and `handoff` share (issue 11):
//   * the unit options (--variant, --config | --frac/--guard, --cutoff, --norm MODEL|all, --coef)
//     and their resolution into a UnitSpec + the C model's shadecore::Unit (never a second model);
//   * the vector list (hard cases, random, exhaustive) and its hex file format (implemented in
//     cmd_vectors.cpp; the handoff bundle's testbench reads the same format);
//   * safe output writing: a regular file is replaced atomically, a symlink is written through
//     (the link stays), a FIFO or character device is written to directly — never replaced by a file.
#pragma once

#include <sys/stat.h>
#include <unistd.h>

#include <cerrno>
#include <cstdint>
#include <cstring>
#include <filesystem>
#include <fstream>
#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include <CLI/CLI.hpp>

#include "shadecore/common/args.hpp"
#include "output.hpp"
#include "shadecore/units/coef.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/unit.hpp"

namespace shadecore::cli {

// ---------------------------------------------------------------------------- unit options
struct UnitOptions {
  std::string variant = "cs16";
  std::string config;  // a name from config/configs.json (empty: the default)
  int frac = -1, guard = -1;
  std::string cutoff = "theta_cr";
  std::string norm;    // "" (off), a model key (phong, ...), or "all" (model and kind chosen per n)
  std::string coef = "fitted";
  int mreg = 0;        // the pipelining parameter (handoff --mreg; rtl/sc_cs16.v MREG)
  CLI::Option* cutoff_opt = nullptr;
  CLI::Option* guard_opt = nullptr;
  CLI::Option* frac_opt = nullptr;
  CLI::Option* coef_opt = nullptr;
};

// Everything that fixes the hardware configuration and its bit-exact model.
struct UnitSpec {
  VariantId variant = VariantId::cs16;
  std::string variant_name = "cs16";
  std::string config_name;  // the named configuration, or "custom" for --frac/--guard
  Format format;
  Cutoff cutoff = Cutoff::ThetaCr;
  bool norm = false;
  int norm_model = -1;  // index into kModels; -1 = per n (Unit::set_energy)
  CoefKind coef_kind = CoefKind::Fitted;
  int mreg = 0;  // rtl/sc_cs16.v MREG: a register inside each product (cs16 only; Unit::set_mreg)

  // cs16 or one of its squarer forms (cs16_faithful, cs16_compact): G and the cut-off apply.
  [[nodiscard]] bool is_cs16() const { return variant == VariantId::cs16 || squarer_form(variant) != nullptr; }
  [[nodiscard]] int coef_bits() const { return format.frac + kCoefIntBits; }                   // COEFW
  [[nodiscard]] int out_bits() const { return norm ? coef_bits() : format.out_bits(); }        // out_spec_o
  [[nodiscard]] bool uses_thr() const { return is_cs16() && cutoff == Cutoff::ThetaCr; }       // mat_thr_i read
  [[nodiscard]] std::string norm_label() const {
    if (!norm) return "off";
    if (norm_model < 0) return "all (any coefficient code; vectors use model n mod 6, classical kind when n/6 is odd)";
    return std::string(kModels[norm_model].key) + ", " + to_string(coef_kind);
  }
  // One line: "cs16 default (F=16 G=5) cutoff theta_cr" (+ ", norm phong fitted").
  [[nodiscard]] std::string describe() const {
    std::string s = variant_name + " " + config_name + " (F=" + std::to_string(format.frac);
    if (is_cs16()) s += " G=" + std::to_string(format.guard) + ") cutoff " + to_string(cutoff);
    else s += ")";
    if (norm) s += ", norm " + norm_label();
    if (mreg) s += ", MREG " + std::to_string(mreg);
    return s;
  }
  [[nodiscard]] Unit unit() const {
    Unit u(variant, format, cutoff);
    if (norm) u.set_energy(true, norm_model, coef_kind);
    u.set_mreg(mreg);
    return u;
  }
};

inline void add_unit_options(CLI::App* sub, const std::shared_ptr<UnitOptions>& o, bool allow_custom_width = true) {
  sub->add_option("--variant", o->variant, "Unit: cs16, schlick_div, schlick_nr, schlick_iter, cs16_faithful, cs16_compact, table256, table1024 (config/configs.json variants)")->check(cliargs::NonEmpty("unit name"));
  sub->add_option("--config", o->config, "Named width configuration (config/configs.json: narrow, default, wide)")->check(cliargs::NonEmpty("config name"));
  if (allow_custom_width) {
    o->frac_opt = sub->add_option("--frac", o->frac, "Fraction bits F (8..24), overrides --config");
    o->guard_opt = sub->add_option("--guard", o->guard, "Guard bits G (4..8, F+G <= 31; cs16 only), overrides --config");
  }
  o->cutoff_opt = sub->add_option("--cutoff", o->cutoff, "cs16 cut-off form: theta_cr | sign_clamp")->check(cliargs::NonEmpty("cut-off"));
  sub->add_option("--norm", o->norm,
                  "Energy normalisation after the unit (ENERGY = 1): a model (phong, phong_mod, blinn, blinn_mod, "
                  "blinn_ndf, blinn_hf) or 'all' (model and kind chosen per n, as the co-simulation)")->check(cliargs::NonEmpty("model"));
  o->coef_opt = sub->add_option("--coef", o->coef, "Coefficient kind with --norm MODEL: fitted | classical")->check(cliargs::NonEmpty("coefficient kind"));
}

// Validates the options; throws std::invalid_argument (one line) on any bad value or combination.
inline UnitSpec resolve_unit(const UnitOptions& o) {
  UnitSpec s;
  s.variant = parse_variant(o.variant);
  s.variant_name = std::string(variant_name(s.variant));
  const NamedConfig& nc = config_named(o.config);
  s.config_name = std::string(nc.name);
  s.format = nc.format;
  const bool custom = (o.frac_opt && o.frac_opt->count() > 0) || (o.guard_opt && o.guard_opt->count() > 0);
  if (o.frac_opt && o.frac_opt->count() > 0) s.format.frac = o.frac;
  if (o.guard_opt && o.guard_opt->count() > 0) s.format.guard = o.guard;
  if (custom) s.config_name = "custom";
  validate(s.format);
  s.cutoff = parse_cutoff_name(o.cutoff);
  if (!s.is_cs16()) {
    if (o.cutoff_opt && o.cutoff_opt->count() > 0)
      throw std::invalid_argument("--cutoff applies to cs16 only, not to " + s.variant_name);
    if (o.guard_opt && o.guard_opt->count() > 0)
      throw std::invalid_argument("--guard applies to cs16 only, not to " + s.variant_name);
  }
  const bool coef_given = o.coef_opt && o.coef_opt->count() > 0;
  if (!o.norm.empty()) {
    s.norm = true;
    if (o.norm == "all") {
      if (coef_given) throw std::invalid_argument("--coef needs --norm MODEL (with --norm all the kind is chosen per n)");
      s.norm_model = -1;
    } else {
      s.norm_model = static_cast<int>(parse_model(o.norm));
      s.coef_kind = parse_coef_kind(o.coef);
    }
  } else if (coef_given) {
    throw std::invalid_argument("--coef needs --norm MODEL");
  }
  s.mreg = o.mreg;
  if (s.mreg != 0 && s.mreg != 1) throw std::invalid_argument("--mreg " + std::to_string(s.mreg) + " out of range (0 or 1)");
  if (s.mreg != 0) Unit(s.variant, s.format, s.cutoff).set_mreg(s.mreg);  // a variant without MREG: its one-line error
  return s;
}

// ---------------------------------------------------------------------------- vectors (cmd_vectors.cpp)
// One test vector: the material ports, the input word and the expected output (bit-exact C model).
struct TestVector {
  int n = 16;          // mat_n_i
  uint32_t thr = 0;    // mat_thr_i (0 where the unit has no threshold)
  uint32_t coef = 0;   // mat_coef_i (0 without ENERGY)
  int64_t code = 0;    // in_cos_i as a signed integer
  uint32_t expected = 0;
};

struct VectorRequest {
  std::string mode = "hard";  // hard | random | exhaustive
  uint64_t count = 1000;      // random
  uint64_t seed = 0;          // random; 0 = pick one (the file records it)
  int n_lo = kNMin, n_hi = kNMax;
};

// The vectors of `req` for `spec` (random: req.seed must be non-zero). Throws std::invalid_argument.
std::vector<TestVector> make_vectors(const UnitSpec& spec, const VectorRequest& req);
// The documented hex file: a `//` header (format, configuration, mode, seed, count, command) and one
// vector per line, five hex words N THR COEF COS EXPECTED ($readmemh-ready).
std::string format_vectors(const UnitSpec& spec, const VectorRequest& req, const std::vector<TestVector>& v);
// A fresh random seed (non-zero).
uint64_t pick_seed();

// ---------------------------------------------------------------------------- safe output
// Checks up front that `path` can be written by write_output_file (so long runs fail early).
inline void check_output_path(const std::string& path) {
  namespace fs = std::filesystem;
  if (path.empty()) throw std::runtime_error("empty output path");
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);  // follows symlinks
  if (fs::is_directory(st)) throw std::runtime_error("cannot write " + path + ": is a directory");
  if (fs::exists(st) && !fs::is_regular_file(st) && !fs::is_fifo(st) && !fs::is_character_file(st))
    throw std::runtime_error("cannot write " + path + ": not a regular file, FIFO or character device");
  if (fs::is_fifo(st) || fs::is_character_file(st)) {
    if (::access(path.c_str(), W_OK) != 0) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    return;
  }
  const fs::path target = fs::is_symlink(fs::symlink_status(path, ec)) ? fs::weakly_canonical(path, ec) : fs::path(path);
  check_writable_file(target.string());
}

// Writes `content` to `path`: a FIFO or character device (e.g. /dev/stdout) is written directly;
// a symlink is followed and its target replaced atomically (the link stays a link); anything else
// goes through output.hpp's write_file_atomic (temporary file + rename: no half-written file).
inline void write_output_file(const std::string& path, const std::string& content) {
  namespace fs = std::filesystem;
  check_output_path(path);
  std::error_code ec;
  const fs::file_status st = fs::status(path, ec);
  if (fs::is_fifo(st) || fs::is_character_file(st)) {
    std::ofstream out(path, std::ios::binary | std::ios::app);
    if (!out) throw std::runtime_error("cannot write " + path + ": " + std::strerror(errno));
    out << content;
    out.flush();
    if (!out) throw std::runtime_error("cannot write " + path + ": write failed");
    return;
  }
  const bool link = fs::is_symlink(fs::symlink_status(path, ec));
  write_file_atomic(link ? fs::weakly_canonical(path, ec).string() : path, content);
}

}  // namespace shadecore::cli
