#pragma once
// The broadphase by dynamic trees: persistent pairs over
// fat volumes, two trees for the moving bodies (those on either side of a
// plane, so that their reinsertions run on two threads) and one for the
// static ones, over either volume policy:
//   AabbVolume           algebra-neutral boxes (core::Aabb) around each body's
//                        bounding sphere: the practical baseline;
//   SphereVolume<Ops>    the report's sphere trees (§4.2.2, fig. 13): leaves
//                        are the bodies' bounding spheres, parents enclosing
//                        spheres, in the backend's algebra (centre and radius;
//                        conformal dual spheres whose enclosing sphere, cost
//                        and overlap are inner products, cga/bounding_volume.hpp).
// §4.2.2 builds a sphere tree per body to approximate its shape; here the
// tree is over the scene's bodies, one sphere each, the use the report's
// broadphase needs (its §2.4.1 spheres, organised as §4.2.2 suggests).
//
// Each detection (update):
//   1. every body's tight volume (its bounding sphere, or the box around it) is
//      checked against the fat volume its leaf holds (the tight one grown by
//      kFatMargin of its radius, a box also stretched along the body's last
//      displacement: kLookAhead); only a body that left it is reinserted;
//   2. the pairs of reinserted bodies are dropped and found again by querying
//      the trees with their new fat volumes (a moving body: every tree; a
//      static one: the moving trees only, so two static bodies are never a
//      pair). A pair of two bodies that stayed is kept: their fat volumes have
//      not changed, so neither has their overlap. A still scene reinserts
//      nothing and queries nothing;
//   3. every kept pair gets the backend's exact sphere test
//      (Ops::balls_overlap on the tight spheres), and the survivors, sorted, are the
//      answer: the same pairs as sort and sweep's and all pairs' (tested).
// Why the answer is exact although tree volumes are rounded: a pair whose tight
// spheres pass Ops::balls_overlap has fat volumes overlapping by at least the two
// margins (kFatMargin of each radius), far more than the rounding of
// any merge, containment or overlap test (~1e-16 of the coordinates' squares
// over the radius; see core/collision/broadphase.hpp for the frame that keeps
// coordinates small), so no rounded test on the way down can lose it. The
// margin only adds kept pairs, which the exact test removes.
#include "core/collision/bounding_volume.hpp"
#include "core/collision/dynamic_tree.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <iterator>
#include <span>
#include <utility>
#include <vector>

namespace gacompare::core {

// How much larger than a body's bounding sphere its leaf is, relative to its
// radius. Larger: fewer reinsertions, more kept pairs to test. Box2D v3 uses
// 0.1 m for bodies of about a metre. The AABB tree's time falls with the
// margin up to about this one and then flattens, its kept pairs growing as
// fast as its reinsertions fall; a denser scene keeps more pairs per margin,
// so one margin for both trees (bench/broadphase_bench.cpp margin<M>_coherent_1000).
inline constexpr double kFatMargin = 0.4;

// How far ahead a reinserted box reaches: the body's displacement since the
// last update, this many times over (AabbVolume only; a sphere cannot be
// stretched one way). A body that left its box is usually on its way
// somewhere, and a box that reaches along its path holds it for several
// updates, as Box2D v2 (b2_aabbMultiplier) and Bullet's predicted boxes do.
// Only the kept pairs grow (the exact test removes them), never the pairs.
// On the 10,000-body box without a search (one run each, two threads): 0,
// 4, 8, 16 updates gave 740, 518, 407, 293 thousand reinsertions, 136, 140,
// 144, 152 million kept pairs, and 5.8, 5.2, 4.8, 4.6 s of broadphase.
inline constexpr double kLookAhead = 8;

// Moved bodies per block of tree queries on the run's threads: a query of a
// 10,000-body tree tests some hundred volumes, about a microsecond, so a
// block holds the ~100 µs a chunk needs (core/parallel.hpp).
inline constexpr std::size_t kGrainQuery = 128;

// Pairs (i, j) of n bodies into ascending order, by two stable counting
// sorts (on j, then on i): O(n + k) for k pairs, where a comparison sort took
// a third of the broadphase's time on the islands' sweeps (thousands of pairs
// per sub-step of a pile of bodies). Also the trees' fresh pairs and an
// island's own pairs (core/collision/collision_step.hpp).
inline void sort_pairs(std::vector<std::pair<int, int>>& pairs, std::size_t n) {
  if (pairs.size() < 64) return std::sort(pairs.begin(), pairs.end());
  std::vector<std::pair<int, int>> tmp(pairs.size());
  std::vector<std::size_t> start(n + 1);
  const auto pass = [&](auto key, const std::vector<std::pair<int, int>>& from, std::vector<std::pair<int, int>>& to) {
    std::fill(start.begin(), start.end(), 0);
    for (const auto& p : from) ++start[static_cast<std::size_t>(key(p)) + 1];
    for (std::size_t k = 1; k <= n; ++k) start[k] += start[k - 1];
    for (const auto& p : from) to[start[static_cast<std::size_t>(key(p))]++] = p;
  };
  pass([](const std::pair<int, int>& p) { return p.second; }, pairs, tmp);
  pass([](const std::pair<int, int>& p) { return p.first; }, tmp, pairs);
}

// What a sphere tree needs of a backend beyond the BoundingSphereOps: the node
// operations of traditional/bounding_volume.hpp and cga/bounding_volume.hpp.
template <class Ops>
concept SphereTreeOps = BoundingSphereOps<Ops> && requires(const typename Ops::Sphere& s, double t) {
  { Ops::enclosing(s, s) } -> std::convertible_to<typename Ops::Sphere>;
  { Ops::encloses(s, s) } -> std::convertible_to<bool>;
  { Ops::grown(s, t) } -> std::convertible_to<typename Ops::Sphere>;
  { Ops::radius_squared(s) } -> std::convertible_to<double>;
};

// Boxes around the bounding spheres; the cost is half the surface area.
struct AabbVolume {
  using Volume = Aabb;
  static constexpr bool grouping_free = true;  // a union of boxes is one box however grouped
  static Aabb merge(const Aabb& a, const Aabb& b) { return {a.min.cwiseMin(b.min), a.max.cwiseMax(b.max)}; }
  static double cost(const Aabb& a) {
    const Vec3 e = a.max - a.min;
    return e.x() * e.y() + e.y() * e.z() + e.z() * e.x();
  }
  static bool overlap(const Aabb& a, const Aabb& b) { return core::overlap(a, b); }
  static bool contains(const Aabb& outer, const Aabb& inner) {
    return (outer.min.array() <= inner.min.array()).all() && (inner.max.array() <= outer.max.array()).all();
  }
  template <class Sphere>
  static Aabb bound(const Vec3& centre, double radius, const Sphere&) {
    return {centre.array() - radius, centre.array() + radius};
  }
  static Aabb grown(const Aabb& a, double by) { return {a.min.array() - by, a.max.array() + by}; }
  // The box and the box moved by d: where the body is headed.
  static Aabb swept(const Aabb& a, const Vec3& d) { return {a.min.cwiseMin(a.min + d), a.max.cwiseMax(a.max + d)}; }
};

// The backend's spheres themselves; the cost is ρ².
template <SphereTreeOps Ops>
struct SphereVolume {
  using Volume = typename Ops::Sphere;
  static Volume merge(const Volume& a, const Volume& b) { return Ops::enclosing(a, b); }
  static double cost(const Volume& a) { return Ops::radius_squared(a); }
  static bool overlap(const Volume& a, const Volume& b) { return Ops::overlap(a, b); }
  static bool contains(const Volume& outer, const Volume& inner) { return Ops::encloses(outer, inner); }
  static const Volume& bound(const Vec3&, double, const Volume& sphere) { return sphere; }
  static Volume grown(const Volume& s, double by) { return Ops::grown(s, by); }
};

// One detection's bodies, in the broadphase's frame. With margins (how far
// each body can move in the step; empty for none), the grown spheres'
// overlaps are wanted too: the islands' links (core/collision/collision_step.hpp).
template <class Sphere>
struct BroadphaseBodies {
  std::span<const Vec3> centres;
  std::span<const double> radii;    // the bounding spheres'
  std::span<const double> margins;  // empty, or one per body
  std::span<const Sphere> spheres;  // Ops::sphere(centre, radius)
  std::span<const Sphere> grown;    // Ops::sphere(centre, radius + margin); = spheres without margins
  std::span<const double> grown_radii;  // radius + margin; = radii without margins
  std::span<const char> is_static;
};

// The work of one update, for the counters.
struct TreeWork {
  std::int64_t volume_tests = 0;  // tree nodes tested by the queries
  std::int64_t exact_tests = 0;   // Ops::balls_overlap calls on kept pairs
  std::int64_t reinserted = 0;    // leaves (re)inserted
  std::int64_t kept = 0;          // pairs kept after the update
};

template <class V, BoundingSphereOps Ops>
class TreeBroadphase {
 public:
  using Sphere = typename Ops::Sphere;
  explicit TreeBroadphase(double margin = kFatMargin, double look_ahead = kLookAhead)
      : margin_(margin), look_ahead_(look_ahead) {}

  // Forgets everything: the next update inserts every body afresh.
  void clear() {
    for (Tree& t : trees_) t.clear();
    leaf_.clear(), tree_.clear(), kept_.clear(), is_static_.clear(), last_.clear();
  }

  // Calls on_body(i) for every body whose fat volume, as the last update
  // left it, meets the sphere (centre in the frame, radius): a superset of
  // the bodies whose spheres then did. Reads the trees only (the caller's
  // stack), so queries on several threads may run at once.
  template <class F>
  void query(const Vec3& centre, double radius, std::vector<int>& stack, F&& on_body) const {
    const auto q = V::bound(centre, radius, Ops::sphere(centre, radius));
    for (const Tree& t : trees_) t.query(q, stack, on_body);
  }

  // Appends the pairs whose spheres overlap to `pairs` and, with margins, the
  // pairs whose grown spheres do to `candidates` (both i < j, sorted; every
  // pair is a candidate). A leaf bounds the grown sphere, so its fat volume
  // holds it while the body moves less than the fat margin less its growth.
  TreeWork update(const BroadphaseBodies<Sphere>& b, std::vector<std::pair<int, int>>& pairs,
                  std::vector<std::pair<int, int>>& candidates) {
    const std::size_t n = b.spheres.size();
    if (leaf_.size() != n) {
      clear();
      leaf_.assign(n, kNull);
      tree_.assign(n, 0);
      is_static_.assign(b.is_static.begin(), b.is_static.end());
      choose_plane(b);
    }
    // A body that became static or moving (it fell asleep or woke,
    // core/collision/sleep.hpp) leaves its tree and is inserted in another
    // below, its pairs found again like a moved body's.
    for (std::size_t i = 0; i < n; ++i) {
      if (is_static_[i] == b.is_static[i]) continue;
      if (leaf_[i] != kNull) trees_[tree_[i]].remove(leaf_[i]), leaf_[i] = kNull;
      is_static_[i] = b.is_static[i];
    }
    const bool growing = !b.margins.empty();
    TreeWork work;
    const auto tight = [&](std::size_t i) {
      return V::bound(b.centres[i], b.radii[i] + (growing ? b.margins[i] : 0.0), b.grown[i]);
    };
    // Which bodies left their fat volumes, on the run's threads: a body's test
    // reads only its own leaf, which no other body's reinsertion changes (a
    // leaf is never moved in place), so testing every body before any is
    // reinserted finds the bodies a test-then-reinsert pass would.
    moved_.assign(n, 0);
    for_each_index(n, [&](std::size_t i) {
      moved_[i] = leaf_[i] == kNull || !V::contains(trees_[tree_[i]].volume(leaf_[i]), tight(i));
    }, kGrainBody);
    if (last_.size() != n) last_.assign(b.centres.begin(), b.centres.end());
    // Each tree's removals and insertions, in body order, then the three
    // trees on the run's threads: a tree's own work touches only that tree
    // and the leaves of the bodies inserted in it. Which tree holds a body
    // changes the trees' shapes, never the pairs (a set).
    for (std::size_t t = 0; t < trees_.size(); ++t) removals_[t].clear(), inserts_[t].clear();
    for (std::size_t i = 0; i < n; ++i) {
      if (!moved_[i]) continue;
      if (leaf_[i] != kNull) removals_[tree_[i]].push_back(leaf_[i]);
      tree_[i] = static_cast<char>(is_static_[i] ? kStaticTree : b.centres[i][axis_] < plane_ ? 0 : 1);
      inserts_[tree_[i]].push_back(static_cast<int>(i));
      ++work.reinserted;
    }
    for_each_index(trees_.size(), [&](std::size_t t) {
      for (const int leaf : removals_[t]) trees_[t].remove(leaf);
      for (const int body : inserts_[t]) {
        const auto i = static_cast<std::size_t>(body);
        auto fat = V::grown(tight(i), margin_ * b.radii[i]);
        if constexpr (requires { V::swept(fat, Vec3()); }) fat = V::swept(fat, look_ahead_ * (b.centres[i] - last_[i]));
        leaf_[i] = trees_[t].insert(fat, body);
      }
    }, 1);
    const bool any = work.reinserted > 0;
    std::copy(b.centres.begin(), b.centres.end(), last_.begin());
    if (any) find_pairs_of_moved();
    work.kept = static_cast<std::int64_t>(kept_.size());
    // The kept pairs' exact tests on the run's threads, each pair's verdict
    // in its own slot (1: a candidate, 2: a pair), gathered in order after.
    verdict_.resize(kept_.size());
    for_each_index(kept_.size(), [&](std::size_t k) {
      const auto ui = static_cast<std::size_t>(kept_[k].first), uj = static_cast<std::size_t>(kept_[k].second);
      char v = 0;
      if (growing) {
        if (!Ops::balls_overlap(b.grown[ui], b.grown_radii[ui], b.grown[uj], b.grown_radii[uj])) return void(verdict_[k] = 0);
        v = 1;
      }
      if (Ops::balls_overlap(b.spheres[ui], b.radii[ui], b.spheres[uj], b.radii[uj])) v |= 2;
      verdict_[k] = v;
    }, kGrainLight);
    const std::size_t had = candidates.size();
    const auto pair = [&](std::size_t k) { return kept_[k]; };
    append_picked(candidates, kept_.size(), [&](std::size_t k) { return (verdict_[k] & 1) != 0; }, pair, kGrainLight);
    append_picked(pairs, kept_.size(), [&](std::size_t k) { return (verdict_[k] & 2) != 0; }, pair, kGrainLight);
    work.exact_tests = static_cast<std::int64_t>(kept_.size() + (candidates.size() - had));  // every kept pair grown, the candidates tight
    for (const Tree& t : trees_) work.volume_tests += t.take_volume_tests();
    return work;
  }

 private:
  using Tree = DynamicTree<V>;
  using Pair = std::pair<int, int>;
  static constexpr int kNull = Tree::kNull;
  double margin_;      // relative to each body's radius
  double look_ahead_;  // kLookAhead
  // The moving bodies' two trees (0: below the plane along axis_, 1: above
  // it, by a body's centre when it is inserted) and the static bodies' one.
  static constexpr std::size_t kStaticTree = 2;
  std::array<Tree, 3> trees_;
  int axis_ = 0;
  double plane_ = 0;
  std::array<std::vector<int>, 3> removals_, inserts_;  // update's, per tree
  std::vector<char> tree_;   // body → the tree its leaf is in
  std::vector<int> leaf_;    // body → its leaf in its tree
  std::vector<Pair> kept_;   // the pairs whose fat volumes overlap, i < j, sorted
  std::vector<char> is_static_;
  std::vector<char> moved_;  // this update's reinserted bodies
  std::vector<Vec3> last_;   // each centre at the last update
  std::vector<Pair> stayed_, fresh_, merged_;  // find_pairs_of_moved's lists
  std::vector<char> verdict_;  // the kept pairs' exact tests (update)
  // The moved bodies' queries (find_pairs_of_moved), a block of them per item.
  std::vector<int> movers_;
  struct Block {
    std::vector<Pair> found;
    std::vector<int> stack;
    std::int64_t tests = 0;
  };
  std::vector<Block> blocks_;

  // The moving trees' plane, when the trees are built afresh: across the
  // axis along which the moving bodies' centres spread most, at their mean,
  // so that each tree holds about half of them (and of their reinsertions,
  // where the bodies move alike). A body far from it is found in the other
  // tree by a test of that tree's root.
  void choose_plane(const BroadphaseBodies<Sphere>& b) {
    Vec3 lo = Vec3::Constant(INFINITY), hi = Vec3::Constant(-INFINITY), sum = Vec3::Zero();
    std::size_t moving = 0;
    for (std::size_t i = 0; i < b.centres.size(); ++i) {
      if (b.is_static[i]) continue;
      lo = lo.cwiseMin(b.centres[i]), hi = hi.cwiseMax(b.centres[i]), sum += b.centres[i], ++moving;
    }
    axis_ = 0, plane_ = 0;
    if (moving == 0) return;
    (hi - lo).maxCoeff(&axis_);
    plane_ = sum[axis_] / static_cast<double>(moving);
  }

  // The kept pairs of two bodies that stayed are still right; every pair of a
  // moved body is dropped and found again by querying the trees with its new
  // fat volume. A pair of two moved bodies may be found from either side (a
  // query descends by rounded tests, so not necessarily from both); sorting
  // the fresh pairs and dropping repeats keeps it once. Both lists are
  // sorted and disjoint (every fresh pair has a moved body, no kept one
  // does), so a merge gives the sorted whole.
  // The queries only read the trees: they run on the run's threads, a block
  // of moved bodies each, every block with its own stack and list. The
  // answer is a sorted set, so it does not depend on how the bodies were
  // blocked or which thread ran a block.
  void find_pairs_of_moved() {
    stayed_.clear();
    append_picked(
        stayed_, kept_.size(),
        [&](std::size_t k) {
          return !moved_[static_cast<std::size_t>(kept_[k].first)] && !moved_[static_cast<std::size_t>(kept_[k].second)];
        },
        [&](std::size_t k) { return kept_[k]; }, kGrainLight);
    movers_.clear();
    for (std::size_t i = 0; i < leaf_.size(); ++i)
      if (moved_[i]) movers_.push_back(static_cast<int>(i));
    const std::size_t m = movers_.size(), grain = grain_of(kGrainQuery);
    const std::size_t per = runs_parallel(m, grain) ? grain : std::max<std::size_t>(m, 1);
    blocks_.resize((m + per - 1) / per);
    for_each_index(blocks_.size(), [&](std::size_t k) {
      Block& block = blocks_[k];
      block.found.clear();
      block.tests = 0;
      for (std::size_t q = k * per; q < std::min(m, (k + 1) * per); ++q) {
        const int me = movers_[q];
        const auto i = static_cast<std::size_t>(me);
        const auto add = [&](int j) {
          if (j != me) block.found.emplace_back(std::min(me, j), std::max(me, j));
        };
        const auto& fat = trees_[tree_[i]].volume(leaf_[i]);
        block.tests += trees_[0].query(fat, block.stack, add) + trees_[1].query(fat, block.stack, add);
        if (!is_static_[i]) block.tests += trees_[kStaticTree].query(fat, block.stack, add);
      }
    }, 1);
    fresh_.clear();
    std::int64_t tests = 0;
    for (const Block& block : blocks_) {
      fresh_.insert(fresh_.end(), block.found.begin(), block.found.end());
      tests += block.tests;
    }
    trees_[0].count_volume_tests(tests);  // the trees' tests are summed by the caller
    sort_pairs(fresh_, leaf_.size());
    fresh_.erase(std::unique(fresh_.begin(), fresh_.end()), fresh_.end());
    // On the run's threads: on one, through a back inserter, the merge of the
    // 10,000-body box's some 143,000 pairs was 1.4 % of its run's own thread.
    merge_sorted(stayed_, fresh_, merged_, kGrainLight);
    kept_.swap(merged_);
  }
};

}  // namespace gacompare::core
