#pragma once
// The narrowphase without per-pair rebuilding through a
// backend: each body's geometry built once and shared by its pairs
// (core/collision/shape.hpp), each pair's separating axis remembered between detections
// (core/collision/separating_axis.hpp SatHint), support points by hill climbing, and
// edge pairs by walking the Gauss map. Each against the plain computation it
// replaces: geometry rebuilt for the pair, no axis remembered, every vertex
// scanned, every edge pair tested. Instantiated by
// tests/{traditional,cga}/narrowphase_test.cpp; `Backend` is a tag with Body.
#include "answers/collision_cases.hpp"
#include "core/collision/kept_contacts.hpp"
#include "core/collision/narrowphase.hpp"
#include "core/collision/separating_axis.hpp"
#include "core/collision/shape.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>
#include <vector>

namespace gacompare::testing {

using collision::Feature;
using collision::FeatureContact;
using collision::Method;
using collision::PairContact;
using collision::Placed;
using collision::Pose;
using Vec3 = Eigen::Vector3d;
using Mat3 = Eigen::Matrix3d;

// Bit for bit: the shared and the rebuilt paths do the same arithmetic on the
// same numbers, so any difference is a stale or mixed-up cache.
inline void expect_same(const PairContact& x, const PairContact& y, const std::string& what) {
  EXPECT_EQ(x.intersect, y.intersect) << what;
  EXPECT_EQ(x.depth, y.depth) << what;
  EXPECT_TRUE(x.normal == y.normal) << what << ": " << x.normal.transpose() << " vs " << y.normal.transpose();
  EXPECT_TRUE(x.contact == y.contact) << what << ": " << x.contact.transpose() << " vs " << y.contact.transpose();
  EXPECT_EQ(x.feature, y.feature) << what;
}
inline void expect_same(const std::vector<FeatureContact>& x, const std::vector<FeatureContact>& y,
                        const std::string& what) {
  ASSERT_EQ(x.size(), y.size()) << what;
  for (std::size_t k = 0; k < x.size(); ++k) {
    EXPECT_TRUE(x[k].point == y[k].point) << what << " contact " << k;
    EXPECT_TRUE(x[k].normal == y[k].normal) << what << " contact " << k;
    EXPECT_EQ(x[k].depth, y[k].depth) << what << " contact " << k;
    EXPECT_EQ(x[k].feature, y[k].feature) << what << " contact " << k;
  }
}

// The degenerate members the simulation meets most: equal cubes face to face
// (offsets 0, 1e-9 and 1e-3 of the size sideways; turned about the normal by
// 0, 1e-9 rad, 90° and 45°), a cube on a ridge, two ridges crossed and two
// ridges aligned (edge on edge, parallel), each at the depth `depth` (< 0: a gap).
inline std::vector<collision::CollisionCase> degenerate_pairs(double depth) {
  static const auto cube = std::make_shared<const core::Mesh>(core::make_box({0.25, 0.25, 0.25}));
  static const auto big = std::make_shared<const core::Mesh>(core::make_box({1, 1, 1}));
  std::vector<collision::CollisionCase> out;
  const auto rot = [](double angle, const Vec3& axis) { return Mat3(Eigen::AngleAxisd(angle, axis)); };
  for (const double turn : {0.0, 1e-9, std::numbers::pi / 2, std::numbers::pi / 4})
    for (const double offset : {0.0, 1e-9 * 0.25, 1e-3 * 0.25})
      out.push_back({"cubes turn " + std::to_string(turn) + " offset " + std::to_string(offset), cube, cube, Pose{},
                     Pose{rot(turn, Vec3::UnitX()), Vec3(0.25 - depth, offset, offset)}});
  const double ridge = std::numbers::sqrt2 / 2;
  const Mat3 rx = rot(std::numbers::pi / 4, Vec3::UnitX()), ry = rot(std::numbers::pi / 4, Vec3::UnitY());
  out.push_back({"cube on a ridge", big, big, Pose{rx, Vec3::Zero()}, Pose{Mat3::Identity(), Vec3(0, 0, ridge + 0.5 - depth)}});
  out.push_back({"ridges crossed", big, big, Pose{rx, Vec3::Zero()}, Pose{ry, Vec3(0, 0, 2 * ridge - depth)}});
  out.push_back({"ridges aligned", big, big, Pose{rx, Vec3::Zero()}, Pose{rx, Vec3(0, 0.1, 2 * ridge - depth)}});
  return out;
}

template <class Backend>
class NarrowphaseCacheCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(NarrowphaseCacheCases);

// Two Shapes serve every pair of a varied list (random hulls, the hand corpus,
// random pairs 1e4 from the origin, the degenerate members touching, 1e-5 deep
// and 1e-5 apart): each case's bodies placed into them, every method asked,
// then a's Shape moved to another body and back and b's Shape paired with the
// next case's a, as a collider's shapes are shared by several pairs. Every
// answer and every contact equals the rebuilt path's bit for bit.
TYPED_TEST_P(NarrowphaseCacheCases, SharedShapesGiveTheAnswersOfRebuiltOnes) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  auto cases = collision::build_cases(collision::random_case_specs(7, 60), "random");
  for (auto& c : collision::load_cases(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision" / "hand.json"))
    cases.push_back(std::move(c));
  for (auto& c : collision::build_cases(collision::random_case_specs(8, 20, Vec3(1e4, -1e4, 1e4)), "far"))
    cases.push_back(std::move(c));
  for (const double depth : {0.0, 1e-5, -1e-5})
    for (auto& c : degenerate_pairs(depth)) cases.push_back(std::move(c));
  Shape sa, sb;
  int compared = 0;
  for (std::size_t k = 0; k < cases.size(); ++k) {
    const auto& c = cases[k];
    const auto& next = cases[(k + 1) % cases.size()];
    for (const Method m : {Method::report, Method::sat, Method::sat_then_report, Method::manifold,
                           Method::sat_then_manifold}) {
      const std::string what = c.name + " method " + std::to_string(static_cast<int>(m));
      std::vector<FeatureContact> rebuilt, shared;
      const PairContact r = collision::narrowphase<Body>(c.a(), c.b(), m, &rebuilt);
      sa.place(c.a()), sb.place(c.b());
      expect_same(collision::narrowphase<Body>(sa, sb, m, &shared), r, what);
      expect_same(shared, rebuilt, what);
      sa.place(c.b()), sa.place(c.a());  // moved away and back: what it built on first use must follow
      shared.clear();
      expect_same(collision::narrowphase<Body>(sa, sb, m, &shared), r, what + " (a placed again)");
      expect_same(shared, rebuilt, what + " (a placed again)");
      // b's Shape in a second pair, with the next case's a.
      std::vector<FeatureContact> other_rebuilt, other_shared;
      const Shape na(next.a());
      const PairContact o = collision::narrowphase<Body>(next.a(), c.b(), m, &other_rebuilt);
      expect_same(collision::narrowphase<Body>(na, sb, m, &other_shared), o, what + " (b with the next a)");
      expect_same(other_shared, other_rebuilt, what + " (b with the next a)");
      ++compared;
    }
  }
  EXPECT_GT(compared, 500);
}

// A pair's remembered axis against none, over seeded random moving pairs: b
// slides through a along the line between their centres (from 1.6 × the sum
// of their radii in front to as far behind) turning as it goes, 48 steps; and
// the degenerate members approaching face to face from 1e-3 apart to 1e-3 deep
// through exactly touching, 41 steps. At every step the two say the same
// yes/no; where the pair intersects the answers and contacts are the same bit
// for bit (the remembered axis only decides pairs apart); where it is apart,
// the remembered answer's normal separates the bodies by at least its gap (to
// 1e-12 of the size: the two projections are computed in other frames) and
// that gap is no larger than the exact reference's (every third apart step:
// the reference is slow). The remembered axis
// decides most of the apart steps (else nothing here would be tested).
TYPED_TEST_P(NarrowphaseCacheCases, RememberedAxesGiveTheAnswersOfColdOnes) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  struct Path {
    collision::CollisionCase c;
    Vec3 from, to;  // b's position
    Mat3 turn;      // b's rotation at the end of the path, relative to the start
    int steps;
  };
  std::vector<Path> paths;
  std::mt19937_64 rng(14);
  std::normal_distribution<double> g;
  for (auto& c : collision::build_cases(collision::random_case_specs(21, 30), "moving")) {
    const Vec3 u = (c.pose_b.position - c.pose_a.position).normalized();
    const double reach = 0.8 * (c.mesh_a->size() + c.mesh_b->size());
    const Mat3 turn(Eigen::AngleAxisd(0.5, Vec3(g(rng), g(rng), g(rng)).normalized()));
    paths.push_back({c, c.pose_a.position + reach * u, c.pose_a.position - reach * u, turn, 48});
  }
  for (auto& c : degenerate_pairs(0)) {
    const Vec3 normal = c.name.rfind("cubes", 0) == 0 ? Vec3::UnitX() : Vec3::UnitZ();
    paths.push_back({c, c.pose_b.position + 1e-3 * normal, c.pose_b.position - 1e-3 * normal, Mat3::Identity(), 41});
  }
  int apart = 0, kept = 0, intersecting = 0;
  for (const auto& p : paths) {
    Shape sa(p.c.a()), sb;
    collision::SatHint hint;
    for (int s = 0; s < p.steps; ++s) {
      const double t = static_cast<double>(s) / (p.steps - 1);
      Placed b = p.c.b();
      b.pose.position = p.from + t * (p.to - p.from);
      b.pose.rotation = Mat3(Eigen::Quaterniond::Identity().slerp(t, Eigen::Quaterniond(p.turn))) * b.pose.rotation;
      sb.place(b);
      std::vector<FeatureContact> cold_c, warm_c;
      const PairContact cold = collision::narrowphase<Body>(sa, sb, Method::sat_then_manifold, &cold_c);
      const PairContact warm = collision::narrowphase<Body>(sa, sb, Method::sat_then_manifold, &warm_c, &hint);
      const std::string what = p.c.name + " step " + std::to_string(s);
      ASSERT_EQ(warm.intersect, cold.intersect) << what;
      if (cold.intersect) {
        ++intersecting;
        expect_same(warm, cold, what);
        expect_same(warm_c, cold_c, what);
        continue;
      }
      ++apart;
      kept += hint.kept;
      const double scale = collision::pair_scale(*p.c.mesh_a, *p.c.mesh_b);
      double hi_a = -INFINITY, lo_b = INFINITY;
      for (const Vec3& x : p.c.mesh_a->vertices()) hi_a = std::max(hi_a, warm.normal.dot(p.c.pose_a.apply(x)));
      for (const Vec3& x : p.c.mesh_b->vertices()) lo_b = std::min(lo_b, warm.normal.dot(b.pose.apply(x)));
      EXPECT_GE(lo_b - hi_a, -warm.depth - 1e-12 * scale) << what;
      if (apart % 3 == 0) {  // the reference is slow (every axis, long double): every third step
        EXPECT_LE(-warm.depth, -collision::sat_reference(p.c.a(), b).depth + 1e-12 * scale) << what;
      }
    }
  }
  EXPECT_GT(intersecting, 300);
  EXPECT_GT(apart, 300);
  EXPECT_GT(kept, apart / 2);
}

// Hill climbing (Shape::climb) against the scan (Shape::scan): the same lowest
// distance from every start, for random planes and for the planes parallel to
// each face (where a whole face ties: any of its vertices is a support), on
// hulls of 8 to 300 points on a sphere, a box, an icosahedron and a flat hull
// (a disc of points with one apex: many vertices tie under the disc's plane).
// The distances are in the shape's unit (~1): a tie's vertices differ by
// rounding only, 1e-15 is ten units in the last place.
TYPED_TEST_P(NarrowphaseCacheCases, HillClimbingFindsTheScansSupport) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  using Algebra = typename Shape::Algebra;
  std::mt19937_64 rng(32);
  std::normal_distribution<double> g;
  const auto direction = [&] { return Vec3(Vec3(g(rng), g(rng), g(rng)).normalized()); };
  std::vector<core::Mesh> meshes{core::make_box({1, 2, 3}), core::make_icosahedron(1)};
  for (const int n : {8, 32, 100, 300}) {
    std::vector<Vec3> p;
    for (int i = 0; i < n; ++i) p.push_back(direction());
    meshes.push_back(core::convex_hull(p));
  }
  std::vector<Vec3> disc{Vec3(0, 0, 1)};
  for (int i = 0; i < 40; ++i) disc.emplace_back(std::cos(0.157 * i), std::sin(0.157 * i), 0);
  meshes.push_back(core::convex_hull(disc));
  int compared = 0;
  for (const auto& mesh : meshes) {
    ASSERT_TRUE(mesh.corners_only()) << mesh.name();
    const Shape s({&mesh, {Mat3(Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized()), Vec3(3, -2, 1)}});
    std::vector<typename Shape::Plane> planes;
    for (int k = 0; k < 300; ++k) planes.push_back(Algebra::plane(direction(), g(rng)));
    for (int k = 0; k < static_cast<int>(mesh.planes().size()); ++k)
      planes.push_back(Algebra::plane(Vec3(-s.normal(k)), 0.5));
    const int v = static_cast<int>(mesh.vertices().size());
    for (const auto& plane : planes)
      for (const int start : {0, v / 2, v - 1}) {
        const auto [scanned, j] = s.scan(plane);
        const auto [climbed, i] = s.climb(plane, start);
        EXPECT_NEAR(climbed, scanned, 1e-15) << mesh.name() << " start " << start;
        EXPECT_EQ(Algebra::distance(plane, s.point(i)), climbed) << mesh.name();
        ++compared;
      }
  }
  EXPECT_GT(compared, 5000);
}

// The walk across the Gauss map (walk_edge) against every edge pair tested
// (spans_minkowski_face over all of b's edges): where the walk says it can be
// trusted, it met exactly the pairs the test finds; on random hulls it can be
// trusted for (nearly) every edge. The degenerate members, whose maps share
// arcs and vertices, may send it back to the test; when they do not, the same
// rule holds.
TYPED_TEST_P(NarrowphaseCacheCases, WalkingTheGaussMapMeetsEveryCrossing) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  auto cases = collision::build_cases(collision::random_case_specs(12, 80), "random");
  const std::size_t random = cases.size();
  for (const double depth : {0.0, 1e-5})
    for (auto& c : degenerate_pairs(depth)) cases.push_back(std::move(c));
  int trusted = 0, edges = 0;
  for (std::size_t n = 0; n < cases.size(); ++n) {
    const auto& c = cases[n];
    const Shape sa(c.a()), sb(c.b());
    const Vec3 o = collision::local_origin(c.a(), c.b());
    const Body a(sa, Vec3(sa.position() - o)), b(sb, Vec3(sb.position() - o));
    std::vector<int> below;
    for (int k = 0; k < static_cast<int>(c.mesh_a->planes().size()); ++k)
      below.push_back(sb.scan(a.plane_toward(k, b)).second);
    const auto& ea = sa.edges();
    const auto& eb = sb.edges();
    for (int i = 0; i < static_cast<int>(ea.size()); ++i) {
      std::vector<int> tested, walked;
      for (int j = 0; j < static_cast<int>(eb.size()); ++j)
        if (collision::spans_minkowski_face(ea[i].n0, ea[i].n1, Vec3(-ea[i].d), eb[j].n0, eb[j].n1, Vec3(-eb[j].d)))
          tested.push_back(j);
      const int r = collision::walk_edge(a, b, i, below, [&](int j) {
        walked.push_back(j);
        return false;
      });
      ASSERT_GE(r, 0) << c.name;
      if (n < random) ++edges, trusted += r;
      if (r == 0) continue;
      std::sort(walked.begin(), walked.end());
      EXPECT_EQ(walked, tested) << c.name << " edge " << i;
    }
  }
  EXPECT_GE(trusted, edges * 99 / 100);
}

// A shape's own unit (core/collision/shape.hpp "Units"): the distance of each vertex of
// o from each face of f, read through the views (f's plane moved into o's
// frame and unit, times o's unit), against n·x − d in long double from the
// meshes and poses, for cubes of 1e-2, 1 and 1e3 m side by side. Within
// 4e-16 of the larger size: a few roundings of numbers of that size. (In
// metres, cga's X·π of the 1e3 m cubes was 5e-7 m off, 1e-10 of their size.)
TYPED_TEST_P(NarrowphaseCacheCases, ShapesMeasureDistancesInMetresAtEveryScale) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  using L = long double;
  for (const double size : {1e-2, 1.0, 1e3}) {
    const core::Mesh small = core::make_box(Vec3::Constant(size)), large = core::make_box(Vec3::Constant(2.5 * size));
    const Placed pf{&small, {Mat3(Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized())), Vec3(0.1, 0.2, 0.3) * size}};
    const Placed po{&large, {Mat3(Eigen::AngleAxisd(1.1, Vec3(-2, 1, 1).normalized())), Vec3(1.7, -0.4, 0.9) * size}};
    const Shape sf(pf), so(po);
    const Vec3 origin = collision::local_origin(pf, po);
    const Body f(sf, Vec3(sf.position() - origin)), o(so, Vec3(so.position() - origin));
    double worst = 0;
    for (int k = 0; k < static_cast<int>(small.planes().size()); ++k) {
      const auto plane = f.plane_toward(k, o);
      const Eigen::Matrix<L, 3, 1> n = pf.pose.rotation.cast<L>() * small.planes()[k].normal.cast<L>();
      const L d = L(small.planes()[k].offset) + n.dot(pf.pose.position.cast<L>());
      for (int j = 0; j < static_cast<int>(large.vertices().size()); ++j) {
        const Eigen::Matrix<L, 3, 1> x =
            po.pose.rotation.cast<L>() * large.vertices()[j].cast<L>() + po.pose.position.cast<L>();
        const double exact = static_cast<double>(n.dot(x) - d);
        worst = std::max(worst, std::abs(Body::distance(plane, so.point(j)) * so.unit() - exact));
      }
    }
    EXPECT_LT(worst, 4e-16 * 2.5 * size * std::sqrt(3.0)) << "size " << size;
  }
}

// Touching (core/collision/narrowphase.hpp): a pair within the touching band has its
// contacts whichever way its yes/no rounds, and one beyond it has none, with or
// without an axis remembered from a pair far apart (which separates it at once:
// the contacts must not depend on where the test stopped). Equal cubes face to
// face at gaps −1e-5 (overlapping), 0, 0.1 and 0.9 of the band, and 2 and 10
// bands; their size is 0.433, the band 1e-9 of it.
TYPED_TEST_P(NarrowphaseCacheCases, TouchingPairsHaveTheirContacts) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  const core::Mesh cube = core::make_box({0.25, 0.25, 0.25});
  const double band = collision::kTouchingBand * cube.size();
  for (const double gap : {-1e-5, 0.0, 0.1 * band, 0.9 * band, 2 * band, 10 * band}) {
    const Shape a(Placed{&cube, {}}), far(Placed{&cube, {Mat3::Identity(), Vec3(1, 0, 0)}});
    const Shape b(Placed{&cube, {Mat3::Identity(), Vec3(0.25 + gap, 0, 0)}});
    collision::SatHint hint;
    collision::narrowphase<Body>(a, far, Method::sat_then_manifold, nullptr, &hint);
    ASSERT_EQ(hint.feature, Feature::face_a);
    std::vector<FeatureContact> cold, warm;
    const PairContact c = collision::narrowphase<Body>(a, b, Method::sat_then_manifold, &cold);
    const PairContact w = collision::narrowphase<Body>(a, b, Method::sat_then_manifold, &warm, &hint);
    EXPECT_EQ(cold.size(), gap <= band ? 4u : 0u) << "gap " << gap;
    expect_same(warm, cold, "gap " + std::to_string(gap));
    EXPECT_EQ(w.intersect, c.intersect) << "gap " << gap;
    for (const auto& p : cold) EXPECT_NEAR(p.depth, -gap, 1e-15) << "gap " << gap;  // exact in binary but gap: 1e-15
  }
}

// The islands' link gap (collision::face_gap, core/collision/collisions.hpp note_apart):
// for every pair apart of the random corpus and of the degenerate members
// 1e-3 apart, it is a lower bound of the distance (at most the exact
// reference's best gap, every axis in long double: 1e-12 of the size for
// rounding), at least the gap of any face axis the early test stops at with
// or without a remembered axis (so a face axis's gap above the reaches may
// decide alone), and the same with whichever axis is remembered, since it
// reads none; stopped at the first gap above a threshold it says whether the
// best is above it. Aligned cubes apart by d give d.
TYPED_TEST_P(NarrowphaseCacheCases, FaceGapBoundsTheDistanceWhateverIsRemembered) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  std::vector<collision::CollisionCase> cases = collision::build_cases(collision::random_case_specs(23, 200), "random");
  for (auto& c : degenerate_pairs(-1e-3)) cases.push_back(c);
  int apart = 0, faces = 0;
  for (const auto& c : cases) {
    const Shape sa(c.a()), sb(c.b());
    const Vec3 o = collision::local_origin(sa.position(), sb.position());
    const Body va(sa, sa.position() - o), vb(sb, sb.position() - o);
    const PairContact cold = collision::narrowphase<Body>(sa, sb, Method::sat_then_manifold);
    if (cold.depth >= 0) continue;
    ++apart;
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    const double gap = collision::face_gap(va, vb);
    EXPECT_LE(gap, -collision::sat_reference(c.a(), c.b()).depth + 1e-12 * scale) << c.name;
    collision::SatHint edge{Feature::edge_edge, 0, 0};  // a remembered axis that is not the cold one
    const PairContact warm = collision::narrowphase<Body>(sa, sb, Method::sat_then_manifold, nullptr, &edge);
    for (const PairContact& r : {cold, warm})
      if (r.feature == Feature::face_a || r.feature == Feature::face_b) {
        ++faces;
        EXPECT_GE(gap, -r.depth) << c.name;
      }
    EXPECT_EQ(collision::face_gap(va, vb), gap) << c.name;
    // Stopping at the first gap above `enough` answers "above or not" alike.
    for (const double enough : {0.5 * gap, gap - 1e-9 * scale, gap + 1e-9 * scale, -1.0})
      EXPECT_EQ(collision::face_gap(va, vb, enough) > enough, gap > enough) << c.name << " enough " << enough;
  }
  EXPECT_GT(apart, 50);
  EXPECT_GT(faces, apart);
  const core::Mesh cube = core::make_box({0.25, 0.25, 0.25});
  for (const double d : {1e-9, 1e-3, 0.1}) {
    const Shape a(Placed{&cube, {}}), b(Placed{&cube, {Mat3::Identity(), Vec3(0.25 + d, 0.01, 0)}});
    const Vec3 o = collision::local_origin(a.position(), b.position());
    EXPECT_NEAR(collision::face_gap(Body(a, a.position() - o), Body(b, b.position() - o)), d, 1e-15) << "d " << d;
  }
}

// Kept contacts (core/collision/kept_contacts.hpp) against the whole test at
// the same poses. Pairs: boxes of seeded random sides resting face to face
// 1e-5 of their size deep, offset sideways, turned about the normal and
// tilted by up to 1e-4 rad (one in four level), and the degenerate cube pairs. Each pair's
// contacts are kept at its pose, then asked again:
//   - at the same pose, and with both bodies moved together by a rigid motion
//     (the relative pose the same): the same points, normals, depths and
//     separating-axis answer, to 1e-14 of the scale (the world's coordinates
//     round the kept and the tested points differently, ~1e-16 of the 1 m
//     the pair is moved by, a few times over);
//   - with b moved along the normal (from 0.3 of the depth deeper to 0.3 of
//     it apart): the same, and the depths the whole test's;
//   - with b slid, or turned, by twice the bound: refused.
// And a cube resting on one edge of its face (tilted so that its other
// edge is 4e-6 of the scale higher): kept, then refused once b has come
// down by that height, where the whole test finds the other edge's points.
TYPED_TEST_P(NarrowphaseCacheCases, KeptContactsGiveTheWholeTestsAnswersWithinTheirBound) {
  using Body = typename TypeParam::Body;
  using Shape = typename Body::Shape;
  struct Full {
    PairContact sat;
    std::vector<FeatureContact> c;
    collision::SatHint hint;
    collision::FaceChoice choice;
  };
  const auto full = [](const Placed& a, const Placed& b) {
    Full f;
    const Shape sa(a), sb(b);
    f.sat = collision::narrowphase<Body>(sa, sb, Method::sat_then_manifold, &f.c, &f.hint, &f.choice);
    return f;
  };
  // The kept answer against the whole test's, to `tol` (points as sets: the
  // clipping's order is not kept).
  const auto expect_near = [](const PairContact& ks, const std::vector<FeatureContact>& kc, const Full& f, double tol,
                              const std::string& what) {
    EXPECT_EQ(ks.intersect, f.sat.intersect) << what;
    EXPECT_EQ(ks.feature, f.sat.feature) << what;
    EXPECT_NEAR(ks.depth, f.sat.depth, tol) << what;
    EXPECT_LE((ks.normal - f.sat.normal).norm(), 1e-14) << what;
    ASSERT_EQ(kc.size(), f.c.size()) << what;
    for (const FeatureContact& k : kc) {
      const FeatureContact* near = &f.c[0];
      for (const FeatureContact& c : f.c)
        if ((c.point - k.point).norm() < (near->point - k.point).norm()) near = &c;
      EXPECT_LE((near->point - k.point).norm(), tol) << what;
      EXPECT_LE((near->normal - k.normal).norm(), 1e-14) << what;
      EXPECT_NEAR(near->depth, k.depth, tol) << what;
      EXPECT_EQ(near->feature, k.feature) << what;
    }
  };
  // Two level faces tie: every axis near the normal (the faces', and edge
  // pairs' of rounding's making) and every point of the overlap at one
  // depth, so which the whole test picks, and which four points it keeps of
  // more (two rectangles turned clip to up to eight), is rounding's, and a
  // move changes it. Their depths are the same.
  const auto same = [&](const collision::CollisionCase& c, const PairContact& ks,
                        const std::vector<FeatureContact>& kc, const Full& f, const std::string& what) {
    const double tol = 1e-14 * collision::pair_scale(*c.mesh_a, *c.mesh_b);
    if (c.name.rfind("level", 0) != 0 && c.name.rfind("cubes", 0) != 0) return expect_near(ks, kc, f, tol, what);
    EXPECT_NEAR(ks.depth, f.sat.depth, tol) << what;
    ASSERT_EQ(kc.size(), f.c.size()) << what;
    for (std::size_t m = 0; m < kc.size(); ++m) EXPECT_NEAR(kc[m].depth, f.c[m].depth, tol) << what;
  };
  std::mt19937_64 rng(29);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<collision::CollisionCase> cases;
  for (int n = 0; n < 40; ++n) {
    const Vec3 sa(0.2 + 0.1 * u(rng), 0.2 + 0.1 * u(rng), 0.2 + 0.1 * u(rng));
    const Vec3 sb(0.2 + 0.1 * u(rng), 0.2 + 0.1 * u(rng), 0.2 + 0.1 * u(rng));
    const auto ma = std::make_shared<const core::Mesh>(core::make_box(sa));
    const auto mb = std::make_shared<const core::Mesh>(core::make_box(sb));
    const double tilt = n % 4 == 0 ? 0.0 : 1e-4 * u(rng);
    const Mat3 r = Mat3(Eigen::AngleAxisd(std::numbers::pi * u(rng), Vec3::UnitZ())) *
                   Mat3(Eigen::AngleAxisd(tilt, Vec3(u(rng), u(rng), 0).normalized()));
    const double scale = collision::pair_scale(*ma, *mb);
    // b lowered onto a until the pair is 1e-5 of the scale deep (bisection:
    // where b overhangs a, its lowest corner is not the one that touches).
    Pose pb{r, Vec3(0.05 * u(rng), 0.05 * u(rng), 0)};
    double lo = -1, hi = 1;
    for (int it = 0; it < 80; ++it) {
      pb.position.z() = 0.5 * (lo + hi);
      const double depth = collision::narrowphase<Body>(Placed{ma.get(), {}}, Placed{mb.get(), pb}, Method::manifold).depth;
      (depth > 1e-5 * scale ? lo : hi) = pb.position.z();
    }
    cases.push_back({(tilt == 0 ? "level boxes " : "boxes ") + std::to_string(n), ma, mb, Pose{}, pb});
  }
  for (auto& c : degenerate_pairs(1e-5))
    if (c.name.rfind("cubes", 0) == 0) cases.push_back(std::move(c));
  const Mat3 carry(Eigen::AngleAxisd(0.7, Vec3(1, -2, 0.5).normalized()));
  const Vec3 shift(0.9, -0.4, 1.3);
  int kept = 0, moved = 0, refused = 0;
  for (const auto& c : cases) {
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    const double band = collision::kTouchingBand * scale;
    const Full f = full(c.a(), c.b());
    collision::KeptContacts k;
    if (!collision::keep(k, *c.mesh_a, *c.mesh_b, c.pose_a, c.pose_b, f.sat, f.hint, f.choice, f.c)) continue;
    ++kept;
    const auto ask = [&](const Pose& pa, const Pose& pb, std::vector<FeatureContact>& out, PairContact& sat) {
      return collision::refresh(k, *c.mesh_a, *c.mesh_b, pa, pb, band, sat, out);
    };
    {
      std::vector<FeatureContact> out;
      PairContact sat;
      ASSERT_TRUE(ask(c.pose_a, c.pose_b, out, sat)) << c.name;
      same(c, sat, out, f, c.name + " at its pose");
      // Both carried by one rigid motion.
      const Pose pa{carry * c.pose_a.rotation, carry * c.pose_a.position + shift};
      const Pose pb{carry * c.pose_b.rotation, carry * c.pose_b.position + shift};
      out.clear();
      ASSERT_TRUE(ask(pa, pb, out, sat)) << c.name;
      same(c, sat, out, full({c.mesh_a.get(), pa}, {c.mesh_b.get(), pb}), c.name + " carried");
    }
    const Vec3 n = f.sat.normal;  // a towards b
    for (const double along : {-3e-6, -1e-6, 1e-6, 3e-6}) {
      Pose pb = c.pose_b;
      pb.position += along * scale * n;
      std::vector<FeatureContact> out;
      PairContact sat;
      const Full g = full(c.a(), {c.mesh_b.get(), pb});
      if (!ask(c.pose_a, pb, out, sat)) {
        // Only where a point has risen above the band, a left-out one could
        // come down into it, or a choice of faces could change.
        EXPECT_TRUE(along > 0 || along * scale + k.left_out <= 0 ||
                    k.faces + std::abs(along) * scale * k.faces_spread >= 0 ||
                    k.edge - std::abs(along) * scale * k.edge_spread <= 0)
            << c.name << " along " << along;
        continue;
      }
      ++moved;
      same(c, sat, out, g, c.name + " along " + std::to_string(along));
    }
    const Vec3 side = n.unitOrthogonal();
    for (const Pose& pb : {Pose{c.pose_b.rotation, c.pose_b.position + 2 * collision::kKeepSlide * scale * side},
                           Pose{Mat3(Eigen::AngleAxisd(2 * collision::kKeepSlide, n)) * c.pose_b.rotation,
                                c.pose_b.position}}) {
      std::vector<FeatureContact> out;
      PairContact sat;
      EXPECT_FALSE(ask(c.pose_a, pb, out, sat)) << c.name;
      EXPECT_TRUE(out.empty()) << c.name;
      ++refused;
    }
  }
  // Most random boxes (some rest on an edge of a, or an edge pair ties
  // with their faces: not kept) and every degenerate cube pair.
  EXPECT_GT(kept, 40);
  EXPECT_GT(moved, 3 * kept);
  // A cube resting on one edge: its far edge 4e-6 of the scale above a's face.
  const auto cube = std::make_shared<const core::Mesh>(core::make_box({0.2, 0.2, 0.2}));
  const double scale = cube->size(), band = collision::kTouchingBand * scale, lift = 4e-6 * scale;
  const Mat3 r(Eigen::AngleAxisd(lift / 0.2, Vec3::UnitY()));
  double low = INFINITY;
  for (const Vec3& x : cube->vertices()) low = std::min(low, (r * x).z());
  const Pose pa{}, pb{r, Vec3(0, 0, 0.1 - low - 1e-9 * scale)};
  const Full f = full({cube.get(), pa}, {cube.get(), pb});
  ASSERT_EQ(f.c.size(), 2u);
  collision::KeptContacts k;
  ASSERT_TRUE(collision::keep(k, *cube, *cube, pa, pb, f.sat, f.hint, f.choice, f.c));
  EXPECT_NEAR(k.left_out, lift, 1e-3 * lift);  // the far edge's height above the band
  for (const double down : {0.5, 0.99, 1.01}) {  // times the lift
    Pose q = pb;
    q.position.z() -= down * lift;
    std::vector<FeatureContact> out;
    PairContact sat;
    const bool ok = collision::refresh(k, *cube, *cube, pa, q, band, sat, out);
    const Full g = full({cube.get(), pa}, {cube.get(), q});
    EXPECT_EQ(ok, down < 1) << "down " << down;
    if (ok) expect_near(sat, out, g, 1e-14 * scale, "on its edge, down " + std::to_string(down));
    else EXPECT_EQ(g.c.size(), 4u) << "down " << down;  // the far edge came into the band
  }
  EXPECT_GT(refused, 0);
}

REGISTER_TYPED_TEST_SUITE_P(NarrowphaseCacheCases, TouchingPairsHaveTheirContacts, SharedShapesGiveTheAnswersOfRebuiltOnes,
                            RememberedAxesGiveTheAnswersOfColdOnes, HillClimbingFindsTheScansSupport,
                            WalkingTheGaussMapMeetsEveryCrossing, ShapesMeasureDistancesInMetresAtEveryScale,
                            FaceGapBoundsTheDistanceWhateverIsRemembered,
                            KeptContactsGiveTheWholeTestsAnswersWithinTheirBound);

}  // namespace gacompare::testing
