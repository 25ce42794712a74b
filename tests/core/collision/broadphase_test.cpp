// core/collision/broadphase.hpp (sort and sweep over bounding spheres, and the
// broadphase the collision pipeline calls: sweep, AABB tree and sphere tree)
// against all pairs, with both backends' sphere tests, and the axis-aligned
// box of core/collision/bounding_volume.hpp.
#include "cga/bounding_volume.hpp"
#include "core/collision/broadphase.hpp"
#include "core/parallel.hpp"
#include "../../scoped_threads.hpp"
#include "traditional/bounding_volume.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <random>
#include <string>
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
class Broadphases : public ::testing::Test {};
using Backends = ::testing::Types<traditional::SphereOps, cga::SphereOps>;
TYPED_TEST_SUITE(Broadphases, Backends);

// 20 seeded sparse scenes of 500 spheres (box of side 60, radii 0.2–1.2: a
// handful of overlapping pairs per scene): the sweep's pairs are exactly all
// pairs' (same backend test), and equal the long-double distance test's (the
// scenes are random: no pair falls in the touching band, which the agreement
// would otherwise need to exclude), with candidates far below n(n−1)/2. Along
// one axis two intervals meet with probability ≈ 2·E[ρ1 + ρ2]/side ≈ 5%, so
// the test asks for under 10%.
TYPED_TEST(Broadphases, SparseScenesGiveAllPairsFromFewCandidates) {
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
TYPED_TEST(Broadphases, DenseAndElongatedScenes) {
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
TYPED_TEST(Broadphases, TouchingNestedAndTrivialScenes) {
  using Ops = TypeParam;
  const std::vector<typename Ops::Sphere> s{Ops::sphere(Vec3(0, 0, 0), 1), Ops::sphere(Vec3(2, 0, 0), 1),
                                            Ops::sphere(Vec3(10, 0, 0), 3), Ops::sphere(Vec3(10.5, 0, 0), 0.5),
                                            Ops::sphere(Vec3(20, 0, 0), 1)};
  const std::vector<std::pair<int, int>> want{{0, 1}, {2, 3}};
  EXPECT_EQ(sort_and_sweep<Ops>(s).pairs, want);
  EXPECT_TRUE(sort_and_sweep<Ops>(std::vector<typename Ops::Sphere>{}).pairs.empty());
  EXPECT_TRUE(sort_and_sweep<Ops>(std::vector<typename Ops::Sphere>{Ops::sphere(Vec3(1, 2, 3), 1)}).pairs.empty());
}

// ---- core::Broadphase: every method the same pairs, through many updates ----

constexpr BroadphaseMethod kMethods[] = {BroadphaseMethod::sweep, BroadphaseMethod::aabb_tree,
                                         BroadphaseMethod::sphere_tree};
const char* name_of(BroadphaseMethod m) {
  return m == BroadphaseMethod::sweep ? "sweep" : m == BroadphaseMethod::aabb_tree ? "aabb_tree" : "sphere_tree";
}

struct Bodies {
  std::vector<Vec3> centres;
  std::vector<double> radii;
  std::vector<char> is_static;
  std::vector<double> margins;  // empty: no candidates asked for
};

// All pairs with the backend's own test on the spheres the broadphase formed
// (the same expression in its frame, so the same numbers), grown by the
// margins or not, static pairs left out.
template <class Ops>
std::vector<std::pair<int, int>> all_pairs_in_frame(const Bodies& b, const Vec3& frame, bool grown) {
  std::vector<typename Ops::Sphere> s;
  for (std::size_t i = 0; i < b.centres.size(); ++i)
    s.push_back(Ops::sphere(b.centres[i] - frame, b.radii[i] + (grown ? b.margins[i] : 0.0)));
  auto out = all_pairs<Ops>(s);
  std::erase_if(out, [&](const auto& p) {
    return b.is_static[static_cast<std::size_t>(p.first)] && b.is_static[static_cast<std::size_t>(p.second)];
  });
  return out;
}

// One broadphase per method, fed the same bodies; each answer checked against
// all pairs, and with margins the candidates against all pairs of the grown
// spheres.
template <class Ops>
struct Methods {
  std::vector<Broadphase<Ops>> bp;
  Methods() {
    for (const auto m : kMethods) bp.emplace_back(m);
  }
  std::vector<BroadphaseResult> find(const Bodies& b, const std::string& where) {
    std::vector<BroadphaseResult> out;
    for (auto& p : bp) {
      out.push_back(p.find(b.centres, b.radii, b.is_static, b.margins));
      const auto& r = out.back();
      EXPECT_EQ(r.pairs, all_pairs_in_frame<Ops>(b, p.frame(), false)) << name_of(p.method()) << " " << where;
      if (b.margins.empty()) EXPECT_TRUE(r.candidates.empty());
      else EXPECT_EQ(r.candidates, all_pairs_in_frame<Ops>(b, p.frame(), true)) << name_of(p.method()) << " " << where;
      EXPECT_EQ(r.counters.pairs, static_cast<std::int64_t>(r.pairs.size()));
    }
    return out;
  }
};

// 400 bodies (radii 0.2–1.0, 20 of them static) in a box of side 20, moving
// coherently (0.02 m per update, bouncing off the box) for 300 updates, a
// tenth of them teleported every 50th: at every update each method's pairs
// equal all pairs'. The trees reinsert every body at the first update and
// then only those that left their fat volumes: under a quarter per update on
// average (a body moving 0.02 a step in a straight line leaves a margin of
// kFatMargin·ρ = 0.4 ρ every 20ρ steps; over ρ uniform in [0.2, 1],
// E[0.05/ρ] = 0.10, and the teleports add 0.002). Every other update asks
// for candidates too, with each sphere grown by 1–2 times its body's step
// (as the collision step grows them by how far a body can move): they equal
// all pairs of the grown spheres. An update with nothing moved reinserts
// nothing and tests no tree node: its candidates are exactly the kept pairs.
// The moving scene above: calls update(bodies, step) after each of the 300
// moves, margins set at every other one.
template <class F>
void move_400_bodies(F&& update) {
  std::mt19937_64 g(21);
  std::uniform_real_distribution<double> u(0, 20), rad(0.2, 1.0), dir(-1, 1);
  const int n = 400;
  Bodies b;
  std::vector<Vec3> v;
  for (int i = 0; i < n; ++i) {
    b.centres.emplace_back(u(g), u(g), u(g));
    b.radii.push_back(rad(g));
    b.is_static.push_back(i % 20 == 0);
    v.push_back(b.is_static.back() ? Vec3::Zero() : Vec3(0.02 * Vec3(dir(g), dir(g), dir(g)).normalized()));
  }
  for (int step = 0; step < 300; ++step) {
    for (int i = 0; i < n; ++i) {
      auto& c = b.centres[static_cast<std::size_t>(i)];
      c += v[static_cast<std::size_t>(i)];
      for (int k = 0; k < 3; ++k)
        if (c[k] < 0 || c[k] > 20) v[static_cast<std::size_t>(i)][k] *= -1;
      if (step % 50 == 49 && i % 10 == 1) c = Vec3(u(g), u(g), u(g));
    }
    b.margins.clear();
    if (step % 2)
      for (int i = 0; i < n; ++i) b.margins.push_back(v[static_cast<std::size_t>(i)].norm() * (1.5 + 0.5 * dir(g)));
    update(b, step);
  }
}

TYPED_TEST(Broadphases, EveryMethodGivesAllPairsAsBodiesMove) {
  using Ops = TypeParam;
  const int n = 400;
  Methods<Ops> m;
  std::int64_t updates = 0, pairs = 0;
  Bodies b;
  move_400_bodies([&](const Bodies& moved, int step) {
    b = moved;
    const auto r = m.find(b, "step " + std::to_string(step));
    pairs += r[0].counters.pairs;
    for (std::size_t k = 1; k < r.size(); ++k) {
      EXPECT_LE(r[k].counters.tree_updates, n);
      EXPECT_GE(r[k].counters.pairs_kept, r[k].counters.pairs);
      if (step == 0) EXPECT_EQ(r[k].counters.tree_updates, n);
      else updates += r[k].counters.tree_updates;
    }
  });
  EXPECT_GT(pairs, 300);
  EXPECT_LT(updates, 2 * 299 * n / 4) << "reinsertions, both trees";
  b.margins.clear();
  const auto again = m.find(b, "still");
  const auto still = m.find(b, "still");
  for (std::size_t k = 1; k < still.size(); ++k) {
    EXPECT_EQ(still[k].counters.tree_updates, 0);
    EXPECT_EQ(still[k].counters.candidates, still[k].counters.pairs_kept);
    EXPECT_EQ(still[k].pairs, again[k].pairs);
  }
  std::printf("[ %s: %.1f reinsertions per update of %d bodies, %.1f pairs ]\n", Ops::name,
              static_cast<double>(updates) / (2 * 299), n, static_cast<double>(pairs) / 300);
}

// The trees' update on two threads (its containment tests, its moved bodies'
// queries in blocks and its kept pairs' exact tests: core/parallel.hpp), with
// every loop cut into chunks of at most 4 so that 400 bodies run every
// parallel path: at every update of the moving scene each tree's pairs,
// candidates and counters equal those of the same tree on one thread, and
// the pairs equal all pairs'.
TYPED_TEST(Broadphases, TreesGiveTheSameAnswerOnTwoThreads) {
  using Ops = TypeParam;
  for (const auto method : {BroadphaseMethod::aabb_tree, BroadphaseMethod::sphere_tree}) {
    Broadphase<Ops> one(method), two(method);
    std::int64_t moved = 0;
    move_400_bodies([&](const Bodies& b, int step) {
      const BroadphaseResult r1 = one.find(b.centres, b.radii, b.is_static, b.margins);
      const BroadphaseResult r2 = [&] {
        const gacompare::testing::ScopedThreads two_threads(2, true);
        return two.find(b.centres, b.radii, b.is_static, b.margins);
      }();
      const std::string where = std::string(name_of(method)) + " step " + std::to_string(step);
      ASSERT_EQ(r2.pairs, r1.pairs) << where;
      ASSERT_EQ(r2.candidates, r1.candidates) << where;
      ASSERT_EQ(r2.pairs, all_pairs_in_frame<Ops>(b, two.frame(), false)) << where;
      EXPECT_EQ(r2.counters.candidates, r1.counters.candidates) << where;
      EXPECT_EQ(r2.counters.overlap_tests, r1.counters.overlap_tests) << where;
      EXPECT_EQ(r2.counters.tree_updates, r1.counters.tree_updates) << where;
      EXPECT_EQ(r2.counters.pairs_kept, r1.counters.pairs_kept) << where;
      moved += r2.counters.tree_updates;
    });
    EXPECT_GT(moved, 300 * 8) << "the scene must move enough bodies per update to split the queries";
  }
}

// The AABB tree's boxes reach along each body's motion (kLookAhead): on the
// moving scene above (straight paths, bounces off the walls, a tenth of the
// bodies teleported every 50 moves) the pairs and candidates at every update
// equal those of boxes that do not reach ahead, and all pairs', while the
// reinsertions fall below 0.7 of theirs (measured: 5,460 against 8,604 in
// both backends; what is left is mostly the margins, which grow every other
// box by its body's reach, and the bounces and teleports).
TYPED_TEST(Broadphases, BoxesReachingAheadKeepThePairsAndReinsertLess) {
  using Ops = TypeParam;
  Broadphase<Ops> ahead(BroadphaseMethod::aabb_tree), still(BroadphaseMethod::aabb_tree, kFatMargin, 0);
  std::int64_t reinserted_ahead = 0, reinserted_still = 0;
  move_400_bodies([&](const Bodies& b, int step) {
    const BroadphaseResult r = ahead.find(b.centres, b.radii, b.is_static, b.margins);
    const BroadphaseResult s = still.find(b.centres, b.radii, b.is_static, b.margins);
    const std::string where = "step " + std::to_string(step);
    ASSERT_EQ(r.pairs, s.pairs) << where;
    ASSERT_EQ(r.candidates, s.candidates) << where;
    ASSERT_EQ(r.pairs, all_pairs_in_frame<Ops>(b, ahead.frame(), false)) << where;
    EXPECT_GE(r.counters.pairs_kept, r.counters.pairs) << where;
    reinserted_ahead += r.counters.tree_updates, reinserted_still += s.counters.tree_updates;
  });
  EXPECT_LE(10 * reinserted_ahead, 7 * reinserted_still);
  std::printf("[ %s: %lld reinsertions reaching ahead, %lld not ]\n", Ops::name,
              static_cast<long long>(reinserted_ahead), static_cast<long long>(reinserted_still));
}

// Degenerate scenes, every method: equal spheres exactly touching (a 6³ grid
// at spacing 1, radius ½: integers and halves, exact in both algebras; the
// 540 face neighbours touch, the diagonals do not), twenty bodies on one
// centre with every radius, a static pair that overlaps (never reported, nor
// as a candidate) with a moving body overlapping both.
TYPED_TEST(Broadphases, TouchingCoincidentAndStaticScenes) {
  using Ops = TypeParam;
  Bodies grid;
  for (int x = 0; x < 6; ++x)
    for (int y = 0; y < 6; ++y)
      for (int z = 0; z < 6; ++z) grid.centres.emplace_back(x, y, z), grid.radii.push_back(0.5);
  grid.is_static.assign(grid.centres.size(), false);
  for (const auto& r : Methods<Ops>().find(grid, "grid")) EXPECT_EQ(r.pairs.size(), 540u);

  Bodies same;
  std::mt19937_64 g(22);
  std::uniform_real_distribution<double> u(0, 10), rad(0.1, 1);
  for (int i = 0; i < 60; ++i) {
    same.centres.push_back(i < 20 ? Vec3(3, 3, 3) : Vec3(u(g), u(g), u(g)));
    same.radii.push_back(i < 20 ? 0.05 * (i + 1) : rad(g));
  }
  same.is_static.assign(same.centres.size(), false);
  Methods<Ops> m;
  for (int round = 0; round < 3; ++round) {  // and again, with the trees built
    const auto r = m.find(same, "coincident");
    EXPECT_GE(r[0].pairs.size(), 190u);  // the 20·19/2 on one centre, and any others
  }

  Bodies statics{{Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(0.5, 0.5, 0)}, {1, 1, 0.3}, {1, 1, 0}, {}};
  const std::vector<std::pair<int, int>> want{{0, 2}, {1, 2}};
  for (const auto& r : Methods<Ops>().find(statics, "statics")) EXPECT_EQ(r.pairs, want);
  statics.margins = {0.5, 0.5, 0.5};
  for (const auto& r : Methods<Ops>().find(statics, "statics grown")) EXPECT_EQ(r.candidates, want);
}

// Far from the origin: 300 random bodies around (D, D, D), D = 1e3 … 1e9 m.
// The pairs equal the distance test on the world coordinates as stored (in
// long double; the frame's subtraction of nearby doubles is exact, so the
// spheres are the stored ones), and every method agrees. The pairs at the
// origin would be the same but for the centres' rounding at 1e9 (6e-8 m).
TYPED_TEST(Broadphases, FarFromTheOriginGivesTheDistanceTestsPairs) {
  using Ops = TypeParam;
  const Scene near = random_scene(23, 300, 20, 0.2, 1.2);
  for (const double d : {1e3, 1e5, 1e7, 1e9}) {
    Scene far = near;
    for (auto& c : far.centres) c += Vec3::Constant(d);
    Bodies b{far.centres, far.radii, std::vector<char>(300, 0), {}};
    Methods<Ops> m;
    for (int round = 0; round < 2; ++round)
      for (const auto& r : m.find(b, "D " + std::to_string(d))) EXPECT_EQ(r.pairs, by_distance(far)) << d;
  }
}

// A cluster drifting away at 1e3 m per update (2e5 m in all): the frame is
// re-centred on the bodies whenever their mean has left it by more than their
// extent, so it never lags by more than that, and the pairs stay exactly the
// distance test's (with the frame left at the start, the conformal spheres
// would lose ten digits by the end, as in world coordinates).
TYPED_TEST(Broadphases, TheFrameFollowsBodiesThatDrift) {
  using Ops = TypeParam;
  Scene s = random_scene(24, 50, 5, 0.2, 0.8);
  Methods<Ops> m;
  for (int step = 0; step < 200; ++step) {
    for (auto& c : s.centres) c += Vec3(1e3, 0, 0);
    Bodies b{s.centres, s.radii, std::vector<char>(50, 0), {}};
    for (const auto& r : m.find(b, "step " + std::to_string(step))) EXPECT_EQ(r.pairs, by_distance(s)) << step;
    Vec3 mean = Vec3::Zero();
    for (const auto& c : s.centres) mean += c / 50.0;
    for (const auto& p : m.bp) EXPECT_LE((p.frame() - mean).norm(), 5 * std::sqrt(3.0)) << step;
  }
  for (const auto& p : m.bp) EXPECT_GT(p.frames(), 1);
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

// The counting sort of pairs gives std::sort's order, repeats included, on
// seeded lists below and above its small-list cut-off.
TEST(SortPairs, MatchesTheComparisonSort) {
  std::mt19937_64 rng(14);
  for (const std::size_t n : {1u, 2u, 7u, 100u, 3000u})
    for (const std::size_t k : {0u, 5u, 63u, 64u, 1000u, 20000u}) {
      if (n < 2 && k > 0) continue;
      std::vector<std::pair<int, int>> pairs;
      for (std::size_t e = 0; e < k; ++e) {
        const int i = static_cast<int>(rng() % (n - 1));
        pairs.emplace_back(i, i + 1 + static_cast<int>(rng() % (n - 1 - static_cast<std::size_t>(i))));
      }
      auto expected = pairs;
      std::sort(expected.begin(), expected.end());
      sort_pairs(pairs, n);
      EXPECT_EQ(pairs, expected) << n << " bodies, " << k << " pairs";
    }
}

}  // namespace
}  // namespace gacompare::core
