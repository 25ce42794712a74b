// Each geometric operation of Table 1 and §1.6–1.7, conformal vs traditional, on the same
// pre-generated random cases (features of size ~1 near the origin, so both
// backends take the same branches: a mix of circles and misses, pairs and
// misses). Entities are built once, outside the timed loop, in each backend's
// native form (dual sphere/plane vectors and line 3-blades; centre–radius,
// normal–offset, point–direction); constructions from points are timed as
// operations of their own (line_through, plane_through, circumcircle,
// sphere_through). Each iteration processes the next case of a 1024-case ring.
//
// Names: BM_<operation>/cga and BM_<operation>/traditional. For the ratio table,
// run interleaved and repeated and compare medians (docs/architecture.md "Measuring"):
//   ./geometry_bench --benchmark_repetitions=10 --benchmark_enable_random_interleaving=true
//       --benchmark_report_aggregates_only=true --benchmark_format=json > geometry_bench.json
// (one command line).
#include "cga/geometry/geometry.hpp"
#include "traditional/geometry.hpp"

#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {

namespace C = gacompare::cga;
namespace T = gacompare::traditional;
using Vec3 = Eigen::Vector3d;

constexpr std::size_t kN = 1024;  // a power of two: the ring index is a mask

struct Data {
  std::vector<Vec3> a, b, c, d, x, s1, s2, n1, n2;
  std::vector<double> r1, r2, o1, o2;
  // native entities
  std::vector<C::DualSphere> cs1, cs2;
  std::vector<C::DualPlane> cp1, cp2;
  std::vector<C::Line> cl;
  std::vector<T::Sphere> ts1, ts2;
  std::vector<T::Plane> tp1, tp2;
  std::vector<T::Line> tl;

  Data() {
    std::mt19937_64 g(2003);
    std::uniform_real_distribution<double> u(-1, 1), rad(0.3, 1.5);
    const auto point = [&] { return Vec3(u(g), u(g), u(g)); };
    const auto unit = [&] {
      for (;;) {
        const Vec3 v = point();
        if (v.norm() > 0.1 && v.norm() <= 1) return Vec3(v.normalized());
      }
    };
    while (a.size() < kN) {
      const Vec3 pa = point(), pb = point(), pc = point(), pd = point();
      if ((pb - pa).norm() < 0.2 || (pc - pa).norm() < 0.2 || (pc - pb).norm() < 0.2) continue;
      a.push_back(pa), b.push_back(pb), c.push_back(pc), d.push_back(pd), x.push_back(point());
      s1.push_back(0.7 * point()), s2.push_back(0.7 * point());
      r1.push_back(rad(g)), r2.push_back(rad(g));
      n1.push_back(unit()), n2.push_back(unit());
      o1.push_back(0.5 * u(g)), o2.push_back(0.5 * u(g));
      cs1.push_back(C::sphere(s1.back(), r1.back())), cs2.push_back(C::sphere(s2.back(), r2.back()));
      cp1.push_back(C::plane(n1.back(), o1.back())), cp2.push_back(C::plane(n2.back(), o2.back()));
      cl.push_back(*C::line_through(pa, pb));
      ts1.push_back(T::sphere(s1.back(), r1.back())), ts2.push_back(T::sphere(s2.back(), r2.back()));
      tp1.push_back(T::plane(n1.back(), o1.back())), tp2.push_back(T::plane(n2.back(), o2.back()));
      tl.push_back(*T::line_through(pa, pb));
    }
  }
};

const Data& data() {
  static const Data d;
  return d;
}

template <class F>
void ring(benchmark::State& st, F f) {
  std::size_t i = 0;
  for (auto _ : st) {
    auto r = f(data(), i);
    benchmark::DoNotOptimize(r);
    i = (i + 1) & (kN - 1);
  }
  st.SetItemsProcessed(static_cast<std::int64_t>(st.iterations()));
}

// One operation, both backends: the two expressions see the same case i of D.
#define GEOMETRY_PAIR(op, cga_expr, trad_expr)                                                      \
  benchmark::RegisterBenchmark("BM_" #op "/cga", [](benchmark::State& st) {                       \
    ring(st, [](const Data& D, std::size_t i) { return cga_expr; });                                \
  });                                                                                               \
  benchmark::RegisterBenchmark("BM_" #op "/traditional", [](benchmark::State& st) {               \
    ring(st, [](const Data& D, std::size_t i) { return trad_expr; });                               \
  })

void register_all() {
  GEOMETRY_PAIR(line_through, C::line_through(D.a[i], D.b[i]), T::line_through(D.a[i], D.b[i]));
  GEOMETRY_PAIR(plane_through, C::plane_through(D.a[i], D.b[i], D.c[i]), T::plane_through(D.a[i], D.b[i], D.c[i]));
  GEOMETRY_PAIR(circumcircle, C::circumcircle(D.a[i], D.b[i], D.c[i]), T::circumcircle(D.a[i], D.b[i], D.c[i]));
  GEOMETRY_PAIR(sphere_through, C::sphere_through(D.a[i], D.b[i], D.c[i], D.d[i]),
                T::sphere_through(D.a[i], D.b[i], D.c[i], D.d[i]));
  GEOMETRY_PAIR(meet_sphere_sphere, C::meet_sphere_sphere(D.cs1[i], D.cs2[i]), T::meet_sphere_sphere(D.ts1[i], D.ts2[i]));
  GEOMETRY_PAIR(meet_sphere_plane, C::meet_sphere_plane(D.cs1[i], D.cp1[i]), T::meet_sphere_plane(D.ts1[i], D.tp1[i]));
  GEOMETRY_PAIR(meet_line_plane, C::meet_line_plane(D.cl[i], D.cp1[i]), T::meet_line_plane(D.tl[i], D.tp1[i]));
  GEOMETRY_PAIR(meet_line_sphere, C::meet_line_sphere(D.cl[i], D.cs1[i]), T::meet_line_sphere(D.tl[i], D.ts1[i]));
  GEOMETRY_PAIR(meet_plane_plane, C::meet_plane_plane(D.cp1[i], D.cp2[i]), T::meet_plane_plane(D.tp1[i], D.tp2[i]));
  GEOMETRY_PAIR(reflect_in_plane, C::reflect_in_plane(D.x[i], D.cp1[i]), T::reflect_in_plane(D.x[i], D.tp1[i]));
  GEOMETRY_PAIR(reflect_in_sphere, C::reflect_in_sphere(D.x[i], D.cs1[i]), T::reflect_in_sphere(D.x[i], D.ts1[i]));
  GEOMETRY_PAIR(reflect_in_line, C::reflect_in_line(D.x[i], D.cl[i]), T::reflect_in_line(D.x[i], D.tl[i]));
  GEOMETRY_PAIR(nearest_on_line, C::nearest_on_line(D.x[i], D.cl[i]), T::nearest_on_line(D.x[i], D.tl[i]));
  GEOMETRY_PAIR(side, C::side(D.cs1[i], D.x[i]), T::side(D.ts1[i], D.x[i]));
  // The report's sandwich form of the vector reflections (docs/architecture.md "Fair
  // comparison": time the pure form as well as the best one).
  benchmark::RegisterBenchmark("BM_reflect_in_plane/cga_sandwich", [](benchmark::State& st) {
    ring(st, [](const Data& D, std::size_t i) { return C::reflect_in_plane_by_sandwich(D.x[i], D.cp1[i]); });
  });
  benchmark::RegisterBenchmark("BM_reflect_in_sphere/cga_sandwich", [](benchmark::State& st) {
    ring(st, [](const Data& D, std::size_t i) { return *C::detail::point_of(C::reflect(D.cs1[i], C::up(D.x[i]))); });
  });
  benchmark::RegisterBenchmark("BM_reflect_in_line/cga_sandwich", [](benchmark::State& st) {
    ring(st, [](const Data& D, std::size_t i) { return C::reflect_in_line_by_sandwich(D.x[i], D.cl[i]); });
  });
  benchmark::RegisterBenchmark("BM_nearest_on_line/cga_sandwich", [](benchmark::State& st) {
    ring(st, [](const Data& D, std::size_t i) { return C::nearest_on_line_by_reflection(D.x[i], D.cl[i]); });
  });
  // The remedy's cost: the same operation with the frame change around it.
  benchmark::RegisterBenchmark("BM_circumcircle/cga_local_origin", [](benchmark::State& st) {
    ring(st, [](const Data& D, std::size_t i) { return C::local::circumcircle(D.a[i], D.b[i], D.c[i]); });
  });
  benchmark::RegisterBenchmark("BM_meet_line_sphere/cga_local_origin", [](benchmark::State& st) {
    ring(st, [](const Data& D, std::size_t i) { return C::local::meet_line_sphere(D.a[i], D.b[i], D.s1[i], D.r1[i]); });
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
