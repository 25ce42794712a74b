#pragma once
// Seeded random cases and the shared error model of the geometry tests.
//
// Tolerance model (one formula, stated once, used by every comparison):
//   |cga − traditional| ≤ kC · eps · A^k · κ · size
// eps   double's unit roundoff (2.2e-16).
// A     1 + max|x|²/ℓ² over the inputs, ℓ their smallest pairwise distance (the
//       feature size; generators keep ℓ ≥ 0.1 by rejection).
//       The conformal embedding carries ½|x|² next to x, so conformal products
//       round at the size of powers of |x|² while the answer is of size ℓ; the
//       traditional twins work with differences and lose at most |x|/ℓ.
// k     how many powers of A an operation's conformal chain amplifies rounding
//       by, per operation: 1 for one point against one entity (reflection in a
//       plane or sphere, inside), 1.5 for lines (a 3-blade of two points and n),
//       2.5 for rounds through points (a 3- or 4-blade reflected: K n K). These
//       are the growth laws that bench/geometry_precision measures (error ∝ D^2k
//       at distance D): the price of the embedding, and the reason for the
//       local-origin remedy; the cases here stay within |x| ≲ 5 (A ≤ 30).
// κ     the problem's own condition number, 1/sin of the angle that vanishes at
//       its degeneracy (the same sin as the kSinTol predicates): near-degenerate
//       cases are ill-conditioned for both backends alike, and the bound grows
//       with them instead of being loosened for them.
// size  the magnitude of the compared quantity (a radius, |point| + ρ, …).
// kC    256: a first-order bound counts one eps per rounding along the longest
//       chain (three outer products, a dual, a sandwich kept to grade 1, the
//       division by the weight: of the order of a hundred multiply-adds), with a
//       margin for the traditional side's own rounding. Not fitted to pass: each
//       test prints the worst error/tolerance ratio it saw.
#include <gtest/gtest.h>
#include <Eigen/Core>

#include <algorithm>
#include <cmath>
#include <limits>
#include <random>
#include <string>

namespace gacompare::geometry::testing {

using Vec3 = Eigen::Vector3d;
inline constexpr double kEps = std::numeric_limits<double>::epsilon();
inline constexpr double kC = 256;
// ≥ 10,000 random cases per operation, near-degenerate ones on top.
// A draw a test rejects (features closer than ℓ = 0.1) is redrawn (`--k`), so
// every loop compares kCases accepted cases.
inline constexpr int kCases = 10000;
inline constexpr int kNearCases = 2000;

struct Rng {
  std::mt19937_64 g;
  explicit Rng(std::uint64_t seed) : g(seed) {}  // fixed per test: failures replay
  double uniform(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
  Vec3 point(double r) { return {uniform(-r, r), uniform(-r, r), uniform(-r, r)}; }
  Vec3 unit() {
    for (;;) {
      const Vec3 v = point(1);
      const double n = v.norm();
      if (n > 0.1 && n <= 1) return v / n;
    }
  }
  // A unit vector perpendicular to u.
  Vec3 perpendicular(const Vec3& u) {
    for (;;) {
      const Vec3 v = unit().cross(u);
      if (v.norm() > 0.1 * u.norm()) return v.normalized();
    }
  }
  // Where a case sits: near the origin for most cases, up to 3.5 away for some,
  // with features of size ~1 around it (|x| ≲ 5, A ≤ 30).
  Vec3 site() { return uniform(0, 1) < 0.75 ? point(0.5) : point(2); }
};

// A^k of the inputs.
inline double amplification(std::initializer_list<Vec3> xs, double k) {
  double m = 0, l2 = std::numeric_limits<double>::infinity();
  for (auto i = xs.begin(); i != xs.end(); ++i) {
    m = std::max(m, i->squaredNorm());
    for (auto j = std::next(i); j != xs.end(); ++j) l2 = std::min(l2, (*i - *j).squaredNorm());
  }
  return std::pow(1 + m / std::min(l2, 1.0), k);
}
// The smallest pairwise distance, for the generators' rejection.
inline double min_distance(std::initializer_list<Vec3> xs) {
  double l2 = std::numeric_limits<double>::infinity();
  for (auto i = xs.begin(); i != xs.end(); ++i)
    for (auto j = std::next(i); j != xs.end(); ++j) l2 = std::min(l2, (*i - *j).squaredNorm());
  return std::sqrt(l2);
}
inline constexpr double kPoint = 1, kLine = 1.5, kRound = 2.5;  // the k above

// |a − b| ≤ tol, with a readable failure.
inline ::testing::AssertionResult near(const Vec3& a, const Vec3& b, double tol, const char* what = "") {
  const double e = (a - b).norm();
  if (e <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": |" << a.transpose() << " − " << b.transpose() << "| = " << e
                                       << " > " << tol;
}
inline ::testing::AssertionResult near(double a, double b, double tol, const char* what = "") {
  const double e = std::abs(a - b);
  if (e <= tol) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << what << ": |" << a << " − " << b << "| = " << e << " > " << tol;
}

// Worst observed error / tolerance, reported at the end of a test so the margin
// is visible in the log.
struct Worst {
  double ratio = 0;
  void see(double err, double tol) { ratio = std::max(ratio, err / tol); }
  ~Worst() { std::printf("[ worst error / tolerance: %.3g ]\n", ratio); }
};

}  // namespace gacompare::geometry::testing
