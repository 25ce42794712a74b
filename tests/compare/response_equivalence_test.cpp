// Both backends through the collision scenes: the same contacts
// (equal contact and search counters) and the same trajectories, within 1e-6 m over the
// whole run (the scenes are not chaotic: the backends differ by rounding,
// measured 1e-15 to 1e-8 m). The 27 bodies in a box are chaotic: they are
// compared over the first half second only (2.4e-7 m measured).
#include "cga/backend.hpp"
#include "core/dynamics/simulator.hpp"
#include "traditional/backend.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>

namespace {

using namespace gacompare;

core::Scene bundled(const std::string& name) {
  return core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
}

void expect_same(const core::Scene& scene) {
  const core::Run a = core::simulate<traditional::Backend>(scene);
  const core::Run b = core::simulate<cga::Backend>(scene);
  ASSERT_FALSE(a.error || b.error) << scene.name;
  ASSERT_EQ(a.samples.size(), b.samples.size());
  double worst = 0;
  for (std::size_t k = 0; k < a.samples.size(); ++k)
    for (std::size_t i = 0; i < a.samples[k].bodies.size(); ++i)
      worst = std::max(worst, (a.samples[k].bodies[i].position - b.samples[k].bodies[i].position).norm());
  EXPECT_LT(worst, 1e-6) << scene.name;
  // The contacts found and the impacts searched; not the Gauss–Seidel impulse
  // count, which rounding changes (a correction of exactly 0 or of 1e-17).
  for (const char* c : {"impact_searches", "contacts", "narrowphase_pairs"})
    EXPECT_EQ(a.counters.at(c), b.counters.at(c)) << scene.name << " " << c;
}

TEST(ResponseEquivalence, BackendsFollowTheSameContacts) {
  for (const char* name : {"cube_drop_flat", "cube_drop_edge", "cube_drop_corner", "box_edge_edge", "elastic_pair",
                           "cube_pyramid_point"})
    expect_same(bundled(name));
}

TEST(ResponseEquivalence, BodiesInABoxAgreeUntilChaosTakesOver) {
  auto scene = bundled("bodies_in_box");
  scene.duration = 0.5;
  expect_same(scene);
}

}  // namespace
