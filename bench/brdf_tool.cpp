// SPDX-License-Identifier: Apache-2.0
// brdf_tool — not a benchmark: the measurement and picture side of docs/brdf.md.
//
//   brdf_tool table51 [MODEL]        table 5.1 measured: per parameter set the worst reciprocity error
//                                    and the largest directional albedo (and where); a summary per model
//   brdf_tool render DIR [SIZE]      one sphere per model, double-precision BRDF, software path
//                                    (orthographic camera, one directional light): DIR/spheres.f32
//                                    (float32, models × SIZE × SIZE, row-major, radiance; −1 off
//                                    the sphere) and
//                                    DIR/spheres.txt (one "name|parameters" line per sphere); the
//                                    contact sheet is drawn by scripts/brdf_sheet.py
#include <fmt/core.h>

#include <cmath>
#include <cstdio>
#include <fstream>
#include <string>
#include <vector>

#include "shadecore/analysis/brdf.hpp"

using namespace shadecore::brdf;

namespace {

int table51(const std::string& only) {
  const double kRecipTol = 1e-9, kEnergyTol = 1e-6;
  std::vector<std::string> names = model_names();
  if (!only.empty()) names = {only};
  fmt::print("# Table 5.1 measured, every parameter set (`brdf_tool table51`)\n\n"
             "Reciprocity: largest |f(ωi,ωo) − f(ωo,ωi)| / max(|f|) over 4000 random direction pairs in random frames.\n"
             "Energy: largest directional albedo over θi ∈ {{0, 30, 60, 75, 85, 89, 89.9, 89.99, 89.999}}°, φi = 30°\n"
             "(anisotropic models also 0° and 90°), nested adaptive Gauss-Kronrod, relative tolerance 1e-7.\n"
             "Summary per model at the end; discussion in docs/brdf.md.\n\n");
  fmt::print("| model | parameters | max rel. reciprocity error | max albedo | at θi, φi | quad. error |\n");
  fmt::print("|---|---|---|---|---|---|\n");
  struct Sum {
    std::string name;
    int n = 0, recip_fail = 0, energy_fail = 0;
    double worst_recip = 0, worst_albedo = 0;
    std::string worst_recip_at, worst_albedo_at;
  };
  std::vector<Sum> sums;
  for (const std::string& name : names) {
    Sum s;
    s.name = name;
    for (const Instance& inst : parameter_grid(name)) {
      const Reciprocity r = reciprocity(inst.f);
      const Energy e = energy(inst);
      ++s.n;
      if (r.max_rel > kRecipTol) ++s.recip_fail;
      if (e.max_albedo > 1 + kEnergyTol) ++s.energy_fail;
      if (r.max_rel >= s.worst_recip) {
        s.worst_recip = r.max_rel;
        s.worst_recip_at = fmt::format("{}: f(ωi,ωo) = {:.6g}, f(ωo,ωi) = {:.6g}", inst.params, r.f_io, r.f_oi);
      }
      if (e.max_albedo >= s.worst_albedo) {
        s.worst_albedo = e.max_albedo;
        s.worst_albedo_at = fmt::format("{}: a = {:.6g} at θi = {:g}°", inst.params, e.max_albedo,
                                        std::round(e.theta_i * 180 / kPi * 1000) / 1000);
      }
      fmt::print("| {} | {} | {:.2e} | {:.6f} | {:g}°, {:.0f}° | {:.1e}{} |\n", inst.model, inst.params, r.max_rel,
                 e.max_albedo, std::round(e.theta_i * 180 / kPi * 1000) / 1000, e.phi_i * 180 / kPi, e.error, e.converged ? "" : " (not converged)");
      std::fflush(stdout);
    }
    sums.push_back(s);
  }
  fmt::print("\n| model | sets | reciprocal (max rel. error ≤ 1e-9) | energy-conserving (max albedo ≤ 1 + 1e-6) | worst albedo |\n");
  fmt::print("|---|---|---|---|---|\n");
  for (const Sum& s : sums)
    fmt::print("| {} | {} | {} ({} of {} fail; worst {:.2e}) | {} ({} of {} fail) | {} |\n", s.name, s.n,
               s.recip_fail ? "no" : "yes", s.recip_fail, s.n, s.worst_recip, s.energy_fail ? "no" : "yes",
               s.energy_fail, s.n, s.worst_albedo_at);
  return 0;
}

// One sphere: orthographic view along +z (viewer direction wo = (0,0,1)), unit sphere filling the
// square, one directional light of irradiance π at normal incidence (so a white Lambert surface has
// radiance 1 facing it) from the upper left front, plus nothing else. Tangent: along the latitude circles
// (d/dφ about the y axis), so anisotropic models show their stretch.
std::vector<float> sphere(const Fn& f, int size, const Vec3& light) {
  std::vector<float> img(static_cast<size_t>(size) * size, 0.0f);
  const Vec3 wo{0, 0, 1};
  for (int j = 0; j < size; ++j)
    for (int i = 0; i < size; ++i) {
      // 2×2 supersampling against jagged rims; pixels entirely off the sphere are marked −1.
      double sum = 0;
      int hits = 0;
      for (int sj = 0; sj < 2; ++sj)
        for (int si = 0; si < 2; ++si) {
          const double x = (2.0 * (i + 0.25 + 0.5 * si) / size - 1) * 1.05;
          const double y = (1 - 2.0 * (j + 0.25 + 0.5 * sj) / size) * 1.05;
          const double r2 = x * x + y * y;
          if (r2 >= 1) continue;
          ++hits;
          const Vec3 n{x, y, std::sqrt(1 - r2)};
          const Vec3 t = normalize(cross(Vec3{0, 1, 0}, n));
          const double ci = dot(n, light);
          if (ci <= 0) continue;
          sum += f(light, wo, n, t) * kPi * ci;
        }
      img[static_cast<size_t>(j) * size + i] = hits ? static_cast<float>(sum / 4) : -1.0f;
    }
  return img;
}

int render(const std::string& dir, int size) {
  struct Item {
    std::string name, params;
    Fn f;
  };
  // The thesis's figure parameters where it gives them (kd = ks = 0.4 for most; n = 50; m = 0.2).
  std::vector<Item> items = {
      {"Lambert", "kd=0.8 (2.5)", Lambert{0.8}},
      {"Phong classic", "kd=0.4 ks=0.4 n=50 (2.6)", PhongClassic{0.4, 0.4, 50}},
      {"Phong BRDF", "kd=0.4 ks=0.4 n=50 (2.7)", PhongBrdf{0.4, 0.4, 50}},
      {"Blinn-Phong", "kd=0.4 ks=0.4 n=50 (2.10)", BlinnPhong{0.4, 0.4, 50}},
      {"Schlick-Phong", "kd=0.4 ks=0.4 n=50 (2.10)+(2.13)", SchlickPhong{0.4, 0.4, 50}},
      {"Cook-Torrance", "kd=ks=0.4 m=0.2 eta=1.5 (3.17)", CookTorrance{0.4, 0.4, 0.2, 1.5, 0}},
      {"Schlick-Cook-Torrance", "kd=ks=0.4 m=0.2 f0(1.5) (3.17)", SchlickCookTorrance{0.4, 0.4, 0.2, fresnel_f0(1.5, 0)}},
      {"Strauss", "C=0.8 s=0.7 e=0 t=0 (4.1)", Strauss{0.8, 0.7, 0.0, 0.0}},
      {"Ward", "rho_d=rho_s=0.4 mx=0.05 my=0.2 (4.14)", Ward{0.4, 0.4, 0.05, 0.2}},
      {"Ashikhmin-Shirley", "Rd=Rs=0.4 nx=10 ny=1000 (4.25)", AshikhminShirley{0.4, 0.4, 10, 1000}},
      {"Schlick", "SINGLE C=0.4 r=0.1 p=0.3 (4.16)", Schlick{{0.4, 0.1, 0.3}}},
      {"Lafortune", "kd=0.4 + Phong lobe ks=0.4 n=50 (4.30)", Lafortune{0.4, {Lafortune::phong_lobe(0.4, 50)}, 1}},
  };
  const Vec3 light = normalize(Vec3{-0.5, 0.6, 0.8});
  std::ofstream bin(dir + "/spheres.f32", std::ios::binary);
  std::ofstream txt(dir + "/spheres.txt");
  if (!bin || !txt) {
    fmt::print(stderr, "brdf_tool: cannot write into {}\n", dir);
    return 1;
  }
  txt << size << "\n";
  for (const Item& it : items) {
    const std::vector<float> img = sphere(it.f, size, light);
    bin.write(reinterpret_cast<const char*>(img.data()), static_cast<std::streamsize>(img.size() * sizeof(float)));
    txt << it.name << "|" << it.params << "\n";
  }
  return bin.good() && txt.good() ? 0 : 1;
}

}  // namespace

int main(int argc, char** argv) {
  const std::string cmd = argc > 1 ? argv[1] : "";
  if (cmd == "table51") return table51(argc > 2 ? argv[2] : "");
  if (cmd == "render" && argc > 2) return render(argv[2], argc > 3 ? std::stoi(argv[3]) : 160);
  fmt::print(stderr, "usage: brdf_tool table51 [MODEL] | brdf_tool render DIR [SIZE]\n");
  return 1;
}
