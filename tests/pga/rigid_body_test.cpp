// pga/rigid_body.hpp (the motor and the momentum line) against the analytic
// rigid-body cases.
#include "pga/backend.hpp"

#include "pga/rotation_group.hpp"
#include "../lie_bodies_cases.hpp"
#include "../rigid_cases.hpp"

namespace gacompare::testing {

struct Motor {
  using Backend = pga::Backend;
  using Group = pga::MotorGroup;  // the Lie-group methods' step (tests/lie_bodies_cases.hpp)
  static constexpr const char* options = "{}";
  static constexpr bool screw = true;  // interpolated_pose is the motor's screw
};
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, RigidCases, Motor);
INSTANTIATE_TYPED_TEST_SUITE_P(Pga, LieBodiesCases, Motor);

// The time of impact's motion in pga is the screw M0 (M̃0 M1)^s: a body that
// turns by θ about an axis perpendicular to its displacement d moves its
// centre on a circular arc, whose midpoint lies (d/2) tan(θ/4) ≈ dθ/8 off
// the chord the other backends interpolate (the bound pga/rigid_body.hpp
// states). Tolerance 1e-13: log, exp and motor products of size-1 numbers.
TEST(PgaRigidBodies, ScrewInterpolationBowsOffTheChordByTheSagitta) {
  using Bodies = pga::RigidBodies;
  const double theta = 0.5, d = 1.0;
  const auto state = [](const Eigen::Quaterniond& q, const Eigen::Vector3d& x) {
    const core::Scene scene = posed_box_scene(q, x, "{}");
    const core::Model compiled = core::compile(scene);
    auto model = Bodies::build(scene, compiled);
    std::vector<double> y(Bodies::state_size(model));
    Bodies::initial_state(model, y);
    return std::make_pair(std::move(model), std::move(y));
  };
  const auto [model, y0] = state(Eigen::Quaterniond::Identity(), Eigen::Vector3d::Zero());
  const auto [model1, y1] =
      state(Eigen::Quaterniond(Eigen::AngleAxisd(theta, Eigen::Vector3d::UnitZ())), Eigen::Vector3d(d, 0, 0));
  const auto mid = Bodies::interpolated_pose(model, y0, y1, 0, 0.5);
  EXPECT_NEAR((mid.position - Eigen::Vector3d(0.5 * d, 0, 0)).norm(), 0.5 * d * std::tan(theta / 4), 1e-13);
  EXPECT_NEAR(mid.position.x(), 0.5 * d, 1e-13);  // off the chord at right angles, in the plane of the turn
  EXPECT_NEAR(mid.position.z(), 0, 1e-15);
}

}  // namespace gacompare::testing
