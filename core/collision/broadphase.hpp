#pragma once
// Broadphase (stage `broadphase`): which pairs of many bodies have
// overlapping bounding spheres, without testing all n(n−1)/2 pairs.
//
// §2.4.1 uses bounding volumes "to eliminate pairs of bodies" and points to
// "fast search algorithms ... to efficiently isolate possible collisions" (fn
// 23) without giving one; the report's simulator tests every pair. Here: sort
// and sweep along one axis (Baraff 1992; Cohen et al., I-COLLIDE 1995), then
// the backend's own sphere test (SphereOps::balls_overlap: the distance test,
// or one conformal inner product, cga/bounding_volume.hpp) on each pair the
// sweep leaves.
//
//   1. Each sphere's extent along the axis, [c − ρ − pad, c + ρ + pad], from
//      Ops::centre and Ops::radius (once per sphere: O(n)).
//   2. Sort the intervals by their lower end: O(n log n).
//   3. Sweep: each interval is paired with those after it whose lower end is
//      ≤ its upper end. These are the candidates; every one gets Ops::balls_overlap.
//      O(n + k), k the number of candidates.
//   4. The overlapping pairs, (i, j) with i < j, sorted.
//
// The axis is the one along which the centres' variance is largest (Ericson,
// Real-Time Collision Detection, §7.5.2): the sweep's cost is the number of
// interval overlaps along the axis, and spreading the centres out shortens that
// list the most. A degenerate scene stacked along one axis (a column of bodies)
// is swept along the column instead of across it.
//
// pad = kSweepPad · (|c_axis| + ρ): the interval's ends are rounded at the size
// of the coordinates, and the conformal overlap test decides touching pairs by
// its own rounding; padding by the collision code's touching band (1e-9 of the
// scale, core/collision/collision.hpp) guarantees the sweep never drops a pair that
// Ops::balls_overlap would accept. It only adds candidates within the band.
#include "core/collision/bounding_volume.hpp"
#include "core/model/scene.hpp"
#include "core/collision/tree_broadphase.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace gacompare::core {

inline constexpr double kSweepPad = 1e-9;

struct BroadphaseCounters {
  std::int64_t candidates = 0;     // volume tests: pairs left by the sweep; tree nodes tested and kept pairs
  std::int64_t overlap_tests = 0;  // Ops::balls_overlap calls on two bodies' spheres (the sweep: = candidates)
  std::int64_t pairs = 0;          // overlapping pairs found
  std::int64_t tree_updates = 0;   // leaves inserted (a body left its fat volume, or a build)
  std::int64_t pairs_kept = 0;     // persistent pairs after the update (fat volumes overlap)
};
struct BroadphaseResult {
  std::vector<std::pair<int, int>> pairs;  // i < j, sorted
  // With margins (Broadphase::find): the pairs whose grown spheres overlap,
  // i < j, sorted, a superset of `pairs`.
  std::vector<std::pair<int, int>> candidates;
  BroadphaseCounters counters;
  int axis = 0;  // 0, 1, 2: x, y, z
};

// Index of the coordinate with the largest variance of the points.
inline int axis_of_largest_spread(std::span<const Vec3> centres) {
  if (centres.empty()) return 0;
  Vec3 mean = Vec3::Zero();
  for (const Vec3& c : centres) mean += c;
  mean /= static_cast<double>(centres.size());
  Vec3 var = Vec3::Zero();
  for (const Vec3& c : centres) var += (c - mean).cwiseAbs2();
  int axis = 0;
  var.maxCoeff(&axis);
  return axis;
}

// `given`: the radii the spheres were built with (Ops::sphere), or empty to
// read them off the spheres.
template <BoundingSphereOps Ops>
BroadphaseResult sort_and_sweep(std::span<const typename Ops::Sphere> spheres, std::span<const double> given = {}) {
  const std::size_t n = spheres.size();
  BroadphaseResult out;
  std::vector<Vec3> centres(n);
  std::vector<double> radii(n);
  for (std::size_t i = 0; i < n; ++i) {
    centres[i] = Ops::centre(spheres[i]);
    radii[i] = given.empty() ? Ops::radius(spheres[i]) : given[i];
  }
  out.axis = axis_of_largest_spread(centres);

  struct Interval {
    double lo, hi;
    int body;
  };
  std::vector<Interval> iv(n);
  for (std::size_t i = 0; i < n; ++i) {
    const double c = centres[i][out.axis], r = radii[i];
    const double ext = r + kSweepPad * (std::abs(c) + std::abs(r));
    iv[i] = {c - ext, c + ext, static_cast<int>(i)};
  }
  std::sort(iv.begin(), iv.end(),
            [](const Interval& a, const Interval& b) { return a.lo < b.lo || (a.lo == b.lo && a.body < b.body); });

  for (std::size_t a = 0; a < n; ++a) {
    const double hi = iv[a].hi;
    for (std::size_t b = a + 1; b < n && iv[b].lo <= hi; ++b) {
      ++out.counters.candidates;
      ++out.counters.overlap_tests;
      const int i = iv[a].body, j = iv[b].body;
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      if (Ops::balls_overlap(spheres[ui], radii[ui], spheres[uj], radii[uj]))
        out.pairs.emplace_back(std::min(i, j), std::max(i, j));
    }
  }
  sort_pairs(out.pairs, n);
  out.counters.pairs = static_cast<std::int64_t>(out.pairs.size());
  return out;
}

// The collision pipeline's broadphase: one call per detection,
// whichever method the scene names (`broadphase`: "sweep", "aabb_tree",
// "sphere_tree"; core/model/scene.hpp), the same pairs from each: those whose
// bounding spheres pass Ops::balls_overlap and, given margins (how far each body can
// move in the step), the candidates whose spheres grown by them do. Two static
// bodies are never a pair.
//
// The frame: a conformal sphere stores ½|c|² beside c, so
// world coordinates 1e5 m from the origin cost its overlap test 10 digits;
// every method works on spheres about a frame origin near the bodies. The trees
// persist between detections, so the frame cannot follow the bodies' mean at
// every detection as it once did: it is fixed at the first detection (their
// mean) and moved to the mean again, with a rebuild of the trees, only when the
// mean has drifted further from it than the bodies' extent about the mean (the
// largest |c − mean| + ρ). Every coordinate then stays within twice the
// extent. Overlap does not depend on the frame, so the pairs do not either.
template <SphereTreeOps Ops>
class Broadphase {
 public:
  using Sphere = typename Ops::Sphere;
  // margin: the trees' fat margin relative to each radius (the benchmarks vary
  // it); look_ahead: the AABB tree's reach along each motion (kLookAhead).
  explicit Broadphase(BroadphaseMethod method = Collisions{}.broadphase, double margin = kFatMargin,
                      double look_ahead = kLookAhead)
      : method_(method), aabb_(margin, look_ahead), spheres_tree_(margin) {}

  // The bodies' bounding spheres by centre (world coordinates) and radius;
  // margins empty, or one per body (≥ 0).
  BroadphaseResult find(std::span<const Vec3> centres, std::span<const double> radii, std::span<const char> is_static,
                        std::span<const double> margins = {}) {
    place(centres, radii, margins);
    BroadphaseResult out;
    const BroadphaseBodies<Sphere> b{local_,  radii, margins, spheres_, margins.empty() ? spheres_ : grown_,
                                     margins.empty() ? radii : std::span<const double>(grown_radii_), is_static};
    if (method_ == BroadphaseMethod::sweep) {
      const auto both_static = [&](const std::pair<int, int>& p) {
        return is_static[static_cast<std::size_t>(p.first)] && is_static[static_cast<std::size_t>(p.second)];
      };
      BroadphaseResult swept = sort_and_sweep<Ops>(b.grown, b.grown_radii);
      std::erase_if(swept.pairs, both_static);
      out.counters = swept.counters;
      if (margins.empty()) {
        out.pairs = std::move(swept.pairs);
      } else {
        out.candidates = std::move(swept.pairs);
        for (const auto& [i, j] : out.candidates) {
          ++out.counters.candidates, ++out.counters.overlap_tests;
          const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
          if (Ops::balls_overlap(spheres_[ui], radii[ui], spheres_[uj], radii[uj])) out.pairs.emplace_back(i, j);
        }
      }
    } else {
      const TreeWork w = method_ == BroadphaseMethod::aabb_tree ? aabb_.update(b, out.pairs, out.candidates)
                                                                : spheres_tree_.update(b, out.pairs, out.candidates);
      out.counters.candidates = w.volume_tests + w.exact_tests;
      out.counters.overlap_tests = w.exact_tests;
      out.counters.tree_updates = w.reinserted;
      out.counters.pairs_kept = w.kept;
    }
    out.counters.pairs = static_cast<std::int64_t>(out.pairs.size());
    return out;
  }

  // Calls on_body(i) for every body whose bounding sphere at the last find
  // may meet the sphere (world centre, radius), and returns true; or returns
  // false, calling nothing, for the sweep, which keeps no structure to ask.
  template <class F>
  bool query(const Vec3& centre, double radius, std::vector<int>& stack, F&& on_body) const {
    if (method_ == BroadphaseMethod::sweep || frames_ == 0) return false;
    if (method_ == BroadphaseMethod::aabb_tree) aabb_.query(centre - frame_, radius, stack, on_body);
    else spheres_tree_.query(centre - frame_, radius, stack, on_body);
    return true;
  }

  BroadphaseMethod method() const { return method_; }
  const Vec3& frame() const { return frame_; }
  int frames() const { return frames_; }  // how often the frame was set (1 + re-centrings)

 private:
  BroadphaseMethod method_;
  Vec3 frame_ = Vec3::Zero();
  int frames_ = 0;
  std::vector<Vec3> local_;  // centres in the frame
  std::vector<Sphere> spheres_, grown_;
  std::vector<double> grown_radii_;  // radius + margin: what grown_ was built with
  TreeBroadphase<AabbVolume, Ops> aabb_;
  TreeBroadphase<SphereVolume<Ops>, Ops> spheres_tree_;

  // The bodies' spheres in the frame, on the run's threads: on one, a
  // 10,000-body world's were half a percent of its run's own thread.
  void place(std::span<const Vec3> centres, std::span<const double> radii, std::span<const double> margins) {
    const std::size_t n = centres.size();
    Vec3 mean = Vec3::Zero();
    for (const Vec3& c : centres) mean += c;
    if (n > 0) mean /= static_cast<double>(n);
    // Each block's largest, then theirs: a maximum is exact in any order.
    std::vector<double> most(blocks_of(n, kGrainBody), 0.0);
    for_each_block(n, kGrainBody, [&](std::size_t b, std::size_t begin, std::size_t end) {
      for (std::size_t i = begin; i < end; ++i) most[b] = std::max(most[b], (centres[i] - mean).norm() + radii[i]);
    });
    double extent = 0;
    for (const double e : most) extent = std::max(extent, e);
    if (frames_ == 0 || n != local_.size() || (mean - frame_).norm() > extent) {
      frame_ = mean;
      ++frames_;
      aabb_.clear();
      spheres_tree_.clear();
    }
    local_.resize(n);
    spheres_.resize(n);
    grown_.resize(margins.empty() ? 0 : n);
    grown_radii_.resize(margins.empty() ? 0 : n);
    for_each_index(n, [&](std::size_t i) {
      local_[i] = centres[i] - frame_;
      spheres_[i] = Ops::sphere(local_[i], radii[i]);
      if (margins.empty()) return;
      grown_radii_[i] = radii[i] + margins[i];
      grown_[i] = Ops::sphere(local_[i], grown_radii_[i]);
    }, kGrainBody);
  }
};

}  // namespace gacompare::core
