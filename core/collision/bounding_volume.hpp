#pragma once
// Bounding volumes (§2.4.1 of the report): the backend-neutral parts.
//
//   Aabb                      the axis-aligned bounding cuboid (§2.4.1 "Bounding
//                             Cuboid", fn 23: overlap by 6 comparisons). Neutral:
//                             min/max corners are the same in both backends.
//   exhaustive_sphere<Ops>    the report's exhaustive search (§2.4.1), kept as a
//                             baseline and corrected (see there)
//   welzl_sphere<Ops>         Welzl's algorithm with move-to-front (§2.4.1 names it
//                             and implements only the exhaustive search)
//
// Both sphere algorithms are templates over a SphereOps policy, which supplies
// the backend's sphere and point types and the constructions the report lists:
// traditional/bounding_volume.hpp (centre and radius, vectors) and
// cga/bounding_volume.hpp (dual spheres C − ½ρ²n built from outer products of
// conformal points). The search logic is written once, here, so a timing
// difference between the two instantiations is the algebra's alone.
//
// Coordinates. Both algorithms move the points to a local origin o (the centre
// of their bounding box) before building anything and move the answer back at
// the end: the conformal embedding carries ½|x|² next to x and loses
// log10(|x|²/ℓ²) digits far from the origin (cga/geometry/local_origin.hpp); in
// the local frame |x| ≤ L/2 (L the box diagonal) for both backends alike.
//
// Containment tolerance. A point x counts as contained in a sphere when
//   side(s, x) = ½(|x − c|² − ρ²) ≤ tol,   tol = kBoundTol · L²,
// the report's inside measure (§2.4.1, "inside < 0", cga/geometry/inside.hpp)
// compared with the square of the set's scale. Why a tolerance at all: the
// minimal sphere has 2 to 4 points on its surface, and for the sets the
// collision code bounds (boxes, cubes, regular solids) all vertices lie on it;
// side() of a point exactly on the surface is rounding noise of either sign, and
// a point rejected by noise would make Welzl grow a degenerate support set (four
// cocircular cube vertices). Why L²: in the local frame side() is computed from
// coordinates of size ≤ L (and, in the conformal form, their squares ≤ L²), so
// its rounding is a few dozen ulps of L², ~1e-14 · L²; kBoundTol = 1e-10 is
// 10⁴ times above that. What it costs: a point may lie outside the returned
// sphere by at most tol/ρ ≤ 2√3 · kBoundTol · L ≈ 3.5e-10 · L (ρ ≥ L/(2√3)
// since some pair of the points is at least L/√3 apart), below the collision
// code's touching band (1e-9 of the pair's scale, core/collision/collision.hpp). A caller
// that needs strict containment pads the radius by that much.
#include "core/error.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <concepts>
#include <cstdint>
#include <limits>
#include <optional>
#include <random>
#include <span>
#include <vector>

namespace gacompare::core {

using Vec3 = Eigen::Vector3d;

// ---- axis-aligned bounding box (§2.4.1 "Bounding Cuboid") -------------------------

// An empty point set gives the empty box (min = +∞, max = −∞), which overlaps
// nothing.
struct Aabb {
  Vec3 min = Vec3::Constant(std::numeric_limits<double>::infinity());
  Vec3 max = Vec3::Constant(-std::numeric_limits<double>::infinity());
};
inline Aabb aabb_of(std::span<const Vec3> points) {
  Aabb box;
  for (const Vec3& p : points) {
    box.min = box.min.cwiseMin(p);
    box.max = box.max.cwiseMax(p);
  }
  return box;
}
// Fn 23's 6 comparisons; touching boxes overlap (closed intervals).
inline bool overlap(const Aabb& a, const Aabb& b) {
  return a.min.x() <= b.max.x() && b.min.x() <= a.max.x() && a.min.y() <= b.max.y() && b.min.y() <= a.max.y() &&
         a.min.z() <= b.max.z() && b.min.z() <= a.max.z();
}

// ---- the sphere policy ---------------------------------------------------------------

// What a backend supplies (traditional::SphereOps, cga::SphereOps). Points are
// converted into the backend's form once (Ops::point: the vector itself, or the
// conformal point up(x)), as a backend would store them, not once per use.
//   sphere_2(a, b)        smallest sphere through 2 points (centre midway)
//   sphere_3(a, b, c)     smallest sphere through 3 points (the circumcircle's);
//                         nullopt when collinear or coincident
//   sphere_4(a, b, c, d)  the circumsphere; nullopt when coplanar
//   contains(s, x, tol)   side(s, x) = ½(|x − c|² − ρ²) ≤ tol (tol in length²)
//   overlap(s1, s2)       the closed balls share a point (touching counts)
template <class Ops>
concept BoundingSphereOps = requires(const typename Ops::Sphere& s, const typename Ops::Point& p, const Vec3& x,
                                     double t) {
  { Ops::point(x) } -> std::convertible_to<typename Ops::Point>;
  { Ops::sphere(x, t) } -> std::convertible_to<typename Ops::Sphere>;
  { Ops::sphere_2(p, p) } -> std::convertible_to<typename Ops::Sphere>;
  { Ops::sphere_3(p, p, p) } -> std::convertible_to<std::optional<typename Ops::Sphere>>;
  { Ops::sphere_4(p, p, p, p) } -> std::convertible_to<std::optional<typename Ops::Sphere>>;
  { Ops::contains(s, p, t) } -> std::convertible_to<bool>;
  { Ops::overlap(s, s) } -> std::convertible_to<bool>;
  // overlap of spheres built by sphere(c, ρ), their radii given: what the
  // broadphase asks (it holds the radii), at the cost of the cheapest form.
  { Ops::balls_overlap(s, t, s, t) } -> std::convertible_to<bool>;
  { Ops::centre(s) } -> std::convertible_to<Vec3>;
  { Ops::radius(s) } -> std::convertible_to<double>;
};

inline constexpr double kBoundTol = 1e-10;  // containment tolerance, relative to L² (see the top)

// The work done, for the benchmarks and the report: spheres built (every
// sphere_2/3/4 call, degenerate ones included) and containment tests.
struct BoundingCounters {
  std::int64_t spheres = 0;
  std::int64_t containment_tests = 0;
};
template <class Sphere>
struct BoundingSphere {
  Sphere sphere;
  BoundingCounters counters;
};

namespace detail {

// The local frame: origin at the centre of the bounding box, L its diagonal.
struct LocalFrame {
  Vec3 origin = Vec3::Zero();
  double scale = 0;
  double tol = 0;  // kBoundTol · L², in side() units (length²)
};
inline LocalFrame local_frame(std::span<const Vec3> points) {
  if (points.empty()) throw run_error("bounding sphere: no points");
  const Aabb box = aabb_of(points);
  const double L = (box.max - box.min).norm();
  return {0.5 * (box.min + box.max), L, kBoundTol * L * L};
}
template <BoundingSphereOps Ops>
std::vector<typename Ops::Point> local_points(std::span<const Vec3> points, const LocalFrame& f) {
  std::vector<typename Ops::Point> out;
  out.reserve(points.size());
  for (const Vec3& p : points) out.push_back(Ops::point(p - f.origin));
  return out;
}
// Back to the caller's frame: the same sphere about centre + o.
template <BoundingSphereOps Ops>
typename Ops::Sphere to_world(const typename Ops::Sphere& s, const LocalFrame& f) {
  return Ops::sphere(Ops::centre(s) + f.origin, Ops::radius(s));
}

// The smallest sphere through some of k ≤ 4 points (pairs, then, for k = 4,
// triples) that contains all k. Welzl's support sets are affinely independent in
// exact arithmetic; rounding can hand it 3 collinear or 4 coplanar points (four
// cocircular box vertices, three collinear ones), for which sphere_3/sphere_4
// have no answer. Then the right sphere is this one: for collinear points the
// 2-point sphere of the extremes, for cocircular ones the sphere of their
// circumcircle, for coplanar ones the planar minimum. Last resort (no candidate
// contains the others, which exact arithmetic rules out): the widest pair.
template <BoundingSphereOps Ops>
typename Ops::Sphere degenerate_support(const typename Ops::Point* p, int k, double tol, BoundingCounters& c) {
  std::optional<typename Ops::Sphere> best;
  double best_r = 0;
  const auto consider = [&](const typename Ops::Sphere& s) {
    const double r = Ops::radius(s);
    if (best && r >= best_r) return;
    for (int i = 0; i < k; ++i) {
      ++c.containment_tests;
      if (!Ops::contains(s, p[i], tol)) return;
    }
    best = s;
    best_r = r;
  };
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j) {
      ++c.spheres;
      consider(Ops::sphere_2(p[i], p[j]));
    }
  if (k == 4)
    for (int i = 0; i < 4; ++i) {  // the triple without point i
      const int a = i == 0 ? 1 : 0, b = i <= 1 ? 2 : 1, d = i == 3 ? 2 : 3;
      ++c.spheres;
      const auto s = Ops::sphere_3(p[a], p[b], p[d]);
      if (s) consider(*s);
    }
  if (best) return *best;
  typename Ops::Sphere widest = Ops::sphere_2(p[0], p[1]);
  for (int i = 0; i < k; ++i)
    for (int j = i + 1; j < k; ++j) {
      ++c.spheres;
      typename Ops::Sphere s = Ops::sphere_2(p[i], p[j]);
      if (Ops::radius(s) > Ops::radius(widest)) widest = s;
    }
  return widest;
}

}  // namespace detail

// ---- the report's exhaustive search (§2.4.1) -------------------------------------------

// §2.4.1: "All spheres in a given class are evaluated and the smallest bounding
// sphere is selected": every 2-point sphere; if none contains every point, every
// 3-point sphere (the circumcircle's, fig. 6b) and every 4-point sphere (fig.
// 6c); the smallest that contains all. O(n⁵): C(n,4) spheres, each checked
// against n points; fine for the ≤ 16 vertices it is used on (16 vertices: 1820
// four-point spheres), a baseline for welzl_sphere.
//
// Corrected: the report stops at the first class in which some sphere contains
// all points. That is right for class 2 (a sphere through a and b has radius
// ≥ |a − b|/2, so a 2-point sphere containing all is the minimum) but wrong for
// class 3: three nearly collinear points on the hull have a huge circumsphere
// that can contain every point while the minimum is a 4-point sphere (the
// collision tests build such a set). So classes 3 and 4 are both searched and
// the smaller wins. A sphere no smaller than the best so far is not tested for
// containment (that skips most of class 4).
template <BoundingSphereOps Ops>
BoundingSphere<typename Ops::Sphere> exhaustive_sphere(std::span<const Vec3> points) {
  using Sphere = typename Ops::Sphere;
  const detail::LocalFrame f = detail::local_frame(points);
  const std::vector<typename Ops::Point> p = detail::local_points<Ops>(points, f);
  const std::size_t n = p.size();
  BoundingCounters c;
  std::optional<Sphere> best;
  double best_r = 0;
  const auto consider = [&](const Sphere& s) {
    const double r = Ops::radius(s);
    if (best && r >= best_r) return;
    for (const auto& x : p) {
      ++c.containment_tests;
      if (!Ops::contains(s, x, f.tol)) return;
    }
    best = s;
    best_r = r;
  };
  for (std::size_t i = 0; i < n; ++i)
    for (std::size_t j = i; j < n; ++j) {  // j = i: a single point is its own sphere
      if (j == i && n > 1) continue;
      ++c.spheres;
      consider(Ops::sphere_2(p[i], p[j]));
    }
  if (!best) {
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        for (std::size_t k = j + 1; k < n; ++k) {
          ++c.spheres;
          const std::optional<Sphere> s = Ops::sphere_3(p[i], p[j], p[k]);
          if (s) consider(*s);
        }
    for (std::size_t i = 0; i < n; ++i)
      for (std::size_t j = i + 1; j < n; ++j)
        for (std::size_t k = j + 1; k < n; ++k)
          for (std::size_t l = k + 1; l < n; ++l) {
            ++c.spheres;
            const std::optional<Sphere> s = Ops::sphere_4(p[i], p[j], p[k], p[l]);
            if (s) consider(*s);
          }
  }
  // Cannot happen: the minimal sphere is one of the candidates (its support of
  // 2 to 4 points is affinely independent) and contains every point.
  if (!best) throw run_error("exhaustive_sphere: no candidate sphere contains all points");
  return {detail::to_world<Ops>(*best, f), c};
}

// ---- Welzl's algorithm (§2.4.1, [13]) -----------------------------------------------------

// §2.4.1 names Welzl's algorithm as the fastest in common use and keeps the
// exhaustive search instead ("there do not appear to be any significant
// benefits to be had from the use of CGA"); the constructions it needs are the
// report's three classes of sphere, so both backends get it here.
//
// The form is Gärtner's move-to-front miniball ("Fast and robust smallest
// enclosing balls", ESA 1999), the heuristic the report describes ("points
// furthest from a previously checked sphere are likely to lie outside any new
// sphere formed"): mtf(end, B) builds the sphere of the support set B, tests
// the points before `end` in list order, and for each one outside recurses with
// it added to B and then moves it to the front of the list. |B| ≤ 4 bounds the
// recursion at 4 levels of support (5 calls deep); every call at |B| = 4 returns
// at once. The list is shuffled first, which gives the expected O(n) work
// regardless of the input's order: with a std::mt19937_64 seeded by `seed`, or
// with the caller's generator (seeding a Mersenne twister, 312 words, costs more
// than bounding a small hull: a simulation keeps one generator).
//
// Degenerate support sets (3 collinear, 4 coplanar points: see
// detail::degenerate_support) get the smallest sphere through some of them that
// contains them all, instead of no sphere.
template <BoundingSphereOps Ops>
BoundingSphere<typename Ops::Sphere> welzl_sphere(std::span<const Vec3> points, std::mt19937_64& rng) {
  using Point = typename Ops::Point;
  using Sphere = typename Ops::Sphere;
  const detail::LocalFrame f = detail::local_frame(points);
  std::vector<Point> list = detail::local_points<Ops>(points, f);
  std::shuffle(list.begin(), list.end(), rng);

  struct State {
    std::vector<Point>& list;
    double tol;
    std::array<Point, 4> support{};
    int ns = 0;
    Sphere ball{};
    bool empty = true;  // B = ∅: the empty ball contains nothing
    BoundingCounters c;

    void make_ball() {
      empty = ns == 0;
      if (ns == 0) return;
      ++c.spheres;
      if (ns == 1) {
        ball = Ops::sphere_2(support[0], support[0]);
      } else if (ns == 2) {
        ball = Ops::sphere_2(support[0], support[1]);
      } else {
        const std::optional<Sphere> s = ns == 3 ? Ops::sphere_3(support[0], support[1], support[2])
                                                : Ops::sphere_4(support[0], support[1], support[2], support[3]);
        ball = s ? *s : detail::degenerate_support<Ops>(support.data(), ns, tol, c);
      }
    }
    void mtf(std::size_t end) {
      make_ball();
      if (ns == 4) return;
      for (std::size_t i = 0; i < end; ++i) {
        ++c.containment_tests;
        if (!empty && Ops::contains(ball, list[i], tol)) continue;
        support[ns++] = list[i];
        mtf(i);
        --ns;
        // Move to front: positions 0..i−1 shift by one, so every caller's `end`
        // (> i) and the next point to test (i + 1) are unaffected.
        std::rotate(list.begin(), list.begin() + static_cast<std::ptrdiff_t>(i),
                    list.begin() + static_cast<std::ptrdiff_t>(i) + 1);
      }
    }
  };
  State st{list, f.tol, {}, 0, {}, true, {}};
  st.mtf(list.size());
  return {detail::to_world<Ops>(st.ball, f), st.c};
}
template <BoundingSphereOps Ops>
BoundingSphere<typename Ops::Sphere> welzl_sphere(std::span<const Vec3> points, std::uint64_t seed) {
  std::mt19937_64 rng(seed);
  return welzl_sphere<Ops>(points, rng);
}

}  // namespace gacompare::core
