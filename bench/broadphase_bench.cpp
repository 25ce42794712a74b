// The collision pipeline's broadphase (issue #14 item 2, core/broadphase.hpp):
// sort and sweep, the AABB tree and the sphere tree, traditional and cga, per
// detection, on N = 100, 1,000 and 10,000 bodies in a box at constant density
// (that of bodies_in_box: 27 bodies in 1.2³ m³, 15.6 per m³), with the box's
// six static walls, whose bounding spheres each reach over most of the box.
//   coherent_<N>     the bodies move 0.5–2 mm per detection (0.5–2 m/s at the
//                    1 ms collision step), bouncing off the walls: what a
//                    simulation asks; 128 precomputed frames played forwards
//                    and backwards, so every detection follows its neighbour
//   incoherent_<N>   every body teleported to a random place each detection
//                    (16 independent frames): every tree leaf is reinserted
//   margin<M>_coherent_1000   the trees with a fat margin of M radii instead
//                    of kFatMargin (0.1): what chose the margin
// Bounding-sphere radii 0.08–0.18 m (the bundled scenes' 0.1–0.2 m bodies).
// Before timing, each benchmark plays every frame once (the trees built,
// the pairs found): the time is the steady state's. One item = one detection
// of Broadphase::find, the frame and the spheres included. Counters, per
// detection: candidates (volume tests: sweep pairs, or tree nodes tested plus
// kept pairs), overlap_tests (exact sphere tests), tree_updates
// (reinsertions), pairs_kept, pairs.
//
// Names BM_<scene>/<backend>_<method>:
//   python3 scripts/bench-ratios.py build/release/bench/broadphase_bench --reference traditional_sweep
#include "cga/bounding_volume.hpp"
#include "core/broadphase.hpp"
#include "traditional/bounding_volume.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <cstdio>
#include <map>
#include <random>
#include <string>
#include <utility>
#include <vector>

namespace {

using namespace gacompare;
using Vec3 = Eigen::Vector3d;
using core::BroadphaseMethod;

constexpr double kDensity = 27 / (1.2 * 1.2 * 1.2);  // bodies per m³
constexpr double kStep = 1e-3;                       // s between detections

struct World {
  std::vector<std::vector<Vec3>> frames;  // centres; walls first
  std::vector<double> radii;
  std::vector<bool> is_static;
  bool ping_pong = false;  // coherent frames are played 0 … K−1 … 1 0 …
  std::size_t frame(std::int64_t i) const {
    const auto k = static_cast<std::int64_t>(frames.size());
    if (!ping_pong) return static_cast<std::size_t>(i % k);
    const std::int64_t p = i % (2 * k - 2);
    return static_cast<std::size_t>(p < k ? p : 2 * k - 2 - p);
  }
};

World make_world(int n, bool coherent) {
  World w;
  const double side = std::cbrt(n / kDensity), h = 0.5 * side;
  // Six walls 0.1 m thick around the box; their spheres' radius is half
  // their diagonal.
  const double wall = 0.5 * std::sqrt(2 * (side + 0.2) * (side + 0.2) + 0.01);
  std::vector<Vec3> start;
  for (int axis = 0; axis < 3; ++axis)
    for (const double s : {-1.0, 1.0}) {
      Vec3 c = Vec3::Zero();
      c[axis] = s * (h + 0.05);
      start.push_back(c);
      w.radii.push_back(wall);
      w.is_static.push_back(true);
    }
  std::mt19937_64 g(static_cast<std::uint64_t>(n));
  std::uniform_real_distribution<double> rad(0.08, 0.18), u(-1, 1), speed(0.5, 2);
  std::vector<Vec3> v(start.size(), Vec3::Zero());
  for (int i = 0; i < n; ++i) {
    const double r = rad(g);
    start.emplace_back(Vec3(u(g), u(g), u(g)) * (h - r));
    w.radii.push_back(r);
    w.is_static.push_back(false);
    v.push_back(speed(g) * Vec3(u(g), u(g), u(g)).normalized());
  }
  w.ping_pong = coherent;
  const int frames = coherent ? 128 : 16;
  std::vector<Vec3> c = start;
  for (int f = 0; f < frames; ++f) {
    for (std::size_t i = 6; i < c.size(); ++i) {
      if (coherent) {
        c[i] += kStep * v[i];
        for (int k = 0; k < 3; ++k)
          if (std::abs(c[i][k]) > h - w.radii[i]) v[i][k] = -v[i][k];
      } else {
        c[i] = Vec3(u(g), u(g), u(g)) * (h - w.radii[i]);
      }
    }
    w.frames.push_back(c);
  }
  return w;
}

const World& world(int n, bool coherent) {
  static std::map<std::pair<int, bool>, World> cache;
  auto it = cache.find({n, coherent});
  if (it == cache.end()) it = cache.emplace(std::pair{n, coherent}, make_world(n, coherent)).first;
  return it->second;
}

template <class Ops>
void detect(benchmark::State& st, int n, bool coherent, BroadphaseMethod method, double margin) {
  const World& w = world(n, coherent);
  core::Broadphase<Ops> bp(method, margin);
  const auto frames = static_cast<std::int64_t>(w.frames.size());
  for (std::int64_t i = 0; i < (coherent ? 2 * frames - 2 : frames); ++i) bp.find(w.frames[w.frame(i)], w.radii, w.is_static);
  core::BroadphaseCounters sum;
  std::int64_t i = 0;
  for (auto _ : st) {
    const auto r = bp.find(w.frames[w.frame(i++)], w.radii, w.is_static);
    benchmark::DoNotOptimize(r.pairs.data());
    sum.candidates += r.counters.candidates;
    sum.overlap_tests += r.counters.overlap_tests;
    sum.tree_updates += r.counters.tree_updates;
    sum.pairs_kept += r.counters.pairs_kept;
    sum.pairs += r.counters.pairs;
  }
  st.SetItemsProcessed(st.iterations());
  const auto per = [](std::int64_t x) { return benchmark::Counter(static_cast<double>(x), benchmark::Counter::kAvgIterations); };
  st.counters["candidates"] = per(sum.candidates);
  st.counters["overlap_tests"] = per(sum.overlap_tests);
  st.counters["tree_updates"] = per(sum.tree_updates);
  st.counters["pairs_kept"] = per(sum.pairs_kept);
  st.counters["pairs"] = per(sum.pairs);
}

const char* method_name(BroadphaseMethod m) {
  return m == BroadphaseMethod::sweep ? "sweep" : m == BroadphaseMethod::aabb_tree ? "aabb_tree" : "sphere_tree";
}

template <class Ops>
void register_scene(const std::string& scene, int n, bool coherent, double margin, bool with_sweep) {
  for (const auto m : {BroadphaseMethod::sweep, BroadphaseMethod::aabb_tree, BroadphaseMethod::sphere_tree}) {
    if (m == BroadphaseMethod::sweep && !with_sweep) continue;
    benchmark::RegisterBenchmark(("BM_" + scene + "/" + Ops::name + "_" + method_name(m)).c_str(),
                                 [=](benchmark::State& st) { detect<Ops>(st, n, coherent, m, margin); });
  }
}

void register_all() {
  for (const int n : {100, 1000, 10000})
    for (const bool coherent : {true, false}) {
      const std::string scene = std::string(coherent ? "coherent_" : "incoherent_") + std::to_string(n);
      register_scene<traditional::SphereOps>(scene, n, coherent, core::kFatMargin, true);
      register_scene<cga::SphereOps>(scene, n, coherent, core::kFatMargin, true);
    }
  for (const double margin : {0.05, 0.2, 0.4}) {
    char scene[64];
    std::snprintf(scene, sizeof scene, "margin%g_coherent_1000", margin);
    register_scene<traditional::SphereOps>(scene, 1000, true, margin, false);
    register_scene<cga::SphereOps>(scene, 1000, true, margin, false);
  }
}

const bool registered = (register_all(), true);  // before BENCHMARK_MAIN runs them

}  // namespace

BENCHMARK_MAIN();
