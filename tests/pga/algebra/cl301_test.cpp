// pga/algebra/cl301.hpp: the conventions its header states, and every closed
// form against the generic products it is written out from (or a power
// series), on seeded random inputs. Tolerances: 1e-13 for a handful of
// products of size-1 numbers; exp/log 1e-12 (trigonometric functions and a
// division by sinc).
#include "pga/algebra/cl301.hpp"

#include <gtest/gtest.h>

#include <random>

namespace gacompare::pga {
namespace {

std::mt19937_64& rng() {
  static std::mt19937_64 g(301);  // fixed seed: failures replay
  return g;
}
double uniform(double lo = -1, double hi = 1) { return std::uniform_real_distribution<double>(lo, hi)(rng()); }
Vec3 random_vec(double scale = 1) { return scale * Vec3(uniform(), uniform(), uniform()); }
Eigen::Quaterniond random_rotation() {
  return Eigen::Quaterniond(uniform(), uniform(), uniform(), uniform()).normalized();
}
template <class M>
double max_difference(const M& a, const M& b) {
  double worst = 0;
  for (int k = 0; k < M::size; ++k) worst = std::max(worst, std::abs(a.c[k] - b.c[k]));
  return worst;
}

// π ∧ X = (n·x − d) e0123; P ∨ D is the line with direction a and moment p × a;
// the join of two lines is v·f + ω·τ (the header's table of entities).
TEST(Cl301, EntitiesMeetAndJoinAsTheHeaderSays) {
  for (int k = 0; k < 100; ++k) {
    const Vec3 n = random_vec(), x = random_vec(), a = random_vec(), p = random_vec(), q = random_vec();
    const double d = uniform();
    EXPECT_NEAR((plane(n, d) ^ point(x)).get<e4::e0123>(), n.dot(x) - d, 1e-14);
    EXPECT_NEAR(distance_of_unit_point(plane(n, d), point(x)), distance(plane(n, d), point(x)), 1e-15);
    EXPECT_NEAR(distance2_of_unit_points(point(p), point(q)), cga::norm2(join<kEuclideanLine>(point(p), point(q))), 1e-14);
    EXPECT_NEAR(max_difference(join(point(p), direction(a)), line(a, p.cross(a))), 0, 1e-14);
    const Line pq = join(point(p), point(q));
    EXPECT_NEAR((line_direction(pq) - (q - p)).norm(), 0, 1e-14);
    const Vec3 w = random_vec(), v = random_vec(), f = random_vec(), t = random_vec();
    EXPECT_NEAR(join(line(w, v), line(f, t)).c[0], v.dot(f) + w.dot(t), 1e-14);
    EXPECT_NEAR((euclid(point(x)) - x).norm(), 0, 0);
  }
}

// The complement is inverted by uncomplement, and b ∧ complement(b) = e0123.
TEST(Cl301, ComplementIsInvertedAndCompletesEachBlade) {
  Multivector<Cl301, Cl301::all> m;
  for (double& x : m.c) x = uniform();
  EXPECT_EQ(max_difference(uncomplement(complement(m)), m), 0);
  for (unsigned b = 0; b < Cl301::blade_count; ++b) {
    Multivector<Cl301, Cl301::all> blade{};
    blade.c[b] = 1;
    EXPECT_EQ((blade ^ complement(blade))[e4::e0123], 1) << "blade " << b;
  }
}

// The motor of a rotation and translation moves points as the quaternion and
// the vector do; apply() is the generic sandwich M X M̃; translation() and
// rotation_matrix() read the motion back.
TEST(Cl301, MotorSandwichIsTheRigidMotionAndTheGenericProduct) {
  for (int k = 0; k < 200; ++k) {
    const Eigen::Quaterniond q = random_rotation();
    const Vec3 t = random_vec(3), x = random_vec(2);
    const Motor m = motor(q, t);
    const Vec3 expected = q * x + t;
    EXPECT_NEAR((apply(m, x) - expected).norm(), 0, 1e-13);
    const Point generic = product<Product::geometric, Point::blades>(m * point(x), reverse(m));
    EXPECT_NEAR((euclid(generic) - expected).norm(), 0, 1e-13);
    EXPECT_NEAR((apply_direction(m, x) - q * x).norm(), 0, 1e-13);
    EXPECT_NEAR((translation(m) - t).norm(), 0, 1e-13);
    EXPECT_NEAR((rotation_matrix(m) - q.toRotationMatrix()).norm(), 0, 1e-13);
    const auto [rho, kk] = study(m);
    EXPECT_NEAR(rho, 1, 1e-14);
    EXPECT_NEAR(kk, 0, 1e-14);
  }
}

// compose(a, b) applies b, then a; the inverse of a unit motor is its reverse.
TEST(Cl301, CompositionIsTheProductOfMotions) {
  for (int k = 0; k < 100; ++k) {
    const Motor a = motor(random_rotation(), random_vec()), b = motor(random_rotation(), random_vec());
    const Vec3 x = random_vec();
    EXPECT_NEAR((apply(compose(a, b), x) - apply(a, apply(b, x))).norm(), 0, 1e-13);
    EXPECT_NEAR((apply(compose(reverse(a), a), x) - x).norm(), 0, 1e-13);
  }
}

// normalised() returns a unit motor (Study number 1 + 0 e0123) and leaves a
// unit motor as it is.
TEST(Cl301, NormalisedMotorsAreUnit) {
  for (int k = 0; k < 100; ++k) {
    const Motor m = motor(random_rotation(), random_vec());
    Motor drifted = m;
    for (double& c : drifted.c) c += 1e-3 * uniform();
    const auto [rho, kk] = study(normalised(drifted));
    EXPECT_NEAR(rho, 1, 1e-14);
    EXPECT_NEAR(kk, 0, 1e-14);
    EXPECT_LT(max_difference(normalised(m), m), 1e-15);
  }
}

// exp against its power series Σ Bᵏ/k! (generic products, 30 terms: |B| ≤ 1.5);
// log inverts it for rotations up to π/2 and pure translations; exp(B) of the
// rotation line through p turns about that line.
TEST(Cl301, ExpIsTheSeriesAndLogItsInverse) {
  for (int k = 0; k < 100; ++k) {
    const double size = k < 10 ? 1e-6 : 1.0;  // the series branch near 0 too
    const Line b = line(random_vec(size * 0.8), random_vec(size));
    Motor series{}, term{};
    term.c[0] = 1;
    series.c[0] = 1;
    for (int j = 1; j < 30; ++j) {
      term = cga::widen<Motor::blades>(cga::project<Motor::blades>(term * b)) / j;
      series += term;
    }
    EXPECT_LT(max_difference(exp(b), series), 1e-12);
    EXPECT_LT(max_difference(log(exp(b)), b), 1e-12);
  }
  const Line shift = line(Vec3::Zero(), Vec3(1, 2, 3));
  EXPECT_LT(max_difference(log(exp(shift)), shift), 1e-15);
  const Vec3 p(1, 2, 0.5), axis = Vec3(0, 0, 1);
  const Motor turn = exp(-0.5 * (std::numbers::pi / 2) * line(axis, p.cross(axis)));
  EXPECT_NEAR((apply(turn, p) - p).norm(), 0, 1e-14);                                  // the axis stays
  EXPECT_NEAR((apply(turn, Vec3(2, 2, 0.5)) - Vec3(1, 3, 0.5)).norm(), 0, 1e-14);       // a quarter turn about it
}

}  // namespace
}  // namespace gacompare::pga
