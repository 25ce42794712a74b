// Round pairs (core/collision/round.hpp) of both backends against the
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
// Capsules (core/collision/capsule.hpp) the same way on data/collision/capsule.json
// against fcl::Capsuled and btCapsuleShapeZ (GJK on the segment, its radius
// the margin), to the same tolerances: measured 8.2e-14 × scale and
// 1.5e-12 rad against Bullet at worst, FCL's distance 0 to 4.1e-6 × scale
// above ours. And the two backends against each other on every capsule pair.
#include "cga/narrowphase.hpp"
#include "compare/referee.hpp"
#include "answers/collision_cases.hpp"
#include "traditional/narrowphase.hpp"

#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <string>
#include <filesystem>

using namespace gacompare;

namespace {

double angle(const Eigen::Vector3d& a, const Eigen::Vector3d& b) { return std::atan2(a.cross(b).norm(), a.dot(b)); }

// Every pair of a round corpus outside the band, both backends against
// Bullet (depth within `depth_tol` × scale, normal within `angle_tol` rad)
// and FCL (yes/no; apart: FCL's distance at or above ours by at most
// `fcl_above` × scale, 1e-9 × scale below for rounding); the worst seen is
// printed, for the tolerances' comments. Returns the pairs compared.
int expect_referees_agree(const std::string& file, double depth_tol, double angle_tol, double fcl_above) {
  const auto cases = collision::load_cases(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision" / file);
  int compared = 0;
  double worst_depth = 0, worst_angle = 0, worst_fcl = 0;
  for (const auto& c : cases) {
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    const compare::BulletShape ba(*c.mesh_a), bb(*c.mesh_b);
    const compare::FclShape fa(*c.mesh_a), fb(*c.mesh_b);
    const auto bullet = compare::bullet_collide(ba, c.pose_a, bb, c.pose_b);
    const auto fcl = compare::fcl_collide(fa, c.pose_a, fb, c.pose_b);
    if (std::abs(bullet.depth) <= 1e-6 * scale) continue;  // touching: rounding and FCL's tolerance decide
    for (const auto& ours : {traditional::narrowphase(c.a(), c.b(), collision::Method::sat_then_manifold),
                             cga::narrowphase(c.a(), c.b(), collision::Method::sat_then_manifold)}) {
      EXPECT_NEAR(ours.depth, bullet.depth, depth_tol * scale) << c.name;
      EXPECT_NEAR(angle(ours.normal, bullet.normal), 0, angle_tol) << c.name;
      EXPECT_EQ(ours.intersect, fcl.intersect) << c.name;
      worst_depth = std::max(worst_depth, std::abs(ours.depth - bullet.depth) / scale);
      worst_angle = std::max(worst_angle, angle(ours.normal, bullet.normal));
      if (!fcl.intersect) {
        const double excess = ours.depth - fcl.depth;  // FCL's distance − ours
        EXPECT_GE(excess, -1e-9 * scale) << c.name;
        EXPECT_LE(excess, fcl_above * scale) << c.name;
        worst_fcl = std::max(worst_fcl, excess / scale);
      }
    }
    ++compared;
  }
  std::printf("%s: %d pairs; worst |depth - Bullet|/scale %.2g, normal %.2g rad, FCL's distance above ours %.2g x scale\n",
              file.c_str(), compared, worst_depth, worst_angle, worst_fcl);
  return compared;
}

TEST(RoundReferee, BothBackendsAgreeWithBulletAndFcl) {
  EXPECT_GE(expect_referees_agree("round.json", 1e-11, 1e-9, 1e-4), 85);
}

// Capsules (core/collision/capsule.hpp) against fcl::Capsuled and btCapsuleShapeZ.
TEST(CapsuleReferee, BothBackendsAgreeWithBulletAndFcl) {
  EXPECT_GE(expect_referees_agree("capsule.json", 1e-11, 1e-9, 1e-4), 100);
}

// The backends against each other on every capsule pair (the touching ones
// too): depth within 1e-12 × scale, the normal within 1e-9 rad, the same
// number of feature contacts, each within 1e-12 × scale of its twin.
TEST(CapsuleReferee, TheBackendsAgreeWithEachOther) {
  const auto cases = collision::load_cases(std::filesystem::path(GACOMPARE_DATA_DIR) / "collision" / "capsule.json");
  for (const auto& c : cases) {
    const double scale = collision::pair_scale(*c.mesh_a, *c.mesh_b);
    std::vector<collision::FeatureContact> ct, cc;
    const auto t = traditional::narrowphase(c.a(), c.b(), collision::Method::sat_then_manifold, &ct);
    const auto g = cga::narrowphase(c.a(), c.b(), collision::Method::sat_then_manifold, &cc);
    EXPECT_NEAR(t.depth, g.depth, 1e-12 * scale) << c.name;
    EXPECT_NEAR(angle(t.normal, g.normal), 0, 1e-9) << c.name;
    EXPECT_NEAR((t.contact - g.contact).norm(), 0, 1e-12 * scale) << c.name;
    ASSERT_EQ(ct.size(), cc.size()) << c.name;
    for (std::size_t i = 0; i < ct.size(); ++i) {
      EXPECT_NEAR((ct[i].point - cc[i].point).norm(), 0, 1e-12 * scale) << c.name;
      EXPECT_NEAR(ct[i].depth, cc[i].depth, 1e-12 * scale) << c.name;
    }
  }
}

}  // namespace
