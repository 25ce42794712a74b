#pragma once
// The compiled model: what a scene's bodies and effects are once their shapes
// are built, derived once per scene and read-only afterwards. Both backends,
// the Bullet world, the budgets, results, metrics, sanity and the reference
// answers read it; none of them builds a mesh or integrates mass properties
// itself. The scene stays the description; the model is what it compiles to.
#include "core/model/mesh.hpp"
#include "core/model/scene.hpp"

#include <Eigen/Core>

#include <memory>
#include <string>
#include <vector>

namespace gacompare::core {

// One body, in its own coordinates about its centre of mass (a scene body's
// `position` is where that centre is in the world).
struct BodyModel {
  // The shape's solid moved so that its centre of mass is the origin: the one
  // mesh every consumer places with a sample's position and orientation.
  std::shared_ptr<const Mesh> mesh;
  double mass = 1;
  double volume = 0;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();  // about the centre of mass, body axes
  // The principal frame (columns: axes in body coordinates) and the moments
  // along them; the identity and the diagonal when the body axes are
  // principal already (off-diagonal terms within 1e-12 of the largest moment).
  Eigen::Matrix3d principal = Eigen::Matrix3d::Identity();
  Vec3 moments = Vec3::Ones();
  double inradius = 0;  // the largest ball about the centre of mass inside (convex bodies)
  double radius = 0;    // the farthest vertex from the centre of mass
  // A static body's box in its own frame: the mesh's bounding box, centre and half sides.
  Vec3 box_mid = Vec3::Zero(), box_half = Vec3::Zero();
  // With the collisions effect: the body's restitution (its own, or the
  // effect's) and whether the mesh is convex (why not, when it is not).
  double restitution = 0;
  double friction = 0;
  bool convex = true;
  std::string not_convex;
  bool is_static = false;
};

// The effects a scene lists, as they act on bodies (every backend applies
// them in its own algebra): gravity, drag on v and ω, forces at points. Only
// the listed ones are evaluated; the flags say which are.
struct BodyEffects {
  bool has_gravity = false, has_linear_drag = false, has_quadratic_drag = false;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double linear_k = 0, linear_k_angular = 0, quadratic_k = 0, quadratic_k_angular = 0;
  struct Push {
    std::size_t body;                // scene index
    Eigen::Vector3d point, force;    // body frame from the centre of mass; world
    double from, until;              // active for from <= t < until
    bool acts_on(std::size_t b, double t) const { return body == b && t >= from && t < until; }
  };
  std::vector<Push> pushes;
};

struct Model {
  std::vector<BodyModel> bodies;  // in scene order
  BodyEffects effects;
  // With the collisions effect: |g|, the resting speed (a contact approaching
  // slower than a fall through the penetration tolerance plus two collision
  // steps of gravity is at rest) and the smallest inradius of all bodies.
  double gravity = 0;
  double resting_speed = 0;
  double min_inradius = 0;
  double seconds = 0;  // compiling it: the mass_properties stage of every run that reads it
};

// Compiles a scene's bodies and effects. Throws input_error "body 'NAME': ..."
// for a shape that encloses no volume; a non-convex body under collisions is
// recorded (BodyModel::convex), and refused by whoever needs convexity.
Model compile(const Scene& scene);
// Throws input_error "body 'NAME': its shape encloses no volume" for the first
// such body: what a simulation of the bodies cannot start from.
void require_volumes(const Scene& scene, const Model& model);

// A scene file loaded and its model compiled, with every refusal of the
// loader and the budgets (core/model/budget.hpp) at its JSON path: what the
// command line runs.
struct Compiled {
  Scene scene;
  std::shared_ptr<const Model> model;
};
Compiled load_compiled(const std::filesystem::path& file, const Limits& limits = {});
Compiled parse_compiled(const std::string& text, const std::filesystem::path& file, const Limits& limits = {});

}  // namespace gacompare::core
