// core/model/model: what the compiled model holds for each body, against
// closed forms and against what it was derived from.
//   - mass and inertia: a box m/12 (b² + c², …) and a regular tetrahedron
//     m a²/20 about its centroid, for a body given by mass and one given by
//     density; a hull far from the origin has its inertia about its own centre
//     of mass. Tolerance 1e-12 relative: a handful of exactly representable
//     products (1e-9 for the far hull: its reference point is 1e3 m away, so
//     1e3² ulps at most).
//   - the centred mesh: its own centre of mass at the origin (integrated again,
//     independently of the offset that moved it), its radius, inradius and box
//     the box's closed forms;
//   - the principal frame: axes diag(moments) axesᵀ = inertia, for a box
//     given as a turned hull;
//   - bodies of one shape share one mesh, and only they: the same box at two
//     masses shares, a box of another size, a hull of the same box (another
//     name) and a box moved off its centre (a hull whose centre of mass moves
//     its vertices) do not; Mesh::identical compares to the last bit;
//   - materials and convexity as the collisions effect reads them, and the
//     refusal of a non-convex body at its JSON path by load_compiled.
#include "core/model/model.hpp"

#include "core/error.hpp"
#include "core/model/mass_properties.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <string>

namespace gacompare::core {
namespace {

TEST(Model, MassPropertiesMatchClosedForms) {
  const Scene s = parse_scene(R"({"name": "p", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
    "bodies": [{"name": "box", "shape": {"box": [1, 2, 3]}, "mass": 6.0, "position": [0, 0, 0]},
               {"name": "tet", "shape": {"tetrahedron": 2.0}, "density": 10.0, "position": [0, 0, 0]},
               {"name": "far", "shape": {"hull": [[1000, 0, 0], [1001, 0, 0], [1000, 2, 0], [1000, 0, 3],
                                                  [1001, 2, 0], [1001, 0, 3], [1000, 2, 3], [1001, 2, 3]]},
                "mass": 6.0, "position": [0, 0, 0]}]})",
                              "p.json");
  const Model model = compile(s);
  const auto& props = model.bodies;
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

TEST(Model, BodiesOfOneShapeShareOneMesh) {
  const Scene s = parse_scene(R"({"name": "p", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
    "bodies": [{"name": "a", "shape": {"box": [1, 2, 3]}, "mass": 6.0, "position": [0, 0, 0]},
               {"name": "b", "shape": {"box": [1, 2, 3]}, "density": 2.0, "position": [5, 0, 0]},
               {"name": "c", "shape": {"box": [1, 2, 3.0000000000000004]}, "mass": 6.0, "position": [0, 5, 0]},
               {"name": "d", "shape": {"hull": [[0, 0, 0], [1, 0, 0], [0, 2, 0], [0, 0, 3],
                                                [1, 2, 0], [1, 0, 3], [0, 2, 3], [1, 2, 3]]},
                "mass": 6.0, "position": [0, 0, 5]},
               {"name": "e", "shape": {"hull": [[0, 0, 0], [1, 0, 0], [0, 2, 0], [0, 0, 3],
                                                [1, 2, 0], [1, 0, 3], [0, 2, 3], [1, 2, 3]]},
                "mass": 1.0, "position": [0, 5, 5]},
               {"name": "f", "shape": {"tetrahedron": 1.0}, "mass": 1.0, "position": [5, 5, 5]}]})",
                              "p.json");
  const Model model = compile(s);
  ASSERT_EQ(model.bodies.size(), 6u);
  const auto& b = model.bodies;
  EXPECT_EQ(b[0].mesh, b[1].mesh);  // the same box, another mass
  EXPECT_NE(b[0].mesh, b[2].mesh);  // one ulp longer
  EXPECT_NE(b[0].mesh, b[3].mesh);  // the same solid, but a hull: another name
  EXPECT_EQ(b[3].mesh, b[4].mesh);  // the same hull
  EXPECT_NE(b[0].mesh, b[5].mesh);
  // What sharing decides on: a copy is identical, a moved copy is not.
  const Mesh box = make_box({1, 2, 3});
  EXPECT_TRUE(box.identical(make_box({1, 2, 3})));
  EXPECT_FALSE(box.identical(box.transformed(Eigen::Matrix3d::Identity(), Vec3(0, 0, std::ldexp(1.0, -52)))));  // one ulp of 1.5
  EXPECT_FALSE(box.identical(make_box({1, 2, 3.0000000000000004})));
}

// The far hull's mesh is moved to its centre of mass, (1000.5, 1, 1.5):
// integrated again, the centred mesh's centre is the origin (to 1e-12 of the
// 1e3 m it was moved by), and its radius, inradius and box are the 1 × 2 × 3
// box's: √14/2, 0.5 and half sides (0.5, 1, 1.5).
TEST(Model, TheMeshIsCentredOnItsCentreOfMass) {
  const Scene s = parse_scene(R"({"name": "p", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
    "bodies": [{"name": "far", "shape": {"hull": [[1000, 0, 0], [1001, 0, 0], [1000, 2, 0], [1000, 0, 3],
                                                  [1001, 2, 0], [1001, 0, 3], [1000, 2, 3], [1001, 2, 3]]},
                "mass": 6.0, "position": [0, 0, 0]}]})",
                              "p.json");
  const Model model = compile(s);
  ASSERT_EQ(model.bodies.size(), 1u);
  const BodyModel& b = model.bodies[0];
  EXPECT_LT(mass_properties(*b.mesh).centre_of_mass.norm(), 1e-12 * 1e3);
  EXPECT_NEAR(b.radius, std::sqrt(14.0) / 2, 1e-12);
  EXPECT_NEAR(b.inradius, 0.5, 1e-12);
  EXPECT_LT((b.box_half - Vec3(0.5, 1, 1.5)).norm(), 1e-12);
  EXPECT_LT(b.box_mid.norm(), 1e-12);
  EXPECT_NEAR(b.volume, 6.0, 1e-12);
}

// A 1 × 2 × 3 box given as a hull turned by 0.3 rad about (1, 2, 3): its
// inertia has off-diagonal terms, the principal frame diagonalises it to the
// box's moments m/12 (b² + c², …) (1e-12 relative: an eigensolver on a 3 × 3
// matrix), and an axis-aligned box keeps the identity and its diagonal.
TEST(Model, ThePrincipalFrameDiagonalisesTheInertia) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.3, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  nlohmann::json hull = nlohmann::json::array();
  for (int c = 0; c < 8; ++c) {
    const Vec3 v = r * Vec3(c & 1 ? 0.5 : -0.5, c & 2 ? 1 : -1, c & 4 ? 1.5 : -1.5);
    hull.push_back({v.x(), v.y(), v.z()});
  }
  const nlohmann::json scene = {{"name", "p"}, {"duration", 1}, {"output", {{"every", 1}}}, {"solver", {{"method", "rk4"}}},
                                {"bodies", {{{"name", "turned"}, {"shape", {{"hull", hull}}}, {"mass", 6.0}, {"position", {0, 0, 0}}},
                                            {{"name", "box"}, {"shape", {{"box", {1, 2, 3}}}}, {"mass", 6.0}, {"position", {0, 0, 0}}}}}};
  const Model model = compile(parse_scene(scene.dump(), "p.json"));
  const BodyModel& t = model.bodies[0];
  const Eigen::Matrix3d back = t.principal * t.moments.asDiagonal() * t.principal.transpose();
  EXPECT_LT((back - t.inertia).norm(), 1e-12 * t.inertia.norm());
  Vec3 sorted = t.moments;
  std::sort(sorted.data(), sorted.data() + 3);
  const Vec3 box(6.0 / 12 * (1 + 4), 6.0 / 12 * (1 + 9), 6.0 / 12 * (4 + 9));  // ascending
  EXPECT_LT((sorted - box).norm(), 1e-12 * box.norm());
  const BodyModel& a = model.bodies[1];
  EXPECT_EQ(a.principal, Eigen::Matrix3d::Identity());
  EXPECT_EQ(a.moments, a.inertia.diagonal());
}

// Under collisions: a body's own restitution, or else the effect's; its
// friction; whether it is convex; the resting speed √(2 |g| tol) + 2 |g| h.
TEST(Model, CollisionsReadMaterialsAndConvexityFromTheModel) {
  const std::string file = std::string(GACOMPARE_TEST_DATA_DIR) + "/scene.json";
  const std::string text = R"({"name": "p", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
    "effects": [{"type": "gravity", "g": [0, 0, -9.81]},
                {"type": "collisions", "restitution": 0.5, "penetration_tolerance": 1e-4, "step": 1e-3}],
    "bodies": [{"name": "a", "shape": {"box": [1, 1, 1]}, "mass": 1.0, "position": [0, 0, 0], "restitution": 0.25, "friction": 0.4},
               {"name": "l", "shape": {"mesh": "meshes/l_shape.obj"}, "mass": 1.0, "position": [5, 0, 0]}]})";
  const Model model = compile(parse_scene(text, file));
  EXPECT_EQ(model.bodies[0].restitution, 0.25);
  EXPECT_EQ(model.bodies[1].restitution, 0.5);
  EXPECT_EQ(model.bodies[0].friction, 0.4);
  EXPECT_TRUE(model.bodies[0].convex);
  EXPECT_FALSE(model.bodies[1].convex);
  EXPECT_EQ(model.resting_speed, std::sqrt(2 * 9.81 * 1e-4) + 2 * 9.81 * 1e-3);
  try {
    parse_compiled(text, file);
    FAIL() << "expected an error";
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    EXPECT_EQ(std::string(e.what()).rfind(file + ": /bodies/1/shape: expected a convex body", 0), 0u) << e.what();
  }
}

}  // namespace
}  // namespace gacompare::core
