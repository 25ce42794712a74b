#include "answers/friction_answers.hpp"

#include "core/error.hpp"
#include "core/model/model.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <numbers>
#include <variant>

namespace gacompare::core {

double FrictionFigure::error() const {
  const double d = std::abs(measured - analytic);
  return analytic == 0 ? d : d / std::abs(analytic);
}

namespace {

const Gravity& gravity_of(const Scene& scene, const Run& run, const std::string& kind) {
  const Gravity* gravity = scene.find_effect<Gravity>();
  if (!gravity || gravity->g.norm() == 0 || run.samples.empty())
    throw input_error(kind + " figures of '" + scene.name + "': expected gravity and a run with samples");
  return *gravity;
}

// The one static and the one dynamic body of a two-body scene.
std::pair<std::size_t, std::size_t> base_and_body(const Scene& scene, const std::string& kind) {
  if (scene.bodies.size() != 2 || scene.bodies[0].is_static == scene.bodies[1].is_static)
    throw input_error(kind + " figures of '" + scene.name + "': expected one static and one dynamic body");
  const std::size_t s = scene.bodies[0].is_static ? 0 : 1;
  return {s, 1 - s};
}

double sphere_radius(const Body& body) {
  const auto* sphere = std::get_if<SphereShape>(&body.shape);
  return sphere ? sphere->radius : 0;
}

}  // namespace

std::vector<FrictionFigure> friction_figures(const Scene& scene, const Run& run) {
  const auto fail = [&](const std::string& why) { return input_error("friction figures of '" + scene.name + "': " + why); };
  const auto [s, b] = base_and_body(scene, "friction");
  const Vec3 g = gravity_of(scene, run, "friction").g;
  const Body& base = scene.bodies[s];
  const Body& body = scene.bodies[b];
  const Vec3 n = rotation_matrix(base.orientation) * Vec3::UnitZ();  // the static body's top face
  const double cos_t = -g.dot(n) / g.norm(), sin_t = (g - g.dot(n) * n).norm() / g.norm();
  const double mu = std::sqrt(base.friction * body.friction);
  const double v0 = body.velocity.norm();
  const double r = sphere_radius(body);  // 0: not round
  // Along the slope (down it), or along the launch on the level.
  const Vec3 along = v0 > 0 ? Vec3(body.velocity / v0) : Vec3((g - g.dot(n) * n).normalized());
  const auto& first = run.samples.front().bodies[b];
  const auto& last = run.samples.back().bodies[b];
  const double t_end = run.samples.back().t;
  std::vector<FrictionFigure> out;
  if (v0 > 0 && r > 0) {
    if (sin_t > 1e-12 || body.angular_velocity.norm() != 0 || !(mu > 0))
      throw fail("a launched sphere must start without spin on a level plane with friction");
    const double a = mu * g.norm(), t_roll = 2 * v0 / (7 * a);
    // The slip (the contact point's velocity along the launch) falls linearly,
    // at 7/2 μ|g|, until it is 0: the time it reaches 0 is found from the last
    // two samples before it does, by their straight line (so the samples'
    // spacing does not round it).
    const auto slip = [&](const BodySample& x) { return (x.velocity + x.angular_velocity.cross(-r * n)).dot(along); };
    double t_measured = NAN;
    for (std::size_t k = 2; k < run.samples.size(); ++k)
      if (slip(run.samples[k].bodies[b]) <= 1e-3 * v0) {
        const auto &p = run.samples[k - 2], &q = run.samples[k - 1];
        const double s_p = slip(p.bodies[b]), s_q = slip(q.bodies[b]);
        t_measured = q.t + s_q * (q.t - p.t) / (s_p - s_q);
        break;
      }
    const Sample* half = &run.samples.front();
    for (const auto& sample : run.samples)
      if (std::abs(sample.t - t_roll / 2) < std::abs(half->t - t_roll / 2)) half = &sample;
    out.push_back({"speed v0 - mu g t while sliding, at t*/2", "m/s", v0 - a * half->t, half->bodies[b].velocity.dot(along)});
    out.push_back({"time rolling starts t* = 2 v0/(7 mu g)", "s", t_roll, t_measured});
    out.push_back({"rolling speed 5 v0/7 at the end", "m/s", 5.0 / 7.0 * v0, last.velocity.dot(along)});
  } else if (v0 > 0) {
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
  } else if (sin_t < mu * cos_t && r == 0) {
    double moved = 0;
    for (const auto& sample : run.samples) moved = std::max(moved, (sample.bodies[b].position - first.position).norm());
    out.push_back({"largest displacement (sticks)", "m", 0, moved});
  } else {
    // A box slides; a sphere rolls without slipping while tan θ ≤ 7/2 μ (the
    // friction rolling needs, 2/7 m|g| sin θ, within μ m|g| cos θ), else slides.
    const bool rolls = r > 0 && 2 * sin_t <= 7 * mu * cos_t;
    const double a = rolls ? 5.0 / 7.0 * g.norm() * sin_t : g.norm() * (sin_t - mu * cos_t);
    const std::string how = rolls ? " (rolls, a = 5/7 g sin θ)" : "";
    out.push_back({"speed a t at the end" + how, "m/s", a * t_end, last.velocity.dot(along)});
    out.push_back({"distance a t^2/2 at the end" + how, "m", 0.5 * a * t_end * t_end, (last.position - first.position).dot(along)});
  }
  return out;
}

std::vector<FrictionFigure> top_figures(const Scene& scene, const Run& run) {
  const auto fail = [&](const std::string& why) { return input_error("top figures of '" + scene.name + "': " + why); };
  const auto [s, b] = base_and_body(scene, "top");
  const Vec3 g = gravity_of(scene, run, "top").g;
  const Body& body = scene.bodies[b];
  if (sphere_radius(body) > 0) throw fail("a top is a polyhedron standing on a vertex");
  const Model model = compile(scene);
  const BodyModel& props = model.bodies[b];
  const Mesh& mesh = *props.mesh;  // about the centre of mass
  const double m = props.mass;
  const Eigen::Matrix3d& inertia = props.inertia;
  const Vec3 up = -g.normalized();
  const Eigen::Matrix3d r0 = rotation_matrix(body.orientation);
  // The apex: the vertex lowest at the start; the axis runs from it to the centre of mass.
  Vec3 apex = mesh.vertices().front();
  for (const Vec3& v : mesh.vertices())
    if ((r0 * v).dot(up) < (r0 * apex).dot(up)) apex = v;
  const double l = apex.norm();
  const Vec3 e3 = -apex / l;
  const Vec3 u = e3.unitOrthogonal(), w = e3.cross(u);
  const double i3 = e3.dot(inertia * e3), i1 = u.dot(inertia * u), scale = inertia.norm();
  if ((inertia * e3 - i3 * e3).norm() > 1e-9 * scale || std::abs(w.dot(inertia * w) - i1) > 1e-9 * scale ||
      std::abs(u.dot(inertia * w)) > 1e-9 * scale)
    throw fail("the body is not symmetric about the line from its lowest vertex to its centre of mass");
  const double mgl = m * g.norm() * l, i1_apex = i1 + m * l * l;
  const double cos_0 = (r0 * e3).dot(up), omega3 = body.angular_velocity.dot(r0 * e3);
  const double d = std::pow(i3 * omega3, 2) - 4 * i1_apex * cos_0 * mgl;
  if (!(cos_0 > 0) || !(d >= 0)) throw fail("no steady precession: spin faster (needs (I3 ω3)² ≥ 4 I1' cos θ m g l)");
  const double precession = 2 * mgl / (i3 * omega3 + std::copysign(std::sqrt(d), omega3));
  const double theta_0 = std::acos(std::clamp(cos_0, -1.0, 1.0));
  const double mu = std::sqrt(scene.bodies[s].friction * body.friction);
  if (precession * precession * l * std::sin(theta_0) > mu * g.norm())
    throw fail("friction cannot hold the apex: needs μ ≥ Ω² l sin θ / g");
  // The axis's azimuth about the vertical, unwrapped; its tilt; the apex's drift.
  const Vec3 h1 = up.unitOrthogonal(), h2 = up.cross(h1);
  const Vec3 apex_0 = body.position + r0 * apex;
  double azimuth = 0, previous = 0, tilt_far = theta_0, drift = 0;
  for (std::size_t k = 0; k < run.samples.size(); ++k) {
    const auto& x = run.samples[k].bodies[b];
    const Eigen::Matrix3d r = rotation_matrix(x.orientation);
    const Vec3 axis = r * e3;
    const double phi = std::atan2(axis.dot(h2), axis.dot(h1));
    if (k > 0) azimuth += std::remainder(phi - previous, 2 * std::numbers::pi);
    previous = phi;
    const double tilt = std::acos(std::clamp(axis.dot(up), -1.0, 1.0));
    if (std::abs(tilt - theta_0) > std::abs(tilt_far - theta_0)) tilt_far = tilt;
    drift = std::max(drift, (x.position + r * apex - apex_0).norm());
  }
  const double t_end = run.samples.back().t - run.samples.front().t;
  return {{"precession rate (slow root)", "rad/s", precession, azimuth / t_end},
          {"tilt, farthest from the start", "rad", theta_0, tilt_far},
          {"apex drift, largest", "m", 0, drift}};
}

namespace {

// An axis-aligned box or a sphere, as the pile's rest rule needs it.
struct Block {
  Vec3 centre{0, 0, 0};
  Vec3 half{0, 0, 0};  // a box's half sides
  double radius = 0;   // > 0: a sphere
  double top() const { return centre.z() + (radius > 0 ? radius : half.z()); }
};

// Horizontal distance from p to a box's footprint (0 inside it).
double to_footprint(const Block& box, const Vec3& p) {
  const double dx = std::max(0.0, std::abs(p.x() - box.centre.x()) - box.half.x());
  const double dy = std::max(0.0, std::abs(p.y() - box.centre.y()) - box.half.y());
  return std::hypot(dx, dy);
}

// The height at which `body`'s centre rests on `under`, or −∞ if `under` is not below it.
double rest_on(const Block& body, const Block& under) {
  const double h = std::hypot(body.centre.x() - under.centre.x(), body.centre.y() - under.centre.y());
  if (body.radius > 0 && under.radius > 0) {
    const double reach = body.radius + under.radius;
    return h < reach ? under.centre.z() + std::sqrt(reach * reach - h * h) : -INFINITY;
  }
  if (body.radius > 0) {
    const double d = to_footprint(under, body.centre);
    return d < body.radius ? under.top() + std::sqrt(body.radius * body.radius - d * d) : -INFINITY;
  }
  if (under.radius > 0) return to_footprint(body, under.centre) == 0 ? under.top() + body.half.z() : -INFINITY;
  const bool overlap = std::abs(body.centre.x() - under.centre.x()) < body.half.x() + under.half.x() &&
                       std::abs(body.centre.y() - under.centre.y()) < body.half.y() + under.half.y();
  return overlap ? under.top() + body.half.z() : -INFINITY;
}

}  // namespace

std::vector<FrictionFigure> pile_figures(const Scene& scene, const Run& run) {
  const auto fail = [&](const std::string& why) { return input_error("pile figures of '" + scene.name + "': " + why); };
  gravity_of(scene, run, "pile");
  std::vector<Block> blocks(scene.bodies.size());
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const Body& body = scene.bodies[i];
    blocks[i].centre = body.position;
    if ((blocks[i].radius = sphere_radius(body)) > 0) continue;
    const auto* box = std::get_if<BoxShape>(&body.shape);
    if (!box || !rotation_matrix(body.orientation).isIdentity(1e-12))
      throw fail("body '" + body.name + "' is neither an axis-aligned box nor a sphere");
    blocks[i].half = box->size / 2;
  }
  // Bottom up: each dynamic body rests on what is already placed under it.
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < blocks.size(); ++i)
    if (!scene.bodies[i].is_static) order.push_back(i);
  const auto bottom = [&](std::size_t i) { return blocks[i].centre.z() - (blocks[i].radius > 0 ? blocks[i].radius : blocks[i].half.z()); };
  std::stable_sort(order.begin(), order.end(), [&](std::size_t i, std::size_t j) { return bottom(i) < bottom(j); });
  std::vector<bool> placed(blocks.size());
  for (std::size_t i = 0; i < blocks.size(); ++i) placed[i] = scene.bodies[i].is_static;
  std::vector<double> rest(blocks.size(), NAN);
  for (const std::size_t i : order) {
    double z = -INFINITY;
    // Only what lies below its centre at the start can hold it (not a box beside it).
    for (std::size_t j = 0; j < blocks.size(); ++j)
      if (placed[j] && blocks[j].top() < scene.bodies[i].position.z()) z = std::max(z, rest_on(blocks[i], blocks[j]));
    if (!std::isfinite(z)) throw fail("nothing is under body '" + scene.bodies[i].name + "'");
    blocks[i].centre.z() = rest[i] = z;
    placed[i] = true;
  }
  const auto& first = run.samples.front().bodies;
  const auto& last = run.samples.back().bodies;
  std::size_t highest = order.back();
  double height = 0, drift = 0, speed = 0, spin = 0;
  for (const std::size_t i : order) {
    if (rest[i] > rest[highest]) highest = i;
    height = std::max(height, std::abs(last[i].position.z() - rest[i]) / std::abs(rest[i]));
    drift = std::max(drift, (last[i].position - first[i].position).head<2>().norm());
    speed = std::max(speed, last[i].velocity.norm());
    spin = std::max(spin, last[i].angular_velocity.norm());
  }
  return {{"rest height of the highest body (" + scene.bodies[highest].name + ")", "m", rest[highest], last[highest].position.z()},
          {"height error / rest height, largest", "1", 0, height},
          {"horizontal drift, largest", "m", 0, drift},
          {"speed at the end, largest", "m/s", 0, speed},
          {"angular speed at the end, largest", "rad/s", 0, spin}};
}

std::vector<FrictionFigure> analytic_figures(const Scene& scene, const Run& run) {
  if (scene.bodies.size() > 2) return pile_figures(scene, run);
  for (const Body& body : scene.bodies)
    if (!body.is_static && sphere_radius(body) == 0 && body.angular_velocity.norm() > 0) return top_figures(scene, run);
  return friction_figures(scene, run);
}

}  // namespace gacompare::core
