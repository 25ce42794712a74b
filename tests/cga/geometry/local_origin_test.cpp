// The precision remedy (local_origin.hpp): at 1e6 from the origin the conformal
// operations lose their digits (they round at the size of |x|², see
// bench/geometry_precision), and building the entities in a local origin near
// the feature gives them back.
//
// Tolerance: at distance D the inputs and outputs themselves are doubles of size
// D, rounded to eps·D (≈ 1.1e-10 at D = 1e6); the traditional twin's answers sit
// at that floor. The remedied conformal answers must agree with the twin within
// kC·eps·D (5.7e-8 at 1e6) on well-conditioned cases (κ ≤ ~3 by rejection); the
// unremedied ones are shown to be off by far more than that (≥ 1e-3 for all but
// the plane–plane meet, whose dual planes carry no |x|² at all).
#include "cases.hpp"
#include "cga/geometry/geometry.hpp"
#include "traditional/geometry.hpp"

namespace gacompare {
namespace {
namespace C = cga;
namespace L = cga::local;
namespace T = traditional;
using geometry::Kind;
using namespace geometry::testing;

constexpr double kFar = 1e6;
constexpr int kFarCases = 500;

struct Far {
  Rng rng{331};
  Vec3 site() { return kFar * rng.unit(); }
};

double dist(const Vec3& a, const Vec3& b) { return (a - b).norm(); }

TEST(LocalOrigin, RestoresRoundsAt1e6) {
  Far f;
  const double tol = kC * kEps * kFar;
  double plain = 0;
  int n = 0;
  while (n < kFarCases) {
    const Vec3 s = f.site();
    const Vec3 a = s + f.rng.point(1), b = s + f.rng.point(1), c = s + f.rng.point(1), d = s + f.rng.point(1);
    const Vec3 u = b - a, v = c - a, w = d - a;
    if (min_distance({a, b, c, d}) < 0.5 || u.cross(v).norm() < 0.3 * u.norm() * v.norm() ||
        std::abs(u.dot(v.cross(w))) < 0.3 * u.norm() * v.norm() * w.norm())
      continue;
    ++n;
    const auto t = T::circumcircle(a, b, c);
    const auto l = L::circumcircle(a, b, c);
    ASSERT_EQ(l.kind, Kind::circle);
    ASSERT_TRUE(near(l.centre, t.centre, tol, "circumcircle centre"));
    ASSERT_TRUE(near(l.radius, t.radius, tol, "circumcircle radius"));
    plain = std::max(plain, dist(C::circumcircle(a, b, c).centre, t.centre));
    const auto ts = T::sphere_through(a, b, c, d);
    const auto ls = L::sphere_through(a, b, c, d);
    ASSERT_EQ(ls.kind, Kind::sphere);
    ASSERT_TRUE(near(ls.centre, ts.centre, tol, "sphere centre"));
    ASSERT_TRUE(near(ls.radius, ts.radius, tol, "sphere radius"));
  }
  std::printf("[ circumcentre error without the remedy: %.2g ]\n", plain);
  EXPECT_GT(plain, 1e-3);
}

TEST(LocalOrigin, RestoresMeetsAt1e6) {
  Far f;
  const double tol = kC * kEps * kFar;
  int n = 0;
  while (n < kFarCases) {
    const Vec3 s = f.site();
    const Vec3 c1 = s + f.rng.point(0.5), c2 = c1 + f.rng.uniform(0.5, 1.5) * f.rng.unit();
    const Vec3 a = s + f.rng.point(1), b = s + f.rng.point(1), nrm = f.rng.unit();
    const double off = nrm.dot(c1) + f.rng.uniform(-0.5, 0.5);
    if (dist(a, b) < 0.5 || std::abs(nrm.dot((b - a).normalized())) < 0.3) continue;
    ++n;
    // Two unit spheres 0.5–1.5 apart: a circle of radius ≥ 0.66 (sin ≥ 0.75).
    const auto tss = T::meet_sphere_sphere(T::sphere(c1, 1), T::sphere(c2, 1));
    const auto lss = L::meet_sphere_sphere(c1, 1, c2, 1);
    ASSERT_EQ(lss.kind, Kind::circle);
    ASSERT_TRUE(near(lss.centre, tss.centre, tol, "sphere–sphere centre"));
    ASSERT_TRUE(near(lss.radius, tss.radius, tol, "sphere–sphere radius"));
    // The plain conformal meet cannot even resolve a unit sphere at 1e6 (ρ² is
    // below the rounding of its ½|c|² components): typed, not wrong.
    EXPECT_EQ(C::meet_sphere_sphere(C::sphere(c1, 1), C::sphere(c2, 1)).kind, Kind::degenerate);
    // A unit sphere and a plane through it at |h| ≤ 0.5: sin ≥ 0.86.
    const auto tsp = T::meet_sphere_plane(T::sphere(c1, 1), T::plane(nrm, off));
    const auto lsp = L::meet_sphere_plane(c1, 1, nrm, off);
    ASSERT_EQ(lsp.kind, Kind::circle);
    ASSERT_TRUE(near(lsp.centre, tsp.centre, tol, "sphere–plane centre"));
    ASSERT_TRUE(near(lsp.radius, tsp.radius, tol, "sphere–plane radius"));
    // A line at ≥ 0.3 rad to the plane.
    const auto tlp = T::meet_line_plane(*T::line_through(a, b), T::plane(nrm, off));
    const auto llp = L::meet_line_plane(a, b, nrm, off);
    ASSERT_EQ(llp.kind, Kind::point);
    ASSERT_TRUE(near(llp.point, tlp.point, tol * (1 + dist(tlp.point, a)), "line–plane"));
    // The line through the first sphere's centre (offset ≤ 0.3): a chord.
    const Vec3 m = c1 + 0.3 * f.rng.unit();
    const auto tls = T::meet_line_sphere(*T::line_through(m, m + (b - a)), T::sphere(c1, 1));
    const auto lls = L::meet_line_sphere(m, m + (b - a), c1, 1);
    ASSERT_EQ(lls.kind, Kind::point_pair);
    ASSERT_TRUE(near(lls.first, tls.first, tol, "line–sphere first"));
    ASSERT_TRUE(near(lls.second, tls.second, tol, "line–sphere second"));
  }
}

TEST(LocalOrigin, RestoresReflectionsAndInsideAt1e6) {
  Far f;
  const double tol = kC * kEps * kFar;
  double plain = 0, plain_side = 0;
  for (int k = 0; k < kFarCases; ++k) {
    const Vec3 s = f.site();
    const Vec3 x = s + f.rng.point(1), a = s + f.rng.point(1), b = s + f.rng.point(1), c = s + f.rng.point(0.3);
    if (dist(a, b) < 0.5 || dist(x, c) < 0.5) continue;
    const Vec3 nrm = f.rng.unit();
    const double off = nrm.dot(s) + f.rng.uniform(-1, 1);
    const auto lt = *T::line_through(a, b);
    const Vec3 tp = T::reflect_in_plane(x, T::plane(nrm, off));
    ASSERT_TRUE(near(L::reflect_in_plane(x, nrm, off), tp, tol, "plane"));
    ASSERT_TRUE(near(L::reflect_in_line(x, a, b), T::reflect_in_line(x, lt), tol, "line"));
    ASSERT_TRUE(near(L::nearest_on_line(x, a, b), T::nearest_on_line(x, lt), tol, "nearest"));
    const auto ts = T::reflect_in_sphere(x, T::sphere(c, 1));
    const auto ls = L::reflect_in_sphere(x, c, 1);
    ASSERT_EQ(ls.kind, Kind::point);
    ASSERT_TRUE(near(ls.point, ts.point, tol * 16, "sphere"));  // κ = (1 + ρ²/|x−c|²)² ≤ 16 (|x−c| ≥ ½ρ)
    // side() is a difference of squares: its absolute error is eps·(feature)²
    // in the local origin, eps·D² without it.
    ASSERT_TRUE(near(L::side(c, 1, x), T::side(T::sphere(c, 1), x), kC * kEps * 16, "side"));
    plain = std::max(plain, dist(C::nearest_on_line(x, *C::line_through(a, b)), T::nearest_on_line(x, lt)));
    plain_side = std::max(plain_side, std::abs(C::side(C::sphere(c, 1), x) - T::side(T::sphere(c, 1), x)));
  }
  std::printf("[ without the remedy: nearest point error %.2g, side error %.2g ]\n", plain, plain_side);
  EXPECT_GT(plain, 1e-3);
  EXPECT_GT(plain_side, 1e-3);
}

TEST(LocalOrigin, WorldResultsAndPlanes) {
  // Round trips of the frame change itself, in exact binary arithmetic.
  const C::LocalOrigin o{{1024, -2048, 4096}};
  EXPECT_TRUE(near(o.world(o.local({1, 2, 3})), {1, 2, 3}, 0));
  const auto p = o.plane({0, 0, 2}, 8192);  // z = 4096: through the origin of the frame
  EXPECT_EQ(C::offset(p), 0);
  const auto line = L::meet_plane_plane({0, 0, 1}, 4096, {1, 0, 0}, 1024, {1000, 7, 4000});
  EXPECT_EQ(line.kind, Kind::line);
  EXPECT_TRUE(near(line.point, {1024, 0, 4096}, 0));  // nearest the world origin
  EXPECT_TRUE(near(line.direction, {0, 1, 0}, 0));
}

}  // namespace
}  // namespace gacompare
