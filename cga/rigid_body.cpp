#include "cga/rigid_body.hpp"

#include "cga/rotation_group.hpp"
#include "core/dynamics/lie_bodies.hpp"
#include "core/error.hpp"
#include "core/parallel.hpp"

#include <algorithm>
#include <cmath>

namespace gacompare::cga {

namespace {
using Mat = Eigen::Matrix3d;

Vector3 vec_at(std::span<const double> y, std::size_t i) { return vector3(y[i], y[i + 1], y[i + 2]); }
Bivector3 biv_at(std::span<const double> y, std::size_t i) { return bivector3(y[i], y[i + 1], y[i + 2]); }
Rotor3 rotor_at(std::span<const double> y, std::size_t i) { return {{y[i], y[i + 1], y[i + 2], y[i + 3]}}; }
template <class M>
void put(std::span<double> y, std::size_t i, const M& m) {
  for (int k = 0; k < M::size; ++k) y[i + static_cast<std::size_t>(k)] = m.c[static_cast<std::size_t>(k)];
}
// Ω = I⁻¹(L) with I given on bivector components.
Bivector3 apply(const Mat& t, const Bivector3& b) {
  const Eigen::Vector3d r = t * Eigen::Vector3d(b.c[0], b.c[1], b.c[2]);
  return bivector3(r[0], r[1], r[2]);
}
// The inertia tensor (axial vectors) as a map on bivector components: B = P a with
// P: (x, y, z) ↦ (e12, e13, e23) = (z, −y, x), so I_biv = P I Pᵀ (P is its own inverse).
Mat on_bivectors(const Mat& axial) {
  Mat p;
  p << 0, 0, 1, 0, -1, 0, 1, 0, 0;
  return p * axial * p.transpose();
}

// Offsets within a body's block: x, R, P, L.
struct Layout {
  std::size_t x, rot, p, l;
};
Layout layout(std::size_t b) {
  const std::size_t base = b * RigidBodies::Model::stride;
  return {base, base + 3, base + 7, base + 10};
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
    const Mat inertia = on_bivectors(p.inertia);
    m.bodies.push_back({fixed ? 0.0 : 1.0 / p.mass, fixed ? Mat::Zero().eval() : inertia.inverse().eval(), inertia,
                        p.mass});
    const Layout at = layout(b);
    const Eigen::Quaterniond q(body.orientation[0], body.orientation[1], body.orientation[2], body.orientation[3]);
    const Rotor3 r = rotor_from_quaternion(q);
    put(m.y0, at.x, vector3(body.position));
    put(m.y0, at.rot, r);
    if (!fixed) {
      put(m.y0, at.p, p.mass * vector3(body.velocity));
      // L = R I(R̃ Ω R) R̃ with Ω the bivector of the world angular velocity.
      const Bivector3 omega_body = sandwich(reverse(r), bivector_of_axial(vector3(body.angular_velocity)));
      put(m.y0, at.l, sandwich(r, apply(inertia, omega_body)));
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
    std::fill(dydt.begin() + static_cast<long>(at.x), dydt.begin() + static_cast<long>(at.x + Model::stride), 0.0);
    if (body.inv_mass == 0 || (!asleep.empty() && asleep[b])) return;  // static or asleep: does not move
    const Vector3 v = body.inv_mass * vec_at(y, at.p);
    const Rotor3 r = rotor_at(y, at.rot);
    // Ω_body from the normalised rotor. With R itself, R̃ L R and
    // the sandwich back to Ω each scale as |R|², so a drifting norm changed
    // the rotation rate as |R|⁴ and the error control paid for it in steps
    // (2.0× the matrix's steps at equal orientation error on the spinning
    // top). Ṙ = −½ Ω R = −½ R Ω_body (Ω R = R Ω_body R̃ R) then scales as |R|,
    // as the quaternion's q̇ = ½ ω q does, and costs one sandwich, not two.
    // The sandwich is quadratic in R, so R̂̃ L R̂ = R̃ L R / |R|²: one division,
    // no square root (the unit rotor is formed only for drag and pushes).
    const double inv_norm2 = 1 / norm2(r);
    const Bivector3 omega_body = apply(body.inv_inertia, sandwich(reverse(r), biv_at(y, at.l))) * inv_norm2;
    const auto unit = [&] { return r * std::sqrt(inv_norm2); };
    const core::BodyEffects& fx = m.effects;
    Vector3 force{};
    Bivector3 torque{};
    if (fx.has_gravity) force += body.mass * vector3(fx.gravity);
    if (fx.has_linear_drag || fx.has_quadratic_drag) {
      const Bivector3 omega = sandwich(unit(), omega_body);  // §2.3.2: Ω = R Ω_body R̃
      if (fx.has_linear_drag) force -= fx.linear_k * v, torque -= fx.linear_k_angular * omega;
      if (fx.has_quadratic_drag) {
        const double speed = std::sqrt(scalar_product(v, v)), spin = std::sqrt(-scalar_product(omega, omega));
        force -= (fx.quadratic_k * speed) * v, torque -= (fx.quadratic_k_angular * spin) * omega;
      }
    }
    for (const auto& push : fx.pushes)
      if (push.acts_on(b, t)) {
        const Vector3 f = vector3(push.force);
        force += f;
        torque += sandwich(unit(), vector3(push.point)) ^ f;  // τ = (R p R̃) ∧ F
      }
    put(dydt, at.x, v);
    put(dydt, at.rot, -0.5 * (r * omega_body));  // eq. 35
    put(dydt, at.p, force);
    put(dydt, at.l, torque);
  }, core::kGrainLight);
}

bool RigidBodies::renormalise(const Model& m, std::span<double> y) {
  if (m.renormalise == core::Renormalise::none) return false;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Layout at = layout(b);
    const Rotor3 r = rotor_at(y, at.rot);
    put(y, at.rot, r / std::sqrt(norm2(r)));  // R / √(R R̃)
  }
  return true;
}

double RigidBodies::rotation_drift(const Model& m, std::span<const double> y) {
  double worst = 0;
  for (std::size_t b = 0; b < m.bodies.size(); ++b) worst = std::max(worst, std::abs(norm2(rotor_at(y, layout(b).rot)) - 1.0));
  return worst;
}

// The angle of R⁻¹ δR: 2|⟨R̃ δR⟩₂|/|R|² (the bivector of the relative rotor,
// twice: R = exp(−Bθ/2)). |δΩ| in the body frame, I⁻¹(R̂̃ δL R̂) (a rotation
// keeps lengths).
double RigidBodies::error_ratio(const Model& m, std::span<const double> y, std::span<const double> ynew,
                                std::span<const double> err, double abs, double rel) {
  double worst = 0;
  const auto worse = [&](double r) { worst = std::isnan(r) || std::isnan(worst) ? NAN : std::max(worst, r); };
  const auto length = [](const auto& v) { return std::sqrt(std::abs(scalar_product(v, v))); };
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    if (body.inv_mass == 0) continue;
    const Layout at = layout(b);
    const auto ratio = [&](double e, double a, double c) { return e / (abs + rel * std::max(a, c)); };
    worse(ratio(length(vec_at(err, at.x)), length(vec_at(y, at.x)), length(vec_at(ynew, at.x))));
    worse(ratio(length(vec_at(err, at.p)), length(vec_at(y, at.p)), length(vec_at(ynew, at.p))));
    const Rotor3 r1 = rotor_at(ynew, at.rot);
    const auto relative = reverse(r1) * rotor_at(err, at.rot);
    const double angle = 2 * length(bivector3(relative[e3::e12], relative[e3::e13], relative[e3::e23])) / norm2(r1);
    worse(angle / (abs + rel));
    const Rotor3 u0 = rotor_at(y, at.rot) / std::sqrt(norm2(rotor_at(y, at.rot))), u1 = r1 / std::sqrt(norm2(r1));
    const double w0 = length(apply(body.inv_inertia, sandwich(reverse(u0), biv_at(y, at.l))));
    const double w1 = length(apply(body.inv_inertia, sandwich(reverse(u1), biv_at(ynew, at.l))));
    worse(ratio(length(apply(body.inv_inertia, sandwich(reverse(u1), biv_at(err, at.l)))), w0, w1));
  }
  return worst;
}

// Through RotorGroup. The module's vectors are axial: L and I⁻¹ turn from
// bivector components by their dual (axial(), on_bivectors, P its own
// inverse); Π = R̃ L R and L = R Π R̃ through RotorGroup::matrix, the rotation
// of R / √(R R̃), as the derivative reads a drifted rotor.
void RigidBodies::group_step(const Model& m, core::SolverMethod method, double t, double h, std::span<const double> y,
                             std::span<double> out, std::span<double> err, std::span<const char> asleep) {
  using G = RotorGroup;
  const auto body_of = [&](std::size_t b) {
    const Body& body = m.bodies[b];
    return core::GroupBody{body.inv_mass, body.mass, on_bivectors(body.inv_inertia)};
  };
  const auto read = [](std::span<const double> s, std::size_t b) {
    const Layout at = layout(b);
    core::lie::BodyState<G> state;
    state.rotation.rotation = rotor_at(s, at.rot);
    state.rotation.momentum = G::matrix(state.rotation.rotation).transpose() * to_eigen(axial(biv_at(s, at.l)));
    state.translation = {to_eigen(vec_at(s, at.x)), to_eigen(vec_at(s, at.p))};
    return state;
  };
  const auto write = [](std::span<double> s, std::size_t b, const core::lie::BodyState<G>& state) {
    const Layout at = layout(b);
    put(s, at.x, vector3(state.translation.x));
    put(s, at.p, vector3(state.translation.momentum));
    put(s, at.rot, state.rotation.rotation);
    put(s, at.l, bivector_of_axial(vector3(G::matrix(state.rotation.rotation) * state.rotation.momentum)));
  };
  core::group_step_bodies<G>(m.effects, m.bodies.size(), Model::stride, method, t, h, y, out, err, asleep, body_of, read, write);
}

void RigidBodies::observe(const Model& m, std::span<const double> y, core::Sample& s) {
  s.bodies.resize(m.bodies.size());
  for (std::size_t b = 0; b < m.bodies.size(); ++b) {
    const Body& body = m.bodies[b];
    const Layout at = layout(b);
    const Rotor3 r = rotor_at(y, at.rot);
    // The reported orientation is the stored rotor normalised; rotation_drift()
    // says how far the stored one is from a rotor.
    const Eigen::Quaterniond q = quaternion_from_rotor(r / std::sqrt(norm2(r)));
    auto& out = s.bodies[b];
    out.position = to_eigen(vec_at(y, at.x));
    out.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    out.velocity = to_eigen(body.inv_mass * vec_at(y, at.p));
    const Rotor3 unit = r / std::sqrt(norm2(r));
    out.angular_velocity = to_eigen(axial(sandwich(unit, apply(body.inv_inertia, sandwich(reverse(unit), biv_at(y, at.l))))));
  }
  s.rotation_drift = rotation_drift(m, y);
}

// ---- collisions (§2.4–2.5) ----

// The narrowphase takes the rotor's 3×3 matrix: built once per body per query
// and applied to every vertex (the outermorphism; docs/architecture.md "Fair
// comparison"). The drifted rotor gives an exact rotation through the
// homogeneous form over R R̃, as the quaternion does (one policy for both).
collision::Pose RigidBodies::pose(const Model& m, std::span<const double> y, std::size_t b) {
  (void)m;
  const Layout at = layout(b);
  const Rotor3 r = rotor_at(y, at.rot);
  return {rotation_matrix(r), to_eigen(vec_at(y, at.x))};
}

// The world inverse inertia on bivectors, once per body and response: the
// rotor's action on bivectors is the orthogonal map S (bivector_rotation_matrix:
// its coefficients once, not three sandwiches), and I⁻¹_world = S I⁻¹ Sᵀ. A
// point carried by the body moves with ṙ = r⌋Ω (the commutator of eq. 35:
// d/dt (R r R̃) = ½(r Ω − Ω r) = r⌋Ω for a vector r and a bivector Ω).
collision::Pose RigidBodies::interpolated_pose(const Model& m, std::span<const double> y0, std::span<const double> y1,
                                               std::size_t b, double s) {
  (void)m;
  const Layout at = layout(b);
  const Rotor3 r0 = rotor_at(y0, at.rot) / std::sqrt(norm2(rotor_at(y0, at.rot)));
  Rotor3 step = reverse(r0) * (rotor_at(y1, at.rot) / std::sqrt(norm2(rotor_at(y1, at.rot))));
  if (step.c[0] < 0) step = step * -1.0;  // R and −R turn alike: the shorter way
  const Rotor3 r = r0 * exp(log(step) * s);
  return {rotation_matrix(r), to_eigen(vec_at(y0, at.x) * (1 - s) + vec_at(y1, at.x) * s)};
}

RigidBodies::Motion RigidBodies::motion(const Model& m, std::span<const double> y, std::size_t b) {
  const Body& body = m.bodies[b];
  const Layout at = layout(b);
  const Mat s = bivector_rotation_matrix(rotor_at(y, at.rot));
  Motion out;
  out.x = vec_at(y, at.x);
  out.inv_mass = body.inv_mass;
  out.inv_inertia = s * body.inv_inertia * s.transpose();
  out.v = body.inv_mass * vec_at(y, at.p);
  out.w = apply(out.inv_inertia, biv_at(y, at.l));  // Ω = R I⁻¹(R̃ L R) R̃
  return out;
}

RigidBodies::Arm RigidBodies::arm(const Motion& b, const Eigen::Vector3d& p, const Eigen::Vector3d& n) {
  const Bivector3 r_n = (vector3(p) - b.x) ^ vector3(n);
  return {r_n, apply(b.inv_inertia, r_n)};
}

// (The sign: eq. 54 prints n∧r inside I⁻¹; with r·(·) on the left the term is
// positive only with r∧n, as the tests against eq. 53 check.)
double RigidBodies::inverse_effective_mass(const Motion& b, const Arm& a) {
  return b.inv_mass - scalar_product(a.r_n, a.turn);
}

Eigen::Vector3d RigidBodies::point_velocity(const Motion& b, const Eigen::Vector3d& p) {
  return to_eigen(b.v + ((vector3(p) - b.x) | b.w));
}

Eigen::Vector3d RigidBodies::in_plane(const Eigen::Vector3d& n, const Eigen::Vector3d& u) {
  const Bivector3 plane = bivector_of_axial(vector3(n));
  return to_eigen((vector3(u) | plane) | ~plane);
}

Eigen::Vector3d RigidBodies::quarter_turn(const Eigen::Vector3d& n, const Eigen::Vector3d& t) {
  return to_eigen(vector3(t) | bivector_of_axial(vector3(n)));
}

void RigidBodies::store(const Model& m, std::span<double> y, std::size_t b, const Motion& motion) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(b);
  put(y, at.p, vec_at(y, at.p) + motion.impulse);
  put(y, at.l, biv_at(y, at.l) + motion.angular_impulse);
}

void RigidBodies::stop(const Model& m, std::span<double> y, std::size_t b) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(b);
  put(y, at.p, Vector3{});
  put(y, at.l, Bivector3{});
}

void RigidBodies::displace(const Model& m, std::span<double> y, std::size_t b, const Motion& pseudo) {
  if (m.bodies[b].inv_mass == 0) return;
  const Layout at = layout(b);
  put(y, at.x, vec_at(y, at.x) + pseudo.v);
  if (!(angular_speed(pseudo) > 0)) return;
  put(y, at.rot, exp(-0.5 * pseudo.w) * rotor_at(y, at.rot));
}

}  // namespace gacompare::cga
