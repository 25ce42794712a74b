#pragma once
// Narrowphase cases run through a backend (traditional/ or cga/
// narrowphase.hpp and segment_triangle.hpp) and checked against independent
// answers: a 3×3 solve for the segment–triangle hit, analytic box contacts,
// the long-double separating-axis reference on the corpus. Instantiated by
// tests/{traditional,cga}/narrowphase_test.cpp; `Backend` is a tag with
// segment_triangle() and narrowphase().
#include "answers/collision_cases.hpp"
#include "core/collision/separating_axis.hpp"

#include <Eigen/Dense>
#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <numbers>
#include <random>
#include <string>

namespace gacompare::testing {

using collision::Feature;
using collision::Method;
using collision::PairContact;
using collision::Placed;
using collision::Pose;
using Vec3 = Eigen::Vector3d;

template <class Backend>
class NarrowphaseCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(NarrowphaseCases);

// Eq. 39–46 on a hand case: the segment x = y = 0.2 through the triangle
// (0,0,0), (1,0,0), (0,1,0) hits at (0.2, 0.2, 0), half way, barycentric
// (0.6, 0.2, 0.2). All inputs exact in binary except 0.2: 1e-15.
TYPED_TEST_P(NarrowphaseCases, SegmentTriangleHandCase) {
  const auto hit = TypeParam::segment_triangle({0.2, 0.2, -1}, {0.2, 0.2, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0});
  ASSERT_TRUE(hit);
  EXPECT_NEAR((hit->point - Vec3(0.2, 0.2, 0)).norm(), 0, 1e-15);
  EXPECT_NEAR(hit->r, 0.5, 1e-15);
  EXPECT_NEAR(hit->barycentric[0], 0.6, 1e-15);
  EXPECT_NEAR(hit->barycentric[1], 0.2, 1e-15);
  EXPECT_NEAR(hit->barycentric[2], 0.2, 1e-15);
  // Misses: beyond the segment's end, outside the triangle, parallel to the plane.
  EXPECT_FALSE(TypeParam::segment_triangle({0.2, 0.2, 0.5}, {0.2, 0.2, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_FALSE(TypeParam::segment_triangle({0.6, 0.6, -1}, {0.6, 0.6, 1}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  EXPECT_FALSE(TypeParam::segment_triangle({0.1, 0.1, 0.5}, {0.3, 0.1, 0.5}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
  // An axis-parallel segment (the report's bounding-box test has zero width here).
  EXPECT_TRUE(TypeParam::segment_triangle({0.25, 0.25, 1}, {0.25, 0.25, -3}, {0, 0, 0}, {1, 0, 0}, {0, 1, 0}));
}

// Seeded random segments and triangles against an independent 3×3 solve
// l0 + r d = t0 + s u + t v (Householder QR). Cases within 1e-9 of a decision
// boundary (r or a barycentric coordinate near 0 or 1) are skipped: there the
// answer is decided by rounding. Values agree to 1e-9: the solve and eq. 39–46
// round differently, and triangles as thin as 1e-3 in the sample amplify it.
TYPED_TEST_P(NarrowphaseCases, SegmentTriangleMatchesALinearSolve) {
  std::mt19937_64 rng(2026);
  std::uniform_real_distribution<double> u(-1, 1);
  const auto point = [&] { return Vec3(u(rng), u(rng), u(rng)); };
  int hits = 0, compared = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 l0 = point(), l1 = point(), t0 = point(), t1 = point(), t2 = point();
    Eigen::Matrix3d m;
    m << l1 - l0, -(t1 - t0), -(t2 - t0);
    const Eigen::Vector3d x = m.colPivHouseholderQr().solve(t0 - l0);  // r, s, t
    const double bary[3] = {1 - x[1] - x[2], x[1], x[2]};
    const double margin = std::min({std::abs(x[0]), std::abs(1 - x[0]), std::abs(bary[0]), std::abs(bary[1]),
                                    std::abs(bary[2])});
    if (margin < 1e-9 || std::abs(m.determinant()) < 1e-6) continue;
    const bool expected = x[0] > 0 && x[0] < 1 && bary[0] > 0 && bary[1] > 0 && bary[2] > 0;
    const auto hit = TypeParam::segment_triangle(l0, l1, t0, t1, t2);
    ASSERT_EQ(hit.has_value(), expected) << i;
    ++compared;
    if (!hit) continue;
    ++hits;
    EXPECT_NEAR(hit->r, x[0], 1e-9) << i;
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(hit->barycentric[k], bary[k], 1e-9) << i;
    EXPECT_NEAR((hit->point - (l0 + x[0] * (l1 - l0))).norm(), 0, 1e-9) << i;
  }
  EXPECT_GT(compared, 15000);
  EXPECT_GT(hits, 500);
}

// A unit cube a and a half cube b centred at (0.6, 0.01, 0.02): b's four left
// vertices are 0.15 inside a's +x face and deeper behind every other face, so
// the report's detector (§2.4.3) finds four vertex–face contacts of depth 0.15
// along x, and the minimum depth is 0.15 along x. 0.6 − 0.25 − 0.5 in doubles: 1e-15.
TYPED_TEST_P(NarrowphaseCases, CubesFaceToFace) {
  const core::Mesh cube = core::make_box({1, 1, 1}), half = core::make_box({0.5, 0.5, 0.5});
  const Placed a{&cube, Pose{}}, b{&half, Pose{Eigen::Matrix3d::Identity(), Vec3(0.6, 0.01, 0.02)}};
  std::vector<collision::FeatureContact> contacts;
  const PairContact r = TypeParam::narrowphase(a, b, Method::report, &contacts);
  EXPECT_TRUE(r.intersect);
  EXPECT_NEAR(r.depth, 0.15, 1e-15);
  EXPECT_NEAR((r.normal - Vec3::UnitX()).norm(), 0, 1e-15);
  int vertex_face = 0;
  for (const auto& c : contacts) {
    if (c.feature != Feature::face_a && c.feature != Feature::face_b) continue;
    ++vertex_face;
    EXPECT_EQ(c.feature, Feature::face_a);
    EXPECT_NEAR(c.depth, 0.15, 1e-15);
    EXPECT_NEAR((c.normal - Vec3::UnitX()).norm(), 0, 1e-15);
  }
  EXPECT_EQ(vertex_face, 4);
  const PairContact apart = TypeParam::narrowphase(a, {&half, Pose{Eigen::Matrix3d::Identity(), Vec3(0.95, 0, 0)}},
                                                   Method::report, nullptr);
  EXPECT_FALSE(apart.intersect);
  EXPECT_NEAR(apart.depth, -0.2, 1e-15);
}

// Edge through edge (fig. 10): a turned 45° about x, b 45° about y, centres
// 1.4 apart along z. No vertex is inside the other body; the detector must find
// the crossing by segment–triangle and report an edge–edge contact with normal
// z (the cross product of the two edges, x × y) and depth √2 − 1.4.
TYPED_TEST_P(NarrowphaseCases, EdgeThroughEdge) {
  const core::Mesh cube = core::make_box({1, 1, 1});
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d ry = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()).toRotationMatrix();
  std::vector<collision::FeatureContact> contacts;
  const PairContact r = TypeParam::narrowphase({&cube, Pose{rx, Vec3::Zero()}}, {&cube, Pose{ry, Vec3(0, 0, 1.4)}},
                                               Method::report, &contacts);
  EXPECT_TRUE(r.intersect);
  EXPECT_EQ(r.feature, Feature::edge_edge);
  EXPECT_NEAR(r.depth, std::numbers::sqrt2 - 1.4, 1e-15);
  ASSERT_EQ(contacts.size(), 1u);
  EXPECT_EQ(contacts[0].feature, Feature::edge_edge);
  EXPECT_NEAR((contacts[0].normal - Vec3::UnitZ()).norm(), 0, 1e-15);
  EXPECT_NEAR(contacts[0].depth, std::numbers::sqrt2 - 1.4, 1e-15);
  EXPECT_NEAR((contacts[0].point - Vec3(0, 0, 0.7)).norm(), 0, 1e-15);
}

// Agreement with the exact reference on a corpus: yes/no outside the touching
// band for both methods (the report's detector and the separating-axis fast
// path), depth within 1e-9 × scale for overlapping pairs (the fast path prunes
// edge pairs and works in double; see core/collision/separating_axis.hpp for why 1e-9
// holds down to edges 1e-6 rad from parallel), and a normal along which the
// reference overlap equals the depth.
template <class Backend>
void expect_agreement(const std::vector<collision::CollisionCase>& cases, int* outside_band = nullptr) {
  int counted = 0;
  for (const auto& c : cases) {
    const auto ref = collision::sat_reference(c.a(), c.b());
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    if (std::abs(ref.depth) <= collision::kTouchingBand * scale) continue;
    ++counted;
    for (const Method m : {Method::report, Method::sat}) {
      const PairContact r = Backend::narrowphase(c.a(), c.b(), m, nullptr);
      ASSERT_EQ(r.intersect, ref.intersect) << c.name << (m == Method::report ? " (report)" : " (sat)")
                                            << " reference depth " << ref.depth;
      if (!ref.intersect) continue;
      EXPECT_NEAR(r.depth, ref.depth, 1e-9 * scale) << c.name;
      EXPECT_NEAR(r.normal.norm(), 1, 1e-12) << c.name;
      EXPECT_GT(r.normal.dot(ref.normal), 1 - 1e-6) << c.name;
    }
  }
  if (outside_band) *outside_band = counted;
}

TYPED_TEST_P(NarrowphaseCases, AgreesWithTheReferenceOnRandomHulls) {
  int counted = 0;
  expect_agreement<TypeParam>(collision::build_cases(collision::random_case_specs(99, 150), "random"), &counted);
  EXPECT_GT(counted, 140);
}

TYPED_TEST_P(NarrowphaseCases, AgreesWithTheReferenceFarFromTheOrigin) {
  expect_agreement<TypeParam>(
      collision::build_cases(collision::random_case_specs(5, 40, Vec3(1e4, -1e4, 1e4)), "random far"));
}

// The corpus under data/collision (the files `gacompare collide` reads).
TYPED_TEST_P(NarrowphaseCases, AgreesWithTheReferenceOnTheCorpus) {
  int files = 0;
  for (const auto& entry : std::filesystem::directory_iterator(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision")) {
    if (entry.path().extension() != ".json") continue;
    SCOPED_TRACE(entry.path().string());
    expect_agreement<TypeParam>(collision::load_cases(entry.path()));
    ++files;
  }
  EXPECT_GE(files, 2);
}

// ---- the contact manifold (core/collision/manifold.hpp) ----

// Two equal cubes face to face, b entering a's +x face by δ: the commonest
// contact, and the one fig. 7's detector gets wrong. The vertices of b's
// leading face lie on a's side faces (y, z = ±h) as much as behind its +x
// face, so §2.4.3's least-deep face is a side face at distance 0: the report's
// contacts carry a normal perpendicular to the motion (the cause of issue
// #12's slide bug, shown here). The manifold's contacts are the corners of
// the overlap square, along +x, each δ deep. Exact in binary but δ: 1e-15.
TYPED_TEST_P(NarrowphaseCases, ManifoldOfEqualCubesFaceToFace) {
  const core::Mesh cube = core::make_box({0.25, 0.25, 0.25});
  const double delta = 1e-5, h = 0.125;
  const Placed a{&cube, Pose{}}, b{&cube, Pose{Eigen::Matrix3d::Identity(), Vec3(2 * h - delta, 0, 0)}};
  std::vector<collision::FeatureContact> report, manifold;
  TypeParam::narrowphase(a, b, Method::report, &report);
  bool sideways = false;
  for (const auto& c : report) sideways |= std::abs(c.normal.x()) < 1e-12;
  EXPECT_TRUE(sideways) << "fig. 7 no longer takes a side face here: update manifold.hpp's account of the cause";
  const PairContact r = TypeParam::narrowphase(a, b, Method::manifold, &manifold);
  EXPECT_NEAR(r.depth, delta, 1e-15);
  ASSERT_EQ(manifold.size(), 4u);
  for (const auto& c : manifold) {
    EXPECT_NEAR((c.normal - Vec3::UnitX()).norm(), 0, 1e-15);
    EXPECT_NEAR(c.depth, delta, 1e-15);
    EXPECT_NEAR(c.point.x(), h - delta / 2, 1e-15);
    EXPECT_NEAR(std::abs(c.point.y()), h, 1e-15);
    EXPECT_NEAR(std::abs(c.point.z()), h, 1e-15);
  }
}

// The degenerate contact family at the level of one query: b offset
// sideways by 0, 1e-9 and 1e-3 of the size along y and z, and turned about
// the contact normal by 0, 1e-9 rad, 90° and 45°. Always: every contact along
// +x, δ deep, on the plane midway between the faces (within 1e-12: the turned
// corners are computed from sin and cos of the angle); the points lie in both
// faces (|y|, |z| ≤ h + offset in a's square, and in b's turned square); three
// or four of them; and their polygon holds the centre of the overlap (a box
// resting on them cannot tip). The same pair swapped gives the same points
// along −x (a's face is then the incident one).
TYPED_TEST_P(NarrowphaseCases, ManifoldOfTheDegenerateFamily) {
  const core::Mesh cube = core::make_box({0.25, 0.25, 0.25});
  const double delta = 1e-5, h = 0.125, size = 0.25;
  for (const double turn : {0.0, 1e-9, std::numbers::pi / 2, std::numbers::pi / 4})
    for (const double offset : {0.0, 1e-9 * size, 1e-3 * size})
      for (const Vec3 side : {Vec3::UnitY(), Vec3::UnitZ()}) {
        const Eigen::Matrix3d r = Eigen::AngleAxisd(turn, Vec3::UnitX()).toRotationMatrix();
        const Vec3 at = Vec3(2 * h - delta, 0, 0) + offset * side;
        for (const bool swapped : {false, true}) {
          const Placed a{&cube, Pose{}}, b{&cube, Pose{r, at}};
          std::vector<collision::FeatureContact> c;
          const PairContact res = swapped ? TypeParam::narrowphase(b, a, Method::manifold, &c)
                                          : TypeParam::narrowphase(a, b, Method::manifold, &c);
          const std::string name = "turn " + std::to_string(turn) + " offset " + std::to_string(offset) +
                                   (side.y() > 0 ? " y" : " z") + (swapped ? " swapped" : "");
          EXPECT_NEAR(res.depth, delta, 1e-12) << name;
          ASSERT_GE(c.size(), 3u) << name;
          ASSERT_LE(c.size(), 4u) << name;
          const Vec3 n = swapped ? Vec3(-Vec3::UnitX()) : Vec3::UnitX();
          Vec3 mean = Vec3::Zero();
          for (const auto& p : c) {
            EXPECT_NEAR((p.normal - n).norm(), 0, 1e-12) << name;
            EXPECT_NEAR(p.depth, delta, 1e-12) << name;
            EXPECT_NEAR(p.point.x(), h - delta / 2, 1e-12) << name;
            EXPECT_LE(p.point.cwiseAbs().tail<2>().maxCoeff(), h + 1e-12) << name;  // in a's face
            const Vec3 in_b = r.transpose() * (p.point - at);
            EXPECT_LE(in_b.cwiseAbs().tail<2>().maxCoeff(), h + 1e-12) << name;  // in b's face
            mean += p.point / static_cast<double>(c.size());
          }
          // The overlap's centre (offset/2 along the side) inside the points' hull:
          // on the inner side of every edge of the polygon they span (sorted by angle).
          std::vector<Vec3> ring;
          for (const auto& p : c) ring.push_back(p.point);
          std::sort(ring.begin(), ring.end(), [&](const Vec3& u, const Vec3& v) {
            return std::atan2(u.z() - mean.z(), u.y() - mean.y()) < std::atan2(v.z() - mean.z(), v.y() - mean.y());
          });
          const Vec3 centre(h - delta / 2, 0.5 * offset * side.y(), 0.5 * offset * side.z());
          for (std::size_t k = 0; k < ring.size(); ++k) {
            const Vec3 e = ring[(k + 1) % ring.size()] - ring[k];
            EXPECT_GT(Vec3::UnitX().dot(e.cross(centre - ring[k])), 0) << name;
          }
        }
      }
}

// Edge on edge (fig. 10, as EdgeThroughEdge): one contact, at the edges'
// closest points, along their common normal.
TYPED_TEST_P(NarrowphaseCases, ManifoldOfCrossedEdges) {
  const core::Mesh cube = core::make_box({1, 1, 1});
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()).toRotationMatrix();
  const Eigen::Matrix3d ry = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitY()).toRotationMatrix();
  std::vector<collision::FeatureContact> c;
  TypeParam::narrowphase({&cube, Pose{rx, Vec3::Zero()}}, {&cube, Pose{ry, Vec3(0, 0, 1.4)}}, Method::manifold, &c);
  ASSERT_EQ(c.size(), 1u);
  EXPECT_EQ(c[0].feature, Feature::edge_edge);
  EXPECT_NEAR((c[0].normal - Vec3::UnitZ()).norm(), 0, 1e-15);
  EXPECT_NEAR(c[0].depth, std::numbers::sqrt2 - 1.4, 1e-15);
  EXPECT_NEAR((c[0].point - Vec3(0, 0, 0.7)).norm(), 0, 1e-15);
}

// A box lying on another's edge: the lower box turned 45° about x, so its top
// is a ridge along x at z = √2/2; the upper box's bottom face 1e-5 below it.
// The upper face is the reference (its axis ties with the ridge × edge axes,
// and a face is preferred): two contacts on the ridge at the upper face's ends
// (x = ±0.5), along +z from the lower box (a) to the upper. Breaking the tie
// for the face keeps the box from being held at one point, which would rock it.
TYPED_TEST_P(NarrowphaseCases, ManifoldOfABoxOnARidge) {
  const core::Mesh cube = core::make_box({1, 1, 1});
  const Eigen::Matrix3d rx = Eigen::AngleAxisd(std::numbers::pi / 4, Vec3::UnitX()).toRotationMatrix();
  const double top = std::numbers::sqrt2 / 2, delta = 1e-5;
  std::vector<collision::FeatureContact> c;
  const PairContact r = TypeParam::narrowphase({&cube, Pose{rx, Vec3::Zero()}},
                                               {&cube, Pose{Eigen::Matrix3d::Identity(), Vec3(0, 0, top + 0.5 - delta)}},
                                               Method::manifold, &c);
  EXPECT_NEAR(r.depth, delta, 1e-12);
  ASSERT_EQ(c.size(), 2u);
  for (const auto& p : c) {
    EXPECT_NEAR((p.normal - Vec3::UnitZ()).norm(), 0, 1e-12);
    EXPECT_NEAR(p.depth, delta, 1e-12);
    EXPECT_NEAR(std::abs(p.point.x()), 0.5, 1e-12);
    EXPECT_NEAR(p.point.y(), 0, 1e-12);
  }
}

REGISTER_TYPED_TEST_SUITE_P(NarrowphaseCases, SegmentTriangleHandCase, SegmentTriangleMatchesALinearSolve,
                            CubesFaceToFace, EdgeThroughEdge, AgreesWithTheReferenceOnRandomHulls,
                            AgreesWithTheReferenceFarFromTheOrigin, AgreesWithTheReferenceOnTheCorpus,
                            ManifoldOfEqualCubesFaceToFace, ManifoldOfTheDegenerateFamily, ManifoldOfCrossedEdges,
                            ManifoldOfABoxOnARidge);

}  // namespace gacompare::testing
