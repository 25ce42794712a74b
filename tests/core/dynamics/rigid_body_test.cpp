// core/dynamics/rigid_body: a bad shape named at its JSON path, and the
// sub-model of an island (copy_bodies) keeping exactly its bodies' pushes.
#include "core/error.hpp"
#include "core/dynamics/rigid_body.hpp"

#include <gtest/gtest.h>

#include <cmath>
#include <string>
#include <vector>

namespace gacompare::core {
namespace {

// A bad mesh is found when the scene loads (it used to be found when a
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
