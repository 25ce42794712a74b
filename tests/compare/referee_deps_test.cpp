// The referee libraries link and keep C++20: FCL 0.7's pkg-config file carries
// -std=c++11, so FCL is found through its CMake config, and this translation unit
// fails to compile if anything lowered the standard. Bullet must be the double
// precision build. One sphere pair through each library against the analytic
// answer, so a broken install fails here, not deep in the collision issue.
#include <btBulletCollisionCommon.h>
#include <fcl/narrowphase/collision.h>
#include <fcl/narrowphase/distance.h>
#include <fcl/geometry/shape/sphere.h>

#include <gtest/gtest.h>

static_assert(__cplusplus >= 202002L, "a dependency lowered the C++ standard below C++20");
static_assert(sizeof(btScalar) == sizeof(double), "Bullet must be the double-precision build (bullet-float64)");

namespace {

TEST(RefereeDeps, FclSeparatedSpheresDistance) {
  auto a = std::make_shared<fcl::Sphered>(1.0);
  auto b = std::make_shared<fcl::Sphered>(0.5);
  fcl::CollisionObjectd oa(a), ob(b);
  ob.setTranslation(fcl::Vector3d(3, 0, 0));
  fcl::DistanceRequestd req;
  fcl::DistanceResultd res;
  fcl::distance(&oa, &ob, req, res);
  EXPECT_NEAR(res.min_distance, 1.5, 1e-6);  // 3 − 1 − 0.5; libccd's GJK converges to ~1e-6
}

TEST(RefereeDeps, BulletOverlappingSpheres) {
  btDefaultCollisionConfiguration config;
  btCollisionDispatcher dispatcher(&config);
  btDbvtBroadphase broadphase;
  btCollisionWorld world(&dispatcher, &broadphase, &config);
  btSphereShape sa(1.0), sb(1.0);
  btCollisionObject a, b;
  a.setCollisionShape(&sa);
  b.setCollisionShape(&sb);
  btTransform t;
  t.setIdentity();
  t.setOrigin(btVector3(1.5, 0, 0));
  b.setWorldTransform(t);
  world.addCollisionObject(&a);
  world.addCollisionObject(&b);
  world.performDiscreteCollisionDetection();
  ASSERT_EQ(dispatcher.getNumManifolds(), 1);
  const btPersistentManifold* m = dispatcher.getManifoldByIndexInternal(0);
  ASSERT_GE(m->getNumContacts(), 1);
  EXPECT_NEAR(m->getContactPoint(0).getDistance(), -0.5, 1e-9);  // sphere–sphere is analytic in Bullet
  world.removeCollisionObject(&b);
  world.removeCollisionObject(&a);
}

}  // namespace
