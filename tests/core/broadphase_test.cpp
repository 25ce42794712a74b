// core/broadphase.hpp (sort and sweep over bounding spheres) against all pairs,
// with both backends' sphere tests, and the axis-aligned box of
// core/bounding_volume.hpp.
#include "cga/bounding_volume.hpp"
#include "core/broadphase.hpp"
#include "traditional/bounding_volume.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <utility>
#include <vector>

namespace gacompare::core {
namespace {

struct Scene {
  std::vector<Vec3> centres;
  std::vector<double> radii;
};

// n spheres with centres uniform in a box of side `side` (stretched by `aspect`
// per axis) and radii uniform in [rmin, rmax].
Scene random_scene(std::uint64_t seed, int n, double side, double rmin, double rmax, const Vec3& aspect = Vec3::Ones()) {
  std::mt19937_64 g(seed);
  std::uniform_real_distribution<double> u(0, side), r(rmin, rmax);
  Scene s;
  for (int i = 0; i < n; ++i) {
    s.centres.push_back(Vec3(u(g), u(g), u(g)).cwiseProduct(aspect));
    s.radii.push_back(r(g));
  }
  return s;
}

template <class Ops>
std::vector<typename Ops::Sphere> spheres_of(const Scene& s) {
  std::vector<typename Ops::Sphere> out;
  for (std::size_t i = 0; i < s.centres.size(); ++i) out.push_back(Ops::sphere(s.centres[i], s.radii[i]));
  return out;
}

// Every pair, with the same backend test: the answer the sweep must reproduce exactly.
template <class Ops>
std::vector<std::pair<int, int>> all_pairs(const std::vector<typename Ops::Sphere>& s) {
  std::vector<std::pair<int, int>> out;
  for (int i = 0; i < static_cast<int>(s.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(s.size()); ++j)
      if (Ops::overlap(s[static_cast<std::size_t>(i)], s[static_cast<std::size_t>(j)])) out.emplace_back(i, j);
  return out;
}

// The distance test in long double, for the cross-backend check.
std::vector<std::pair<int, int>> by_distance(const Scene& s) {
  std::vector<std::pair<int, int>> out;
  for (int i = 0; i < static_cast<int>(s.centres.size()); ++i)
    for (int j = i + 1; j < static_cast<int>(s.centres.size()); ++j) {
      const auto a = static_cast<std::size_t>(i), b = static_cast<std::size_t>(j);
      long double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const long double x = static_cast<long double>(s.centres[a][k]) - s.centres[b][k];
        d2 += x * x;
      }
      const long double r = static_cast<long double>(s.radii[a]) + s.radii[b];
      if (d2 <= r * r) out.emplace_back(i, j);
    }
  return out;
}

template <class Ops>
class Broadphase : public ::testing::Test {};
using Backends = ::testing::Types<traditional::SphereOps, cga::SphereOps>;
TYPED_TEST_SUITE(Broadphase, Backends);

// 20 seeded sparse scenes of 500 spheres (box of side 60, radii 0.2–1.2: a
// handful of overlapping pairs per scene): the sweep's pairs are exactly all
// pairs' (same backend test), and equal the long-double distance test's (the
// scenes are random: no pair falls in the touching band, which the agreement
// would otherwise need to exclude), with candidates far below n(n−1)/2. Along
// one axis two intervals meet with probability ≈ 2·E[ρ1 + ρ2]/side ≈ 5%, so
// the test asks for under 10%.
TYPED_TEST(Broadphase, SparseScenesGiveAllPairsFromFewCandidates) {
  using Ops = TypeParam;
  const int n = 500;
  const std::int64_t all = std::int64_t{n} * (n - 1) / 2;
  for (std::uint64_t seed = 0; seed < 20; ++seed) {
    const Scene scene = random_scene(seed, n, 60, 0.2, 1.2);
    const auto spheres = spheres_of<Ops>(scene);
    const BroadphaseResult r = sort_and_sweep<Ops>(spheres);
    EXPECT_EQ(r.pairs, all_pairs<Ops>(spheres)) << "seed " << seed;
    EXPECT_EQ(r.pairs, by_distance(scene)) << "seed " << seed;
    EXPECT_GT(r.counters.pairs, 0);
    EXPECT_EQ(r.counters.pairs, static_cast<std::int64_t>(r.pairs.size()));
    EXPECT_EQ(r.counters.overlap_tests, r.counters.candidates);
    EXPECT_LT(r.counters.candidates, all / 10) << "seed " << seed;
    if (seed == 0)
      std::printf("[ %s: %lld candidates of %lld pairs, %lld overlapping ]\n", Ops::name,
                  static_cast<long long>(r.counters.candidates), static_cast<long long>(all),
                  static_cast<long long>(r.counters.pairs));
  }
}

// A dense scene (everything near everything) and a flat, elongated one: still
// exactly all pairs; the flat one is swept along its long axis (z here).
TYPED_TEST(Broadphase, DenseAndElongatedScenes) {
  using Ops = TypeParam;
  const Scene dense = random_scene(100, 200, 3, 0.5, 1.5);
  const auto ds = spheres_of<Ops>(dense);
  EXPECT_EQ(sort_and_sweep<Ops>(ds).pairs, all_pairs<Ops>(ds));
  const Scene column = random_scene(101, 400, 50, 0.1, 0.6, Vec3(0.05, 0.02, 1));
  const auto cs = spheres_of<Ops>(column);
  const BroadphaseResult r = sort_and_sweep<Ops>(cs);
  EXPECT_EQ(r.axis, 2);
  EXPECT_EQ(r.pairs, all_pairs<Ops>(cs));
}

// Touching spheres (exactly, in integers) and nested ones are pairs; an empty
// scene and a single sphere have none.
TYPED_TEST(Broadphase, TouchingNestedAndTrivialScenes) {
  using Ops = TypeParam;
  const std::vector<typename Ops::Sphere> s{Ops::sphere(Vec3(0, 0, 0), 1), Ops::sphere(Vec3(2, 0, 0), 1),
                                            Ops::sphere(Vec3(10, 0, 0), 3), Ops::sphere(Vec3(10.5, 0, 0), 0.5),
                                            Ops::sphere(Vec3(20, 0, 0), 1)};
  const std::vector<std::pair<int, int>> want{{0, 1}, {2, 3}};
  EXPECT_EQ(sort_and_sweep<Ops>(s).pairs, want);
  EXPECT_TRUE(sort_and_sweep<Ops>(std::vector<typename Ops::Sphere>{}).pairs.empty());
  EXPECT_TRUE(sort_and_sweep<Ops>(std::vector<typename Ops::Sphere>{Ops::sphere(Vec3(1, 2, 3), 1)}).pairs.empty());
}

// Fn 23's six comparisons: boxes overlap when their intervals do on every axis
// (touching faces included), and the empty box overlaps nothing.
TEST(Aabb, CornersAndSixComparisons) {
  const std::vector<Vec3> p{Vec3(1, -2, 3), Vec3(-1, 4, 0), Vec3(0.5, 0, 7)};
  const Aabb box = aabb_of(p);
  EXPECT_EQ(box.min, Vec3(-1, -2, 0));
  EXPECT_EQ(box.max, Vec3(1, 4, 7));
  for (int axis = 0; axis < 3; ++axis) {
    Aabb moved = box;
    moved.min[axis] += 2 * (box.max[axis] - box.min[axis]);
    moved.max[axis] += 2 * (box.max[axis] - box.min[axis]);
    EXPECT_FALSE(overlap(box, moved)) << axis;
    EXPECT_FALSE(overlap(moved, box)) << axis;
    Aabb touching = box;
    touching.min[axis] = box.max[axis];
    touching.max[axis] = box.max[axis] + 1;
    EXPECT_TRUE(overlap(box, touching)) << axis;
  }
  const Aabb inner{Vec3(0, 0, 1), Vec3(0.5, 0.5, 2)};
  EXPECT_TRUE(overlap(box, inner));
  EXPECT_TRUE(overlap(inner, box));
  EXPECT_FALSE(overlap(box, Aabb{}));
  EXPECT_FALSE(overlap(Aabb{}, Aabb{}));
  EXPECT_FALSE(overlap(aabb_of(std::vector<Vec3>{}), box));
}

}  // namespace
}  // namespace gacompare::core
