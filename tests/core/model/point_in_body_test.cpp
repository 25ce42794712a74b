// Point in body (§2.4.3, §2.3.3): face planes against ray parity on random
// points, the boundary cases, and rays aimed at vertices and edges (fn 20).
#include "core/model/mesh.hpp"
#include "core/model/point_in_body.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <random>

namespace {

using namespace gacompare::core;

std::vector<Mesh> convex_shapes() {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4, Vec3(1, -2, 0.5).normalized()).toRotationMatrix();
  return {make_box({1, 2, 3}),       make_tetrahedron(1.5), make_pyramid(2, 1.5), make_octahedron(0.8),
          make_icosahedron(1.1),     make_box({1, 2, 3}).transformed(r, {0.3, -0.2, 5})};
}

TEST(PointInBody, PlanesAndParityAgreeOnRandomPoints) {
  std::mt19937_64 rng(20);
  for (const Mesh& m : convex_shapes()) {
    Eigen::AlignedBox3d box;
    for (const auto& v : m.vertices()) box.extend(v);
    const Vec3 lo = box.min() - 0.2 * box.sizes(), span = 1.4 * box.sizes();
    std::uniform_real_distribution<double> u(0, 1);
    // 1e-9 × size: far above rounding (1e-16 × size), and the chance that one of
    // 10,000 uniform points falls that close to the surface is ~1e-5.
    const double tol = 1e-9 * m.size();
    int inside = 0;
    for (int i = 0; i < 10000; ++i) {
      const Vec3 p = lo + span.cwiseProduct(Vec3(u(rng), u(rng), u(rng)));
      const Where a = classify_convex(m, p, tol);
      const ParityResult b = classify_by_parity(m, p, tol);
      ASSERT_EQ(a, b.where) << m.name() << " at " << p.transpose();
      inside += a == Where::inside;
    }
    EXPECT_GT(inside, 100) << m.name();  // the sample does test both answers
    EXPECT_LT(inside, 9900) << m.name();
  }
}

TEST(PointInBody, PointsOnFacesEdgesAndVerticesAreBoundary) {
  const Mesh box = make_box({2, 2, 2});
  const double tol = 1e-12;
  std::vector<Vec3> on;
  for (const auto& v : box.vertices()) on.push_back(v);            // vertices
  on.insert(on.end(), {{1, 1, 0}, {0, -1, 1}, {-1, 0.3, -1}});       // edges
  on.insert(on.end(), {{1, 0, 0}, {0.2, -1, 0.7}, {0.5, 0.5, 1}});  // faces, one on a triangulation diagonal
  for (const auto& p : on) {
    EXPECT_EQ(classify_convex(box, p, tol), Where::boundary) << p.transpose();
    EXPECT_EQ(classify_by_parity(box, p, tol).where, Where::boundary) << p.transpose();
    // Just inside and just outside (1e-6 along the outward diagonal of p).
    const Vec3 out = p.cwiseSign() * 1e-6;
    EXPECT_EQ(classify_convex(box, p - out, tol), Where::inside);
    EXPECT_EQ(classify_by_parity(box, p - out, tol).where, Where::inside) << p.transpose();
    EXPECT_EQ(classify_convex(box, p + out, tol), Where::outside);
    EXPECT_EQ(classify_by_parity(box, p + out, tol).where, Where::outside) << p.transpose();
  }
  // With no tolerance a point on the surface still gets an answer (either is right).
  for (const auto& p : on) EXPECT_NO_THROW(classify_by_parity(box, p, 0));
}

TEST(PointInBody, RaysThroughVerticesAndEdgesAreRejected) {
  const Mesh box = make_box({2, 2, 2});
  struct Case { Vec3 p, d; Where expected; };
  const Case cases[] = {
      {{0, 0, 0}, {1, 1, 1}, Where::inside},     // through a corner: 3 faces, 6 triangles meet there
      {{0, 0, 0}, {1, 1, 0}, Where::inside},     // through an edge between two faces
      {{0, 0, 0}, {1, 0, 0}, Where::inside},     // through a face centre, on its triangulation diagonal
      {{2, 1, 0}, {-1, 0, 0}, Where::outside},   // grazing: runs in the plane of the face y = 1
      {{2, 1, 1}, {-1, 0, 0}, Where::outside},   // along an edge: touches 4 triangles, enters none
      {{3, 3, 3}, {-1, -1, -1}, Where::outside}, // through two opposite corners
  };
  for (const auto& c : cases) {
    const ParityResult r = classify_by_parity(box, c.p, 1e-12, c.d);
    EXPECT_EQ(r.where, c.expected) << c.p.transpose() << " towards " << c.d.transpose();
    EXPECT_GE(r.directions_tried, 2) << "the aimed ray should have been rejected";
    EXPECT_GT((r.direction - c.d.normalized()).norm(), 1e-3);
  }
  // A clean first direction is kept.
  const ParityResult clean = classify_by_parity(box, {0.1, 0.2, 0.3}, 1e-12, Vec3(0.3, 0.5, 0.7));
  EXPECT_EQ(clean.directions_tried, 1);
  EXPECT_EQ(clean.crossings, 1);
  EXPECT_EQ(clean.where, Where::inside);
}

TEST(PointInBody, ParityWorksForNonConvexMeshes) {
  // The box of half-size 1 with its top face pushed into a pyramidal dent of
  // apex (0, 0, 0.5): inside iff |x|, |y|, |z| < 1 and z < 0.5 + 0.5 max(|x|, |y|).
  const Mesh box = make_box({2, 2, 2});
  std::vector<Vec3> v = box.vertices();
  v.emplace_back(0, 0, 0.5);
  std::vector<Triangle> t;
  for (std::size_t i = 0; i < box.triangles().size(); ++i)
    if (box.normals()[i].z() < 0.5) t.push_back(box.triangles()[i]);
  const int ring[] = {4, 5, 7, 6};
  for (int k = 0; k < 4; ++k) t.push_back({ring[k], ring[(k + 1) % 4], 8});
  const Mesh dented = Mesh::from_triangles("dented box", v, t);
  std::mt19937_64 rng(21);
  std::uniform_real_distribution<double> u(-1.3, 1.3);
  int inside = 0;
  for (int i = 0; i < 10000; ++i) {
    const Vec3 p(u(rng), u(rng), u(rng));
    const double top = 0.5 + 0.5 * std::max(std::abs(p.x()), std::abs(p.y()));
    const bool expected = p.cwiseAbs().maxCoeff() < 1 && p.z() < top;
    const Where w = classify_by_parity(dented, p, 1e-9).where;
    ASSERT_NE(w, Where::boundary) << p.transpose();
    ASSERT_EQ(w == Where::inside, expected) << p.transpose();
    inside += expected;
  }
  EXPECT_GT(inside, 1000);
  // Straight down through the dent's apex (a vertex shared by 4 triangles).
  const ParityResult r = classify_by_parity(dented, {0, 0, 0.9}, 1e-12, Vec3(0, 0, -1));
  EXPECT_EQ(r.where, Where::outside);
  EXPECT_GE(r.directions_tried, 2);
}

TEST(PointInBody, DistanceToTriangleMatchesRegions) {
  const Vec3 a(0, 0, 0), b(2, 0, 0), c(0, 2, 0);
  EXPECT_DOUBLE_EQ(distance_to_triangle({0.5, 0.5, 3}, a, b, c), 3);      // above the interior
  EXPECT_DOUBLE_EQ(distance_to_triangle({-3, -4, 0}, a, b, c), 5);        // nearest a vertex
  EXPECT_DOUBLE_EQ(distance_to_triangle({1, -2, 0}, a, b, c), 2);         // nearest an edge
  EXPECT_NEAR(distance_to_triangle({2, 2, 0}, a, b, c), std::sqrt(2.0), 1e-15);  // the hypotenuse
}

}  // namespace
