// What accuracy costs in time for mass properties (§2.3.3): the
// report's voxel method against the exact polyhedral integrals, per cell count
// and cell test. Prints a markdown table; errors are relative to the exact values.
//
//   mass_properties_sweep [--quick]
//
// Times are medians of repeats in one process (a plain program, not Google
// Benchmark: one voxel run at 256³ cells takes seconds, and the table needs the
// error next to the time).
#include "core/model/mass_properties.hpp"
#include "core/model/mesh.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstring>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace gacompare::core;
using Clock = std::chrono::steady_clock;

// Median seconds per call: repeats until ~0.2 s or `max_repeats`, at least 3.
double median_seconds(const std::function<void()>& f, int max_repeats) {
  std::vector<double> t;
  double total = 0;
  while (static_cast<int>(t.size()) < 3 || (total < 0.2 && static_cast<int>(t.size()) < max_repeats)) {
    const auto start = Clock::now();
    f();
    t.push_back(std::chrono::duration<double>(Clock::now() - start).count());
    total += t.back();
  }
  std::nth_element(t.begin(), t.begin() + static_cast<long>(t.size() / 2), t.end());
  return t[t.size() / 2];
}

std::string seconds(double s) {
  char b[32];
  if (s < 1e-3) std::snprintf(b, sizeof b, "%.3g µs", s * 1e6);
  else if (s < 1) std::snprintf(b, sizeof b, "%.3g ms", s * 1e3);
  else std::snprintf(b, sizeof b, "%.3g s", s);
  return b;
}

}  // namespace

int main(int argc, char** argv) {
  const bool quick = argc > 1 && std::strcmp(argv[1], "--quick") == 0;
  const Eigen::Matrix3d rot = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  std::mt19937_64 rng(1);
  std::normal_distribution<double> g;
  std::vector<Vec3> cloud(100);
  for (auto& p : cloud) p = Vec3(g(rng), g(rng), g(rng));
  struct Body { std::string label; Mesh mesh; };
  const std::vector<Body> bodies = {
      {"box 1×2×3, rotated", make_box({1, 2, 3}).transformed(rot, Vec3::Zero())},
      {"icosahedron r = 1, rotated", make_icosahedron(1).transformed(rot, Vec3::Zero())},
      {"hull of 100 random points", convex_hull(cloud)},
  };
  const std::vector<int> sides = quick ? std::vector<int>{8, 16, 32} : std::vector<int>{8, 16, 32, 64, 128, 256};
  const int parity_max = quick ? 16 : 64;

  std::printf("| body | method | cells per side | cells | rel. error V | error c / size | rel. error I | time | × exact |\n");
  std::printf("|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& [label, mesh] : bodies) {
    MassProperties exact;
    const double t_exact = median_seconds([&] { exact = mass_properties(mesh); }, 100000);
    std::printf("| %s | exact (divergence theorem) | – | – | – | – | – | %s | 1 |\n", label.c_str(), seconds(t_exact).c_str());
    Eigen::AlignedBox3d box;
    for (const auto& v : mesh.vertices()) box.extend(v);
    for (const CellTest test : {CellTest::face_planes, CellTest::parity})
      for (int n : sides) {
        if (test == CellTest::parity && n > parity_max) continue;
        const double h = box.sizes().maxCoeff() / n;
        VoxelMassProperties vox;
        const double t = median_seconds([&] { vox = voxel_mass_properties(mesh, h, 1, test); }, 9);
        const MassProperties& p = vox.properties;
        std::printf("| %s | voxel, %s | %d | %ld | %.2e | %.2e | %.2e | %s | %.3g |\n", label.c_str(),
                    test == CellTest::face_planes ? "face planes" : "ray parity", n, vox.cells,
                    std::abs(p.volume - exact.volume) / exact.volume,
                    (p.centre_of_mass - exact.centre_of_mass).norm() / mesh.size(),
                    (p.inertia - exact.inertia).norm() / exact.inertia.norm(), seconds(t).c_str(), t / t_exact);
        std::fflush(stdout);
      }
  }
  return 0;
}
