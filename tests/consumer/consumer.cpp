// Uses the installed algebra as another project would: a Cl(3,0) rotor turns
// e1 into e2, and in Cl(4,1) the inner product of a conformal point with a
// dual sphere is ½(ρ² − |x − c|²) and of two points −½|x − y|²; in Cl(3,0,1) a
// plane and a point meet in their signed distance. Exits 0 only
// when every answer agrees with its closed form to 1e-14 (a few roundings).
#include <cga/algebra/cl3.hpp>
#include <cga/geometry/entities.hpp>
#include <pga/algebra/cl301.hpp>

#include <cmath>
#include <cstdio>
#include <numbers>

int main() {
  using namespace gacompare::cga;
  int failures = 0;
  auto expect = [&](const char* what, double got, double want) {
    if (!(std::abs(got - want) <= 1e-14 * std::max(1.0, std::abs(want)))) {
      std::printf("consumer: %s = %.17g, expected %.17g\n", what, got, want);
      ++failures;
    }
  };
  const Rotor3 r = rotor_from_axis_angle(vector3(0, 0, 1), std::numbers::pi / 2);
  const Vector3 y = sandwich(r, vector3(1, 0, 0));
  expect("R e1 R~ . e1", y.c[0], 0);
  expect("R e1 R~ . e2", y.c[1], 1);
  const Eigen::Vector3d x(1, 2, 2), c(0, 0, 0);
  expect("up(x) . S", scalar_product(up(x), sphere(c, 2.0)), 0.5 * (4.0 - 9.0));
  expect("up(x) . up(c)", scalar_product(up(x), up(c)), -0.5 * 9.0);
  const Eigen::Vector3d n(0, 0, 1);
  expect("(plane ^ point) e0123", gacompare::pga::distance(gacompare::pga::plane(n, 0.5), gacompare::pga::point(x)), 1.5);
  if (failures == 0) std::printf("consumer: gacompare::algebra from the install works\n");
  return failures == 0 ? 0 : 1;
}
