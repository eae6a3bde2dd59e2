// SPDX-License-Identifier: Apache-2.0
// `shadecore eval`, `shadecore vectors` and the argument checks of `shadecore handoff` (issue 11).
// The bundles themselves are simulated by the ctest tests handoff.* (handoff/test_bundle.sh).
#include <gtest/gtest.h>
#include <sys/stat.h>
#include <unistd.h>

#include <cctype>
#include <filesystem>
#include <fstream>
#include <regex>
#include <set>
#include <sstream>
#include <string>
#include <vector>

#include <nlohmann/json.hpp>

#include "cli_run.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/analysis/golden.hpp"
#include "shadecore/features.hpp"
#include "shadecore/units/hard_cases.hpp"
#include "shadecore/light.hpp"
#include "shadecore/light_axi.hpp"
#include "shadecore/unit.hpp"

namespace fs = std::filesystem;
using namespace shadecore::testing;  // tests/cli_run.hpp

namespace {

fs::path temp_dir(const std::string& tag) {
  const fs::path d = fs::temp_directory_path() / ("shadecore_h11_" + tag + "_" + std::to_string(::getpid()));
  fs::remove_all(d);
  fs::create_directories(d);
  return d;
}

std::string slurp(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream ss;
  ss << in.rdbuf();
  return ss.str();
}

// `shadecore vectors ARGS --out DIR/NAME`, which must succeed; the file's text.
std::string vectors_file(const fs::path& dir, const std::string& name, const std::string& args) {
  const CliRun r = run_cli("vectors " + args + " --out " + (dir / name).string());
  EXPECT_EQ(r.status, 0) << r.err;
  return slurp(dir / name);
}

// A data line of a lighting vector file: ten hex words (KIND, then a register write ADDR DATA or a
// fragment NX NY NZ PX PY PZ and the expected R G B). False when the line does not hold ten words.
bool read_record(const std::string& line, std::vector<uint64_t>& w) {
  std::stringstream ss(line);
  w.assign(10, 0);
  for (auto& x : w) ss >> std::hex >> x;
  return !ss.fail();
}

// The fragment of a record: normals in F+2 bits, positions in F+8 bits, two's complement.
shadecore::Fragment record_fragment(const std::vector<uint64_t>& w, int F) {
  shadecore::Fragment f;
  for (int i = 0; i < 3; ++i) {
    f.n[i] = shadecore::sign_extend(w[1 + i], F + 2);
    f.p[i] = shadecore::sign_extend(w[4 + i], F + 8);
  }
  return f;
}

struct Line {
  uint32_t n, thr, coef, cos, expected;
};

// Data lines of a vector file (five hex words each), header lines skipped.
std::vector<Line> read_vectors(const fs::path& p, std::string* header = nullptr) {
  std::ifstream in(p);
  std::string line;
  std::vector<Line> v;
  while (std::getline(in, line)) {
    if (line.rfind("//", 0) == 0) {
      if (header) *header += line + "\n";
      continue;
    }
    std::stringstream ss(line);
    Line l{};
    ss >> std::hex >> l.n >> l.thr >> l.coef >> l.cos >> l.expected;
    EXPECT_FALSE(ss.fail()) << line;
    std::string rest;
    EXPECT_FALSE(ss >> rest) << "more than five words: " << line;
    v.push_back(l);
  }
  return v;
}

std::string fmt_hex(unsigned long v, size_t digits) {
  std::stringstream ss;
  ss << std::hex << v;
  std::string s = ss.str();
  return s.size() < digits ? std::string(digits - s.size(), '0') + s : s;
}

int64_t sign_extend(uint32_t word, int bits) {
  const int sh = 64 - bits;
  return static_cast<int64_t>(static_cast<uint64_t>(word) << sh) >> sh;
}

nlohmann::json eval_json(const std::string& args) {
  const CliRun r = run_cli("eval " + args + " --json -");
  EXPECT_EQ(r.status, 0) << args << "\n" << r.err;
  return nlohmann::json::parse(r.out);
}

}  // namespace

// ---------------------------------------------------------------------------- eval
TEST(EvalCli, BadArgumentsGiveOneLineErrors) {
  expect_one_line_error("eval --n 15 --code 0", "out of range");
  expect_one_line_error("eval --n 128", "exactly one of --code K and --cos X");
  expect_one_line_error("eval --n 128 --code 1 --cos 0.5", "exactly one of --code K and --cos X");
  expect_one_line_error("eval --n 128 --code 0x40000", "does not fit");
  expect_one_line_error("eval --n 128 --code 131072", "out of range");
  expect_one_line_error("eval --n 128 --code 12x", "malformed --code");
  expect_one_line_error("eval --n 128 --cos 2.5", "outside the input word");
  expect_one_line_error("eval --variant nosuch --n 128 --code 0", "unknown variant");
  expect_one_line_error("eval --variant schlick_div --cutoff sign_clamp --n 128 --code 0", "cs16 only");
  expect_one_line_error("eval --coef classical --n 128 --code 0", "--coef needs --norm");
  expect_one_line_error("eval --norm nosuch --n 128 --code 0", "unknown model");
  expect_one_line_error("eval --frac 25 --n 128 --code 0", "fraction width 25 out of range");
  expect_one_line_error("eval --n 128 --code 0 --json /nonexistent-dir/e.json", "cannot write");
}

TEST(EvalCli, PrintsTheTraceAndMatchesTheModel) {
  const CliRun r = run_cli("eval --n 128 --cos 0.95");
  ASSERT_EQ(r.status, 0) << r.err;
  for (const char* s : {"S0  c", "S0  d", "S1  base", "S1  cut", "S1  x0", "S2  x1", "S3  x2", "S4  x3", "S5  x4",
                        "S6  out", "out_spec_o", "cos^n", "cs16 ="})
    EXPECT_NE(r.out.find(s), std::string::npos) << s << "\n" << r.out;
  const auto j = eval_json("--n 128 --cos 0.95");
  const shadecore::Format f = shadecore::default_format();
  const shadecore::Unit u(shadecore::VariantId::cs16, f, shadecore::Cutoff::ThetaCr);
  EXPECT_EQ(j["code"].get<int64_t>(), 62259);  // round(0.95 * 2^16)
  EXPECT_EQ(j["out"].get<uint32_t>(), u.eval(u.setup(128), 62259));
  EXPECT_EQ(j["trace"]["x"].size(), 5u);
  // Hex codes are the raw (F+2)-bit word: 0x3ffff is -1 at F = 16 (clamped to 0: output 0).
  const auto neg = eval_json("--n 128 --code 0x3ffff");
  EXPECT_EQ(neg["code"].get<int64_t>(), -1);
  EXPECT_EQ(neg["out"].get<uint32_t>(), 0u);
  const auto one = eval_json("--n 1024 --code 0x10000");
  EXPECT_EQ(one["out"].get<uint32_t>(), 65536u);
  // Schlick and ENERGY: the output is Unit::eval of the same configuration.
  shadecore::Unit nu(shadecore::VariantId::schlick_nr, shadecore::config_named("narrow").format, shadecore::Cutoff::ThetaCr);
  nu.set_energy(true, static_cast<int>(shadecore::Model::Blinn), shadecore::CoefKind::Classical);
  const auto sj = eval_json("--variant schlick_nr --config narrow --norm blinn --coef classical --n 300 --code 200");
  EXPECT_EQ(sj["out"].get<uint32_t>(), nu.eval(nu.setup(300), 200));
  EXPECT_EQ(sj["material"]["coef"].get<uint32_t>(), nu.setup(300).coef);
  EXPECT_TRUE(sj["trace"].contains("mt"));
  EXPECT_TRUE(sj["trace"].contains("norm"));
}

// The sweep's extreme quantisation errors, re-evaluated one by one with eval, give the same numbers.
TEST(EvalCli, AgreesWithTheSweepExtremes) {
  const fs::path d = temp_dir("sweep");
  for (const std::string variant : {"cs16", "schlick_nr", "schlick_div"}) {
    const fs::path js = d / (variant + ".json");
    const CliRun s = run_cli("sweep --variant " + variant + " --frac 10 --n 16..60 --no-progress --json " + js.string());
    ASSERT_EQ(s.status, 0) << s.err;
    const auto sj = nlohmann::json::parse(slurp(js));
    for (const char* which : {"max", "min"}) {
      const auto& e = sj["quant_ulp"][which];
      const auto j = eval_json("--variant " + variant + " --frac 10 --n " + std::to_string(e["n"].get<int>()) +
                               " --code " + std::to_string(e["code"].get<int64_t>()));
      EXPECT_NEAR(j["double"]["error_ulp"].get<double>(), e["value"].get<double>(), 1e-9) << variant << " " << which;
    }
  }
  fs::remove_all(d);
}

// ---------------------------------------------------------------------------- vectors
TEST(VectorsCli, HardCasesFromTheModel) {
  const fs::path d = temp_dir("hard");
  const fs::path out = d / "hard.hex";
  const CliRun r = run_cli("vectors --mode hard --out " + out.string());
  ASSERT_EQ(r.status, 0) << r.err;
  std::string header;
  const auto v = read_vectors(out, &header);
  const shadecore::Format f = shadecore::default_format();
  const auto hc = shadecore::hard_cases(f);
  ASSERT_EQ(v.size(), hc.size());
  EXPECT_NE(header.find(std::to_string(hc.size()) + " vectors"), std::string::npos) << header;
  EXPECT_NE(header.find("N THR COEF COS EXPECTED"), std::string::npos);
  const shadecore::Unit u(shadecore::VariantId::cs16, f, shadecore::Cutoff::ThetaCr);
  for (size_t i = 0; i < v.size(); ++i) {
    const auto m = u.setup(hc[i].n);
    EXPECT_EQ(v[i].n, static_cast<uint32_t>(hc[i].n));
    EXPECT_EQ(v[i].thr, m.thr);
    EXPECT_EQ(v[i].coef, 0u);
    EXPECT_EQ(sign_extend(v[i].cos, f.in_bits()), hc[i].code);
    EXPECT_EQ(v[i].expected, u.eval(m, hc[i].code));
  }
  // eval of a few lines gives the file's EXPECTED word.
  for (size_t i : {size_t{7}, v.size() / 2, v.size() - 3}) {
    const auto j = eval_json("--n " + std::to_string(v[i].n) + " --code " + std::to_string(sign_extend(v[i].cos, f.in_bits())));
    EXPECT_EQ(j["out"].get<uint32_t>(), v[i].expected) << i;
  }
  fs::remove_all(d);
}

TEST(VectorsCli, RandomIsReproducibleFromItsSeed) {
  const fs::path d = temp_dir("rand");
  auto make = [&](const std::string& name, const std::string& args) {
    vectors_file(d, name, "--variant schlick_div --config narrow --mode random " + args);
    std::string header;
    auto v = read_vectors(d / name, &header);
    return std::make_pair(v, header);
  };
  const auto [a, ha] = make("a.hex", "--count 500 --seed 42");
  const auto [b, hb] = make("b.hex", "--count 500 --seed 42");
  const auto [c, hc] = make("c.hex", "--count 500 --seed 43");
  const auto [p, hp] = make("p.hex", "--count 300");  // seed picked and recorded
  ASSERT_EQ(a.size(), 500u);
  EXPECT_EQ(slurp(d / "a.hex").substr(slurp(d / "a.hex").find("\n0")), slurp(d / "b.hex").substr(slurp(d / "b.hex").find("\n0")));
  EXPECT_NE(slurp(d / "a.hex").substr(slurp(d / "a.hex").find("\n0")), slurp(d / "c.hex").substr(slurp(d / "c.hex").find("\n0")));
  EXPECT_NE(ha.find("seed 42"), std::string::npos);
  std::smatch m;
  ASSERT_TRUE(std::regex_search(hp, m, std::regex("seed (\\d+)"))) << hp;
  const auto [q, hq] = make("q.hex", "--count 300 --seed " + m[1].str());
  EXPECT_EQ(slurp(d / "p.hex").substr(slurp(d / "p.hex").find("\n0")), slurp(d / "q.hex").substr(slurp(d / "q.hex").find("\n0")));
  // Several materials, out-of-range codes, and every expected value from the model.
  const shadecore::Format f = shadecore::config_named("narrow").format;
  const shadecore::Unit u(shadecore::VariantId::schlick_div, f, shadecore::Cutoff::ThetaCr);
  std::set<uint32_t> ns;
  int outside = 0;
  for (const auto& l : a) {
    ns.insert(l.n);
    const int64_t code = sign_extend(l.cos, f.in_bits());
    outside += code < 0 || code > f.one();
    EXPECT_EQ(l.thr, 0u);  // the Schlick units have no threshold
    EXPECT_EQ(l.expected, u.eval(u.setup(l.n), code));
  }
  EXPECT_GT(ns.size(), 20u);
  EXPECT_GT(outside, 10);
  fs::remove_all(d);
}

TEST(VectorsCli, ExhaustiveAndNorm) {
  const fs::path d = temp_dir("exh");
  const CliRun r = run_cli("vectors --config narrow --norm phong --mode exhaustive --n 16..17 --out " + (d / "e.hex").string());
  ASSERT_EQ(r.status, 0) << r.err;
  const auto v = read_vectors(d / "e.hex");
  const shadecore::Format f = shadecore::config_named("narrow").format;
  ASSERT_EQ(v.size(), 2u * (f.one() + 1 + 4));
  shadecore::Unit u(shadecore::VariantId::cs16, f, shadecore::Cutoff::ThetaCr);
  u.set_energy(true, static_cast<int>(shadecore::Model::Phong), shadecore::CoefKind::Fitted);
  std::set<int64_t> codes;
  for (const auto& l : v) {
    const auto m = u.setup(l.n);
    EXPECT_EQ(l.coef, m.coef);
    EXPECT_NE(l.coef, 0u);
    const int64_t code = sign_extend(l.cos, f.in_bits());
    codes.insert(code);
    EXPECT_EQ(l.expected, u.eval(m, code));
  }
  EXPECT_EQ(codes.size(), static_cast<size_t>(f.one() + 1 + 4));
  EXPECT_TRUE(codes.count(f.in_min()) && codes.count(f.in_max()) && codes.count(-1) && codes.count(f.one() + 1));
  fs::remove_all(d);
}

// --mode ports (docs/spec.md §3.1 "Beyond the host's values"): n in 1..1024 (0..1024 for the dividers) with the ends
// first, thr off the host's thr(n) (below it, where the cut decides a non-zero output, and above 1.0), never an uncut
// |base| > 1; the expected values are the model's for the words on the ports; the same seed gives the same file.
TEST(VectorsCli, PortsModeGoesBeyondTheHostsValues) {
  const fs::path d = temp_dir("pvec");
  const std::string a = vectors_file(d, "a.hex", "--variant cs16 --mode ports --count 2000 --seed 21");
  EXPECT_EQ(a.substr(a.find("\n0")), vectors_file(d, "b.hex", "--variant cs16 --mode ports --count 2000 --seed 21")
                                         .substr(a.find("\n0")));
  const shadecore::Unit unit(shadecore::VariantId::cs16, shadecore::default_format(), shadecore::Cutoff::ThetaCr);
  const int F = unit.format().frac;
  std::stringstream in(a);
  std::string line;
  std::set<int> ns;
  int vectors = 0, below = 0, above_one = 0, lit_below = 0;
  while (std::getline(in, line)) {
    if (line.rfind("//", 0) == 0) continue;
    std::istringstream w(line);
    uint64_t n = 0, thr = 0, coef = 0, cos = 0, out = 0;
    ASSERT_TRUE(w >> std::hex >> n >> thr >> coef >> cos >> out) << line;
    ++vectors;
    ASSERT_GE(n, 1u) << line;
    ASSERT_LE(n, 1024u) << line;
    ns.insert(static_cast<int>(n));
    const int64_t code = (cos & (uint64_t{1} << (F + 1))) ? static_cast<int64_t>(cos) - (int64_t{1} << (F + 2))
                                                          : static_cast<int64_t>(cos);
    shadecore::UnitMaterial m = unit.setup(std::max<int64_t>(16, n));
    const uint32_t host = m.thr;
    m.n = static_cast<int>(n);
    m.thr = static_cast<uint32_t>(thr);
    EXPECT_EQ(out, unit.eval(m, code)) << line;
    const int64_t c = std::clamp<int64_t>(code, 0, int64_t{1} << F);
    if (c >= static_cast<int64_t>(thr))  // uncut: |base| <= 1, n·d <= 2^(F+5)
      EXPECT_LE(static_cast<int64_t>(n) * ((int64_t{1} << F) - c), int64_t{1} << (F + 5)) << line;
    below += n >= 16 && thr < host;
    lit_below += n >= 16 && thr < host && c >= static_cast<int64_t>(thr) && c < host && out != 0;
    above_one += thr > (uint64_t{1} << F);
  }
  EXPECT_EQ(vectors, 2000);
  for (int end : {1, 2, 15, 1024}) EXPECT_TRUE(ns.count(end)) << end;
  EXPECT_GT(below, 500);      // half the materials: a threshold below the host's
  EXPECT_GT(lit_below, 50);   // fragments the host's threshold would cut, lit: a moved cut shows
  EXPECT_GT(above_one, 20);   // thresholds above 1.0 (every code cut)
  // The dividers are the C model's at n = 0 too (Unit::port_n_min): their files start with n = 0 and keep drawing it.
  EXPECT_EQ(unit.port_n_min(), 1);
  const shadecore::Unit div(shadecore::VariantId::schlick_div, shadecore::default_format(), shadecore::Cutoff::ThetaCr);
  EXPECT_EQ(div.port_n_min(), 0);
  EXPECT_EQ(div.port_thr_min(16), 0);
  EXPECT_EQ(unit.port_thr_min(16), 0);  // 2^F - 2^(F+5)/16 < 0
  EXPECT_EQ(unit.port_thr_min(1024), (int64_t{1} << F) - (int64_t{1} << (F + 5)) / 1024);
  const std::string dv = vectors_file(d, "div.hex", "--variant schlick_div --mode ports --count 2000 --seed 21");
  EXPECT_NE(dv.find("n in 0..1024"), std::string::npos);
  std::stringstream din(dv);
  int zeros = 0;
  bool first = true;
  while (std::getline(din, line)) {
    if (line.rfind("//", 0) == 0) continue;
    std::istringstream w(line);
    uint64_t n = 0, thr = 0, coef = 0, cos = 0, out = 0;
    ASSERT_TRUE(w >> std::hex >> n >> thr >> coef >> cos >> out) << line;
    if (first) EXPECT_EQ(n, 0u) << line;
    first = false;
    zeros += n == 0;
    ASSERT_LE(n, 1024u) << line;
    const int64_t code = (cos & (uint64_t{1} << (F + 1))) ? static_cast<int64_t>(cos) - (int64_t{1} << (F + 2))
                                                          : static_cast<int64_t>(cos);
    shadecore::UnitMaterial m = div.setup(std::max<int64_t>(16, n));
    m.n = static_cast<int>(n);
    m.thr = static_cast<uint32_t>(thr);
    EXPECT_EQ(out, div.eval(m, code)) << line;
  }
  EXPECT_GE(zeros, 256);  // the n = 0 run is 256 fragments long (kZeroRun), then n = 0 is as rare as any n
}

TEST(VectorsCli, BadArgumentsAndOutputRules) {
  const fs::path d = temp_dir("rules");
  expect_one_line_error("vectors --mode sometimes --out " + (d / "x.hex").string(), "unknown mode");
  expect_one_line_error("vectors --mode hard --n 16..20 --out " + (d / "x.hex").string(), "--n does not apply");
  expect_one_line_error("vectors --mode exhaustive --seed 3 --out " + (d / "x.hex").string(), "random and ports only");
  expect_one_line_error("vectors --mode ports --n 16..20 --out " + (d / "x.hex").string(), "--n does not apply to --mode ports");
  expect_one_line_error("vectors --mode random --count 0 --out " + (d / "x.hex").string(), "--count must be");
  expect_one_line_error("vectors --mode exhaustive --config wide --out " + (d / "x.hex").string(), "over the limit");
  expect_one_line_error("vectors --mode hard --out " + d.string(), "is a directory");
  expect_one_line_error("vectors --mode hard --out /nonexistent-dir/x.hex", "cannot write");
  EXPECT_FALSE(fs::exists(d / "x.hex"));
  // A symlink is written through (the link stays a link); a character device is written in place.
  std::ofstream(d / "target.hex") << "old\n";
  fs::create_symlink(d / "target.hex", d / "link.hex");
  ASSERT_EQ(run_cli("vectors --mode hard --out " + (d / "link.hex").string()).status, 0);
  EXPECT_TRUE(fs::is_symlink(d / "link.hex"));
  EXPECT_NE(slurp(d / "target.hex").find("shadecore vectors"), std::string::npos);
  ASSERT_EQ(run_cli("vectors --mode hard --out /dev/null").status, 0);
  EXPECT_TRUE(fs::is_character_file("/dev/null"));
  for (const auto& e : fs::directory_iterator(d))
    EXPECT_EQ(e.path().filename().string().find(".tmp."), std::string::npos) << "temporary file left behind";
  fs::remove_all(d);
}

// `vectors --core lighting`: the bundle's format; reproducible from the seed; every colour LightCore's.
TEST(VectorsCli, LightingRecordsReplayThroughTheModel) {
  const fs::path d = temp_dir("lvec");
  auto make = [&](const std::string& name, const std::string& args) {
    return vectors_file(d, name, "--core lighting --features mono_spec " + args);
  };
  const std::string a = make("a.hex", "--mode random --count 80 --seed 21");
  EXPECT_EQ(a.substr(a.find("\n0 ")), make("b.hex", "--mode random --count 80 --seed 21").substr(a.find("\n0 ")));
  const std::string c = make("c.hex", "--mode random --count 80 --seed 22");
  EXPECT_NE(a.substr(a.find("\n0 ")), c.substr(c.find("\n0 ")));
  const std::string h = make("h.hex", "--mode hard");
  EXPECT_NE(a.find("seed 21"), std::string::npos);
  const shadecore::FeatureSet fset = shadecore::feature_set_named_or_file("mono_spec");
  const shadecore::LightCore core(fset);
  const int F = fset.format().frac;
  for (const std::string* text : {&a, &h}) {
    shadecore::LightRegs regs;
    std::stringstream in(*text);
    std::string line;
    int frags = 0, lit = 0;
    while (std::getline(in, line)) {
      if (line.rfind("//", 0) == 0) continue;
      std::vector<uint64_t> w;
      ASSERT_TRUE(read_record(line, w)) << line;
      if (w[0] == 0) {
        regs.write(core.widths(), static_cast<uint32_t>(w[1]), static_cast<uint32_t>(w[2]));
        continue;
      }
      const shadecore::Colour col = core.eval(regs, record_fragment(w, F));
      for (int i = 0; i < 3; ++i) EXPECT_EQ(w[7 + i], col.c[i]) << line;
      EXPECT_EQ(w[8], 0u);  // mono
      lit += w[7] != 0;
      ++frags;
    }
    EXPECT_GT(frags, 50);
    EXPECT_GT(lit, 5);  // not all black: the specular terms are exercised
  }
  expect_one_line_error("vectors --core lighting --features mono_spec --mode exhaustive --out " + (d / "x.hex").string(),
                        "unknown mode");
  expect_one_line_error("vectors --core lighting --mode hard --out " + (d / "x.hex").string(), "needs --features");
  expect_one_line_error("vectors --core lighting --features mono_spec --variant cs16 --mode hard --out " + (d / "x.hex").string(),
                        "--variant does not apply");
  expect_one_line_error("vectors --features mono_spec --mode hard --out " + (d / "x.hex").string(), "--core lighting only");
  EXPECT_FALSE(fs::exists(d / "x.hex"));
  fs::remove_all(d);
}

// ---------------------------------------------------------------------------- handoff (arguments only)
TEST(HandoffCli, BadArgumentsGiveOneLineErrorsAndWriteNothing) {
  const fs::path d = temp_dir("ho");
  expect_one_line_error("handoff", "--out DIR is required");
  expect_one_line_error("handoff --core nosuch --out " + (d / "b").string(), "unknown --core");
  expect_one_line_error("handoff --features diffuse --out " + (d / "b").string(), "applies to --core lighting only");
  expect_one_line_error("handoff --axi --out " + (d / "b").string(), "--axi applies to --core lighting only");
  expect_one_line_error("handoff --axi --print-port-table", "--axi applies to --core lighting only");
  expect_one_line_error("handoff --synth sometimes --out " + (d / "b").string(), "unknown --synth");
  expect_one_line_error("handoff --tagw 0 --out " + (d / "b").string(), "--tagw");
  expect_one_line_error("handoff --top 9x --out " + (d / "b").string(), "not a Verilog identifier");
  expect_one_line_error("handoff --top sc_cs16 --out " + (d / "b").string(), "clashes");
  expect_one_line_error("handoff --variant nosuch --out " + (d / "b").string(), "unknown variant");
  expect_one_line_error("handoff --config huge --out " + (d / "b").string(), "unknown config");
  expect_one_line_error("handoff --no-sim --out " + (d / "b").string(), "--no-sim needs --signoff off");
  expect_one_line_error("handoff --no-sim --signoff on --out " + (d / "b").string(), "--no-sim needs --signoff off");
  std::ofstream(d / "file") << "x";
  expect_one_line_error("handoff --out " + (d / "file").string(), "not a directory");
  fs::create_directories(d / "full");
  std::ofstream(d / "full" / "keep.txt") << "mine";
  expect_one_line_error("handoff --out " + (d / "full").string(), "not empty");
  EXPECT_EQ(slurp(d / "full" / "keep.txt"), "mine");
  EXPECT_FALSE(fs::exists(d / "b"));
  EXPECT_FALSE(fs::exists(d / "b.tar.gz"));
  fs::remove_all(d);
}

// --core lighting: bad feature sets and the options that do not apply are one-line errors, nothing written.
TEST(HandoffCli, LightingBadArgumentsGiveOneLineErrorsAndWriteNothing) {
  const fs::path d = temp_dir("hol");
  const std::string out = " --out " + (d / "b").string();
  expect_one_line_error("handoff --core lighting" + out, "needs --features");
  expect_one_line_error("handoff --core lighting --features nosuch" + out, "unknown feature set 'nosuch'");
  std::ofstream(d / "bad.json") << "{ \"lights\": [\"directional\"], \"specular\": \"cs17\" }";
  expect_one_line_error("handoff --core lighting --features " + (d / "bad.json").string() + out, "cs17");
  std::ofstream(d / "broken.json") << "{ \"lights\": [";
  expect_one_line_error("handoff --core lighting --features " + (d / "broken.json").string() + out, "malformed JSON");
  for (const char* opt : {"--variant cs16", "--config narrow", "--frac 12", "--guard 5", "--cutoff sign_clamp",
                          "--norm phong", "--coef classical"})
    expect_one_line_error("handoff --core lighting --features diffuse " + std::string(opt) + out,
                          std::string(opt).substr(0, std::string(opt).find(' ')) + " does not apply to --core lighting");
  // diffuse: latency 4, up to 5 fragments in flight: TAGW 2 cannot tell them apart.
  expect_one_line_error("handoff --core lighting --features diffuse --tagw 2" + out, "too narrow");
  expect_one_line_error("handoff --core lighting --features diffuse --tagw 33" + out, "--tagw");
  expect_one_line_error("handoff --core lighting --features diffuse --count 0" + out, "--count");
  expect_one_line_error("handoff --core lighting --features diffuse --synth fast" + out, "unknown --synth");
  expect_one_line_error("handoff --core lighting --features diffuse --top tb_shadecore_light" + out, "clashes");
  expect_one_line_error("handoff --core lighting --features diffuse --out " + (d / "bad.json").string(), "not a directory");
  EXPECT_FALSE(fs::exists(d / "b"));
  EXPECT_FALSE(fs::exists(d / "b.tar.gz"));
  fs::remove_all(d);
}

// The lighting core's bundle (diffuse: the smallest set; few random fragments, synthesis skipped — Yosys
// on the named sets is the rtl.yosys.sc_light.* tests): handoff exits 0 only after both delivered
// simulators passed; the vector files replay through the C model; one corrupted expected colour makes
// run_icarus.sh and run_verilator.sh FAIL naming that vector, and breaks the manifest.
TEST(HandoffLighting, DiffuseBundlePassesAndACorruptedCopyFails) {
  const fs::path d = temp_dir("hld");
  const fs::path b = d / "hl", vobj = d / "vobj";
  const CliRun r = run_shell("VERILATOR_OBJ_DIR=" + vobj.string() + " " + SHADECORE_CLI +
                             " handoff --core lighting --features diffuse --count 60 --seed 9 --synth skip --no-ice40 --signoff off --out " +
                             b.string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("run_icarus.sh: PASS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("run_verilator.sh: PASS"), std::string::npos) << r.out;
  {  // --no-sim writes the very same design files without running the benches (scripts/timing_report.py's check)
    const fs::path ns = d / "ns";
    const CliRun q = run_shell(std::string(SHADECORE_CLI) + " handoff --core lighting --features diffuse --count 60 --seed 9"
                               " --synth skip --no-ice40 --signoff off --no-sim --out " + ns.string());
    ASSERT_EQ(q.status, 0) << q.out << q.err;
    EXPECT_NE(q.out.find("run_icarus.sh: not run at generation time (--no-sim)"), std::string::npos) << q.out;
    EXPECT_EQ(q.out.find("PASS"), std::string::npos) << q.out;
    const auto design = [](const fs::path& f) {  // without the "made by" lines (the command, --no-sim and --out in it)
      std::istringstream in(slurp(f));
      std::string line, out;
      while (std::getline(in, line)) {
        std::string low = line;
        for (char& c : low) c = static_cast<char>(std::tolower(static_cast<unsigned char>(c)));
        if (low.find("made by") == std::string::npos) out += line + "\n";
      }
      return out;
    };
    int compared = 0;
    for (const auto& e : fs::recursive_directory_iterator(b)) {
      const std::string rel = fs::relative(e.path(), b).string();
      if (!e.is_regular_file() || !(rel.rfind("rtl/", 0) == 0 || rel.rfind("tb/", 0) == 0 ||
                                    rel.rfind("vectors/", 0) == 0 || rel == "filelist.f"))
        continue;
      ASSERT_TRUE(fs::exists(ns / rel)) << rel;
      EXPECT_EQ(design(e.path()), design(ns / rel)) << rel;
      ++compared;
    }
    EXPECT_GT(compared, 8);
  }
  for (const char* f : {"rtl/shadecore_light_top.v", "rtl/sc_light.v", "rtl/sc_delay.v", "rtl/sc_light_regs.vh",
                        "filelist.f", "constraints.sdc", "interface.md", "tb/tb_shadecore_light.v", "tb/tb_config.vh",
                        "tb/tb_dut.vh", "run_icarus.sh", "run_verilator.sh", "vectors/hard.hex", "vectors/random.hex",
                        "reports/verilator_lint.log", "reports/yosys_synth.log", "reports/yosys_synth.ys",
                        "reports/sim_icarus.log", "reports/sim_verilator.log", "MANIFEST.sha256", "LICENSE"})
    EXPECT_TRUE(fs::exists(b / f)) << f;
  // The licence travels with the RTL: every shipped source carries its SPDX line.
  for (const char* f : {"rtl/sc_light.v", "rtl/sc_delay.v", "rtl/sc_light_regs.vh", "tb/tb_shadecore_light.v"})
    EXPECT_NE(slurp((b / f).string()).find("SPDX-License-Identifier: Apache-2.0"), std::string::npos) << f;
  // diffuse has no specular unit, no normaliser, no reciprocal: none of their files.
  for (const char* f : {"rtl/sc_specular.v", "rtl/sc_cs16.v", "rtl/sc_normalize.v", "rtl/sc_recip.v"})
    EXPECT_FALSE(fs::exists(b / f)) << f;
  EXPECT_TRUE(fs::exists(d / "hl.tar.gz"));
  EXPECT_EQ(run_shell("sha256sum -c --quiet MANIFEST.sha256", b.string()).status, 0);
  const std::string md = slurp(b / "interface.md");
  EXPECT_NE(md.find("| `reg_ready_o` | out | 1 |"), std::string::npos);
  EXPECT_NE(md.find("| `mat_diffuse` | 0x18..0x1a | 3"), std::string::npos) << md;
  EXPECT_NE(md.find("**4 cycles**"), std::string::npos);
  // every register of the map says whether this core reads it (no "?" row: a register the table forgot)
  EXPECT_EQ(md.find("| ? |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `colour_material` | 0x08 | 1 | mode: bit 0 GL_COLOR_MATERIAL"), std::string::npos) << md;

  // Replay vectors/random.hex through the C model: every expected colour is LightCore::eval's.
  const shadecore::FeatureSet fs = shadecore::feature_set_named_or_file("diffuse");
  const shadecore::LightCore core(fs);
  const int F = fs.format().frac;
  shadecore::LightRegs regs;
  std::ifstream in(b / "vectors" / "random.hex");
  std::string line;
  int records = 0, frags = 0, writes = 0;
  while (std::getline(in, line)) {
    if (line.rfind("//", 0) == 0) continue;
    std::vector<uint64_t> w;
    ASSERT_TRUE(read_record(line, w)) << line;
    ++records;
    if (w[0] == 0) {
      regs.write(core.widths(), static_cast<uint32_t>(w[1]), static_cast<uint32_t>(w[2]));
      ++writes;
      continue;
    }
    ASSERT_EQ(w[0] & 0xF, 1u) << line;
    EXPECT_EQ(w[0] >> 4, static_cast<uint64_t>(core.latency(regs))) << line;  // T = 1 + 16·latency
    const shadecore::Colour c = core.eval(regs, record_fragment(w, F));
    for (int i = 0; i < 3; ++i) EXPECT_EQ(w[7 + i], c.c[i]) << line;
    ++frags;
  }
  EXPECT_EQ(frags, 60);
  EXPECT_GT(writes, 10);  // the program, at least
  for (const char* log : {"sim_icarus.log", "sim_verilator.log"})
    EXPECT_NE(slurp(b / "reports" / log).find("PASS " + std::to_string(records) + " vectors (60 fragments checked, " +
                                              std::to_string(writes) + " register writes"),
              std::string::npos)
        << log;

  // One corrupted expected colour: the first fragment record of hard.hex whose R is not 0 gets R + 1.
  const fs::path c = d / "corrupt";
  ASSERT_EQ(run_shell("cp -rp " + b.string() + " " + c.string()).status, 0);
  std::ifstream hin(b / "vectors" / "hard.hex");
  std::string text;
  int rec = -1, bad = -1;
  while (std::getline(hin, line)) {
    if (line.rfind("//", 0) != 0) {
      ++rec;
      std::stringstream ss(line);
      std::vector<std::string> w;  // the record's words (16 per record, docs/handoff.md)
      for (std::string x; ss >> x;) w.push_back(x);
      ASSERT_EQ(w.size(), 16u) << line;
      if (bad < 0 && w[0] != "0" && std::stoul(w[7], nullptr, 16) != 0) {
        bad = rec;
        w[7] = fmt_hex(std::stoul(w[7], nullptr, 16) + 1, w[7].size());
        line = w[0];
        for (size_t i = 1; i < w.size(); ++i) line += " " + w[i];
      }
    }
    text += line + "\n";
  }
  ASSERT_GE(bad, 0);
  std::ofstream(c / "vectors" / "hard.hex", std::ios::trunc) << text;
  for (const char* script : {"run_icarus.sh", "run_verilator.sh"}) {
    const CliRun f = run_shell("VERILATOR_OBJ_DIR=" + vobj.string() + " ./" + script, c.string());
    EXPECT_NE(f.status, 0) << script << "\n" << f.out;
    EXPECT_NE(f.out.find("FAIL vector " + std::to_string(bad) + ":"), std::string::npos) << script << "\n" << f.out;
    EXPECT_NE(f.out.find(std::string(script) + ": FAIL"), std::string::npos) << f.out;
  }
  EXPECT_NE(run_shell("sha256sum -c --quiet MANIFEST.sha256", c.string()).status, 0);
  fs::remove_all(d);
}

// The core behind its AXI wrapper (--axi, issue 39): the bundle's bench drives AXI4-Lite and AXI4-Stream and both
// delivered simulators pass; the write records carry the response each address gets (axi_reg_exists); and a wrapper
// that breaks a bus rule fails the bench naming it: TLAST not carried, the stream open while a write waits, a
// partial-strobe write reaching the read-back shadow, an OKAY response before the core drained.
TEST(HandoffLighting, AxiBundlePassesAndBusMutantsFail) {
  const fs::path d = temp_dir("hla");
  const fs::path b = d / "ha", vobj = d / "vobj";
  const CliRun r = run_shell("VERILATOR_OBJ_DIR=" + vobj.string() + " " + SHADECORE_CLI +
                             " handoff --core lighting --features diffuse --axi --count 200 --seed 9 --synth skip --no-ice40"
                             " --signoff off --out " + b.string());
  ASSERT_EQ(r.status, 0) << r.out << r.err;
  EXPECT_NE(r.out.find("run_icarus.sh: PASS"), std::string::npos) << r.out;
  EXPECT_NE(r.out.find("run_verilator.sh: PASS"), std::string::npos) << r.out;
  EXPECT_NE(slurp(b / "rtl" / "shadecore_light_top.v").find("  sc_light_axi #("), std::string::npos);
  EXPECT_NE(slurp(b / "tb" / "tb_config.vh").find("`define TB_AXI"), std::string::npos);
  EXPECT_NE(slurp(b / "reports" / "sim_icarus.log").find("fragments checked with TLAST"), std::string::npos);
  const std::string md = slurp(b / "interface.md");
  EXPECT_NE(md.find("### The AXI view"), std::string::npos) << md;
  EXPECT_NE(md.find("| `s_axis_tdata_i` | in | 184 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `m_axis_tdata_o` | out | 104 |"), std::string::npos) << md;
  // every write record's fourth word is the response of its address in this build; both kinds occur
  const shadecore::FeatureSet fs = shadecore::feature_set_named_or_file("diffuse");
  int okay = 0, slverr = 0;
  for (const char* v : {"hard.hex", "random.hex"}) {
    std::ifstream in(b / "vectors" / v);
    for (std::string line; std::getline(in, line);) {
      if (line.rfind("//", 0) == 0) continue;
      std::vector<uint64_t> w;
      ASSERT_TRUE(read_record(line, w)) << line;
      if (w[0] != 0) continue;
      const bool exists = shadecore::axi_reg_exists(fs, static_cast<uint32_t>(w[1]));
      EXPECT_EQ(w[3], exists ? 0u : 2u) << line;
      (exists ? okay : slverr) += 1;
    }
  }
  EXPECT_GT(okay, 20);
  EXPECT_GT(slverr, 5);
  // the bus mutants: each a one-line edit of the bundle's wrapper (the edit must apply), run in Icarus
  const std::vector<std::pair<std::string, std::string>> mutants = {
      {"s/assign m_axis_tlast_o  = o_tag\\[TAGW\\];/assign m_axis_tlast_o = 1'b0;/", ": TLAST 0, sent with 1"},
      {"s/assign stream_open     = w_state_q == W_IDLE;/assign stream_open = w_state_q != W_CORE;/",
       "s_axis_tready_o is high while a register write awaits its response"},
      {"s/if (aw_take \\&\\& aw_ok) shadow/if (aw_take) shadow/", "read back"},
      {"s/W_CORE: if (core_reg_ready) w_state_q <= W_RESP;/W_CORE: w_state_q <= W_RESP;/", "answered OKAY with"}};
  int k = 0;
  for (const auto& [edit, why] : mutants) {
    const fs::path m = d / ("m" + std::to_string(k++));
    ASSERT_EQ(run_shell("cp -rp " + b.string() + " " + m.string() + " && sed -i \"" + edit + "\" " +
                        (m / "rtl" / "sc_light_axi.v").string()).status, 0);
    ASSERT_NE(slurp(m / "rtl" / "sc_light_axi.v"), slurp(b / "rtl" / "sc_light_axi.v")) << edit;
    const CliRun f = run_shell("./run_icarus.sh", m.string());
    EXPECT_NE(f.status, 0) << edit << "\n" << f.out;
    EXPECT_NE(f.out.find(why), std::string::npos) << edit << "\n" << f.out;
  }
  fs::remove_all(d);
}

// config/interface.json (the README table's and every interface.md's source) lists exactly the ports
// of rtl/sc_specular.v ("ports"), rtl/sc_light.v ("light_ports") and rtl/sc_light_axi.v ("light_axi_ports"), in order,
// with their directions.
TEST(HandoffCli, PortTableMatchesTheRtl) {
  for (const auto& [args, file] : {std::pair<std::string, std::string>{"", "sc_specular.v"}, {" --core lighting", "sc_light.v"},
                                   {" --core lighting --axi", "sc_light_axi.v"}}) {
    const CliRun r = run_cli("handoff --print-port-table" + args);
    ASSERT_EQ(r.status, 0) << r.err;
    std::vector<std::string> table, rtl;
    std::smatch m;
    std::stringstream ts(r.out);
    std::string line;
    while (std::getline(ts, line))
      if (std::regex_search(line, m, std::regex("^\\| `(\\w+)` \\| (in|out) \\|"))) table.push_back(m[2].str() + " " + m[1].str());
    const fs::path src = fs::path(__FILE__).parent_path().parent_path() / "rtl" / file;
    std::stringstream rs(slurp(src));
    while (std::getline(rs, line))
      if (std::regex_search(line, m, std::regex("^\\s*(input|output)\\s+wire\\b.*?(\\w+)\\s*,?\\s*$")))
        rtl.push_back((m[1] == "input" ? "in " : "out ") + m[2].str());
    ASSERT_FALSE(rtl.empty()) << file;
    EXPECT_EQ(table, rtl) << file;
  }
}

// docs/spec.md states what an independent implementer needs (issue 11): its coefficient table (§7.0)
// and its per-unit latency table (§4) must be the C model's.
TEST(SpecDocs, CoefficientAndLatencyTablesMatchTheModel) {
  const std::string spec = slurp(fs::path(__FILE__).parent_path().parent_path() / "docs" / "spec.md");
  ASSERT_FALSE(spec.empty());
  int rows = 0;
  for (const auto& m : shadecore::kModels) {
    std::smatch r;
    const std::regex re("\\| [^|]*\\(`" + std::string(m.key) + "`\\) \\| (\\d+) \\| ([0-9.]+) \\| ([0-9.]+) \\|");
    ASSERT_TRUE(std::regex_search(spec, r, re)) << m.key;
    EXPECT_EQ(std::stoi(r[1]), m.k) << m.key;
    EXPECT_DOUBLE_EQ(std::stod(r[2]), m.pub_a) << m.key;
    EXPECT_DOUBLE_EQ(std::stod(r[3]), m.pub_b) << m.key;
    ++rows;
  }
  EXPECT_EQ(rows, shadecore::kNumModels);
  const shadecore::Format f = shadecore::default_format();
  auto lat = [&](shadecore::VariantId v, bool norm) {
    shadecore::Unit u(v, f, shadecore::Cutoff::ThetaCr);
    u.set_energy(norm);
    return u.latency();
  };
  EXPECT_NE(spec.find("| `sc_cs16` (cs16) | " + std::to_string(lat(shadecore::VariantId::cs16, false)) + " |"), std::string::npos);
  EXPECT_NE(spec.find("| `sc_schlick_nr` | " + std::to_string(lat(shadecore::VariantId::schlick_nr, false)) + " |"), std::string::npos);
  EXPECT_NE(spec.find("F + 4 (12 / 20 / 28 at F = 8 / 16 / 24)"), std::string::npos);
  EXPECT_EQ(lat(shadecore::VariantId::schlick_div, false), f.frac + 4);
  EXPECT_EQ(lat(shadecore::VariantId::schlick_iter, false), f.frac + 4);
  EXPECT_NE(spec.find("the unit's + 2 (cs16: " + std::to_string(lat(shadecore::VariantId::cs16, true)) + ")"), std::string::npos);
}
