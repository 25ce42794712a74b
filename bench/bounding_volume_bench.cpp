// Bounding volumes and broadphase (§2.4.1), conformal vs traditional:
//   exhaustive_sphere_<hull>  the report's exhaustive search (hulls of ≤ 16 vertices)
//   welzl_sphere_<hull>       Welzl's algorithm with move-to-front (one generator
//       for the run: each call shuffles anew, so its work is an average)
//       hulls: hull8, hull16, hull64 (core::convex_hull of seeded points on an
//       ellipsoid 1 × 0.95 × 0.9, all of them vertices, round enough that the
//       minimal sphere has 3 or 4 support points, so the exhaustive search runs
//       through its 3- and 4-point classes: its `spheres` counter is 154 for 8
//       vertices, 2500 for 16) and box (1 × 2 × 3: every vertex on the minimal
//       sphere, found among the 2-point spheres)
//   sphere_2, sphere_3, sphere_4, contains   the constructions one by one, on a
//       ring of 1024 pre-generated cases (points already in each backend's form)
//   sphere_overlap            the distance test vs the conformal test by inner
//       products (what the simulation runs); cga_meet: the report's meet (C² ≥ 0
//       plus the nesting test)
//   broadphase_100, broadphase_1000   sort and sweep over sparse random scenes
//       (centres in a box of side 6·n^(1/3), radii 0.2–1.2), spheres pre-built;
//       cga_meet: the conformal policy with the report's overlap_by_meet
// The same search code (core/collision/bounding_volume.hpp, core/collision/broadphase.hpp) runs on
// both policies, so a ratio is the algebra's. Counters report the work per call
// (spheres built, containment tests; candidates and pairs).
//
// Names: BM_<operation>/cga and BM_<operation>/traditional, as geometry_bench:
//   scripts/bench-ratios.py build/release/bench/bounding_volume_bench --reference traditional
#include "cga/bounding_volume.hpp"
#include "core/collision/bounding_volume.hpp"
#include "core/collision/broadphase.hpp"
#include "core/model/mesh.hpp"
#include "traditional/bounding_volume.hpp"

#include <benchmark/benchmark.h>

#include <cmath>
#include <map>
#include <random>
#include <string>
#include <vector>

namespace {

using namespace gacompare;
using Vec3 = Eigen::Vector3d;
using T = traditional::SphereOps;
using C = cga::SphereOps;

constexpr std::size_t kN = 1024;  // ring of cases, a power of two

std::vector<Vec3> ellipsoid_hull(int n, std::uint64_t seed) {
  std::mt19937_64 g(seed);
  std::normal_distribution<double> N;
  std::vector<Vec3> p;
  for (int i = 0; i < n; ++i) p.push_back(Vec3(N(g), N(g), N(g)).normalized().cwiseProduct(Vec3(1, 0.95, 0.9)));
  return core::convex_hull(p, "bench hull").vertices();
}

const std::map<std::string, std::vector<Vec3>>& hulls() {
  static const std::map<std::string, std::vector<Vec3>> h{
      {"hull8", ellipsoid_hull(8, 1)},
      {"hull16", ellipsoid_hull(16, 1)},
      {"hull64", ellipsoid_hull(64, 1)},
      {"box", core::make_box(Vec3(1, 2, 3)).vertices()},
  };
  return h;
}

template <class Ops>
struct Ring {
  std::vector<typename Ops::Point> a, b, c, d, x;
  std::vector<typename Ops::Sphere> s1, s2;
  Ring() {
    std::mt19937_64 g(2003);
    std::uniform_real_distribution<double> u(-1, 1), rad(0.1, 1.5);
    const auto point = [&] { return Vec3(u(g), u(g), u(g)); };
    while (a.size() < kN) {
      const Vec3 pa = point(), pb = point(), pc = point(), pd = point();
      if ((pb - pa).norm() < 0.2 || (pc - pa).norm() < 0.2 || (pc - pb).norm() < 0.2) continue;
      a.push_back(Ops::point(pa)), b.push_back(Ops::point(pb)), c.push_back(Ops::point(pc));
      d.push_back(Ops::point(pd)), x.push_back(Ops::point(point()));
      // Sphere pairs: a mix of apart, crossing and nested (one in eight nested).
      const Vec3 c1 = 1.5 * point();
      const double r1 = rad(g);
      if (s1.size() % 8 == 0) {
        s1.push_back(Ops::sphere(c1, r1)), s2.push_back(Ops::sphere(c1 + 0.2 * r1 * point(), 0.5 * r1));
      } else {
        s1.push_back(Ops::sphere(c1, r1)), s2.push_back(Ops::sphere(1.5 * point(), rad(g)));
      }
    }
  }
};
template <class Ops>
const Ring<Ops>& ring() {
  static const Ring<Ops> r;
  return r;
}

template <class Ops, class F>
void on_ring(benchmark::State& st, F f) {
  const Ring<Ops>& R = ring<Ops>();
  std::size_t i = 0;
  for (auto _ : st) {
    auto r = f(R, i);
    benchmark::DoNotOptimize(r);
    i = (i + 1) & (kN - 1);
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()));
}

template <class Ops, bool Welzl>
void bounding_sphere(benchmark::State& st, const std::string& hull) {
  const std::vector<Vec3>& p = hulls().at(hull);
  double spheres = 0, tests = 0;
  std::mt19937_64 rng(1);  // one generator for the run, as a simulation would keep
  for (auto _ : st) {
    auto r = Welzl ? core::welzl_sphere<Ops>(p, rng) : core::exhaustive_sphere<Ops>(p);
    benchmark::DoNotOptimize(r.sphere);
    spheres += static_cast<double>(r.counters.spheres);
    tests += static_cast<double>(r.counters.containment_tests);
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()));
  st.counters["vertices"] = static_cast<double>(p.size());
  st.counters["spheres"] = benchmark::Counter(spheres, benchmark::Counter::kAvgIterations);
  st.counters["containment_tests"] = benchmark::Counter(tests, benchmark::Counter::kAvgIterations);
}

template <class Ops>
void broadphase(benchmark::State& st, int n) {
  std::mt19937_64 g(static_cast<std::uint64_t>(n));
  const double side = 6 * std::cbrt(static_cast<double>(n));
  std::uniform_real_distribution<double> u(0, side), rad(0.2, 1.2);
  std::vector<typename Ops::Sphere> s;
  for (int i = 0; i < n; ++i) s.push_back(Ops::sphere(Vec3(u(g), u(g), u(g)), rad(g)));
  core::BroadphaseCounters c;
  for (auto _ : st) {
    auto r = core::sort_and_sweep<Ops>(s);
    benchmark::DoNotOptimize(r.pairs.data());
    c = r.counters;
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()));
  st.counters["candidates"] = static_cast<double>(c.candidates);
  st.counters["pairs"] = static_cast<double>(c.pairs);
}

template <class Ops>
void register_backend() {
  const std::string impl = Ops::name;
  for (const auto& [name, p] : hulls()) {
    if (p.size() <= 16)
      benchmark::RegisterBenchmark(("BM_exhaustive_sphere_" + name + "/" + impl).c_str(),
                                   [name = name](benchmark::State& st) { bounding_sphere<Ops, false>(st, name); });
    benchmark::RegisterBenchmark(("BM_welzl_sphere_" + name + "/" + impl).c_str(),
                                 [name = name](benchmark::State& st) { bounding_sphere<Ops, true>(st, name); });
  }
  using R = Ring<Ops>;
  benchmark::RegisterBenchmark(("BM_sphere_2/" + impl).c_str(), [](benchmark::State& st) {
    on_ring<Ops>(st, [](const R& D, std::size_t i) { return Ops::sphere_2(D.a[i], D.b[i]); });
  });
  benchmark::RegisterBenchmark(("BM_sphere_3/" + impl).c_str(), [](benchmark::State& st) {
    on_ring<Ops>(st, [](const R& D, std::size_t i) { return Ops::sphere_3(D.a[i], D.b[i], D.c[i]); });
  });
  benchmark::RegisterBenchmark(("BM_sphere_4/" + impl).c_str(), [](benchmark::State& st) {
    on_ring<Ops>(st, [](const R& D, std::size_t i) { return Ops::sphere_4(D.a[i], D.b[i], D.c[i], D.d[i]); });
  });
  benchmark::RegisterBenchmark(("BM_contains/" + impl).c_str(), [](benchmark::State& st) {
    on_ring<Ops>(st, [](const R& D, std::size_t i) { return Ops::contains(D.s1[i], D.x[i], 1e-10); });
  });
  benchmark::RegisterBenchmark(("BM_sphere_overlap/" + impl).c_str(), [](benchmark::State& st) {
    on_ring<Ops>(st, [](const R& D, std::size_t i) { return Ops::overlap(D.s1[i], D.s2[i]); });
  });
  for (int n : {100, 1000})
    benchmark::RegisterBenchmark(("BM_broadphase_" + std::to_string(n) + "/" + impl).c_str(),
                                 [n](benchmark::State& st) { broadphase<Ops>(st, n); });
}

// The conformal policy with the report's overlap by the meet
// (cga::overlap_by_meet): the same sign, more products.
struct CgaMeet : C {
  static constexpr const char* name = "cga_meet";
  static bool overlap(const Sphere& s1, const Sphere& s2) { return cga::overlap_by_meet(s1, s2); }
};

void register_all() {
  register_backend<T>();
  register_backend<C>();
  for (int n : {100, 1000})
    benchmark::RegisterBenchmark(("BM_broadphase_" + std::to_string(n) + "/cga_meet").c_str(),
                                 [n](benchmark::State& st) { broadphase<CgaMeet>(st, n); });
  benchmark::RegisterBenchmark("BM_sphere_overlap/cga_meet", [](benchmark::State& st) {
    on_ring<C>(st, [](const Ring<C>& D, std::size_t i) { return cga::overlap_by_meet(D.s1[i], D.s2[i]); });
  });
}

}  // namespace

int main(int argc, char** argv) {
  benchmark::Initialize(&argc, argv);
  if (benchmark::ReportUnrecognizedArguments(argc, argv)) return 1;
  register_all();
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
