#include "core/friction_answers.hpp"

#include "core/error.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>

namespace gacompare::core {

double FrictionFigure::error() const {
  const double d = std::abs(measured - analytic);
  return analytic == 0 ? d : d / std::abs(analytic);
}

std::vector<FrictionFigure> friction_figures(const Scene& scene, const Run& run) {
  const auto fail = [&](const std::string& why) { return input_error("friction figures of '" + scene.name + "': " + why); };
  if (scene.bodies.size() != 2 || scene.bodies[0].is_static == scene.bodies[1].is_static)
    throw fail("expected one static and one dynamic body");
  const std::size_t s = scene.bodies[0].is_static ? 0 : 1, b = 1 - s;
  const Gravity* gravity = scene.find_effect<Gravity>();
  if (!gravity || run.samples.empty()) throw fail("expected gravity and a run with samples");
  const Body& base = scene.bodies[s];
  const Body& body = scene.bodies[b];
  const Eigen::Quaterniond q(base.orientation[0], base.orientation[1], base.orientation[2], base.orientation[3]);
  const Vec3 n = q.normalized() * Vec3::UnitZ();  // the static body's top face
  const Vec3 g = gravity->g;
  const double cos_t = -g.dot(n) / g.norm(), sin_t = (g - g.dot(n) * n).norm() / g.norm();
  const double mu = std::sqrt(base.friction * body.friction);
  const double v0 = body.velocity.norm();
  // Along the slope (down it), or along the launch on the level.
  const Vec3 along = v0 > 0 ? Vec3(body.velocity / v0) : Vec3((g - g.dot(n) * n).normalized());
  const auto& first = run.samples.front().bodies[b];
  const auto& last = run.samples.back().bodies[b];
  const double t_end = run.samples.back().t;
  std::vector<FrictionFigure> out;
  if (v0 > 0) {
    const double decel = g.norm() * (mu * cos_t - sin_t);
    if (!(decel > 0)) throw fail("a launched body must stop: tan θ < μ");
    double stop = NAN;
    for (const auto& sample : run.samples)
      if (sample.bodies[b].velocity.norm() <= 1e-3 * v0) {
        stop = sample.t;
        break;
      }
    out.push_back({"stopping distance v0^2/(2 a)", "m", v0 * v0 / (2 * decel), (last.position - first.position).dot(along)});
    out.push_back({"stopping time v0/a", "s", v0 / decel, stop});
  } else if (sin_t < mu * cos_t) {
    double moved = 0;
    for (const auto& sample : run.samples) moved = std::max(moved, (sample.bodies[b].position - first.position).norm());
    out.push_back({"largest displacement (sticks)", "m", 0, moved});
  } else {
    const double a = g.norm() * (sin_t - mu * cos_t);
    out.push_back({"speed a t at the end", "m/s", a * t_end, last.velocity.dot(along)});
    out.push_back({"distance a t^2/2 at the end", "m", 0.5 * a * t_end * t_end, (last.position - first.position).dot(along)});
  }
  return out;
}

}  // namespace gacompare::core
