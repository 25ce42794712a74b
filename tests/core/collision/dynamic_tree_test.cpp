// core/collision/dynamic_tree.hpp over its three volume policies (core/collision/tree_broadphase.hpp):
// boxes, traditional spheres and conformal spheres. Checked against brute
// force (every leaf tested against the query), the structure's invariants,
// each parent's containment of its children measured independently (long
// double distances, not the policies' own tests), and the height.
#include "cga/bounding_volume.hpp"
#include "core/collision/dynamic_tree.hpp"
#include "core/collision/tree_broadphase.hpp"
#include "traditional/bounding_volume.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <cstdio>
#include <random>
#include <type_traits>
#include <vector>

namespace gacompare::core {
namespace {

// A policy with how the test builds a leaf and reads a volume back.
template <class V, class Ops>
struct Case {
  using Volume = typename V::Volume;
  using Policy = V;
  static Volume make(const Vec3& c, double r) {
    if constexpr (std::is_same_v<V, AabbVolume>) return {c.array() - r, c.array() + r};
    else return Ops::sphere(c, r);
  }
  // How far `inner` reaches outside `outer` (≤ 0: contained), in long double
  // from each volume's parameters: for boxes per face, for spheres
  // |c_i − c_o| + ρ_i − ρ_o.
  static long double outside(const Volume& outer, const Volume& inner) {
    if constexpr (std::is_same_v<V, AabbVolume>) {
      long double worst = -INFINITY;
      for (int k = 0; k < 3; ++k) {
        worst = std::max(worst, static_cast<long double>(outer.min[k]) - inner.min[k]);
        worst = std::max(worst, static_cast<long double>(inner.max[k]) - outer.max[k]);
      }
      return worst;
    } else {
      const Vec3 co = Ops::centre(outer), ci = Ops::centre(inner);
      long double d2 = 0;
      for (int k = 0; k < 3; ++k) {
        const long double x = static_cast<long double>(ci[k]) - co[k];
        d2 += x * x;
      }
      return std::sqrt(d2) + Ops::radius(inner) - static_cast<long double>(Ops::radius(outer));
    }
  }
  // How far a parent may miss its child by rounding. Boxes: not at all (the
  // union is exact). Traditional spheres: an enclosing sphere is a handful of
  // roundings of coordinates of size s = |c| + ρ ≤ 80 here: 1e-13·s (measured
  // 2e-14 at s = 50). Conformal spheres: S1², S2², S1·S2 are sums of products
  // of components as large as ½s², so each carries ~ε·s⁴/2 of rounding;
  // d² = S1² + S2² − 2 S1·S2 gathers about 2ε·s⁴ and the radii read from
  // them (by roots) that over 2ρ: tol = 2ε·s⁴/ρ ≈ 4e-16·s⁴/ρ of the child
  // (1e-8 m for a 1 m sphere 80 m from the origin; measured at most 0.25 of
  // it). The broadphase keeps its frame near the bodies for this reason
  // (core/collision/broadphase.hpp).
  static double tolerance(const Volume& parent, const Volume& child) {
    if constexpr (std::is_same_v<V, AabbVolume>) return 0;
    else {
      const double s = std::max(Ops::centre(parent).norm(), Ops::centre(child).norm()) + Ops::radius(parent);
      if constexpr (std::is_same_v<Ops, traditional::SphereOps>) return 1e-13 * s;
      else return 4e-16 * s * s * s * s / Ops::radius(child);
    }
  }
};

using Boxes = Case<AabbVolume, traditional::SphereOps>;
using Spheres = Case<SphereVolume<traditional::SphereOps>, traditional::SphereOps>;
using ConformalSpheres = Case<SphereVolume<cga::SphereOps>, cga::SphereOps>;

template <class C>
class Tree : public ::testing::Test {};
using Policies = ::testing::Types<Boxes, Spheres, ConformalSpheres>;
TYPED_TEST_SUITE(Tree, Policies);

// Every parent holds its children, to C::tolerance.
template <class C>
void expect_parents_hold_children(const DynamicTree<typename C::Policy>& tree) {
  double worst = 0;
  for (const auto& n : tree.nodes()) {
    if (n.height <= 0) continue;  // leaves and free nodes
    for (const int c : {n.child1, n.child2}) {
      const auto& child = tree.volume(c);
      const double out = static_cast<double>(C::outside(n.volume, child)), tol = C::tolerance(n.volume, child);
      EXPECT_LE(out, tol);
      if (tol > 0) worst = std::max(worst, out / tol);
    }
  }
  std::printf("[ worst miss %.2g of the tolerance ]\n", worst);
}

// 1500 leaves in a cube of side 40 (radii 0.2–1.2), then 6000 edits (a leaf
// removed and inserted again: a small move, or a jump anywhere): the
// structure, the containment, and 200 queries against brute force after
// every 1500 edits. Random data, so no leaf touches a query within rounding:
// the answers are equal. The queries test few nodes: under 10% of a brute
// force's tests on average (a query here meets about 1% of the leaves;
// measured 2.7% for boxes, 5.7% for spheres, which bound a group of leaves
// less tightly).
TYPED_TEST(Tree, QueriesEqualBruteForceThroughRandomEdits) {
  using C = TypeParam;
  using V = typename C::Policy;
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(0, 40), rad(0.2, 1.2), small(-0.3, 0.3), f(0, 1);
  DynamicTree<V> tree;
  const int n = 1500;
  std::vector<typename C::Volume> vol;
  std::vector<int> leaf;
  std::vector<Vec3> centre;
  std::vector<double> radius;
  for (int i = 0; i < n; ++i) {
    centre.emplace_back(u(g), u(g), u(g));
    radius.push_back(rad(g));
    vol.push_back(C::make(centre.back(), radius.back()));
    leaf.push_back(tree.insert(vol.back(), i));
  }
  ASSERT_EQ(tree.check(), "");
  std::int64_t tests = 0, brute = 0;
  for (int round = 0; round < 4; ++round) {
    for (int e = 0; e < 1500; ++e) {
      const auto i = static_cast<std::size_t>(g() % n);
      tree.remove(leaf[i]);
      centre[i] = f(g) < 0.8 ? Vec3(centre[i] + Vec3(small(g), small(g), small(g))) : Vec3(u(g), u(g), u(g));
      vol[i] = C::make(centre[i], radius[i]);
      leaf[i] = tree.insert(vol[i], static_cast<int>(i));
    }
    ASSERT_EQ(tree.check(), "") << "round " << round;
    ASSERT_EQ(tree.leaves(), n);
    expect_parents_hold_children<C>(tree);
    tree.take_volume_tests();
    for (int q = 0; q < 200; ++q) {
      const auto query = C::make(Vec3(u(g), u(g), u(g)), 2 * rad(g));
      std::vector<int> found, want;
      tree.query(query, [&](int item) { found.push_back(item); });
      for (int i = 0; i < n; ++i)
        if (V::overlap(vol[static_cast<std::size_t>(i)], query)) want.push_back(i);
      std::sort(found.begin(), found.end());
      EXPECT_EQ(found, want) << "round " << round << " query " << q;
      brute += n;
    }
    tests += tree.take_volume_tests();
  }
  EXPECT_LT(tests, brute / 10);
  std::printf("[ height %d for %d leaves; %.1f node tests per query ]\n", tree.height(), n,
              static_cast<double>(tests) / 800);
}

// The height, for 4096 leaves inserted at random and in order along a line
// (cost-driven insertion alone would hang each new leaf beside the last and
// grow a chain of height n; the rotations keep it logarithmic). A balanced
// tree has height 12; the bound 30 is 2.5× that.
TYPED_TEST(Tree, HeightStaysLogarithmic) {
  using C = TypeParam;
  std::mt19937_64 g(8);
  std::uniform_real_distribution<double> u(0, 100);
  for (const bool line : {false, true}) {
    DynamicTree<typename C::Policy> tree;
    for (int i = 0; i < 4096; ++i)
      tree.insert(C::make(line ? Vec3(0.5 * i, 0, 0) : Vec3(u(g), u(g), u(g)), 0.3), i);
    ASSERT_EQ(tree.check(), "");
    EXPECT_LE(tree.height(), 30) << (line ? "line" : "random");
    std::printf("[ %s: height %d ]\n", line ? "line" : "random", tree.height());
  }
}

// Removing every leaf empties the tree; inserting and removing again reuses
// the freed nodes (the node store does not grow).
TYPED_TEST(Tree, RemovingEverythingEmptiesItAndNodesAreReused) {
  using C = TypeParam;
  DynamicTree<typename C::Policy> tree;
  std::vector<int> leaf;
  for (int i = 0; i < 100; ++i) leaf.push_back(tree.insert(C::make(Vec3(i % 10, i / 10, 0), 0.4), i));
  const std::size_t size = tree.nodes().size();
  for (int cycle = 0; cycle < 3; ++cycle) {
    for (int i = 0; i < 100; ++i) tree.remove(leaf[static_cast<std::size_t>(i)]);
    EXPECT_EQ(tree.leaves(), 0);
    EXPECT_EQ(tree.root(), DynamicTree<typename C::Policy>::kNull);
    EXPECT_EQ(tree.check(), "");
    int found = 0;
    tree.query(C::make(Vec3(5, 5, 0), 100), [&](int) { ++found; });
    EXPECT_EQ(found, 0);
    for (int i = 0; i < 100; ++i) leaf[static_cast<std::size_t>(i)] = tree.insert(C::make(Vec3(i / 10, i % 10, 1), 0.4), i);
    EXPECT_EQ(tree.nodes().size(), size);
  }
}

}  // namespace
}  // namespace gacompare::core
