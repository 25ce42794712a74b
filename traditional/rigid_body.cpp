#include "traditional/rigid_body.hpp"

#include "core/dynamics/lie_bodies.hpp"
#include "core/error.hpp"
#include "traditional/rotation_group.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>
#include <type_traits>

namespace gacompare::traditional {

namespace {
using Vec = Eigen::Vector3d;
using Mat = Eigen::Matrix3d;

Vec vec_at(std::span<const double> y, std::size_t i) { return Vec(y[i], y[i + 1], y[i + 2]); }
void put(std::span<double> y, std::size_t i, const Vec& v) {
  for (int k = 0; k < 3; ++k) y[i + k] = v[k];
}
Mat matrix_at(std::span<const double> y, std::size_t i) {
  Mat r;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) r(a, b) = y[i + 3 * a + b];
  return r;
}
void put(std::span<double> y, std::size_t i, const Mat& r) {
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) y[i + 3 * a + b] = r(a, b);
}
// The stored quaternion, not normalised: its drift is what renormalisation is for.
Eigen::Quaterniond quat_at(std::span<const double> y, std::size_t i) {
  return Eigen::Quaterniond(y[i], y[i + 1], y[i + 2], y[i + 3]);
}
void put(std::span<double> y, std::size_t i, const Eigen::Quaterniond& q) {
  y[i] = q.w(), y[i + 1] = q.x(), y[i + 2] = q.y(), y[i + 3] = q.z();
}
Mat skew(const Vec& w) {  // w* of eq. 32: w* v = w × v
  Mat s;
  s << 0, -w.z(), w.y(), w.z(), 0, -w.x(), -w.y(), w.x(), 0;
  return s;
}

// Offsets within a body's block: x, rotation, P, L.
struct Layout {
  std::size_t x, rot, p, l;
};
Layout layout(const RigidBodies::Model& m, std::size_t b) {
  const std::size_t base = b * m.stride, rot = m.rotation == core::Rotation::matrix ? 9 : 4;
  return {base, base + 3, base + 3 + rot, base + 6 + rot};
}
// The rotation the state stands for. A quaternion's is that of q/|q|, as the
// cga backend reads its rotor (one policy): Eigen's
// toRotationMatrix assumes a unit quaternion, so a drifted one gave a matrix
// that is not a rotation, and ω = R I⁻¹ Rᵀ L a rate off by the drift. The
// homogeneous form (every entry quadratic in q) divided by |q|² is exact for
// any norm and needs no square root. The matrix state is used as it is:
// making it a rotation takes a polar decomposition, and its drift is what
// renormalise is for.
Mat rotation_of(const Eigen::Quaterniond& q) {
  const double w = q.w(), x = q.x(), y = q.y(), z = q.z(), s = 1 / q.squaredNorm();
  Mat r;
  r << w * w + x * x - y * y - z * z, 2 * (x * y - w * z), 2 * (x * z + w * y),
       2 * (x * y + w * z), w * w - x * x + y * y - z * z, 2 * (y * z - w * x),
       2 * (x * z - w * y), 2 * (y * z + w * x), w * w - x * x - y * y + z * z;
  return s * r;
}
// q̄ v q for a quaternion of any norm: |q|² Rᵀ v (the homogeneous form, no division).
Vec conj_rotate(const Eigen::Quaterniond& q, const Vec& v) {
  const Vec u = q.vec();
  return (q.w() * q.w() - u.squaredNorm()) * v + 2 * u.dot(v) * u - 2 * q.w() * u.cross(v);
}
Mat rotation(const RigidBodies::Model& m, std::span<const double> y, const Layout& at) {
  return m.rotation == core::Rotation::matrix ? matrix_at(y, at.rot) : rotation_of(quat_at(y, at.rot));
}
}  // namespace

RigidBodies::Model RigidBodies::build(const core::Scene& scene, const core::Model& model) {
  Model m;
  m.rotation = scene.rigid_body.rotation;
  m.renormalise = scene.rigid_body.renormalise;
  m.stride = m.rotation == core::Rotation::matrix ? 18 : 13;
  m.effects = model.effects;
  m.y0.assign(m.stride * scene.bodies.size(), 0.0);
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const auto& body = scene.bodies[b];
    const core::BodyModel& p = model.bodies[b];
    m.names.push_back(body.name);
    const bool fixed = body.is_static;
    m.bodies.push_back({fixed ? 0.0 : 1.0 / p.mass, fixed ? Mat::Zero().eval() : p.inertia.inverse().eval(), p.inertia,
                        p.mass});
    const Layout at = layout(m, b);
    const Eigen::Quaterniond q(body.orientation[0], body.orientation[1], body.orientation[2], body.orientation[3]);
    const Mat r = q.toRotationMatrix();
    put(m.y0, at.x, body.position);
    if (m.rotation == core::Rotation::matrix) {
      put(m.y0, at.rot, r);
    } else {
      for (int k = 0; k < 4; ++k) m.y0[at.rot + k] = body.orientation[k];
    }
    if (!fixed) {
      put(m.y0, at.p, Vec(p.mass * body.velocity));
      put(m.y0, at.l, Vec(r * p.inertia * r.transpose() * body.angular_velocity));  // L = I(t) ω
    }
  }
  return m;
}

RigidBodies::Model RigidBodies::subset(const Model& m, std::span<const int> which) {
  Model out;
  out.rotation = m.rotation;
  out.renormalise = m.renormalise;
  out.stride = m.stride;
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
    const Layout at = layout(m, b);
    std::fill(dydt.begin() + static_cast<long>(at.x), dydt.begin() + static_cast<long>(at.x + m.stride), 0.0);
    if (body.inv_mass == 0 || (!asleep.empty() && asleep[b])) return;  // static or asleep: does not move
    const Vec P = vec_at(y, at.p), L = vec_at(y, at.l);
    const Vec v = body.inv_mass * P;
    const core::BodyEffects& fx = m.effects;
    const bool matrix = m.rotation == core::Rotation::matrix;
    // The quaternion takes the rotor's body-frame form (cga/rigid_body.cpp),
    // its algebraic twin: ω_body = I⁻¹ q̄ L q / |q|², one rotation, and
    // q̇ = ½ q ω_body. Through the matrix (ω = R I⁻¹ Rᵀ L, q̇ = ½ ω q) it cost
    // the matrix's 27 products to form R and two products by it, and the
    // quaternion ran 1.2× the rotor's time per step for a formulation, not an
    // algebra. R and the world ω are formed only where an effect needs them.
    const Eigen::Quaterniond q = matrix ? Eigen::Quaterniond::Identity() : quat_at(y, at.rot);
    const Vec w_body = matrix ? Vec::Zero() : Vec(body.inv_inertia * (conj_rotate(q, L) / q.squaredNorm()));
    const bool need_r = matrix || !fx.pushes.empty();
    const Mat r = need_r ? rotation(m, y, at) : Mat::Identity();
    const Vec w = matrix ? Vec(r * (body.inv_inertia * (r.transpose() * L)))  // ω = R I⁻¹ Rᵀ L
                 : fx.has_linear_drag || fx.has_quadratic_drag ? Vec(rotation_of(q) * w_body)
                                                                : Vec::Zero();
    Vec force = Vec::Zero(), torque = Vec::Zero();
    if (fx.has_gravity) force += body.mass * fx.gravity;
    if (fx.has_linear_drag) force -= fx.linear_k * v, torque -= fx.linear_k_angular * w;
    if (fx.has_quadratic_drag) force -= fx.quadratic_k * v.norm() * v, torque -= fx.quadratic_k_angular * w.norm() * w;
    for (const auto& push : fx.pushes)
      if (push.acts_on(b, t)) {
        force += push.force;
        torque += (r * push.point).cross(push.force);  // τ = (R p) × F
      }
    put(dydt, at.x, v);
    if (matrix) {
      put(dydt, at.rot, Mat(skew(w) * r));  // eq. 33
    } else {
      // q (0, ω_b) = (−u·ω_b, w ω_b + u × ω_b), in scalars as the rotor's
      // product is (Eigen's packed quaternion product measured 1.2× slower here).
      const Vec u = q.vec();
      const Vec v = 0.5 * (q.w() * w_body + u.cross(w_body));
      dydt[at.rot] = -0.5 * u.dot(w_body);
      dydt[at.rot + 1] = v.x();
      dydt[at.rot + 2] = v.y();
      dydt[at.rot + 3] = v.z();
    }
    put(dydt, at.p, force);
    put(dydt, at.l, torque);
  }, core::kGrainLight);
}

bool RigidBodies::renormalise(const Model& m, std::span<double> y) {
  if (m.renormalise == core::Renormalise::none) return false;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Layout at = layout(m, b);
    if (m.rotation == core::Rotation::matrix) {
      // Gram–Schmidt on the columns (the rotated body axes, eq. 27).
      Mat r = matrix_at(y, at.rot);
      const Vec c0 = r.col(0).normalized();
      const Vec c1 = (r.col(1) - c0.dot(r.col(1)) * c0).normalized();
      r.col(0) = c0;
      r.col(1) = c1;
      r.col(2) = c0.cross(c1);
      put(y, at.rot, r);
    } else {
      const double n = quat_at(y, at.rot).norm();
      for (int k = 0; k < 4; ++k) y[at.rot + k] /= n;
    }
  }
  return true;
}

double RigidBodies::rotation_drift(const Model& m, std::span<const double> y) {
  double worst = 0;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Layout at = layout(m, b);
    const double d = m.rotation == core::Rotation::matrix
                         ? (matrix_at(y, at.rot).transpose() * matrix_at(y, at.rot) - Mat::Identity()).norm()
                         : std::abs(quat_at(y, at.rot).squaredNorm() - 1.0);
    worst = std::max(worst, d);
  }
  return worst;
}

// The angle of R⁻¹ δR: for a matrix the axial vector of the antisymmetric part
// of Rᵀ δR (its symmetric part is stretch, the drift renormalise is for); for
// a quaternion 2 vec(q* δq)/|q|². |δω| in the body frame, I⁻¹ Rᵀ δL (a rotation
// keeps lengths), with R normalised as everywhere else.
double RigidBodies::error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                                std::span<const double> err, double abs, double rel) {
  double worst = 0;
  const auto worse = [&](double r) { worst = std::isnan(r) || std::isnan(worst) ? NAN : std::max(worst, r); };
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (body.inv_mass == 0) continue;
    const Layout at = layout(m, b);
    const auto ratio = [&](double e, double a, double c) { return e / (abs + rel * std::max(a, c)); };
    worse(ratio(vec_at(err, at.x).norm(), vec_at(y, at.x).norm(), vec_at(ynew, at.x).norm()));
    worse(ratio(vec_at(err, at.p).norm(), vec_at(y, at.p).norm(), vec_at(ynew, at.p).norm()));  // δP/m over |P|/m
    double angle;
    if (m.rotation == core::Rotation::matrix) {
      const Mat a = matrix_at(ynew, at.rot).transpose() * matrix_at(err, at.rot);
      angle = 0.5 * Vec(a(2, 1) - a(1, 2), a(0, 2) - a(2, 0), a(1, 0) - a(0, 1)).norm();
    } else {
      const Eigen::Quaterniond q = quat_at(ynew, at.rot);
      angle = 2 * (q.conjugate() * quat_at(err, at.rot)).vec().norm() / q.squaredNorm();
    }
    worse(angle / (abs + rel));
    const Mat r0 = rotation(m, y, at), r1 = rotation(m, ynew, at);
    const Vec w0 = body.inv_inertia * (r0.transpose() * vec_at(y, at.l));
    const Vec w1 = body.inv_inertia * (r1.transpose() * vec_at(ynew, at.l));
    worse(ratio((body.inv_inertia * (r1.transpose() * vec_at(err, at.l))).norm(), w0.norm(), w1.norm()));
  }
  return worst;
}

namespace {
// Through group G (MatrixGroup or QuaternionGroup). Π = Rᵀ L and L = R Π
// through G::matrix, the rotation the state stands for (a quaternion's is
// that of q/|q|, as everywhere in this backend).
template <class G>
void group_step_in(const RigidBodies::Model& m, core::SolverMethod method, double t, double h,
                   std::span<const double> y, std::span<double> out, std::span<double> err,
                   std::span<const char> asleep) {
  const auto body_of = [&](std::size_t b) {
    const RigidBodies::Body& body = m.bodies[b];
    return core::GroupBody{body.inv_mass, body.mass, body.inv_inertia};
  };
  const auto read = [&](std::span<const double> s, std::size_t b) {
    const Layout at = layout(m, b);
    core::lie::BodyState<G> out;
    if constexpr (std::is_same_v<G, MatrixGroup>) out.rotation.rotation = matrix_at(s, at.rot);
    else out.rotation.rotation = quat_at(s, at.rot);
    out.rotation.momentum = G::matrix(out.rotation.rotation).transpose() * vec_at(s, at.l);
    out.translation = {vec_at(s, at.x), vec_at(s, at.p)};
    return out;
  };
  const auto write = [&](std::span<double> s, std::size_t b, const core::lie::BodyState<G>& state) {
    const Layout at = layout(m, b);
    const auto& r = state.rotation.rotation;
    put(s, at.x, state.translation.x);
    put(s, at.p, state.translation.momentum);
    put(s, at.rot, r);
    put(s, at.l, Vec(G::matrix(r) * state.rotation.momentum));
  };
  core::group_step_bodies<G>(m.effects, m.bodies.size(), m.stride, method, t, h, y, out, err, asleep, body_of, read, write);
}
}  // namespace

void RigidBodies::group_step(const Model& m, core::SolverMethod method, double t, double h, std::span<const double> y,
                             std::span<double> out, std::span<double> err, std::span<const char> asleep) {
  if (m.rotation == core::Rotation::matrix) group_step_in<MatrixGroup>(m, method, t, h, y, out, err, asleep);
  else group_step_in<QuaternionGroup>(m, method, t, h, y, out, err, asleep);
}

void RigidBodies::observe(const Model& m, std::span<const double> y, core::Sample& s) {
  s.bodies.resize(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    const Layout at = layout(m, b);
    const Mat r = rotation(m, y, at);
    // The reported orientation is the stored rotation's nearest unit quaternion;
    // rotation_drift() says how far the stored one is from a rotation.
    const Eigen::Quaterniond q = m.rotation == core::Rotation::matrix ? Eigen::Quaterniond(r).normalized()
                                                                      : quat_at(y, at.rot).normalized();
    auto& out = s.bodies[b];
    out.position = vec_at(y, at.x);
    out.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    out.velocity = body.inv_mass * vec_at(y, at.p);
    out.angular_velocity = r * (body.inv_inertia * (r.transpose() * vec_at(y, at.l)));
  }
  s.rotation_drift = rotation_drift(m, y);
}

// ---- collisions (§2.4–2.5) ----

collision::Pose RigidBodies::pose(const Model& m, std::span<const double> y, std::size_t b) {
  const Layout at = layout(m, b);
  return {rotation(m, y, at), vec_at(y, at.x)};
}

collision::Pose RigidBodies::interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                               std::size_t b, double s) {
  const Layout at = layout(m, b);
  const auto quaternion = [&](std::span<const double> y) {
    return m.rotation == core::Rotation::matrix ? Eigen::Quaterniond(matrix_at(y, at.rot)) : quat_at(y, at.rot).normalized();
  };
  const Eigen::Quaterniond q = quaternion(y0).slerp(s, quaternion(y1));  // Eigen takes the shorter arc
  return {q.toRotationMatrix(), Vec((1 - s) * vec_at(y0, at.x) + s * vec_at(y1, at.x))};
}

RigidBodies::Motion RigidBodies::motion(const Model& m, std::span<const double> y, std::size_t b) {
  const Body& body = m.bodies[b];
  const Layout at = layout(m, b);
  const Mat r = rotation(m, y, at);
  Motion out;
  out.x = vec_at(y, at.x);
  out.inv_mass = body.inv_mass;
  out.inv_inertia = r * body.inv_inertia * r.transpose();
  out.v = body.inv_mass * vec_at(y, at.p);
  out.w = out.inv_inertia * vec_at(y, at.l);  // ω = R I⁻¹ Rᵀ L
  return out;
}

RigidBodies::Arm RigidBodies::arm(const Motion& b, const Vec& p, const Vec& n) {
  const Vec r_n = (p - b.x).cross(n);
  return {r_n, b.inv_inertia * r_n};
}

double RigidBodies::inverse_effective_mass(const Motion& b, const Arm& a) { return b.inv_mass + a.r_n.dot(a.turn); }

Vec RigidBodies::point_velocity(const Motion& b, const Vec& p) { return b.v + b.w.cross(p - b.x); }

Vec RigidBodies::in_plane(const Vec& n, const Vec& u) { return n.cross(u.cross(n)); }

Vec RigidBodies::quarter_turn(const Vec& n, const Vec& t) { return n.cross(t); }

void RigidBodies::store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(m, b);
  put(y, at.p, Vec(vec_at(y, at.p) + motion.impulse));
  put(y, at.l, Vec(vec_at(y, at.l) + motion.angular_impulse));
}

void RigidBodies::stop(const Model& m, std::span<double> y, std::size_t b) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(m, b);
  put(y, at.p, Vec(Vec::Zero()));
  put(y, at.l, Vec(Vec::Zero()));
}

void RigidBodies::displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(m, b);
  put(y, at.x, Vec(vec_at(y, at.x) + pseudo.v));
  const double angle = pseudo.w.norm();
  if (!(angle > 0)) return;
  const Eigen::AngleAxisd turn(angle, pseudo.w / angle);
  if (m.rotation == core::Rotation::matrix) {
    put(y, at.rot, Mat(turn.toRotationMatrix() * matrix_at(y, at.rot)));
  } else {
    put(y, at.rot, Eigen::Quaterniond(Eigen::Quaterniond(turn) * quat_at(y, at.rot)));
  }
}

}  // namespace gacompare::traditional
