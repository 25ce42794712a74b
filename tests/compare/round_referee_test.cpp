// Round pairs (issue #17, core/round.hpp) of both backends against the
// referees' own sphere primitives (fcl::Sphered, btSphereShape;
// compare/referee.hpp) on data/collision/round.json, outside the touching band:
//   - Bullet (GJK on the sphere's centre, its radius added back as the margin;
//     EPA when penetrating, to 1e-12): depth within 1e-11 × scale, normal
//     within 1e-9 rad (measured: 9.9e-14 and 5.7e-13 at worst);
//   - FCL: yes/no everywhere. Its distance for apart pairs is libccd's GJK,
//     which on a curved shape converges only linearly and stops when an
//     iteration improves by less than its tolerance, so it stops short from
//     above: always at or above the exact distance (GJK's simplex distance is an
//     upper bound), by up to 3.6e-5 × scale on these pairs (not its nominal
//     1e-6). So FCL's distance is checked as that: an upper bound of ours
//     (1e-9 × scale below for rounding), at most 1e-4 × scale above. Its
//     penetration depth is MPR's, not the minimum, and is not compared.
#include "cga/narrowphase.hpp"
#include "compare/referee.hpp"
#include "core/collision_cases.hpp"
#include "traditional/narrowphase.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>

using namespace gacompare;

namespace {

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

TEST(RoundReferee, BothBackendsAgreeWithBulletAndFcl) {
  const auto cases = collision::load_cases(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision" / "round.json");
  int compared = 0;
  for (const auto& c : cases) {
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    const compare::BulletShape ba(*c.mesh_a), bb(*c.mesh_b);
    const compare::FclShape fa(*c.mesh_a), fb(*c.mesh_b);
    const auto bullet = compare::bullet_collide(ba, c.pose_a, bb, c.pose_b);
    const auto fcl = compare::fcl_collide(fa, c.pose_a, fb, c.pose_b);
    if (std::abs(bullet.depth) <= 1e-6 * scale) continue;  // touching: rounding and FCL's tolerance decide
    for (const auto& ours : {traditional::narrowphase(c.a(), c.b(), collision::Method::sat_then_manifold),
                             cga::narrowphase(c.a(), c.b(), collision::Method::sat_then_manifold)}) {
      EXPECT_NEAR(ours.depth, bullet.depth, 1e-11 * scale) << c.name;
      EXPECT_NEAR(angle(ours.normal, bullet.normal), 0, 1e-9) << c.name;
      EXPECT_EQ(ours.intersect, fcl.intersect) << c.name;
      if (!fcl.intersect) {
        const double excess = ours.depth - fcl.depth;  // FCL's distance − ours
        EXPECT_GE(excess, -1e-9 * scale) << c.name;
        EXPECT_LE(excess, 1e-4 * scale) << c.name;
      }
    }
    ++compared;
  }
  EXPECT_GE(compared, 85);
}

}  // namespace
