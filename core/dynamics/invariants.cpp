#include "core/dynamics/invariants.hpp"

#include <Eigen/Geometry>

#include <cmath>
#include <variant>

namespace gacompare::core {

void fill_invariants(const Scene& scene, const Model& model, Sample& s) {
  s.kinetic = s.potential = 0;
  s.linear_momentum.setZero();
  s.angular_momentum.setZero();
  const auto& ps = scene.particles;
  for (std::size_t i = 0; i < ps.size(); ++i) {
    const double m = ps[i].mass;
    const Vec3& x = s.particles[i].position;
    const Vec3& v = s.particles[i].velocity;
    s.kinetic += 0.5 * m * v.squaredNorm();
    s.linear_momentum += m * v;
    s.angular_momentum += x.cross(m * v);
  }
  for (std::size_t b = 0; b < s.bodies.size(); ++b) {
    if (scene.bodies[b].is_static) continue;
    const auto& body = s.bodies[b];
    const double m = model.bodies[b].mass;
    const Eigen::Matrix3d r =
        Eigen::Quaterniond(body.orientation[0], body.orientation[1], body.orientation[2], body.orientation[3])
            .toRotationMatrix();
    const Vec3 L = r * model.bodies[b].inertia * r.transpose() * body.angular_velocity;
    s.kinetic += 0.5 * m * body.velocity.squaredNorm() + 0.5 * body.angular_velocity.dot(L);
    s.linear_momentum += m * body.velocity;
    s.angular_momentum += body.position.cross(m * body.velocity) + L;
  }
  for (const auto& e : scene.effects) {
    if (const auto* g = std::get_if<Gravity>(&e)) {
      for (std::size_t i = 0; i < ps.size(); ++i) s.potential -= ps[i].mass * g->g.dot(s.particles[i].position);
      for (std::size_t b = 0; b < s.bodies.size(); ++b)
        if (!scene.bodies[b].is_static) s.potential -= model.bodies[b].mass * g->g.dot(s.bodies[b].position);
    } else if (const auto* a = std::get_if<AttractionToPoint>(&e)) {
      for (std::size_t i = 0; i < ps.size(); ++i)
        s.potential -= a->D * ps[i].mass /
                       std::sqrt((s.particles[i].position - a->point).squaredNorm() + a->softening * a->softening);
    } else if (const auto* c = std::get_if<AttractionBetweenParticles>(&e)) {
      for (std::size_t i = 0; i < ps.size(); ++i)
        for (std::size_t j = i + 1; j < ps.size(); ++j)
          s.potential -= c->C * ps[i].mass * ps[j].mass /
                         std::sqrt((s.particles[i].position - s.particles[j].position).squaredNorm() +
                                   c->softening * c->softening);
    }
  }
}

}  // namespace gacompare::core
