// traditional/rigid_body.hpp, with the rotation as a matrix (eq. 34) and as a
// quaternion, against the analytic rigid-body cases.
#include "traditional/backend.hpp"
#include "traditional/rotation_group.hpp"
#include "../lie_bodies_cases.hpp"
#include "../rigid_cases.hpp"

namespace gacompare::testing {
struct Matrix {
  using Backend = traditional::Backend;
  using Group = traditional::MatrixGroup;  // the Lie-group methods' step (tests/lie_bodies_cases.hpp)
  static constexpr const char* options = R"({"rotation": "matrix"})";
};
struct Quaternion {
  using Backend = traditional::Backend;
  using Group = traditional::QuaternionGroup;
  static constexpr const char* options = R"({"rotation": "quaternion"})";
};
using Variants = ::testing::Types<Matrix, Quaternion>;
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, RigidCases, Variants);
INSTANTIATE_TYPED_TEST_SUITE_P(Traditional, LieBodiesCases, Variants);
}  // namespace gacompare::testing

#include "core/model/model.hpp"

#include <random>

namespace gacompare::testing {
// The quaternion's rate in the rotor's body-frame form, ½ q ω_body with
// ω_body = I⁻¹ q̄ L q / |q|², is the world form ½ (0, ω) q with
// ω = R I⁻¹ Rᵀ L and R the rotation of q/|q|: the same number, to rounding
// (1e-14 relative: a few operations on values of order 1), for quaternions
// off the unit sphere by up to 30% (a drifted state reads as the rotation of
// q/|q|, as the rotor's does).
TEST(TraditionalQuaternion, BodyFrameRateIsTheWorldFormsRate) {
  const core::Scene scene = rigid_scene(R"({"name": "b", "shape": {"box": [0.1, 0.4, 0.9]}, "mass": 2, "position": [0, 0, 0]})", "",
                                        R"({"rotation": "quaternion"})", 1, 1, R"({"method": "rk4"})");
  const auto model = core::compiled_model(scene);
  const auto m = traditional::RigidBodies::build(scene, *model);
  std::mt19937_64 rng(20261203);
  std::uniform_real_distribution<double> u(-1, 1);
  for (int trial = 0; trial < 100; ++trial) {
    std::vector<double> y(m.y0), dydt(y.size());
    const Eigen::Quaterniond q = Eigen::Quaterniond(u(rng), u(rng), u(rng), u(rng)).normalized();
    const double scale = 1 + 0.3 * u(rng);
    const Eigen::Vector3d L(u(rng), u(rng), u(rng));
    for (int k = 0; k < 4; ++k) y[3 + k] = scale * q.coeffs()[(k + 3) % 4];  // w x y z
    for (int k = 0; k < 3; ++k) y[10 + k] = L[k];
    traditional::RigidBodies::derivative(m, 0, y, dydt);
    const Eigen::Matrix3d r = q.toRotationMatrix();
    const Eigen::Vector3d w = r * (m.bodies[0].inv_inertia * (r.transpose() * L));
    const Eigen::Quaterniond sq(y[3], y[4], y[5], y[6]);
    const Eigen::Quaterniond world = Eigen::Quaterniond(0, w.x(), w.y(), w.z()) * sq;
    const double expected[] = {0.5 * world.w(), 0.5 * world.x(), 0.5 * world.y(), 0.5 * world.z()};
    for (int k = 0; k < 4; ++k) EXPECT_NEAR(dydt[3 + k], expected[k], 1e-14 * (1 + w.norm() * scale)) << trial;
  }
}
}  // namespace gacompare::testing
