// core/rigid_body: the mass properties a backend receives for each scene body,
// against closed forms — a box m/12 (b² + c², …) and a regular tetrahedron
// m a²/20 about its centroid — for a body given by mass and one given by density;
// a hull far from the origin has its inertia about its own centre of mass.
// Tolerance 1e-12 relative: a handful of exactly representable products.
#include "core/error.hpp"
#include "core/rigid_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace gacompare::core {
namespace {

TEST(RigidBody, PropertiesMatchClosedForms) {
  const Scene s = parse_scene(R"({"name": "p", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
    "bodies": [{"name": "box", "shape": {"box": [1, 2, 3]}, "mass": 6.0, "position": [0, 0, 0]},
               {"name": "tet", "shape": {"tetrahedron": 2.0}, "density": 10.0, "position": [0, 0, 0]},
               {"name": "far", "shape": {"hull": [[1000, 0, 0], [1001, 0, 0], [1000, 2, 0], [1000, 0, 3],
                                                  [1001, 2, 0], [1001, 0, 3], [1000, 2, 3], [1001, 2, 3]]},
                "mass": 6.0, "position": [0, 0, 0]}]})",
                              "p.json");
  const auto props = body_properties(s);
  ASSERT_EQ(props.size(), 3u);
  const Eigen::Vector3d box(6.0 / 12 * (4 + 9), 6.0 / 12 * (1 + 9), 6.0 / 12 * (1 + 4));
  EXPECT_NEAR(props[0].mass, 6.0, 1e-12);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(props[0].inertia(k, k), box[k], 1e-12 * box[k]);
  const double volume = std::pow(2.0, 3) / (6 * std::sqrt(2.0)), m = 10.0 * volume;
  EXPECT_NEAR(props[1].mass, m, 1e-12 * m);
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(props[1].inertia(k, k), m * 4.0 / 20, 1e-12 * m);
  EXPECT_NEAR(props[1].inertia(0, 1), 0.0, 1e-12 * m);
  // The same box as a hull 1 km away: the same inertia, about its own centre (the
  // reference point is the vertex mean, so 1 km costs ~ 1e3² ulps at most: 1e-9).
  for (int k = 0; k < 3; ++k) EXPECT_NEAR(props[2].inertia(k, k), box[k], 1e-9 * box[k]);
}

// A bad mesh is found when the scene loads (issue #16: it was found when a
// backend built the body, and the line named neither the file nor the key),
// named by the scene file, the JSON path and the mesh's own complaint.
TEST(RigidBody, ADegenerateShapeIsNamedAtItsPath) {
  const std::string file = std::string(GACOMPARE_TEST_DATA_DIR) + "/scene.json";
  try {
    parse_scene(R"({"name": "p", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
    "bodies": [{"name": "broken", "shape": {"mesh": "meshes/open_cube.obj"}, "mass": 1.0, "position": [0, 0, 0]}]})",
                file);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    EXPECT_EQ(std::string(e.what()).rfind(file + ": /bodies/0/shape/mesh: ", 0), 0u) << e.what();
    EXPECT_NE(std::string(e.what()).find("open_cube.obj: not closed"), std::string::npos) << e.what();
  }
}

// An island's sub-model lists its moving bodies, then its static ones, so
// `which` is not ascending: every push on a chosen body must follow it,
// re-indexed, and no other (a binary search over such a list dropped the
// applied force of a moving body numbered above a static one, so a pushed
// cube stepped alone beside its fixed pyramid lost its push).
TEST(RigidBody, CopyBodiesKeepsEveryChosenBodysPushInAnyOrder) {
  struct Model {
    std::vector<std::string> names;
    std::vector<int> bodies;
    BodyEffects effects;
  };
  Model from{{"pyramid", "cube", "other"}, {10, 11, 12}, {}};
  const auto push = [](std::size_t body, double f) {
    return BodyEffects::Push{body, Eigen::Vector3d::Zero(), Eigen::Vector3d(f, 0, 0), 0, 1};
  };
  from.effects.pushes = {push(1, -4), push(2, 7), push(0, 9)};
  const std::vector<int> which = {1, 0};  // the cube (moving), then the pyramid (static)
  Model to;
  copy_bodies(from, which, to);
  EXPECT_EQ(to.names, (std::vector<std::string>{"cube", "pyramid"}));
  EXPECT_EQ(to.bodies, (std::vector<int>{11, 10}));
  ASSERT_EQ(to.effects.pushes.size(), 2u);
  EXPECT_EQ(to.effects.pushes[0].body, 0u);
  EXPECT_EQ(to.effects.pushes[0].force.x(), -4);
  EXPECT_EQ(to.effects.pushes[1].body, 1u);
  EXPECT_EQ(to.effects.pushes[1].force.x(), 9);
}

}  // namespace
}  // namespace gacompare::core
