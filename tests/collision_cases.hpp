#pragma once
// Bounding spheres (core/collision/bounding_volume.hpp over a backend's
// SphereOps), checked against independent answers: an analytic minimal sphere
// (cube, box, regular tetrahedron and icosahedron, points on a sphere), an
// independent brute force (every circumsphere of 1–4 points, its centre solved
// in the points' affine hull by Eigen's QR: neither backend's formulas), the
// other backend, and a distance test for overlap. Instantiated per backend by
// tests/{traditional,cga}/bounding_volume_test.cpp with the backend's SphereOps.
//
// Tolerances (length units, relative to the set's scale L, its bounding-box
// diagonal):
//   kTol = 1e-9 · L for radii, centres and containment. The algorithms accept a
//   point outside a sphere by up to kBoundTol·L²/ρ ≤ 2√3·kBoundTol·L ≈ 3.5e-10 L
//   (core/collision/bounding_volume.hpp), so a returned radius may be that much below the
//   true minimum; the rounding of the constructions themselves is ~1e-14 L for
//   these well-separated points. 1e-9 is ~3× the designed slack; tighter would
//   test the slack, not the algorithm. Each test prints its worst error/kTol.
#include "cga/bounding_volume.hpp"
#include "core/collision/bounding_volume.hpp"
#include "traditional/bounding_volume.hpp"

#include <Eigen/Geometry>
#include <Eigen/QR>
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <numbers>
#include <optional>
#include <random>
#include <string>
#include <tuple>
#include <type_traits>
#include <vector>

namespace gacompare::testing {

using Vec3 = Eigen::Vector3d;
inline constexpr double kTol = 1e-9;

// The other backend's policy, for the agreement checks.
template <class Ops>
using OtherOps =
    std::conditional_t<std::is_same_v<Ops, traditional::SphereOps>, cga::SphereOps, traditional::SphereOps>;

struct Ball {
  Vec3 centre = Vec3::Zero();
  double radius = 0;
};

inline double scale_of(const std::vector<Vec3>& p) {
  const core::Aabb box = core::aabb_of(p);
  return (box.max - box.min).norm();
}

// The independent brute force: for every subset of 1 to 4 points, the sphere
// through them centred in their affine hull (c = p0 + U λ with UᵀU λ = ½ diag(UᵀU),
// U the differences to p0, solved by column-pivoting QR; rank-deficient subsets
// skipped), kept when every point is within ρ + 1e-10·L of its centre (the same
// slack as the algorithms', see kBoundTol); the smallest such sphere. O(n⁵).
inline Ball brute_force_minimum(const std::vector<Vec3>& p) {
  const double L = scale_of(p);
  const int n = static_cast<int>(p.size());
  std::optional<Ball> best;
  const auto consider = [&](const std::vector<int>& idx) {
    const int k = static_cast<int>(idx.size()) - 1;
    Ball b{p[static_cast<std::size_t>(idx[0])], 0};
    if (k > 0) {
      Eigen::MatrixXd U(3, k);
      for (int j = 0; j < k; ++j)
        U.col(j) = p[static_cast<std::size_t>(idx[static_cast<std::size_t>(j) + 1])] - b.centre;
      const Eigen::MatrixXd G = U.transpose() * U;
      Eigen::ColPivHouseholderQR<Eigen::MatrixXd> qr(G);
      qr.setThreshold(1e-12);
      if (qr.rank() < k) return;
      const Eigen::VectorXd lambda = qr.solve(Eigen::VectorXd(0.5 * G.diagonal()));
      const Vec3 c = b.centre + U * lambda;
      b = {c, (c - b.centre).norm()};
    }
    if (best && b.radius >= best->radius) return;
    for (const Vec3& x : p)
      if ((x - b.centre).norm() > b.radius + 1e-10 * L) return;
    best = b;
  };
  for (int i = 0; i < n; ++i) {
    consider({i});
    for (int j = i + 1; j < n; ++j) {
      consider({i, j});
      for (int k = j + 1; k < n; ++k) {
        consider({i, j, k});
        for (int l = k + 1; l < n; ++l) consider({i, j, k, l});
      }
    }
  }
  return *best;
}

// Worst observed error / tolerance, printed at the end of a test.
struct Worst {
  double ratio = 0;
  void see(double err, double tol) { ratio = std::max(ratio, err / tol); }
  ~Worst() { std::printf("[ worst error / tolerance: %.3g ]\n", ratio); }
};

// A sphere's centre and radius within kTol·L of the expected, and every point
// inside it within kTol·L.
template <class Ops>
::testing::AssertionResult matches(const typename Ops::Sphere& s, const std::vector<Vec3>& p, const Ball& want,
                                   Worst& worst) {
  const double L = std::max(scale_of(p), 1e-300), tol = kTol * L;
  const Vec3 c = Ops::centre(s);
  const double r = Ops::radius(s);
  const double ec = (c - want.centre).norm(), er = std::abs(r - want.radius);
  worst.see(ec, tol);
  worst.see(er, tol);
  if (!(ec <= tol && er <= tol))
    return ::testing::AssertionFailure() << Ops::name << ": centre " << c.transpose() << " radius " << r
                                         << ", want " << want.centre.transpose() << " radius " << want.radius
                                         << " (centre error " << ec << ", radius error " << er << ", tol " << tol
                                         << ")";
  for (const Vec3& x : p) {
    const double out = (x - c).norm() - r;
    worst.see(std::max(out, 0.0), tol);
    if (!(out <= tol))
      return ::testing::AssertionFailure() << Ops::name << ": point " << x.transpose() << " is " << out
                                           << " outside (tol " << tol << ")";
  }
  return ::testing::AssertionSuccess();
}

inline Eigen::Matrix3d random_rotation(std::mt19937_64& g) {
  std::normal_distribution<double> N;
  Eigen::Quaterniond q(N(g), N(g), N(g), N(g));
  q.normalize();
  return q.toRotationMatrix();
}

inline std::vector<Vec3> cube_vertices(const Vec3& half) {
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i)
    v.emplace_back((i & 1 ? 1 : -1) * half.x(), (i & 2 ? 1 : -1) * half.y(), (i & 4 ? 1 : -1) * half.z());
  return v;
}

template <class Ops>
class BoundingVolumeCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(BoundingVolumeCases);

// 200 seeded random sets of 4–12 points (a box of random aspect 0.2–3 per axis,
// anywhere within ±5 of the origin, so the local frame matters): Welzl and the
// exhaustive search both equal the independent brute force, and the other
// backend's Welzl sphere. Welzl does less work than the exhaustive search.
TYPED_TEST_P(BoundingVolumeCases, WelzlAndExhaustiveEqualTheBruteForceMinimum) {
  using Ops = TypeParam;
  std::mt19937_64 g(6);
  std::uniform_real_distribution<double> u(-1, 1), aspect(0.2, 3), site(-5, 5);
  std::uniform_int_distribution<int> count(4, 12);
  Worst worst;
  std::int64_t welzl_tests = 0, exhaustive_tests = 0;
  for (int set = 0; set < 200; ++set) {
    const Vec3 axes(aspect(g), aspect(g), aspect(g)), at(site(g), site(g), site(g));
    std::vector<Vec3> p(static_cast<std::size_t>(count(g)));
    for (Vec3& x : p) x = at + Vec3(u(g), u(g), u(g)).cwiseProduct(axes);
    const Ball want = brute_force_minimum(p);
    const auto w = core::welzl_sphere<Ops>(p, static_cast<std::uint64_t>(set));
    const auto e = core::exhaustive_sphere<Ops>(p);
    const auto o = core::welzl_sphere<OtherOps<Ops>>(p, static_cast<std::uint64_t>(set));
    EXPECT_TRUE(matches<Ops>(w.sphere, p, want, worst)) << "Welzl, set " << set;
    EXPECT_TRUE(matches<Ops>(e.sphere, p, want, worst)) << "exhaustive, set " << set;
    EXPECT_TRUE(matches<Ops>(w.sphere, p, {OtherOps<Ops>::centre(o.sphere), OtherOps<Ops>::radius(o.sphere)}, worst))
        << "the other backend, set " << set;
    welzl_tests += w.counters.containment_tests;
    exhaustive_tests += e.counters.containment_tests;
  }
  EXPECT_LT(welzl_tests, exhaustive_tests);
  std::printf("[ containment tests over the 200 sets: Welzl %lld, exhaustive %lld ]\n",
              static_cast<long long>(welzl_tests), static_cast<long long>(exhaustive_tests));
}

// The shuffle changes the path, not the answer.
TYPED_TEST_P(BoundingVolumeCases, WelzlDoesNotDependOnTheSeed) {
  using Ops = TypeParam;
  std::mt19937_64 g(7);
  std::uniform_real_distribution<double> u(-1, 1);
  std::vector<Vec3> p(40);
  for (Vec3& x : p) x = Vec3(u(g), u(g), u(g));
  const Ball want = brute_force_minimum(p);
  Worst worst;
  for (std::uint64_t seed = 0; seed < 20; ++seed)
    EXPECT_TRUE(matches<Ops>(core::welzl_sphere<Ops>(p, seed).sphere, p, want, worst)) << "seed " << seed;
}

// Sets whose minimal sphere is known in closed form, several with every vertex
// on it (the degenerate support sets: cocircular face vertices of a cube or a
// box, four coplanar icosahedron vertices), moved and rotated off the axes.
TYPED_TEST_P(BoundingVolumeCases, KnownMinimalSpheres) {
  using Ops = TypeParam;
  std::mt19937_64 g(8);
  const double phi = std::numbers::phi;
  struct Case {
    std::string name;
    std::vector<Vec3> points;
    Ball want;
  };
  std::vector<Case> cases;
  cases.push_back({"cube", cube_vertices(Vec3(1, 1, 1)), {Vec3::Zero(), std::sqrt(3.0)}});
  cases.push_back({"box 1x2x3", cube_vertices(Vec3(0.5, 1, 1.5)), {Vec3::Zero(), 0.5 * std::sqrt(14.0)}});
  cases.push_back({"regular tetrahedron",
                   {Vec3(1, 1, 1), Vec3(1, -1, -1), Vec3(-1, 1, -1), Vec3(-1, -1, 1)},
                   {Vec3::Zero(), std::sqrt(3.0)}});
  std::vector<Vec3> ico;
  for (double s : {-1.0, 1.0})
    for (double t : {-phi, phi}) {
      ico.emplace_back(0, s, t);
      ico.emplace_back(s, t, 0);
      ico.emplace_back(t, 0, s);
    }
  cases.push_back({"icosahedron", ico, {Vec3::Zero(), std::sqrt(1 + phi * phi)}});
  // 30 random points on a sphere and its 6 axis points (so the centre is inside
  // their hull and the sphere is their minimum): every point on the boundary.
  {
    std::normal_distribution<double> N;
    const Vec3 c(0.3, -0.2, 0.1);
    std::vector<Vec3> p;
    for (int i = 0; i < 30; ++i) p.push_back(c + 2 * Vec3(N(g), N(g), N(g)).normalized());
    for (int a = 0; a < 3; ++a)
      for (double s : {-2.0, 2.0}) p.push_back(c + s * Vec3::Unit(a));
    cases.push_back({"points on a sphere", p, {c, 2.0}});
  }
  // Interior points don't change the answer: a cube with a point cloud inside.
  {
    std::vector<Vec3> p = cube_vertices(Vec3(1, 1, 1));
    std::uniform_real_distribution<double> u(-0.99, 0.99);
    for (int i = 0; i < 12; ++i) p.emplace_back(u(g), u(g), u(g));
    cases.push_back({"cube with interior points", p, {Vec3::Zero(), std::sqrt(3.0)}});
  }
  // Coincident points: one point repeated (radius 0), and a cube with every vertex twice.
  cases.push_back({"one point repeated", std::vector<Vec3>(5, Vec3(1, 2, 3)), {Vec3(1, 2, 3), 0}});
  {
    std::vector<Vec3> p = cube_vertices(Vec3(1, 1, 1));
    p.insert(p.end(), p.begin(), p.end());
    cases.push_back({"cube, every vertex twice", p, {Vec3::Zero(), std::sqrt(3.0)}});
  }
  cases.push_back({"single point", {Vec3(-1, 0, 2)}, {Vec3(-1, 0, 2), 0}});
  cases.push_back({"two points", {Vec3(-1, 0, 2), Vec3(1, 2, 3)}, {Vec3(0, 1, 2.5), 1.5}});
  // Each case also rotated about its centre and moved to (3, −2, 5).
  const std::size_t base = cases.size();
  for (std::size_t i = 0; i < base; ++i) {
    const Eigen::Matrix3d R = random_rotation(g);
    const Vec3 t(3, -2, 5);
    Case moved{cases[i].name + ", rotated and moved", {}, {}};
    for (const Vec3& x : cases[i].points) moved.points.push_back(R * (x - cases[i].want.centre) + cases[i].want.centre + t);
    moved.want = {cases[i].want.centre + t, cases[i].want.radius};
    cases.push_back(moved);
  }
  Worst worst;
  for (const Case& c : cases) {
    for (std::uint64_t seed = 0; seed < 5; ++seed)
      EXPECT_TRUE(matches<Ops>(core::welzl_sphere<Ops>(c.points, seed).sphere, c.points, c.want, worst))
          << c.name << ", Welzl seed " << seed;
    EXPECT_TRUE(matches<Ops>(core::exhaustive_sphere<Ops>(c.points).sphere, c.points, c.want, worst))
        << c.name << ", exhaustive";
  }
}

// Collinear and coplanar sets (random lines and planes, exactly degenerate up
// to the rounding of the rotation): the 2-point sphere of the extremes, and the
// planar minimum (brute force) with its centre in the plane.
TYPED_TEST_P(BoundingVolumeCases, CollinearAndCoplanarSets) {
  using Ops = TypeParam;
  std::mt19937_64 g(9);
  std::uniform_real_distribution<double> u(-1, 1);
  Worst worst;
  for (int set = 0; set < 50; ++set) {
    const Vec3 a(u(g), u(g), u(g)), dir = Vec3(u(g), u(g), u(g)).normalized();
    std::vector<Vec3> line;
    double lo = 1e300, hi = -1e300;
    for (int i = 0; i < 8; ++i) {
      const double t = 2 * u(g);
      lo = std::min(lo, t), hi = std::max(hi, t);
      line.push_back(a + t * dir);
    }
    const Ball want{a + 0.5 * (lo + hi) * dir, 0.5 * (hi - lo)};
    EXPECT_TRUE(matches<Ops>(core::welzl_sphere<Ops>(line, static_cast<std::uint64_t>(set)).sphere, line, want, worst))
        << "collinear set " << set << ", Welzl";
    EXPECT_TRUE(matches<Ops>(core::exhaustive_sphere<Ops>(line).sphere, line, want, worst))
        << "collinear set " << set << ", exhaustive";

    const Eigen::Matrix3d R = random_rotation(g);
    std::vector<Vec3> plane;
    for (int i = 0; i < 10; ++i) plane.push_back(a + R * Vec3(u(g), u(g), 0));
    const Ball want_p = brute_force_minimum(plane);
    const auto w = core::welzl_sphere<Ops>(plane, static_cast<std::uint64_t>(set));
    EXPECT_TRUE(matches<Ops>(w.sphere, plane, want_p, worst)) << "coplanar set " << set << ", Welzl";
    EXPECT_TRUE(matches<Ops>(core::exhaustive_sphere<Ops>(plane).sphere, plane, want_p, worst))
        << "coplanar set " << set << ", exhaustive";
    // In the plane: the centre's height above it, within kTol of the set's scale.
    const double height = std::abs((R.col(2)).dot(Ops::centre(w.sphere) - a));
    EXPECT_LE(height, kTol * scale_of(plane)) << "coplanar set " << set;
  }
}

// Welzl's fallback for support sets that define no sphere (rounding can hand
// it these; exact arithmetic cannot): 3 collinear points get the 2-point
// sphere of the extremes, 4 cocircular ones the sphere of their circle, 4
// coplanar ones the planar minimum (here the hypotenuse's 2-point sphere of a
// right triangle, the fourth point inside). Tolerance: kTol of the set's size;
// containment tolerance 4e-10 = kBoundTol · L² for L = 2.
TYPED_TEST_P(BoundingVolumeCases, DegenerateSupportSetsGetTheSmallestSphereThroughThem) {
  using Ops = TypeParam;
  const auto check = [](std::vector<Vec3> p, const Ball& want) {
    std::vector<typename Ops::Point> q;
    for (const Vec3& x : p) q.push_back(Ops::point(x));
    core::BoundingCounters c;
    const auto s = core::detail::degenerate_support<Ops>(q.data(), static_cast<int>(q.size()), 1e-10 * 4, c);
    Worst worst;
    EXPECT_TRUE(matches<Ops>(s, p, want, worst));
    EXPECT_GT(c.spheres, 0);
  };
  check({Vec3(0, 0, 0), Vec3(2, 2, 2), Vec3(0.5, 0.5, 0.5)}, {Vec3(1, 1, 1), std::sqrt(3.0)});  // collinear
  check({Vec3(1, 2, 0.5), Vec3(1, 2, 0.5), Vec3(3, 2, 0.5)}, {Vec3(2, 2, 0.5), 1});            // coincident
  check({Vec3(1, 1, 0), Vec3(-1, 1, 0), Vec3(1, -1, 0), Vec3(-1, -1, 0)}, {Vec3::Zero(), std::sqrt(2.0)});  // cocircular
  check({Vec3(0, 0, 1), Vec3(1, 0, 1), Vec3(0, 1, 1), Vec3(0.3, 0.3, 1)}, {Vec3(0.5, 0.5, 1), std::sqrt(0.5)});  // coplanar
  check({Vec3(0, 0, 0), Vec3(1, 0, 0), Vec3(2, 0, 0), Vec3(3, 0, 0)}, {Vec3(1.5, 0, 0), 1.5});  // collinear four
}

// The report's exhaustive search stops at the first class in which a sphere
// contains every point (§2.4.1). Wrong for class 3: a regular tetrahedron
// (minimal sphere: the unit sphere, 4 points) with three nearly collinear
// points just below its base, on a circle of radius 20 whose sphere contains
// the whole set. The corrected search and Welzl find the unit sphere.
TYPED_TEST_P(BoundingVolumeCases, AThreePointSphereContainingAllNeedNotBeTheMinimum) {
  using Ops = TypeParam;
  const double s = std::sqrt(2.0 / 9), h = std::sqrt(2.0 / 3);
  std::vector<Vec3> p{Vec3(0, 0, 1), Vec3(2 * s, 0, -1.0 / 3), Vec3(-s, h, -1.0 / 3), Vec3(-s, -h, -1.0 / 3)};
  const Vec3 m(0, 0, -1.0 / 3 - 0.05 + 20);  // the big circle's centre, 20 above its lowest point
  const double st = 0.015, ct = std::sqrt(1 - st * st);
  const Vec3 q1 = m + 20 * Vec3(st, 0, -ct), q2 = m + 20 * Vec3(0, 0, -1), q3 = m + 20 * Vec3(-st, 0, -ct);
  p.insert(p.end(), {q1, q2, q3});
  for (const Vec3& x : {q1, q2, q3}) ASSERT_LT(x.norm(), 1.0);  // inside the tetrahedron's sphere
  // The class-3 sphere through them contains every point: the report would stop there.
  const auto big = Ops::sphere_3(Ops::point(q1), Ops::point(q2), Ops::point(q3));
  ASSERT_TRUE(big.has_value());
  EXPECT_NEAR(Ops::radius(*big), 20, 1e-9 * 20);  // 1e-9: rounding of a circle through points 0.3 apart, radius 20
  // tol 1e-9 (side units): q1, q2, q3 lie on it up to the rounding of side() at
  // the circle's size, 20² · eps ≈ 1e-13; every other point is inside by > 0.5.
  for (const Vec3& x : p) EXPECT_TRUE(Ops::contains(*big, Ops::point(x), 1e-9)) << x.transpose();
  Worst worst;
  const Ball want{Vec3::Zero(), 1.0};
  EXPECT_TRUE(matches<Ops>(core::exhaustive_sphere<Ops>(p).sphere, p, want, worst));
  EXPECT_TRUE(matches<Ops>(core::welzl_sphere<Ops>(p, 1).sphere, p, want, worst));
}

// The constructions one by one, against the other backend (centre and radius
// within kTol of size 1 inputs: both are closed forms with condition ≤ 1/sin ≤
// 1e3 for these draws, so rounding stays below 1e-12), and their degenerate
// inputs: collinear → no 3-point sphere, coplanar → no 4-point sphere.
TYPED_TEST_P(BoundingVolumeCases, ConstructionsAgreeWithTheOtherBackend) {
  using Ops = TypeParam;
  using O = OtherOps<Ops>;
  std::mt19937_64 g(10);
  std::uniform_real_distribution<double> u(-1, 1);
  Worst worst;
  const auto same = [&](const typename Ops::Sphere& a, const typename O::Sphere& b, const char* what, int i) {
    const double ec = (Ops::centre(a) - O::centre(b)).norm(), er = std::abs(Ops::radius(a) - O::radius(b));
    worst.see(ec, kTol);
    worst.see(er, kTol);
    EXPECT_LE(ec, kTol) << what << " " << i;
    EXPECT_LE(er, kTol) << what << " " << i;
  };
  for (int i = 0; i < 1000; ++i) {
    const Vec3 a(u(g), u(g), u(g)), b(u(g), u(g), u(g)), c(u(g), u(g), u(g)), d(u(g), u(g), u(g));
    const Vec3 ab = b - a, ac = c - a, ad = d - a;
    if (ab.norm() < 0.1 || ac.norm() < 0.1 || ab.cross(ac).norm() < 1e-3 * ab.norm() * ac.norm() ||
        std::abs(ab.dot(ac.cross(ad))) < 1e-3 * ab.norm() * ac.norm() * ad.norm())
      continue;  // keep the condition ≤ 1e3 (see above)
    const auto A = Ops::point(a), B = Ops::point(b), C = Ops::point(c), D = Ops::point(d);
    const auto A2 = O::point(a), B2 = O::point(b), C2 = O::point(c), D2 = O::point(d);
    same(Ops::sphere_2(A, B), O::sphere_2(A2, B2), "sphere_2", i);
    const auto s3 = Ops::sphere_3(A, B, C);
    const auto o3 = O::sphere_3(A2, B2, C2);
    ASSERT_TRUE(s3 && o3) << i;
    same(*s3, *o3, "sphere_3", i);
    const auto s4 = Ops::sphere_4(A, B, C, D);
    const auto o4 = O::sphere_4(A2, B2, C2, D2);
    ASSERT_TRUE(s4 && o4) << i;
    same(*s4, *o4, "sphere_4", i);
    // Every defining point on its sphere: side() = ½(|x − c|² − ρ²) at rounding
    // level, a few eps of the squares it subtracts (ρ reaches ~1e3 for the
    // flattest draws): tol 1e-12 · max(1, ρ²).
    const double t3 = 1e-12 * std::max(1.0, Ops::radius(*s3) * Ops::radius(*s3));
    const double t4 = 1e-12 * std::max(1.0, Ops::radius(*s4) * Ops::radius(*s4));
    for (const auto& X : {A, B, C}) {
      EXPECT_TRUE(Ops::contains(*s3, X, t3)) << i;
      EXPECT_TRUE(Ops::contains(*s4, X, t4)) << i;
    }
    EXPECT_TRUE(Ops::contains(*s4, D, t4)) << i;
    // sphere() round trip.
    same(Ops::sphere(a, 0.7), O::sphere(a, 0.7), "sphere", i);
  }
  // Degenerate: collinear (exactly, and up to rounding of a rotated line), coplanar.
  const auto P = [](const Vec3& x) { return Ops::point(x); };
  EXPECT_FALSE(Ops::sphere_3(P(Vec3(0, 0, 0)), P(Vec3(1, 1, 1)), P(Vec3(3, 3, 3))));
  EXPECT_FALSE(Ops::sphere_3(P(Vec3(0, 1, 0)), P(Vec3(0, 1, 0)), P(Vec3(3, 3, 3))));  // coincident
  const Vec3 dir = Vec3(0.3, -0.7, 0.2).normalized();
  EXPECT_FALSE(Ops::sphere_3(P(Vec3(1, 2, 3)), P(Vec3(1, 2, 3) + 0.3 * dir), P(Vec3(1, 2, 3) + 1.9 * dir)));
  EXPECT_FALSE(Ops::sphere_4(P(Vec3(1, 1, 1)), P(Vec3(1, -1, 1)), P(Vec3(-1, 1, 1)), P(Vec3(-1, -1, 1))));  // cocircular
  EXPECT_FALSE(Ops::sphere_4(P(Vec3(0, 0, 0)), P(Vec3(1, 0, 0)), P(Vec3(0, 1, 0)), P(Vec3(2, 3, 0))));  // coplanar
  // Coincident points: a sphere of radius 0.
  EXPECT_EQ(Ops::radius(Ops::sphere_2(P(Vec3(1, 2, 3)), P(Vec3(1, 2, 3)))), 0.0);
}

// contains(): the report's convention (inside < 0) with the tolerance in side()
// units, ½(|x − c|² − ρ²): a point at distance ρ + δ is inside within tol
// exactly when ρδ + δ²/2 ≤ tol.
TYPED_TEST_P(BoundingVolumeCases, ContainsUsesTheSideConvention) {
  using Ops = TypeParam;
  const auto s = Ops::sphere(Vec3(1, 2, 3), 2.0);
  const auto at = [](double r) { return Ops::point(Vec3(1, 2, 3) + r * Vec3(0.6, 0, 0.8)); };
  EXPECT_TRUE(Ops::contains(s, at(0), 0));
  EXPECT_TRUE(Ops::contains(s, at(1.9), 0));
  EXPECT_FALSE(Ops::contains(s, at(2.1), 0));
  // δ = 1e-3: side = 2e-3 + 5e-7; rounding of side ~1e-15, far from either threshold.
  EXPECT_TRUE(Ops::contains(s, at(2.001), 2.0006e-3));
  EXPECT_FALSE(Ops::contains(s, at(2.001), 2.0004e-3));
}

// overlap() and balls_overlap() against the distance test |c1 − c2| ≤ ρ1 + ρ2 on 20,000 random
// pairs (centres within ±2, radii 0.05–1.5: apart, crossing and nested), of
// which a third are drawn nested (one sphere strictly inside the other) and a
// few concentric. Outside the touching band |d − (ρ1 + ρ2)| ≤ 1e-9·(scale),
// scale = |c1| + |c2| + ρ1 + ρ2: there the conformal test's sign is decided by
// rounding (its B² ∝ (ρ1+ρ2)·gap is computed from components of size scale²,
// rounding ~1e-15·scale², so the gap's sign is resolved above ~1e-14·scale).
// Exactly touching spheres (integer data, exact in both algebras) overlap.
TYPED_TEST_P(BoundingVolumeCases, OverlapAgreesWithTheDistanceTest) {
  using Ops = TypeParam;
  std::mt19937_64 g(11);
  std::uniform_real_distribution<double> u(-2, 2), rad(0.05, 1.5), f(0, 1);
  int checked = 0, nested = 0, apart = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 c1(u(g), u(g), u(g));
    const double r1 = rad(g);
    Vec3 c2(u(g), u(g), u(g));
    double r2 = rad(g);
    if (i % 3 == 0) {  // nested: r2 < r1 − d
      c2 = c1 + 0.45 * r1 * f(g) * Vec3(u(g), u(g), u(g)).normalized();  // d ≤ 0.45 ρ1
      r2 = (r1 - (c2 - c1).norm()) * (0.05 + 0.9 * f(g));                    // ρ2 < ρ1 − d
      if (i % 30 == 0) c2 = c1;  // concentric
    }
    const double d = (c2 - c1).norm();
    const double scale = c1.norm() + c2.norm() + r1 + r2;
    if (std::abs(d - (r1 + r2)) <= 1e-9 * scale) continue;
    const bool want = d <= r1 + r2;
    const auto s1 = Ops::sphere(c1, r1), s2 = Ops::sphere(c2, r2);
    EXPECT_EQ(Ops::overlap(s1, s2), want) << i << ": d " << d << " r1 " << r1 << " r2 " << r2;
    EXPECT_EQ(Ops::overlap(s2, s1), want) << i;
    EXPECT_EQ(Ops::balls_overlap(s1, r1, s2, r2), want) << i << ": d " << d << " r1 " << r1 << " r2 " << r2;
    EXPECT_EQ(Ops::balls_overlap(s2, r2, s1, r1), want) << i;
    ++checked;
    nested += d < std::abs(r1 - r2);
    apart += !want;
  }
  EXPECT_GT(nested, 5000);
  EXPECT_GT(apart, 3000);
  std::printf("[ %d pairs: %d nested, %d apart ]\n", checked, nested, apart);
  // Exactly touching, outside and inside; a point (radius 0) on a sphere.
  EXPECT_TRUE(Ops::overlap(Ops::sphere(Vec3(0, 0, 0), 1), Ops::sphere(Vec3(2, 0, 0), 1)));
  EXPECT_TRUE(Ops::overlap(Ops::sphere(Vec3(0, 0, 0), 2), Ops::sphere(Vec3(1, 0, 0), 1)));
  EXPECT_TRUE(Ops::overlap(Ops::sphere(Vec3(0, 0, 0), 2), Ops::sphere_2(Ops::point(Vec3(0, 2, 0)), Ops::point(Vec3(0, 2, 0)))));
  EXPECT_FALSE(Ops::overlap(Ops::sphere(Vec3(0, 0, 0), 1), Ops::sphere(Vec3(2.5, 0, 0), 1)));
  EXPECT_TRUE(Ops::balls_overlap(Ops::sphere(Vec3(0, 0, 0), 1), 1, Ops::sphere(Vec3(2, 0, 0), 1), 1));
  EXPECT_TRUE(Ops::balls_overlap(Ops::sphere(Vec3(0, 0, 0), 2), 2, Ops::sphere(Vec3(1, 0, 0), 1), 1));
  EXPECT_TRUE(Ops::balls_overlap(Ops::sphere(Vec3(0, 0, 0), 2), 2, Ops::sphere(Vec3(0, 0, 0), 0), 0));
  EXPECT_FALSE(Ops::balls_overlap(Ops::sphere(Vec3(0, 0, 0), 1), 1, Ops::sphere(Vec3(2.5, 0, 0), 1), 1));
}

// The sphere trees' node operations (core/collision/tree_broadphase.hpp)
// against a closed form evaluated in long double from the centres and radii
// (the smallest ball holding two balls: the larger one if it holds the other,
// else R = ½(d + ρ1 + ρ2) centred on the line of centres), against the
// distance test for encloses (d ≤ ρo − ρi), and against the other backend, on
// 20,000 pairs like OverlapAgreesWithTheDistanceTest's (centres within ±2,
// radii 0.05–1.5; a third nested, some concentric). Tolerance 1e-11: inputs of
// size s ≤ 5; the conformal forms read radii from inner products of
// components up to ½s², whose rounding ~ε·s⁴ ≈ 1.4e-13 becomes ~ε·s⁴/ρ ≤
// 3e-12 in a radius of 0.05 (the traditional forms: ~1e-15). encloses is
// compared outside the band where the conformal test's sign is rounding's: it
// decides by So·Si − ρoρi = ½((ρo − ρi)² − d²), read from products of size
// s² (rounding ~1e-15·s²), so outside |(ρo − ρi)² − d²| ≤ 1e-13·s². (Near
// coincident centres that band is a room ρo − ρi of √1e-13·s ≈ 3e-7·s: the
// conformal form cannot tell nearly equal concentric spheres apart more
// finely; the tree's fat volumes leave a room of 0.4 ρ.)
TYPED_TEST_P(BoundingVolumeCases, TreeNodeOperationsAgreeWithTheDistances) {
  using Ops = TypeParam;
  using O = OtherOps<Ops>;
  const double tol = 1e-11;
  std::mt19937_64 g(15);
  std::uniform_real_distribution<double> u(-2, 2), rad(0.05, 1.5), f(0, 1), by(0, 0.5);
  Worst worst;
  int nested = 0, checked = 0;
  for (int i = 0; i < 20000; ++i) {
    const Vec3 c1(u(g), u(g), u(g));
    const double r1 = rad(g);
    Vec3 c2(u(g), u(g), u(g));
    double r2 = rad(g);
    if (i % 3 == 0) {
      c2 = c1 + 0.45 * r1 * f(g) * Vec3(u(g), u(g), u(g)).normalized();
      r2 = (r1 - (c2 - c1).norm()) * (0.05 + 0.9 * f(g));
      if (i % 30 == 0) c2 = c1;
    }
    long double d2 = 0;
    for (int k = 0; k < 3; ++k) d2 += (static_cast<long double>(c2[k]) - c1[k]) * (static_cast<long double>(c2[k]) - c1[k]);
    const long double d = std::sqrt(d2);
    Vec3 want_c;
    long double want_r;
    if (d + r2 <= r1) want_c = c1, want_r = r1;
    else if (d + r1 <= r2) want_c = c2, want_r = r2;
    else {
      want_r = 0.5L * (d + r1 + r2);
      const long double t = (want_r - r1) / d;
      for (int k = 0; k < 3; ++k) want_c[k] = static_cast<double>(c1[k] + t * (static_cast<long double>(c2[k]) - c1[k]));
    }
    const auto s1 = Ops::sphere(c1, r1), s2 = Ops::sphere(c2, r2);
    const auto e = Ops::enclosing(s1, s2);
    const double ec = (Ops::centre(e) - want_c).norm(), er = std::abs(Ops::radius(e) - static_cast<double>(want_r));
    worst.see(ec, tol), worst.see(er, tol);
    EXPECT_LE(ec, tol) << i;
    EXPECT_LE(er, tol) << i;
    const auto swapped = Ops::enclosing(s2, s1);
    EXPECT_LE((Ops::centre(swapped) - Ops::centre(e)).norm(), tol) << i;
    EXPECT_NEAR(Ops::radius(swapped), Ops::radius(e), tol) << i;
    const auto eo = O::enclosing(O::sphere(c1, r1), O::sphere(c2, r2));
    EXPECT_LE((Ops::centre(e) - O::centre(eo)).norm(), tol) << i;
    EXPECT_NEAR(Ops::radius(e), O::radius(eo), tol) << i;
    EXPECT_NEAR(Ops::radius_squared(e), Ops::radius(e) * Ops::radius(e), 2 * tol) << i;
    const double grow = by(g);
    const auto grown = Ops::grown(s1, grow);
    EXPECT_LE((Ops::centre(grown) - c1).norm(), tol) << i;
    EXPECT_NEAR(Ops::radius(grown), r1 + grow, tol) << i;
    const double scale = c1.norm() + c2.norm() + r1 + r2;
    for (const auto& [outer, inner, ro, ri] : {std::tuple{s1, s2, r1, r2}, std::tuple{s2, s1, r2, r1}}) {
      if (std::abs((ro - ri) * (ro - ri) - static_cast<double>(d2)) <= 1e-13 * scale * scale) continue;
      EXPECT_EQ(Ops::encloses(outer, inner), d <= ro - ri) << i;
      ++checked;
      nested += d <= ro - ri;
    }
    // The enclosing sphere holds both, once they are shrunk by 1e-6·s (the
    // band above).
    EXPECT_TRUE(Ops::encloses(e, Ops::grown(s1, -1e-6 * scale)) && Ops::encloses(e, Ops::grown(s2, -1e-6 * scale)))
        << i;
  }
  EXPECT_GT(nested, 5000);
  std::printf("[ encloses: %d cases, %d nested ]\n", checked, nested);
  // Exact cases (integers): internally tangent and equal spheres are enclosed;
  // coincident centres give the larger sphere; externally tangent give the
  // sphere through both far points.
  const auto S = [](double x, double r) { return Ops::sphere(Vec3(x, 0, 0), r); };
  EXPECT_TRUE(Ops::encloses(S(0, 2), S(1, 1)));
  EXPECT_TRUE(Ops::encloses(S(0, 1), S(0, 1)));
  EXPECT_FALSE(Ops::encloses(S(0, 1), S(0, 2)));
  EXPECT_FALSE(Ops::encloses(S(0, 2), S(1.5, 1)));
  EXPECT_EQ(Ops::radius(Ops::enclosing(S(0, 1), S(0, 1))), 1.0);
  EXPECT_EQ(Ops::radius(Ops::enclosing(S(3, 1), S(3, 2))), 2.0);
  EXPECT_EQ(Ops::radius(Ops::enclosing(S(0, 1), S(2, 1))), 2.0);
  EXPECT_EQ(Ops::centre(Ops::enclosing(S(0, 1), S(2, 1))), Vec3(1, 0, 0));
}

REGISTER_TYPED_TEST_SUITE_P(BoundingVolumeCases, WelzlAndExhaustiveEqualTheBruteForceMinimum,
                            WelzlDoesNotDependOnTheSeed, KnownMinimalSpheres, CollinearAndCoplanarSets,
                            DegenerateSupportSetsGetTheSmallestSphereThroughThem,
                            AThreePointSphereContainingAllNeedNotBeTheMinimum, ConstructionsAgreeWithTheOtherBackend,
                            ContainsUsesTheSideConvention, OverlapAgreesWithTheDistanceTest,
                            TreeNodeOperationsAgreeWithTheDistances);

}  // namespace gacompare::testing
