// SPDX-License-Identifier: Apache-2.0
// shadecore eval — one input through the bit-exact C model, with every named intermediate (the
// model's trace structs Cs16Trace / SchlickTrace, stage names as in the RTL), the output code and
// value, and the double-precision references (docs/spec.md §5).
//
//   shadecore eval --n 128 --cos 0.95
//   shadecore eval --variant schlick_nr --config narrow --n 1000 --code 0xfe
//   shadecore eval --norm blinn --coef classical --n 64 --cos 0.99 --json -
#include <cmath>
#include <regex>

#include <fmt/core.h>
#include <nlohmann/json.hpp>

#include "commands.hpp"
#include "output.hpp"
#include "shadecore/analysis/golden.hpp"
#include "unit_spec.hpp"

namespace shadecore::cli {
namespace {

struct EvalArgs {
  std::shared_ptr<UnitOptions> unit = std::make_shared<UnitOptions>();
  long long n = 0;
  std::string code_text;
  double cos = 0.0;
  std::string json_path;
  CLI::Option* code_opt = nullptr;
  CLI::Option* cos_opt = nullptr;
};

// --code: a signed decimal integer, or 0x-hex as the raw (F+2)-bit input word (two's complement,
// so at F = 16 0x3ffff is -1).
int64_t parse_code(const std::string& text, const Format& f) {
  static const std::regex dec(R"(^\s*-?\d{1,12}\s*$)"), hex(R"(^\s*0[xX]([0-9a-fA-F]{1,12})\s*$)");
  std::smatch m;
  int64_t code;
  if (std::regex_match(text, m, hex)) {
    const uint64_t raw = std::stoull(m[1].str(), nullptr, 16);
    if (raw >> f.in_bits())
      throw std::invalid_argument(fmt::format("--code {} does not fit the {}-bit input word", text, f.in_bits()));
    const int sh = 64 - f.in_bits();
    code = static_cast<int64_t>(raw << sh) >> sh;
  } else if (std::regex_match(text, dec)) {
    code = std::stoll(text);
  } else {
    throw std::invalid_argument("malformed --code '" + text + "' (a signed integer or 0x-hex input word)");
  }
  if (code < f.in_min() || code > f.in_max())
    throw std::invalid_argument(fmt::format("--code {} out of range [{}, {}] (F+2 = {}-bit signed word)", text,
                                            f.in_min(), f.in_max(), f.in_bits()));
  return code;
}

std::string hexw(uint64_t v, int bits) { return fmt::format("0x{:0{}x}", v, (bits + 3) / 4); }

struct Row {
  std::string stage, name;
  std::string hex;
  std::string dec;
  std::string value;  // real value, or empty
  std::string note;
};

void run(EvalArgs& a) {
  const UnitSpec spec = resolve_unit(*a.unit);
  const Format& f = spec.format;
  const int F = f.frac;
  validate_n(a.n);
  const bool by_code = a.code_opt->count() > 0, by_cos = a.cos_opt->count() > 0;
  if (by_code == by_cos) throw std::invalid_argument("give exactly one of --code K and --cos X");
  int64_t code;
  if (by_cos) {
    if (!std::isfinite(a.cos)) throw std::invalid_argument("--cos must be a finite number");
    const double scaled = std::ldexp(a.cos, F);
    if (scaled < double(f.in_min()) - 0.5 || scaled >= double(f.in_max()) + 0.5)
      throw std::invalid_argument(fmt::format("--cos {} is outside the input word's range [-2, 2) at F = {}", a.cos, F));
    code = std::llround(scaled);  // nearest code, ties away from zero
  } else {
    code = parse_code(a.code_text, f);
  }
  if (!a.json_path.empty() && a.json_path != "-") check_output_path(a.json_path);

  const Unit unit = spec.unit();
  const UnitMaterial mat = unit.setup(a.n);
  const uint32_t out = unit.eval(mat, code);  // the value every other tool (sim, vectors) uses
  const int n = static_cast<int>(a.n);
  const int W = f.work();
  auto val = [](double x) { return fmt::format("{:.9f}", x); };
  auto fixed = [&](uint64_t v, int frac_bits) { return val(std::ldexp(static_cast<double>(v), -frac_bits)); };
  const uint64_t in_word = static_cast<uint64_t>(code) & ((uint64_t{1} << f.in_bits()) - 1);

  std::vector<Row> rows;
  nlohmann::json trace;
  uint32_t unit_out = 0;
  double ref = 0.0;  // the variant in double for the same (clamped) input
  std::string ref_name;
  const double c_real = std::ldexp(static_cast<double>(std::clamp<int64_t>(code, 0, f.one())), -F);
  if (spec.is_cs16()) {
    Cs16Trace t;
    const Unit u = spec.unit();
    const bool form = u.is_cs16_form();
    unit_out = form ? cs16f_eval(f, spec.cutoff, u.stages(), Cs16Material{mat.n, mat.thr}, code, &t)
                    : cs16_eval(f, spec.cutoff, Cs16Material{mat.n, mat.thr}, code, &t);
    rows.push_back({"S0", "c", hexw(t.c, F + 1), std::to_string(t.c), fixed(t.c, F), "cos clamped to [0, 2^F]"});
    rows.push_back({"S0", "d", hexw(t.d, F + 1), std::to_string(t.d), fixed(t.d, F), "2^F - c"});
    rows.push_back({"S1", "base", hexw(static_cast<uint64_t>(t.base) & ((uint64_t{1} << (F + 13)) - 1), F + 13),
                    std::to_string(t.base), val(std::ldexp(static_cast<double>(t.base), -(F + 4))),
                    "2^(F+4) - n*d, signed, F+4 fraction bits"});
    rows.push_back({"S1", "cut", t.cut ? "1" : "0", t.cut ? "1" : "0", "",
                    spec.cutoff == Cutoff::ThetaCr ? fmt::format("c < thr ({} {} {})", t.c, t.c < mat.thr ? "<" : ">=", mat.thr)
                                                   : fmt::format("base <= 0 ({})", t.base <= 0 ? "yes" : "no")});
    if (form) {  // docs/spec.md §3.4: per-stage widths, truncated folded squarers
      const Cs16Stages& st = u.stages();
      for (int k = 0; k <= 3; ++k)
        rows.push_back({fmt::format("S{}", k + 1), fmt::format("x{}", k), hexw(t.x[k], st.w[k] + 1), std::to_string(t.x[k]),
                        fixed(t.x[k], st.w[k]),
                        k == 0 ? fmt::format("base if not cut (cut also where base <= 0), {} fraction bits", st.w[0])
                               : fmt::format("x^2 to {} fraction bits ({} columns dropped{})", st.w[k], st.sq[k].drop,
                                             squarer_form(spec.variant)->compensate ? ", compensated, rounded" : ", floor")});
      rows.push_back({"S5", "out", hexw(t.out, F + 1), std::to_string(t.out), fixed(t.out, F),
                      fmt::format("x3^2 rounded half up to F bits ({} columns dropped); S6 registers it", st.sq[4].drop)});
    } else {
      for (int k = 0; k <= 4; ++k)
        rows.push_back({fmt::format("S{}", k + 1), fmt::format("x{}", k), hexw(t.x[k], W + 1), std::to_string(t.x[k]),
                        fixed(t.x[k], W), k == 0 ? fmt::format("|base| aligned to W = {} fraction bits", W)
                                                 : "floor(x^2 / 2^W)"});
      rows.push_back({"S6", "out", hexw(t.out, F + 1), std::to_string(t.out), fixed(t.out, F), "round half up to F bits"});
    }
    trace = {{"c", t.c}, {"d", t.d}, {"base", t.base}, {"cut", t.cut},
             {"x", {t.x[0], t.x[1], t.x[2], t.x[3], t.x[4]}}, {"out", t.out}};
    ref = spec.cutoff == Cutoff::ThetaCr ? golden::cs16_theta_cr(c_real, n) : golden::cs16_sign_clamp(c_real, n);
    ref_name = "cs16";
  } else if (is_table_variant(spec.variant)) {
    const int E = unit.entries();
    TableTrace t;
    unit_out = table_eval(f, mat.tab->data(), E, code, &t);
    rows.push_back({"-", "c", hexw(t.c, F + 1), std::to_string(t.c), fixed(t.c, F), "cos clamped to [0, 2^F]"});
    rows.push_back({"-", "i", std::to_string(t.index), std::to_string(t.index), "",
                    fmt::format("((E-1)*c) >> F, E = {}: RAM read address", E)});
    rows.push_back({"S0", "fr", hexw(t.frac, F), std::to_string(t.frac), fixed(t.frac, F), "((E-1)*c) mod 2^F"});
    rows.push_back({"S0", "V", hexw(t.value, F + 1), std::to_string(t.value), fixed(t.value, F), "RAM[i] value"});
    rows.push_back({"S0", "D", hexw(t.delta, F + 1), std::to_string(t.delta), fixed(t.delta, F), "RAM[i] delta"});
    rows.push_back({"S1", "prod", hexw(t.prod, 2 * F + 1), std::to_string(t.prod), "", "D*fr + 2^(F-1)"});
    rows.push_back({"S2", "out", hexw(t.out, F + 1), std::to_string(t.out), fixed(t.out, F), "V + (prod >> F)"});
    trace = {{"c", t.c}, {"index", t.index}, {"frac", t.frac}, {"value", t.value}, {"delta", t.delta},
             {"prod", t.prod}, {"out", t.out}};
    ref = golden::table_lerp(E, n, c_real);
    ref_name = "table_lerp";
  } else {
    SchlickTrace t;
    const SchlickMaterial sm{mat.n};
    switch (spec.variant) {
      case VariantId::schlick_nr: unit_out = schlick_nr_eval(f, sm, code, &t); break;
      case VariantId::schlick_iter: unit_out = schlick_iter_eval(f, sm, code, &t); break;
      default: unit_out = schlick_div_eval(f, sm, code, &t); break;
    }
    const int DB = schlick_den_bits(F);
    rows.push_back({"S0", "c", hexw(t.c, F + 1), std::to_string(t.c), fixed(t.c, F), "cos clamped to [0, 2^F]"});
    rows.push_back({"S1", "Dc", hexw(t.den, DB), std::to_string(t.den), fixed(t.den, F), "n*(2^F - c) + c, exact"});
    trace = {{"c", t.c}, {"n", t.n}, {"den", t.den}, {"out", t.out}};
    if (spec.variant == VariantId::schlick_nr) {
      const int R = schlick_nr_recip_frac(F);
      rows.push_back({"S2", "s", std::to_string(t.shift), std::to_string(t.shift), "", "leading-zero count of Dc"});
      rows.push_back({"S2", "mt", hexw(t.mt, R + 1), std::to_string(t.mt), fixed(t.mt, R), "Dc normalised to [1, 2), R fraction bits"});
      rows.push_back({"S3", "idx", std::to_string(t.idx), std::to_string(t.idx), "", "table index"});
      rows.push_back({"S3", "y0", hexw(t.y[0], 10), std::to_string(t.y[0]), fixed(t.y[0], kSchlickNrTableFrac), "table entry"});
      rows.push_back({"S5", "y1", hexw(t.y[1], R + 1), std::to_string(t.y[1]), fixed(t.y[1], R), "Newton-Raphson 1"});
      rows.push_back({"S7", "y2", hexw(t.y[2], R + 1), std::to_string(t.y[2]), fixed(t.y[2], R), "Newton-Raphson 2"});
      rows.push_back({"S8", "p", hexw(t.prod, 2 * F + 8), std::to_string(t.prod), "", "c * y2"});
      trace.update({{"shift", t.shift}, {"mt", t.mt}, {"idx", t.idx}, {"y", {t.y[0], t.y[1], t.y[2]}}, {"prod", t.prod}});
    } else {
      rows.push_back({fmt::format("Q{}", F + 1), "q", hexw(t.quot, F + 2), std::to_string(t.quot), fixed(t.quot, F + 1),
                      "floor(c * 2^(F+1) / Dc)"});
      rows.push_back({fmt::format("Q{}", F + 1), "r", hexw(t.rem, DB), std::to_string(t.rem), "", "remainder"});
      trace.update({{"quot", t.quot}, {"rem", t.rem}});
    }
    rows.push_back({spec.variant == VariantId::schlick_nr ? "S9" : fmt::format("Q{}", F + 1), "out", hexw(t.out, F + 1),
                    std::to_string(t.out), fixed(t.out, F), "round half up to F bits"});
    ref = golden::schlick(c_real, n);
    ref_name = "schlick";
  }
  double coef_real = 1.0;
  if (spec.norm) {
    const EnergyFormat nf{F, kCoefIntBits};
    const uint64_t p = static_cast<uint64_t>(unit_out) * mat.coef;
    const uint64_t nout = energy_eval(nf, mat.coef, unit_out);
    rows.push_back({"N1", "p", hexw(p, nf.prod_bits()), std::to_string(p), fixed(p, 2 * F), "unit out * coef, exact"});
    rows.push_back({"N2", "out", hexw(nout, nf.out_bits()), std::to_string(nout), fixed(nout, F), "round half up to F bits"});
    trace["norm"] = {{"p", p}, {"out", nout}};
    unit_out = static_cast<uint32_t>(nout);
  }
  if (unit_out != out)  // the trace and Unit::eval are the same model: this cannot happen
    throw std::runtime_error(fmt::format("internal: trace output {} != Unit::eval {}", unit_out, out));

  // Which coefficient model this n used (with --norm all it depends on n, as in Unit::set_energy).
  std::string norm_desc;
  if (spec.norm) {
    const int model = spec.norm_model >= 0 ? spec.norm_model : n % kNumModels;
    const CoefKind kind = spec.norm_model >= 0 ? spec.coef_kind : ((n / kNumModels) % 2 ? CoefKind::Classical : CoefKind::Fitted);
    coef_real = coef_value(static_cast<Model>(model), kind, n);
    norm_desc = fmt::format("{} {}", kModels[model].key, to_string(kind));
  }
  const double cos_pow = golden::cos_pow(c_real, n);
  const double err_ulp = static_cast<double>(out) - std::ldexp(coef_real * ref, F);

  if (a.json_path != "-") {  // with --json - stdout carries the JSON only
    fmt::print("eval: {}, n = {}\n", spec.describe(), n);
    fmt::print("material   mat_n_i = {}", n);
    if (spec.is_cs16()) fmt::print(", mat_thr_i = {} ({}) = thr(n) = ceil(cos(6/sqrt(n))*2^F)", hexw(mat.thr, F + 1), mat.thr);
    if (mat.tab) fmt::print(", table RAM = {} words {{D, V}} (V[i] = round((i/{})^n * 2^F))", mat.tab->size(), mat.tab->size() - 1);
    if (spec.norm) fmt::print(", mat_coef_i = {} ({}) = {} coef(n) = {:.9f}", hexw(mat.coef, spec.coef_bits()), mat.coef,
                              norm_desc, coef_real);
    fmt::print("\n");
    fmt::print("input      in_cos_i = {} (code {}) = {}{}\n", hexw(in_word, f.in_bits()), code,
               val(std::ldexp(static_cast<double>(code), -F)), by_cos ? fmt::format("  (--cos {})", a.cos) : "");
    for (const Row& r : rows)
      fmt::print("{:<3} {:<5} {:>14} {:>12}  {:<13}  {}\n", r.stage, r.name, r.hex, r.dec, r.value, r.note);
    fmt::print("output     out_spec_o = {} ({}) = {}\n", hexw(out, spec.out_bits()), out, fixed(out, F));
    fmt::print("double     cos^n = {:.9g}, {} = {:.9g}{}; out - 2^F*{} = {:+.6f} ulp\n", cos_pow, ref_name, ref,
               spec.norm ? fmt::format(", coef*{} = {:.9g}", ref_name, coef_real * ref) : "",
               spec.norm ? "coef*" + ref_name : ref_name, err_ulp);
  }

  if (!a.json_path.empty()) {
    nlohmann::json j = {{"variant", spec.variant_name}, {"config", spec.config_name},
                        {"format", {{"frac", f.frac}, {"guard", f.guard}}}, {"cutoff", to_string(spec.cutoff)},
                        {"n", n}, {"code", code}, {"in_word", hexw(in_word, f.in_bits())},
                        {"material", {{"n", mat.n}, {"thr", mat.thr}, {"coef", mat.coef}}},
                        {"trace", trace}, {"out", out}, {"out_hex", hexw(out, spec.out_bits())},
                        {"out_value", std::ldexp(static_cast<double>(out), -F)},
                        {"double", {{"cos_pow", cos_pow}, {ref_name, ref}, {"error_ulp", err_ulp}}}};
    if (spec.norm) {
      j["norm"] = {{"model", norm_desc}, {"coef", coef_real}};
      j["double"]["coef_times_" + ref_name] = coef_real * ref;
    } else {
      j["norm"] = nullptr;
    }
    const std::string text = j.dump(2) + "\n";
    if (a.json_path == "-") fmt::print("{}", text);
    else write_output_file(a.json_path, text);
  }
}

}  // namespace

void add_eval(CLI::App& app) {
  auto a = std::make_shared<EvalArgs>();
  auto* sub = app.add_subcommand("eval", "Evaluate one input on the bit-exact C model, with every intermediate");
  add_unit_options(sub, a->unit);
  sub->add_option("--n", a->n, "Specular exponent n (16..1024)")->required();
  a->code_opt = sub->add_option("--code", a->code_text, "Input code: signed integer, or 0x-hex (F+2)-bit word")->check(cliargs::NonEmpty("code"));
  a->cos_opt = sub->add_option("--cos", a->cos, "Input cos θ as a real number (rounded to the nearest code)");
  sub->add_option("--json", a->json_path, "Also write the result as JSON (- for stdout)")->check(cliargs::NonEmpty("path"));
  sub->callback([a] { run(*a); });
}

}  // namespace shadecore::cli
