#pragma once
// Backend-neutral rigid-body data (§2.3): what every backend needs to know about
// a body before it picks its own representation of rotation.
#include "core/scene.hpp"

#include <Eigen/Core>

#include <algorithm>
#include <span>

#include <vector>

namespace gacompare::core {

// Mass and the inertia tensor about the centre of mass in body coordinates. A
// body's scene `position` is the world position of its centre of mass.
struct BodyProperties {
  double mass = 1;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();
};

// The effects a scene lists, as they act on bodies (read once; every backend
// applies them in its own algebra): gravity, drag on v and ω, forces at points.
// Only the listed ones are evaluated (docs/architecture.md: an effect not listed
// costs nothing): the flags say which are.
struct BodyEffects {
  bool has_gravity = false, has_linear_drag = false, has_quadratic_drag = false;
  Eigen::Vector3d gravity = Eigen::Vector3d::Zero();
  double linear_k = 0, linear_k_angular = 0, quadratic_k = 0, quadratic_k_angular = 0;
  struct Push {
    std::size_t body;                // scene index
    Eigen::Vector3d point, force;    // body frame from the centre of mass; world
    double from, until;              // active for from <= t < until
  };
  std::vector<Push> pushes;
};
BodyEffects body_effects(const Scene& scene);

// Bodies `which` (scene indices, any order) of model `from` into `to`, whose
// settings the backend has already copied: the bodies' entries and names, the
// effects, and the applied forces on those bodies re-indexed (body k of `to` is
// body which[k] of `from`). The model of an island integrated on its own
// (core/collision_step.hpp); both backends' `subset` call it, so the two
// sub-models hold the same bodies in the same order.
template <class Model>
void copy_bodies(const Model& from, std::span<const int> which, Model& to) {
  to.names.reserve(which.size());
  to.bodies.reserve(which.size());
  for (const int b : which) {
    to.names.push_back(from.names[static_cast<std::size_t>(b)]);
    to.bodies.push_back(from.bodies[static_cast<std::size_t>(b)]);
  }
  to.effects = from.effects;
  to.effects.pushes.clear();
  for (auto push : from.effects.pushes) {
    // A linear search: `which` need not be ascending (an island lists its
    // moving bodies, then its static ones), and a binary search over it
    // dropped the pushes of moving bodies numbered above a static one.
    const auto it = std::find(which.begin(), which.end(), static_cast<int>(push.body));
    if (it == which.end()) continue;
    push.body = static_cast<std::size_t>(it - which.begin());
    to.effects.pushes.push_back(push);
  }
}

// One per scene body, in scene order, from its shape and its mass or density
// (uniform density): exact polyhedral mass properties (core/mass_properties.hpp).
std::vector<BodyProperties> body_properties(const Scene& scene);

}  // namespace gacompare::core
