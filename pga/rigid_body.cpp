#include "pga/rigid_body.hpp"

#include "core/dynamics/lie_bodies.hpp"
#include "core/error.hpp"
#include "pga/rotation_group.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace gacompare::pga {

namespace {
using Mat = Eigen::Matrix3d;

Motor motor_at(std::span<const double> y, std::size_t i) {
  Motor m;
  for (int k = 0; k < Motor::size; ++k) m.c[k] = y[i + static_cast<std::size_t>(k)];
  return m;
}
Line line_at(std::span<const double> y, std::size_t i) {
  Line l;
  for (int k = 0; k < Line::size; ++k) l.c[k] = y[i + static_cast<std::size_t>(k)];
  return l;
}
template <class M>
void put(std::span<double> y, std::size_t i, const M& m) {
  for (int k = 0; k < M::size; ++k) y[i + static_cast<std::size_t>(k)] = m.c[static_cast<std::size_t>(k)];
}

// Offsets within a body's block: the motor, then the momentum line.
struct Layout {
  std::size_t motor, momentum;
};
Layout layout(std::size_t b) {
  const std::size_t base = b * RigidBodies::Model::stride;
  return {base, base + 8};
}

// The inverse inertia map in the centre's frame with world axes: the rate
// A⁻¹[Π] = (I⁻¹ L) + (P/m) e0, swapping the line's two parts (I⁻¹ the world's).
Line rate_of(const Mat& inv_inertia, double inv_mass, const Line& momentum) {
  return line(inv_inertia * line_moment(momentum), inv_mass * line_direction(momentum));
}
}  // namespace

RigidBodies::Model RigidBodies::build(const core::Scene& scene, const core::Model& model) {
  Model m;
  m.renormalise = scene.rigid_body.renormalise;
  m.effects = model.effects;
  m.y0.assign(Model::stride * scene.bodies.size(), 0.0);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const auto& body = scene.bodies[b];
    const core::BodyModel& p = model.bodies[b];
    m.names.push_back(body.name);
    const bool fixed = body.is_static;
    m.bodies.push_back({fixed ? 0.0 : 1.0 / p.mass, fixed ? Mat::Zero().eval() : p.inertia.inverse().eval(), p.inertia,
                        p.mass});
    const Layout at = layout(b);
    const Eigen::Quaterniond q(body.orientation[0], body.orientation[1], body.orientation[2], body.orientation[3]);
    const Motor mo = motor(q, body.position);
    put(m.y0, at.motor, mo);
    if (!fixed) {
      const Mat r = rotation_matrix(mo);
      // Π = A[V]: direction m v, moment I ω (world).
      put(m.y0, at.momentum, line(p.mass * body.velocity, r * p.inertia * r.transpose() * body.angular_velocity));
    }
  }
  return m;
}

RigidBodies::Model RigidBodies::subset(const Model& m, std::span<const int> which) {
  Model out;
  out.renormalise = m.renormalise;
  core::copy_bodies(m, which, out);
  return out;
}

void RigidBodies::initial_state(const Model& m, std::span<double> y) {
  std::copy(m.y0.begin(), m.y0.end(), y.begin());
}

void RigidBodies::derivative(const Model& m, double t, std::span<const double> y, std::span<double> dydt,
                             std::span<const char> asleep) {
  // Each body's slice of dydt is its own: bodies in parallel (core/parallel.hpp).
  core::for_each_index(m.bodies.size(), [&](std::size_t b) {
    const Body& body = m.bodies[b];
    const Layout at = layout(b);
    std::fill(dydt.begin() + static_cast<long>(at.motor), dydt.begin() + static_cast<long>(at.motor + Model::stride),
              0.0);
    if (body.inv_mass == 0 || (!asleep.empty() && asleep[b])) return;  // static or asleep: does not move
    const Motor mo = motor_at(y, at.motor);
    const Mat r = rotation_matrix(mo);  // exact for a drifted motor (cl301.hpp)
    const Line momentum = line_at(y, at.momentum);
    // The rate in the body's frame, V_b = R̃ V R: ω_b = I⁻¹ Rᵀ L, v_b = Rᵀ v.
    const Vec3 wb = body.inv_inertia * (r.transpose() * line_moment(momentum));
    const Vec3 v = body.inv_mass * line_direction(momentum);
    // Forces as lines through the centre's frame; their sum is Π̇.
    const core::BodyEffects& fx = m.effects;
    Line wrench{};
    if (fx.has_gravity) wrench += line(body.mass * fx.gravity, Vec3::Zero());  // through the centre
    if (fx.has_linear_drag || fx.has_quadratic_drag) {
      const Vec3 w = r * wb;
      if (fx.has_linear_drag) wrench -= line(fx.linear_k * v, fx.linear_k_angular * w);
      if (fx.has_quadratic_drag) wrench -= line(fx.quadratic_k * v.norm() * v, fx.quadratic_k_angular * w.norm() * w);
    }
    for (const auto& push : fx.pushes)
      if (push.acts_on(b, t))
        wrench += join(point(r * push.point), direction(push.force));  // F = X ∨ D
    // Ṁ = −½ V_w M = −½ M V_b (V_w M = T V T̃ T R = T V R = M R̃ V R): the body
    // frame's rate needs no translation read back from M, and the product
    // scales with |M| as the quaternion's q̇ does with |q|.
    put(dydt, at.motor, cga::widen<Motor::blades>(-0.5 * (mo * line(wb, r.transpose() * v))));
    put(dydt, at.momentum, wrench);
  }, core::kGrainLight);
}

bool RigidBodies::renormalise(const Model& m, std::span<double> y) {
  if (m.renormalise == core::Renormalise::none) return false;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Layout at = layout(b);
    put(y, at.motor, normalised(motor_at(y, at.motor)));
  }
  return true;
}

double RigidBodies::rotation_drift(const Model& m, std::span<const double> y) {
  double worst = 0;
  for (std::size_t b = 0; b < m.bodies.size(); ++b)
    worst = std::max(worst, std::abs(study(motor_at(y, layout(b).motor)).first - 1.0));
  return worst;
}

// |δx| from the two motors' translations (the error estimate is a difference
// of states, so the translation of ynew − err is the other solution's); the
// angle of R⁻¹ δR as for the rotor (2|⟨R̃ δR⟩₂|/|R|²); |δv| and |δω| from the
// momentum line (|δω| in the body frame: a rotation keeps lengths).
double RigidBodies::error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                                std::span<const double> err, double abs, double rel) {
  double worst = 0;
  const auto worse = [&](double r) { worst = std::isnan(r) || std::isnan(worst) ? NAN : std::max(worst, r); };
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (body.inv_mass == 0) continue;
    const Layout at = layout(b);
    const auto ratio = [&](double e, double a, double c) { return e / (abs + rel * std::max(a, c)); };
    const Motor m0 = motor_at(y, at.motor), m1 = motor_at(ynew, at.motor), dm = motor_at(err, at.motor);
    const Vec3 x0 = translation(m0), x1 = translation(m1);
    worse(ratio((x1 - translation(m1 - dm)).norm(), x0.norm(), x1.norm()));
    const Line p0 = line_at(y, at.momentum), p1 = line_at(ynew, at.momentum), dp = line_at(err, at.momentum);
    worse(ratio(line_direction(dp).norm(), line_direction(p0).norm(), line_direction(p1).norm()));  // δP/m over |P|/m
    const Rotor r1 = project<Rotor::blades>(m1);
    const auto relative = reverse(r1) * project<Rotor::blades>(dm);
    const double angle = 2 *
                         std::sqrt(relative.get<e4::e12>() * relative.get<e4::e12>() +
                                   relative.get<e4::e13>() * relative.get<e4::e13>() +
                                   relative.get<e4::e23>() * relative.get<e4::e23>()) /
                         cga::norm2(r1);
    worse(angle / (abs + rel));
    const Mat rm0 = rotation_matrix(m0), rm1 = rotation_matrix(m1);
    const Vec3 w0 = body.inv_inertia * (rm0.transpose() * line_moment(p0));
    const Vec3 w1 = body.inv_inertia * (rm1.transpose() * line_moment(p1));
    worse(ratio((body.inv_inertia * (rm1.transpose() * line_moment(dp))).norm(), w0.norm(), w1.norm()));
  }
  return worst;
}

// Through MotorGroup, on the whole motor M = T(x) R: the body-frame turn
// M exp(θ) = T(x) R exp(θ) keeps the translation, so the module steps M as it
// is, and the new centre x' then replaces it, M' = T(x') R' (as build() makes
// a motor). Π = Rᵀ L and L = R Π through MotorGroup::matrix, exact for a
// drifted motor; L and P are the momentum line's moment and direction.
void RigidBodies::group_step(const Model& m, core::SolverMethod method, double t, double h, std::span<const double> y,
                             std::span<double> out, std::span<double> err, std::span<const char> asleep) {
  using G = MotorGroup;
  const auto body_of = [&](std::size_t b) {
    const Body& body = m.bodies[b];
    return core::GroupBody{body.inv_mass, body.mass, body.inv_inertia};
  };
  const auto read = [](std::span<const double> s, std::size_t b) {
    const Layout at = layout(b);
    const Motor mo = motor_at(s, at.motor);
    const Line momentum = line_at(s, at.momentum);
    core::lie::BodyState<G> state;
    state.rotation = {mo, G::matrix(mo).transpose() * line_moment(momentum)};
    state.translation = {translation(mo), line_direction(momentum)};
    return state;
  };
  const auto write = [](std::span<double> s, std::size_t b, const core::lie::BodyState<G>& state) {
    const Layout at = layout(b);
    const Motor& turned = state.rotation.rotation;
    put(s, at.motor, cga::widen<Motor::blades>(translator(state.translation.x) * project<1 | kEuclideanLine>(turned)));
    put(s, at.momentum, line(state.translation.momentum, G::matrix(turned) * state.rotation.momentum));
  };
  core::group_step_bodies<G>(m.effects, m.bodies.size(), Model::stride, method, t, h, y, out, err, asleep, body_of, read, write);
}

void RigidBodies::observe(const Model& m, std::span<const double> y, core::Sample& s) {
  s.bodies.resize(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    const Layout at = layout(b);
    const Motor mo = motor_at(y, at.motor);
    // The reported orientation is the motor's rotation normalised;
    // rotation_drift() says how far the stored motor is from a unit one.
    const Eigen::Quaterniond q = quaternion_of(mo).normalized();
    const Mat r = rotation_matrix(mo);
    const Line rate = rate_of(r * body.inv_inertia * r.transpose(), body.inv_mass, line_at(y, at.momentum));
    auto& out = s.bodies[b];
    out.position = translation(mo);
    out.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    out.velocity = line_moment(rate);
    out.angular_velocity = line_direction(rate);
  }
  s.rotation_drift = rotation_drift(m, y);
}

// ---- collisions (§2.4–2.5) ----

// The narrowphase takes the motor's rotation as a 3×3 matrix, built once per
// body and query and applied to every vertex (the outermorphism, as for the
// other two backends: docs/architecture.md "Fair comparison").
collision::Pose RigidBodies::pose(const Model& m, std::span<const double> y, std::size_t b) {
  (void)m;
  const Motor mo = motor_at(y, layout(b).motor);
  return {rotation_matrix(mo), translation(mo)};
}

collision::Pose RigidBodies::interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                               std::size_t b, double s) {
  (void)m;
  const Layout at = layout(b);
  const Motor m0 = normalised(motor_at(y0, at.motor));
  const Motor step = normalised(reverse(m0) * motor_at(y1, at.motor));
  const Motor ms = m0 * exp(s * log(step));  // log takes the shorter way round
  return {rotation_matrix(ms), translation(ms)};
}

RigidBodies::Motion RigidBodies::motion(const Model& m, std::span<const double> y, std::size_t b) {
  const Body& body = m.bodies[b];
  const Layout at = layout(b);
  const Motor mo = motor_at(y, at.motor);
  const Mat r = rotation_matrix(mo);
  Motion out;
  out.x = translation(mo);
  out.inv_mass = body.inv_mass;
  out.inv_inertia = r * body.inv_inertia * r.transpose();
  const Line momentum = line_at(y, at.momentum);
  out.rate = rate_of(out.inv_inertia, body.inv_mass, momentum);
  return out;
}

RigidBodies::Arm RigidBodies::arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  // J = r ∨ n, the join of the point and the direction written out (cl301.hpp's
  // table: direction n, moment r × n): the generic join would multiply by the
  // direction's weight 0 and the point's 1.
  const Vec3 r = p - b.x;
  const Line row = line(n, r.cross(n));
  return {row, rate_of(b.inv_inertia, b.inv_mass, row)};  // A⁻¹[J]
}

double RigidBodies::inverse_effective_mass(const Motion& b, const Arm& a) {
  (void)b;
  return join(a.row, a.turn).c[0];
}

Eigen::Vector3d RigidBodies::point_velocity(const Motion& b, const Eigen::Vector3d& p) {
  return velocity_of(b.rate, point(p - b.x));
}

Eigen::Vector3d RigidBodies::in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u) {
  // u and n as planes through the origin (e1..e3 are Euclidean): the
  // rejection (u ∧ n)⌊n = u − (u·n) n for a unit n.
  const Plane pn = plane(n, 0);
  return normal(cga::widen<Plane::blades>(cga::rc(plane(u, 0) ^ pn, pn)));
}

Eigen::Vector3d RigidBodies::quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t) {
  return velocity_of(line(n, Vec3::Zero()), direction(t));
}

void RigidBodies::store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(b);
  put(y, at.momentum, line_at(y, at.momentum) + motion.impulse);
}

void RigidBodies::stop(const Model& m, std::span<double> y, std::size_t b) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(b);
  put(y, at.momentum, Line{});
}

void RigidBodies::displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(b);
  const Vec3 w = line_direction(pseudo.rate), v = line_moment(pseudo.rate);
  Motor d = cga::widen<Motor::blades>(translator(v));
  if (w.squaredNorm() > 0) d = compose(d, exp(-0.5 * line(w, pseudo.x.cross(w))));  // about the line through x
  put(y, at.motor, compose(d, motor_at(y, at.motor)));
}

}  // namespace gacompare::pga
