// SPDX-License-Identifier: Apache-2.0
// shadecore vectors — stimulus and expected results from the bit-exact C model (shadecore::Unit,
// the model the co-simulation scoreboard uses), as a hex file any simulator can read with $readmemh.
//
//   shadecore vectors --variant cs16 --config default --mode hard --out hard.hex
//   shadecore vectors --variant schlick_nr --config narrow --mode random --count 5000 --seed 7 --out r.hex
//   shadecore vectors --config narrow --norm phong --mode exhaustive --n 16..20 --out e.hex
//   shadecore vectors --variant cs16 --mode ports --count 4000 --seed 3 --out p.hex
//
// --mode ports: random material port values beyond what the host's setup writes (docs/spec.md §3.1, "Beyond the
// host's values"): n in Unit::port_n_min()..1024 (below the host's 16 too; 0 for the dividers; the first material
// runs n = 0, 1, 2, 15, 1024, the n = 0 run 256 fragments with a quarter of its codes uniform over [0, 1.0]) and thr
// on the F+1-bit port, 0..2^(F+1)-1 (half below the host's thr(n) of the legal n nearest n, where the cut decides a
// non-zero output, a quarter within ±512 of thr(n), a quarter over the port; the coefficient and a table unit's
// contents those of that legal n); codes within ±4 of thr (a quarter), within ±512 of it (a quarter), uniform over
// the signed input word (a quarter) and within ±4 of 0 and 1.0 (the rest). Material runs of ~8 fragments, as
// --mode random. Three limits, where the RTL is sized for the host's values and the C model and the RTL differ
// (found by this mode, 2026-12-07): n above 1024 (the cs16 family's n·d products wrap); n = 0 (base = 1.0 for
// every code, which the squarer forms' sign test of base mod 2^(F+5) cuts; schlick_nr's Dc = c < 2^F is not
// normalised as its later stages assume); and in the cs16 family with the θcr cut-off an uncut |base| > 1
// (c < 2^F - 2^(F+5)/n, only with a thr below thr(n): the reference form's W-bit squarings overflow, the other
// forms' sign test of base mod 2^(F+5) wraps): there thr is drawn from 2^F - 2^(F+5)/n up.
//
// File format (also written as the file's header): one vector per line, five hex words
//   N THR COEF COS EXPECTED
// N = mat_n_i (11 bits), THR = mat_thr_i (F+1 bits, 0 for units without a threshold), COEF =
// mat_coef_i (COEFW bits, 0 without ENERGY), COS = in_cos_i (F+2-bit two's complement), EXPECTED =
// out_spec_o (F+1 bits, COEFW with ENERGY). Lines starting with // are comments.
//
// The lighting core (--core lighting --features NAME|FILE, --mode hard|random): register writes,
// fragments and expected colours, one record per line (format: docs/handoff.md, cli/handoff_light.cpp).
#include <algorithm>
#include <cinttypes>
#include <random>

#include <fmt/core.h>

#include "commands.hpp"
#include "handoff_bundle.hpp"
#include "output.hpp"
#include "shadecore/features.hpp"
#include "shadecore/units/hard_cases.hpp"
#include "shadecore/stimulus/rng.hpp"
#include "shadecore/stimulus/specular.hpp"
#include "unit_spec.hpp"

namespace shadecore::cli {

namespace {

constexpr uint64_t kMaxVectors = 20'000'000;  // ~0.8 GB of text; split larger exhaustive runs by --n

int hex_digits(int bits) { return (bits + 3) / 4; }

// The co-simulation's stimulus digest of random vectors: the sum over transaction i of
// stimulus::item_digest(i, −1, code) (n = −1: random mode attaches no exponent to a code).
uint64_t random_digest(const std::vector<TestVector>& v) {
  uint64_t d = 0;
  for (size_t i = 0; i < v.size(); ++i) d += stimulus::item_digest(i, -1, v[i].code);
  return d;
}

struct VectorsArgs {
  std::shared_ptr<UnitOptions> unit = std::make_shared<UnitOptions>();
  VectorRequest req;
  std::string n_range = "16..1024";
  std::string out;
  CLI::Option* count_opt = nullptr;
  CLI::Option* seed_opt = nullptr;
  CLI::Option* n_opt = nullptr;
  std::string core = "specular", features;
  CLI::App* sub = nullptr;
};

void run_lighting(VectorsArgs& a) {
  for (const char* opt : {"--variant", "--config", "--frac", "--guard", "--cutoff", "--norm", "--coef", "--n"})
    if (a.sub->count(opt) > 0)
      throw std::invalid_argument(std::string(opt) + " does not apply to --core lighting (the feature set fixes the "
                                  "specular unit and the widths)");
  if (a.features.empty()) throw std::invalid_argument("--core lighting needs --features NAME|FILE");
  const FeatureSet fset = feature_set_named_or_file(a.features);
  VectorRequest req = a.req;
  if (req.mode != "hard" && req.mode != "random")
    throw std::invalid_argument("unknown mode '" + req.mode + "' for the lighting core (known: hard, random)");
  if (req.mode != "random" && (a.count_opt->count() > 0 || a.seed_opt->count() > 0))
    throw std::invalid_argument("--count and --seed apply to --mode random only");
  if (req.mode == "random" && req.count == 0) throw std::invalid_argument("--count must be >= 1");
  if (req.count > kMaxVectors) throw std::invalid_argument(fmt::format("--count {} is over the limit of {}", req.count, kMaxVectors));
  if (req.mode == "random" && req.seed == 0) req.seed = pick_seed();
  check_output_path(a.out);
  size_t records = 0, fragments = 0;
  const std::string text = handoff::lighting_vectors(fset, req.mode, req.count, req.seed, &records, &fragments);
  write_output_file(a.out, text);
  fmt::print("vectors: {} {} records ({} fragments) for the lighting core, feature set '{}'{} -> {}\n", records,
             req.mode, fragments, fset.name, req.mode == "random" ? fmt::format(", seed {}", req.seed) : "", a.out);
}

void run(VectorsArgs& a) {
  if (a.core == "lighting") return run_lighting(a);
  if (a.core != "specular") throw std::invalid_argument("unknown --core '" + a.core + "' (known: specular, lighting)");
  if (!a.features.empty()) throw std::invalid_argument("--features applies to --core lighting only");
  const UnitSpec spec = resolve_unit(*a.unit);
  VectorRequest req = a.req;
  if (req.mode != "hard" && req.mode != "random" && req.mode != "exhaustive" && req.mode != "ports")
    throw std::invalid_argument("unknown mode '" + req.mode + "' (known: hard, random, exhaustive, ports)");
  if (req.mode == "ports" && a.n_opt->count() > 0)
    throw std::invalid_argument("--n does not apply to --mode ports (it draws n in 1..1024, 0..1024 for schlick_div and schlick_iter)");
  const auto [lo, hi] = parse_range(a.n_range);
  validate_n(lo);
  validate_n(hi);
  req.n_lo = lo;
  req.n_hi = hi;
  if (req.mode == "hard" && a.n_opt->count() > 0)
    throw std::invalid_argument("--n does not apply to --mode hard (the hard-case list fixes its exponents)");
  const bool drawn = req.mode == "random" || req.mode == "ports";
  if (!drawn && (a.count_opt->count() > 0 || a.seed_opt->count() > 0))
    throw std::invalid_argument("--count and --seed apply to --mode random and ports only");
  if (drawn && req.count == 0) throw std::invalid_argument("--count must be >= 1");
  if (drawn && req.seed == 0) req.seed = pick_seed();
  check_output_path(a.out);

  const std::vector<TestVector> v = make_vectors(spec, req);
  write_output_file(a.out, format_vectors(spec, req, v));
  fmt::print("vectors: {} {} vector(s) for {}{} -> {}\n", v.size(), req.mode, spec.describe(),
             req.mode == "random" ? fmt::format(", seed {}, stimulus digest {}", req.seed, random_digest(v))
             : req.mode == "ports" ? fmt::format(", seed {}", req.seed) : "", a.out);
}

}  // namespace

uint64_t pick_seed() {
  std::random_device rd;
  uint64_t s = (static_cast<uint64_t>(rd()) << 32) ^ rd();
  s &= 0x7fffffffull;  // fits the testbench's +seed= (a 32-bit integer) as well
  return s == 0 ? 1 : s;
}

std::vector<TestVector> make_vectors(const UnitSpec& spec, const VectorRequest& req) {
  const Unit unit = spec.unit();
  const Format& f = spec.format;
  const int64_t one = f.one();
  std::vector<TestVector> v;
  auto add = [&](int n, const UnitMaterial& m, int64_t code) {
    v.push_back(TestVector{n, m.thr, m.coef, code, unit.eval(m, code)});
  };
  if (req.mode == "hard") {
    // shadecore::hard_cases(): the list the C model tests and the directed co-simulation use.
    for (const HardCase& h : hard_cases(f)) add(h.n, unit.setup(h.n), h.code);
  } else if (req.mode == "exhaustive") {
    const uint64_t per_n = static_cast<uint64_t>(one) + 1 + 4;
    const uint64_t total = per_n * static_cast<uint64_t>(req.n_hi - req.n_lo + 1);
    if (total > kMaxVectors)
      throw std::invalid_argument(fmt::format("exhaustive run of {} vectors is over the limit of {}; split it with --n",
                                              total, kMaxVectors));
    v.reserve(total);
    for (int n = req.n_lo; n <= req.n_hi; ++n) {
      const UnitMaterial m = unit.setup(n);
      for (int64_t c = 0; c <= one; ++c) add(n, m, c);
      for (int64_t c : {f.in_min(), int64_t{-1}, one + 1, f.in_max()}) add(n, m, c);  // clamp, never wrap
    }
  } else if (req.mode == "ports") {
    if (req.seed == 0) throw std::invalid_argument("port vectors need a non-zero seed");
    if (req.count > kMaxVectors)
      throw std::invalid_argument(fmt::format("--count {} is over the limit of {}", req.count, kMaxVectors));
    sim::Rng r(sim::mix64(req.seed ^ 0x706f727473ull));
    const int64_t thr_port = (int64_t{1} << (f.frac + 1)) - 1;
    v.reserve(req.count);
    int n = 0;
    size_t runs = 0;
    UnitMaterial m;
    // the first runs: the ends of the port's range (n = 0 where the model covers it), then random
    const int n_min = unit.port_n_min();
    const std::vector<int> ends = n_min == 0 ? std::vector<int>{0, 1, 2, kNMin - 1, kNMax}
                                             : std::vector<int>{1, 2, kNMin - 1, kNMax};
    // n = 0 (the dividers only: Dc = c, the quotient's integer-bit path for every code) is rare among the random n,
    // so its first run is kZeroRun fragments, codes uniform over [0, 1.0] where the other runs' are over the signed
    // word: a change seen only at n = 0 with some bit of c set shows. The other units' files are as before.
    constexpr uint64_t kZeroRun = 256;
    for (uint64_t i = 0; i < req.count; ++i) {
      if (i == 0 || (r.next() % 8 == 0 && (n != 0 || i >= kZeroRun))) {
        n = runs < ends.size() ? ends[runs] : static_cast<int>(r.uniform(n_min, kNMax));
        ++runs;
        m = unit.setup(std::clamp(n, kNMin, kNMax));
        m.n = n;
        const int64_t thr_lo = unit.port_thr_min(n);
        // thr: half between thr_lo and the host's thr (where the cut decides a non-zero output), a quarter within
        // ±512 of the host's thr, a quarter over the port
        const int64_t host = m.thr;
        const uint64_t tk = r.next() % 4;
        const int64_t t = tk < 2 ? r.uniform(std::min(thr_lo, host), host)
                          : tk == 2 ? host + r.uniform(-512, 512) : r.uniform(thr_lo, thr_port);
        m.thr = static_cast<uint32_t>(std::clamp(t, thr_lo, thr_port));
      }
      // codes: a quarter within ±4 of thr (both sides of the cut), a quarter within ±512 of it, a quarter over the
      // signed input word, the rest within ±4 of 0 and 1.0
      const uint64_t kind = r.next() % 4;
      int64_t code = kind == 0 ? int64_t{m.thr} + r.uniform(-4, 4)
                     : kind == 1 ? int64_t{m.thr} + r.uniform(-512, 512)
                     : kind == 2 ? (n == 0 ? r.uniform(0, one) : r.uniform(f.in_min(), f.in_max()))
                                 : (r.next() % 2 ? one : 0) + r.uniform(-4, 4);
      add(n, m, std::clamp(code, f.in_min(), f.in_max()));
    }
  } else {
    if (req.seed == 0) throw std::invalid_argument("random vectors need a non-zero seed");
    if (req.count > kMaxVectors)
      throw std::invalid_argument(fmt::format("--count {} is over the limit of {}", req.count, kMaxVectors));
    // Codes from the one specular generator (stimulus/specular.hpp): transaction i gets the code the
    // co-simulation's transaction i gets with the same seed (`cosim --seed S`: the same stimulus_digest).
    // The exponent runs (~8 fragments a material) come from a stream of their own, seeded from the seed.
    sim::Rng mat(sim::mix64(req.seed ^ 0x6d6174657269616cull));
    v.reserve(req.count);
    int n = static_cast<int>(mat.uniform(req.n_lo, req.n_hi));
    UnitMaterial m = unit.setup(n);
    for (uint64_t i = 0; i < req.count; ++i) {
      if (i > 0 && mat.next() % 8 == 0) {  // material runs of ~8 fragments: writes between fragments
        n = static_cast<int>(mat.uniform(req.n_lo, req.n_hi));
        m = unit.setup(n);
      }
      const int64_t code = stimulus::random_code(unit, req.seed, i, req.n_lo, req.n_hi);
      add(n, m, code);
    }
  }
  return v;
}

std::string format_vectors(const UnitSpec& spec, const VectorRequest& req, const std::vector<TestVector>& v) {
  const Format& f = spec.format;
  const int wn = hex_digits(kNBits), wt = hex_digits(f.frac + 1), wc = hex_digits(spec.coef_bits()),
            wx = hex_digits(f.in_bits()), we = hex_digits(spec.out_bits());
  const uint64_t cos_mask = (uint64_t{1} << f.in_bits()) - 1;
  std::string s;
  s += "// shadecore vectors: " + spec.describe() + "\n";
  s += "// mode " + req.mode;
  if (req.mode == "ports")
    s += fmt::format(", seed {}: n in {}..{} and thr over its whole port", req.seed, spec.unit().port_n_min(), kNMax);
  if (req.mode == "random")
    s += fmt::format(", seed {}, n {}..{}, stimulus digest {}", req.seed, req.n_lo, req.n_hi, random_digest(v));
  if (req.mode == "exhaustive") s += fmt::format(", n {}..{}: every code 0..2^F, then -2^(F+1), -1, 2^F+1, 2^(F+1)-1", req.n_lo, req.n_hi);
  if (req.mode == "hard") s += " (shadecore::hard_cases: input extremes, 1.0 +-2, 1.0 + 2^k, thr +-2, the base zero +-2, 12 exponents)";
  s += fmt::format("; {} vectors\n", v.size());
  s += "// made by: " + command_line() + "\n";
  s += "// expected values: the bit-exact C model (cmodel/include/shadecore/unit.hpp), as the co-simulation\n";
  s += "// format: one vector per line, five hex words N THR COEF COS EXPECTED ($readmemh into a 32-bit memory,\n";
  s += "// 5 words a vector; // lines are comments):\n";
  s += fmt::format("//   N        mat_n_i, 11 bits, exponent n (16..1024)\n");
  s += fmt::format("//   THR      mat_thr_i, F+1 = {} bits, thr(n) = ceil(cos(6/sqrt(n))*2^F); 0 where unused\n", f.frac + 1);
  s += fmt::format("//   COEF     mat_coef_i, COEFW = {} bits, coefficient code (8 integer, F fraction bits); 0 without ENERGY\n",
                   spec.coef_bits());
  s += fmt::format("//   COS      in_cos_i, F+2 = {} bits, two's complement, 1.0 = 0x{:x}\n", f.in_bits(), f.one());
  s += fmt::format("//   EXPECTED out_spec_o, {} bits, 1.0 = 0x{:x}\n", spec.out_bits(), f.one());
  s += "// apply: load N, THR, COEF with mat_we_i (one cycle without a fragment) whenever they differ from the\n";
  s += "// loaded material, then present COS; the result must equal EXPECTED bit for bit.\n";
  s.reserve(s.size() + v.size() * static_cast<size_t>(wn + wt + wc + wx + we + 5));
  for (const TestVector& t : v)
    s += fmt::format("{:0{}x} {:0{}x} {:0{}x} {:0{}x} {:0{}x}\n", t.n, wn, t.thr, wt, t.coef, wc,
                     static_cast<uint64_t>(t.code) & cos_mask, wx, t.expected, we);
  return s;
}

void add_vectors(CLI::App& app) {
  auto a = std::make_shared<VectorsArgs>();
  auto* sub = app.add_subcommand("vectors", "Write test vectors (stimulus + expected results from the C model) as hex");
  a->sub = sub;
  add_unit_options(sub, a->unit);
  sub->add_option("--core", a->core, "specular (default): the unit; lighting: register writes, fragments, colours")->check(cliargs::NonEmpty("core"));
  sub->add_option("--features", a->features, "Lighting core feature set: a name of config/configs.json or a JSON file")->check(cliargs::NonEmpty("feature set"));
  sub->add_option("--mode", a->req.mode, "hard (the hard-case list) | random | exhaustive | ports (n in 1..1024 or 0..1024, thr over its port)")->check(cliargs::NonEmpty("mode"));
  a->count_opt = sub->add_option("--count", a->req.count, "Random, ports: number of vectors (default 1000)");
  a->seed_opt = sub->add_option("--seed", a->req.seed, "Random, ports: seed (default: picked and recorded in the file)");
  a->n_opt = sub->add_option("--n", a->n_range, "Random, exhaustive: exponent range LO..HI or N (default 16..1024)")->check(cliargs::NonEmpty("range"));
  sub->add_option("--out", a->out, "Output file (written atomically)")->required()->check(cliargs::NonEmpty("path"));
  sub->callback([a] { run(*a); });
}

}  // namespace shadecore::cli
