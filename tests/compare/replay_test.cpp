// What the replay and trajectories.csv are made of (compare/replay.hpp,
// compare/results.hpp): the frames a replay keeps, the CSV against the samples
// it was written from, and the scene record's meshes against the box's
// analytic vertices. The page itself is rendered by report_render_test.
#include "compare/replay.hpp"
#include "compare/results.hpp"

#include "csv_fields.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <sstream>

using namespace gacompare;
using namespace gacompare::compare;

namespace {

const std::string kScenes = std::string(GACOMPARE_DATA_DIR) + "/scenes/";


}  // namespace

TEST(ReplayFrames, EveryKthAndTheLastWithinTheCap) {
  for (const std::size_t cap : {3u, 10u, 2000u})
    for (std::size_t n = 0; n <= 4 * cap + 7; ++n) {
      const auto f = replay_frames(n, cap);
      if (n == 0) {
        EXPECT_TRUE(f.empty());
        continue;
      }
      ASSERT_LE(f.size(), std::max(cap, std::size_t{1})) << n << " samples, cap " << cap;
      EXPECT_EQ(f.front(), 0u);
      EXPECT_EQ(f.back(), n - 1);
      if (n <= cap) {
        EXPECT_EQ(f.size(), n);
      }
      // One stride throughout, the last gap no longer than it.
      const std::size_t stride = f.size() > 1 ? f[1] - f[0] : 1;
      for (std::size_t k = 1; k + 1 < f.size(); ++k) ASSERT_EQ(f[k] - f[k - 1], stride) << n;
      if (f.size() > 1) {
        EXPECT_LE(f.back() - f[f.size() - 2], stride);
      }
    }
}

TEST(TrajectoriesCsv, HoldsEverySampleToTheLastDigit) {
  // %.17g round-trips a double exactly (IEEE 754: 17 significant digits), so
  // each field reads back equal to the sample it came from.
  const SceneResult r = compare_scene(core::load_scene(kScenes + "tumbling_box.json"), {"traditional", "cga"}, 1,
                                      Selection::exactly);
  std::istringstream csv(trajectories_csv(r));
  std::string line;
  std::getline(csv, line);
  EXPECT_EQ(line, "t,backend,kind,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz");
  std::size_t rows = 0;
  for (const auto& b : r.backends)
    for (const auto& s : b.run.samples) {
      ASSERT_TRUE(std::getline(csv, line));
      const auto f = csv_fields(line);
      ASSERT_EQ(f.size(), 17u) << line;
      EXPECT_EQ(std::stod(f[0]), s.t);
      EXPECT_EQ(f[1], b.run.backend);
      EXPECT_EQ(f[2], "body");
      EXPECT_EQ(f[3], "box");
      const auto& x = s.bodies[0];
      for (int k = 0; k < 3; ++k) EXPECT_EQ(std::stod(f[4 + k]), x.position[k]);
      for (int k = 0; k < 4; ++k) EXPECT_EQ(std::stod(f[7 + k]), x.orientation[k]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(std::stod(f[11 + k]), x.velocity[k]);
      for (int k = 0; k < 3; ++k) EXPECT_EQ(std::stod(f[14 + k]), x.angular_velocity[k]);
      ++rows;
    }
  EXPECT_EQ(rows, 2u * 301u);  // two backends, 3 s at 0.01 s
  EXPECT_FALSE(std::getline(csv, line));
}

TEST(TrajectoriesCsv, AParticleHasNoOrientation) {
  const SceneResult r = compare_scene(core::load_scene(kScenes + "pendulum.json"), {"traditional"}, 1);
  std::istringstream csv(trajectories_csv(r));
  std::string line;
  std::getline(csv, line);
  std::getline(csv, line);
  const auto f = csv_fields(line);
  ASSERT_EQ(f.size(), 17u) << line;
  EXPECT_EQ(f[2], "particle");
  EXPECT_EQ(f[3], "bob");
  EXPECT_EQ(std::stod(f[4]), 0.5984721441039565);  // the scene's start, x
  for (int k = 7; k < 11; ++k) EXPECT_EQ(f[k], "") << k;
  for (int k = 14; k < 17; ++k) EXPECT_EQ(f[k], "") << k;
}

TEST(SceneRecord, BodiesAboutTheirCentreOfMassAndConstraints) {
  // The 0.1 x 0.4 x 0.9 m box: 8 vertices at (±0.05, ±0.2, ±0.45) about its
  // centre of mass, 12 triangles, radius half the space diagonal
  // ½√(0.01 + 0.16 + 0.81). 1e-15: the vertices are halves of the sides,
  // the centre of mass their mean (rounding only).
  const auto box_scene = core::load_scene(kScenes + "tumbling_box.json");
  const auto box = scene_json(box_scene, core::compile(box_scene));
  ASSERT_EQ(box["bodies"].size(), 1u);
  const auto& b = box["bodies"][0];
  EXPECT_EQ(b["name"], "box");
  EXPECT_EQ(b["static"], false);
  EXPECT_NEAR(b["radius"].get<double>(), 0.5 * std::sqrt(0.98), 1e-15);
  ASSERT_EQ(b["vertices"].size(), 8u);
  EXPECT_EQ(b["triangles"].size(), 12u);
  for (const auto& v : b["vertices"]) {
    EXPECT_NEAR(std::abs(v[0].get<double>()), 0.05, 1e-15) << v;
    EXPECT_NEAR(std::abs(v[1].get<double>()), 0.2, 1e-15) << v;
    EXPECT_NEAR(std::abs(v[2].get<double>()), 0.45, 1e-15) << v;
  }
  EXPECT_EQ(box["output_every"], 0.01);
  EXPECT_EQ(box["check"]["baseline_tolerance"], 1e-9);  // CheckSpec's default

  const auto pendulum_scene = core::load_scene(kScenes + "pendulum.json");
  const auto pendulum = scene_json(pendulum_scene, core::compile(pendulum_scene));
  EXPECT_EQ(pendulum["particles"], nlohmann::ordered_json::array({"bob"}));
  ASSERT_EQ(pendulum["constraints"].size(), 1u);
  const auto& c = pendulum["constraints"][0];
  EXPECT_EQ(c["type"], "distance_to_point");
  EXPECT_EQ(c["particles"], nlohmann::ordered_json::array({"bob"}));
  EXPECT_EQ(c["point"], nlohmann::ordered_json::array({0.0, 0.0, 0.0}));
  EXPECT_EQ(c["length"], 1.0);
}
