#pragma once
// Backend-neutral rigid-body data (§2.3): what every backend needs to know about
// a body before it picks its own representation of rotation.
#include "core/scene.hpp"

#include <Eigen/Core>

#include <vector>

namespace gacompare::core {

// Mass and the inertia tensor about the centre of mass in body coordinates. A
// body's scene `position` is the world position of its centre of mass.
struct BodyProperties {
  double mass = 1;
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Identity();
};

// One per scene body, in scene order, from its shape and its mass or density
// (uniform density): exact polyhedral mass properties (core/mass_properties.hpp).
std::vector<BodyProperties> body_properties(const Scene& scene);

}  // namespace gacompare::core
