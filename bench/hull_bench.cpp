// Hulls in bounded time: Qhull on N points of a sphere, and
// on nearly flat point sets, and what a body built from them costs before the
// first step (the loader's checks and mass properties, the bounding sphere).
//   build/release/bench/hull_bench --benchmark_repetitions=5 --benchmark_report_aggregates_only=true
#include "core/collision/bounding_volume.hpp"
#include "core/model/mesh.hpp"
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "traditional/bounding_volume.hpp"

#include <benchmark/benchmark.h>
#include <nlohmann/json.hpp>

#include <cmath>
#include <numbers>
#include <random>

namespace {
using namespace gacompare;
using core::Vec3;

// N points spread evenly on a sphere of radius 0.1 (the golden-angle spiral).
std::vector<Vec3> sphere(int n) {
  std::vector<Vec3> p;
  const double turn = std::numbers::pi * (3 - std::sqrt(5.0));
  for (int i = 0; i < n; ++i) {
    const double z = 1 - 2 * (i + 0.5) / n, r = std::sqrt(1 - z * z);
    p.emplace_back(0.1 * r * std::cos(turn * i), 0.1 * r * std::sin(turn * i), 0.1 * z);
  }
  return p;
}

// N points in a 0.2 m square, within `thickness` of its plane.
std::vector<Vec3> flat(int n, double thickness) {
  std::mt19937_64 rng(7);
  std::uniform_real_distribution<double> u(-0.1, 0.1), w(-thickness / 2, thickness / 2);
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) p.emplace_back(u(rng), u(rng), w(rng));
  return p;
}

void BM_HullOfSphere(benchmark::State& state) {
  const auto p = sphere(static_cast<int>(state.range(0)));
  for (auto _ : state) benchmark::DoNotOptimize(core::convex_hull(p));
}
BENCHMARK(BM_HullOfSphere)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

void BM_HullOfFlatPoints(benchmark::State& state) {
  const auto p = flat(1000, std::pow(10.0, -static_cast<double>(state.range(0))));
  for (auto _ : state) {
    try {
      benchmark::DoNotOptimize(core::convex_hull(p));
    } catch (const Error&) {  // refused is as good an answer as built
    }
  }
}
BENCHMARK(BM_HullOfFlatPoints)->Arg(9)->Arg(12)->Unit(benchmark::kMillisecond);

// Everything a body of a hull costs before the first step: the loader (which
// builds the hull), the compiled model (mass properties, centred mesh,
// convexity) with the budgets it is checked against, and its bounding sphere
// (Welzl), as a collision scene needs them.
void BM_HullBodyReady(benchmark::State& state) {
  const auto p = sphere(static_cast<int>(state.range(0)));
  nlohmann::json points = nlohmann::json::array();
  for (const auto& x : p) points.push_back({x.x(), x.y(), x.z()});
  const nlohmann::json scene = {
      {"name", "hull"}, {"duration", 0.01}, {"output", {{"every", 0.01}}}, {"solver", {{"method", "rk4"}}},
      {"effects", {{{"type", "collisions"}}}},
      {"bodies",
       {{{"name", "ball"}, {"shape", {{"hull", points}}}, {"mass", 1}, {"position", {0, 0, 1}}},
        {{"name", "floor"}, {"shape", {{"box", {2, 2, 0.2}}}}, {"mass", 1}, {"position", {0, 0, -0.1}}, {"static", true}}}}};
  const std::string text = scene.dump();
  for (auto _ : state) {
    const core::Compiled c = core::parse_compiled(text, "hull.json");
    const core::Mesh& mesh = *c.model->bodies[0].mesh;
    std::mt19937_64 rng(1);
    benchmark::DoNotOptimize(
        core::welzl_sphere<traditional::SphereOps>(std::span<const Vec3>(mesh.vertices()), rng));
  }
}
BENCHMARK(BM_HullBodyReady)->Arg(1000)->Arg(10000)->Arg(100000)->Unit(benchmark::kMillisecond);

}  // namespace

BENCHMARK_MAIN();
