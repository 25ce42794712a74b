#include "core/dynamics/lie_bodies.hpp"

#include <stdexcept>

namespace gacompare::core {

lie::GroupMethod group_method(SolverMethod m) {
  switch (m) {
    case SolverMethod::rkmk4: return lie::GroupMethod::rkmk4;
    case SolverMethod::rkmk45: return lie::GroupMethod::rkmk5;
    case SolverMethod::crouch_grossman4: return lie::GroupMethod::crouch_grossman4;
    default: throw std::logic_error("group_method: '" + std::string(to_string(m)) + "' is not a Lie-group method");
  }
}

Eigen::Vector3d BodyForces::force(double t, const Eigen::Vector3d& momentum) const {
  const BodyEffects& fx = *effects;
  const Eigen::Vector3d v = momentum / mass;
  Eigen::Vector3d f = Eigen::Vector3d::Zero();
  if (fx.has_gravity) f += mass * fx.gravity;
  if (fx.has_linear_drag) f -= fx.linear_k * v;
  if (fx.has_quadratic_drag) f -= fx.quadratic_k * v.norm() * v;
  for (const auto& push : fx.pushes)
    if (push.acts_on(body, t)) f += push.force;
  return f;
}

Eigen::Vector3d BodyForces::torque(double t, const Eigen::Matrix3d& r, const Eigen::Vector3d& l) const {
  const BodyEffects& fx = *effects;
  Eigen::Vector3d tau = Eigen::Vector3d::Zero();
  if (fx.has_linear_drag || fx.has_quadratic_drag) {
    const Eigen::Vector3d w = r * (inv_inertia * (r.transpose() * l));  // ω = R I⁻¹ Rᵀ L
    if (fx.has_linear_drag) tau -= fx.linear_k_angular * w;
    if (fx.has_quadratic_drag) tau -= fx.quadratic_k_angular * w.norm() * w;
  }
  for (const auto& push : fx.pushes)
    if (push.acts_on(body, t)) tau += (r * push.point).cross(push.force);
  return tau;
}

bool BodyForces::turns() const {
  const BodyEffects& fx = *effects;
  if ((fx.has_linear_drag && fx.linear_k_angular != 0) || (fx.has_quadratic_drag && fx.quadratic_k_angular != 0))
    return true;
  for (const auto& push : fx.pushes)
    if (push.body == body) return true;
  return false;
}

lie::FreeBody BodyForces::free_body() const {
  lie::FreeBody out{Eigen::Vector3d::Ones(), {}, inv_inertia};
  if (turns())
    out.torque = [this](double t, const Eigen::Matrix3d& r, const Eigen::Vector3d& l) { return torque(t, r, l); };
  return out;
}

}  // namespace gacompare::core
