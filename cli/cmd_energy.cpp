// SPDX-License-Identifier: Apache-2.0
// shadecore energy — directional-hemispherical reflectance R(θi) of each normalised BRDF, with the
// fixed-point unit output and the fixed-point coefficient (bit-accurate), over the hemisphere.
#include <algorithm>
#include <atomic>
#include <chrono>
#include <cmath>
#include <mutex>
#include <sstream>
#include <thread>

#include <fmt/core.h>
#include <fmt/format.h>
#include <nlohmann/json.hpp>

#include "shadecore/common/args.hpp"
#include "commands.hpp"
#include "output.hpp"
#include "shadecore/common/progress.hpp"
#include "shadecore/units/coef.hpp"
#include "shadecore/configs.hpp"
#include "shadecore/analysis/energy.hpp"

namespace shadecore::cli {
namespace {

struct EnergyArgs {
  std::string model = "all";
  std::string n_range = "16..1024";
  int n_step = 1;
  std::string angles = "0,15,30,45,60,75,85";
  std::string coef = "fitted";
  std::string cutoff = "theta_cr";
  std::string config;
  std::string method = "cells";
  int radial = 400, azimuth = 200;
  bool double_model = false;
  int threads = 1;
  std::string json_path, plots_dir;
  bool grid_option_given = false;  // --radial / --azimuth given explicitly (they apply to --method grid)
  ProgressFlags progress;
};

const std::vector<std::string> kPlotFiles = {"energy.csv", "energy_vs_angle.png", "energy_max_vs_n.png"};

std::vector<double> parse_angles(const std::string& s) {
  std::vector<double> out;
  std::stringstream ss(s);
  std::string tok;
  while (std::getline(ss, tok, ',')) {
    std::size_t pos = 0;
    double v;
    try {
      v = std::stod(tok, &pos);
    } catch (const std::exception&) {
      throw std::invalid_argument("malformed angle list '" + s + "' (expected degrees, e.g. 0,30,60)");
    }
    if (pos != tok.size() && tok.find_first_not_of(' ', pos) != std::string::npos)
      throw std::invalid_argument("malformed angle list '" + s + "'");
    if (!(v >= 0 && v < 90)) throw std::invalid_argument("incidence angle " + tok + " out of range [0, 90)");
    out.push_back(v);
  }
  if (out.empty()) throw std::invalid_argument("empty angle list");
  return out;
}

void run(const EnergyArgs& a) {
  energy::Options o;
  o.format = config_named(a.config).format;
  o.cutoff = parse_cutoff_name(a.cutoff);
  o.coef = parse_coef_kind(a.coef);
  o.fixed_point = !a.double_model;
  if (a.radial < 8 || a.radial > 100000 || a.azimuth < 8 || a.azimuth > 100000)
    throw std::invalid_argument("--radial and --azimuth must be in [8, 100000]");
  if (a.method == "cells") o.method = energy::Options::Method::Cells;
  else if (a.method == "grid") o.method = energy::Options::Method::Grid;
  else throw std::invalid_argument("unknown method '" + a.method + "' (known: cells, grid)");
  if (a.grid_option_given && o.method != energy::Options::Method::Grid)
    throw std::invalid_argument("--radial and --azimuth apply to --method grid only");
  o.radial = a.radial;
  o.azimuth = a.azimuth;
  const auto [lo, hi] = cliargs::parse_n_range(a.n_range);
  const int threads = cliargs::resolve_parallel(a.threads);
  const std::vector<double> angles = parse_angles(a.angles);
  std::vector<Model> models;
  if (a.model == "all") for (const auto& mi : kModels) models.push_back(mi.model);
  else models.push_back(parse_model(a.model));
  // Every output is checked before the run and written only if the whole run succeeds.
  io::OutputSet outs;
  const int json_out = a.json_path.empty() ? -1 : outs.file("--json", a.json_path);
  const int plots_out = a.plots_dir.empty() ? -1 : outs.dir("--plots", a.plots_dir, kPlotFiles);
  std::vector<int> ns;
  for (int n = lo; n <= hi; n += a.n_step) ns.push_back(n);
  if (ns.back() != hi) ns.push_back(hi);

  // R[model][n][angle]
  const std::size_t NA = angles.size(), NN = ns.size();
  std::vector<double> R(models.size() * NN * NA);
  const auto t0 = std::chrono::steady_clock::now();
  std::atomic<std::size_t> next{0};
  std::mutex err_mu;
  std::string err;
  // The cost of one reflectance grows with n (the lobe is narrower, more cells): weight progress by n.
  uint64_t work = 0;
  for (int n : ns) work += static_cast<uint64_t>(n);
  io::Progress bar(work * models.size() * NA, a.progress.enabled());
  auto worker = [&] {
    for (std::size_t idx; (idx = next++) < R.size();) {
      const std::size_t mi = idx / (NN * NA), ni = (idx / NA) % NN, ai = idx % NA;
      try {
        R[idx] = energy::reflectance(models[mi], ns[ni], angles[ai] * M_PI / 180, o);
      } catch (const std::exception& e) {
        std::lock_guard<std::mutex> lk(err_mu);
        err = e.what();
      }
      bar.add(static_cast<uint64_t>(ns[ni]));
    }
  };
  std::vector<std::thread> pool;
  for (int t = 0; t < threads; ++t) pool.emplace_back(worker);
  for (auto& t : pool) t.join();
  bar.stop();
  if (!err.empty()) throw std::runtime_error(err);
  const double secs = std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count();

  const std::string method_text =
      o.method == energy::Options::Method::Cells
          ? std::string("cells: exact per input code, azimuth in closed form, 3-point Gauss-Legendre per code cell")
          : fmt::format("grid: 2-D midpoint {}x{} (polar x azimuth over [0,pi])", o.radial, o.azimuth);
  fmt::print("shadecore energy  coef={} cutoff={} F={} G={} I={}  {}  n={}..{} step {} ({} values)\nquadrature {}\n",
             a.coef, a.cutoff, o.format.frac, o.format.guard, o.coef_int_bits,
             o.fixed_point ? "fixed-point unit output × fixed-point coefficient" : "double cs16 × double coefficient",
             lo, hi, a.n_step, NN, method_text);
  fmt::print("{} reflectances in {:.2f} s on {} thread(s)\n\n", R.size(), secs, threads);
  fmt::print("R(θi) = ∫ f_r cos θo dωo; max and min over n, per incidence angle:\n");
  fmt::print("{:<12}", "model");
  for (double ang : angles) fmt::print(" | {:>6.0f}° max      min", ang);
  fmt::print(" | overall max (n, θi)\n");
  nlohmann::json jm = nlohmann::json::array();
  std::ostringstream csv;
  csv << "model,n,theta_i_deg,R\n";
  for (std::size_t mi = 0; mi < models.size(); ++mi) {
    const ModelInfo& inf = info(models[mi]);
    fmt::print("{:<12}", inf.key);
    double omax = -1;
    int on = 0;
    double oang = 0;
    nlohmann::json per_angle = nlohmann::json::array();
    std::vector<std::pair<int, double>> over;  // (n, angle) where R > 1
    for (std::size_t ai = 0; ai < NA; ++ai) {
      double mx = -1, mn = 1e300;
      int nmx = 0, nmn = 0;
      for (std::size_t ni = 0; ni < NN; ++ni) {
        const double v = R[(mi * NN + ni) * NA + ai];
        if (v > mx) { mx = v; nmx = ns[ni]; }
        if (v < mn) { mn = v; nmn = ns[ni]; }
        if (v > omax) { omax = v; on = ns[ni]; oang = angles[ai]; }
        if (v > 1) over.push_back({ns[ni], angles[ai]});
        csv << fmt::format("{},{},{},{:.9e}\n", inf.key, ns[ni], angles[ai], v);
      }
      fmt::print(" | {:>8.5f} {:>8.5f}", mx, mn);
      per_angle.push_back({{"theta_i_deg", angles[ai]}, {"max", mx}, {"max_at_n", nmx}, {"min", mn}, {"min_at_n", nmn}});
    }
    fmt::print(" | {:.5f} (n={}, {}°)\n", omax, on, oang);
    // Where energy is created: count and the angle/n ranges.
    std::string where = "none";
    if (!over.empty()) {
      int nlo = 1 << 30, nhi = 0;
      std::vector<double> angs;
      for (auto& [n, ang] : over) {
        nlo = std::min(nlo, n);
        nhi = std::max(nhi, n);
        if (std::find(angs.begin(), angs.end(), ang) == angs.end()) angs.push_back(ang);
      }
      std::string al;
      for (double x : angs) al += (al.empty() ? "" : ",") + fmt::format("{:g}", x);
      where = fmt::format("{} of {} (n, θi) points, n in {}..{}, θi in {{{}}}°", over.size(), NN * NA, nlo, nhi, al);
    }
    jm.push_back({{"model", inf.key}, {"max", omax}, {"max_at_n", on}, {"max_at_theta_i_deg", oang},
                  {"per_angle", per_angle}, {"R_gt_1", where}});
  }
  fmt::print("\nwhere R > 1 (energy created):\n");
  for (const auto& m : jm) fmt::print("  {:<12} {}\n", m["model"].get<std::string>(), m["R_gt_1"].get<std::string>());

  if (json_out >= 0) {
    nlohmann::json j;
    j["command"] = "shadecore energy";
    j["date"] = utc_now();
    j["format"] = {{"frac", o.format.frac}, {"guard", o.format.guard}, {"coef_int_bits", o.coef_int_bits}};
    j["coef"] = a.coef;
    j["cutoff"] = a.cutoff;
    j["fixed_point"] = o.fixed_point;
    j["quadrature"] = method_text;
    j["n"] = ns;
    j["angles_deg"] = angles;
    j["models"] = jm;
    j["seconds"] = secs;
    outs.set(json_out, j.dump(2) + "\n");
  }
  commit_with_fit_plots(outs, plots_out, a.plots_dir, "energy.csv", csv.str(), "--energy");
}

}  // namespace

void add_energy(CLI::App& app) {
  auto args = std::make_shared<EnergyArgs>();
  auto* sub = app.add_subcommand("energy", "Directional-hemispherical reflectance of the normalised BRDFs (bit-accurate)");
  sub->add_option("--model", args->model, "all | phong | phong_mod | blinn | blinn_mod | blinn_ndf | blinn_hf")->check(cliargs::NonEmpty("model"));
  sub->add_option("--n", args->n_range, "Exponent range LO..HI (within 16..1024)")->check(cliargs::NonEmpty("range"));
  sub->add_option("--n-step", args->n_step, "Stride over n (the last n is always included)")
      ->check(cliargs::Int(1, 1024));
  sub->add_option("--angles", args->angles, "Incidence angles in degrees, comma-separated, each in [0, 90)")->check(cliargs::NonEmpty("angle list"));
  sub->add_option("--coef", args->coef, "Coefficient: fitted (the paper's) | classical")->check(cliargs::NonEmpty("coefficient kind"));
  sub->add_option("--cutoff", args->cutoff, "cs16 cut-off: theta_cr | sign_clamp")->check(cliargs::NonEmpty("cut-off"));
  sub->add_option("--config", args->config, "Named width configuration from config/configs.json")
      ->check(cliargs::NonEmpty("config name"));
  sub->add_option("--method", args->method, "cells (exact per input code, azimuth in closed form) | grid (2-D midpoint)")->check(cliargs::NonEmpty("method"));
  auto* radial = sub->add_option("--radial", args->radial, "grid: midpoint cells in the polar angle around the lobe axis");
  auto* azimuth = sub->add_option("--azimuth", args->azimuth, "grid: quadrature cells in the azimuth over [0, pi]");
  sub->add_flag("--double", args->double_model, "Use the double-precision cs16 and coefficient instead of the fixed point");
  sub->add_option("--threads", args->threads, "Worker threads (default 1; 0 = all cores; at most 64)")
      ->check(cliargs::Int(0, cliargs::kMaxParallel));
  sub->add_option("--json", args->json_path, "Write the results as JSON (atomic)")->check(cliargs::NonEmpty("path"));
  sub->add_option("--plots", args->plots_dir, "Write PNG plots (and the CSV data) into this directory")
      ->check(cliargs::NonEmpty("path"));
  args->progress.add(sub);
  sub->callback([args, radial, azimuth] {
    args->grid_option_given = radial->count() + azimuth->count() > 0;
    run(*args);
  });
}

}  // namespace shadecore::cli
