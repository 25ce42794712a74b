// The collision pipeline's broadphase (core/collision/broadphase.hpp):
// sort and sweep, the AABB tree and the sphere tree, traditional and cga, per
// detection, on N = 100, 1,000 and 10,000 bodies in a box at constant density
// (that of bodies_in_box: 27 bodies in 1.2³ m³, 15.6 per m³), with the box's
// six static walls, whose bounding spheres each reach over most of the box.
//   coherent_<N>     the bodies fly straight at 0.5–2 m/s, 1 ms between
//                    detections (the collision step), reflected off the walls:
//                    what a simulation asks. The flight is inside the timed
//                    loop; flight_alone times it (under 2% of any detection)
//   incoherent_<N>   every body teleported to a random place each detection
//                    (16 independent frames): every tree leaf is reinserted
//   margin<M>_coherent_<N>   the trees with a fat margin of M radii instead
//                    of kFatMargin: what chose the margin
// Bounding-sphere radii 0.08–0.18 m (the bundled scenes' 0.1–0.2 m bodies).
// Before timing, each benchmark flies 256 steps (or sees every teleported
// frame once), the trees built and the pairs found: the time is the steady
// state's. One item = one detection
// of Broadphase::find as the collision step asks it: every sphere also grown
// by how far its body flies in the step (the islands' candidates), the frame
// and the spheres included. Counters, per
// detection: candidates (volume tests: sweep pairs, or tree nodes tested plus
// kept pairs), overlap_tests (exact sphere tests), tree_updates
// (reinsertions), pairs_kept, pairs, grown_pairs (the candidates).
//
// Names BM_<scene>/<backend>_<method>:
//   python3 scripts/bench-ratios.py build/release/bench/broadphase_bench --reference traditional_sweep
#include "cga/bounding_volume.hpp"
#include "core/collision/broadphase.hpp"
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

// The bodies: walls first (static), then n bodies with a velocity each.
struct World {
  std::vector<Vec3> start, velocity;
  std::vector<double> radii;
  std::vector<char> is_static;
  std::vector<double> margins;  // how far each body flies in a step: the collision step's reach
  double half = 0;                     // the box's half side
  std::vector<std::vector<Vec3>> teleported;  // incoherent: 16 frames of uniform positions
};

World make_world(int n) {
  World w;
  const double side = std::cbrt(n / kDensity);
  w.half = 0.5 * side;
  // Six walls 0.1 m thick around the box; their spheres' radius is half
  // their diagonal.
  const double wall = 0.5 * std::sqrt(2 * (side + 0.2) * (side + 0.2) + 0.01);
  for (int axis = 0; axis < 3; ++axis)
    for (const double s : {-1.0, 1.0}) {
      Vec3 c = Vec3::Zero();
      c[axis] = s * (w.half + 0.05);
      w.start.push_back(c);
      w.velocity.push_back(Vec3::Zero());
      w.radii.push_back(wall);
      w.is_static.push_back(true);
      w.margins.push_back(0);
    }
  std::mt19937_64 g(static_cast<std::uint64_t>(n));
  std::uniform_real_distribution<double> rad(0.08, 0.18), u(-1, 1), speed(0.5, 2);
  for (int i = 0; i < n; ++i) {
    const double r = rad(g);
    w.start.push_back(Vec3(u(g), u(g), u(g)) * (w.half - r));
    w.velocity.push_back(speed(g) * Vec3(u(g), u(g), u(g)).normalized());
    w.radii.push_back(r);
    w.is_static.push_back(false);
    w.margins.push_back(kStep * w.velocity.back().norm());
  }
  for (int f = 0; f < 16; ++f) {
    std::vector<Vec3> c(w.start.begin(), w.start.begin() + 6);
    for (int i = 0; i < n; ++i) c.push_back(Vec3(u(g), u(g), u(g)) * (w.half - w.radii[static_cast<std::size_t>(6 + i)]));
    w.teleported.push_back(std::move(c));
  }
  return w;
}

const World& world(int n) {
  static std::map<int, World> cache;
  auto it = cache.find(n);
  if (it == cache.end()) it = cache.emplace(n, make_world(n)).first;
  return it->second;
}

// One collision step of straight flight, reflected off the box's walls.
void fly(const World& w, std::vector<Vec3>& c, std::vector<Vec3>& v) {
  for (std::size_t i = 6; i < c.size(); ++i) {
    c[i] += kStep * v[i];
    for (int k = 0; k < 3; ++k)
      if (std::abs(c[i][k]) > w.half - w.radii[i] && c[i][k] * v[i][k] > 0) v[i][k] = -v[i][k];
  }
}

template <class Ops>
void detect(benchmark::State& st, int n, bool coherent, BroadphaseMethod method, double margin) {
  const World& w = world(n);
  core::Broadphase<Ops> bp(method, margin);
  std::vector<Vec3> c = w.start, v = w.velocity;
  // Steady state first: the trees built and 256 steps flown (or every
  // teleported frame seen once).
  for (int i = 0; i < (coherent ? 256 : 16); ++i) {
    if (coherent) fly(w, c, v);
    bp.find(coherent ? c : w.teleported[static_cast<std::size_t>(i)], w.radii, w.is_static, w.margins);
  }
  core::BroadphaseCounters sum;
  std::int64_t sum_candidates = 0;
  std::size_t i = 0;
  for (auto _ : st) {
    if (coherent) fly(w, c, v);
    const auto r = bp.find(coherent ? c : w.teleported[i++ % 16], w.radii, w.is_static, w.margins);
    benchmark::DoNotOptimize(r.pairs.data());
    sum.candidates += r.counters.candidates;
    sum.overlap_tests += r.counters.overlap_tests;
    sum.tree_updates += r.counters.tree_updates;
    sum.pairs_kept += r.counters.pairs_kept;
    sum.pairs += r.counters.pairs;
    sum_candidates += static_cast<std::int64_t>(r.candidates.size());
  }
  st.SetItemsProcessed(st.iterations());
  const auto per = [](std::int64_t x) { return benchmark::Counter(static_cast<double>(x), benchmark::Counter::kAvgIterations); };
  st.counters["candidates"] = per(sum.candidates);
  st.counters["overlap_tests"] = per(sum.overlap_tests);
  st.counters["tree_updates"] = per(sum.tree_updates);
  st.counters["pairs_kept"] = per(sum.pairs_kept);
  st.counters["pairs"] = per(sum.pairs);
  st.counters["grown_pairs"] = per(sum_candidates);
}

// The flight alone, which the coherent benchmarks include in their time.
void flight(benchmark::State& st, int n) {
  const World& w = world(n);
  std::vector<Vec3> c = w.start, v = w.velocity;
  for (auto _ : st) {
    fly(w, c, v);
    benchmark::DoNotOptimize(c.data());
  }
  st.SetItemsProcessed(st.iterations());
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
      if (coherent)
        benchmark::RegisterBenchmark(("BM_" + scene + "/flight_alone").c_str(), [n](benchmark::State& st) { flight(st, n); });
    }
  for (const double margin : {0.1, 0.2, 0.8}) {
    char scene[64];
    std::snprintf(scene, sizeof scene, "margin%g_coherent_1000", margin);
    register_scene<traditional::SphereOps>(scene, 1000, true, margin, false);
    register_scene<cga::SphereOps>(scene, 1000, true, margin, false);
  }
}

const bool registered = (register_all(), true);  // before BENCHMARK_MAIN runs them

}  // namespace

BENCHMARK_MAIN();
