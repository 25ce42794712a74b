#include "cga/constraint.hpp"

#include "core/error.hpp"

#include <cmath>
#include <numbers>

namespace gacompare::cga {

namespace {
Vector position(std::span<const double> y, int i) { return vector3(y[6 * i], y[6 * i + 1], y[6 * i + 2]); }
Vector velocity(std::span<const double> y, int i) { return vector3(y[6 * i + 3], y[6 * i + 4], y[6 * i + 5]); }
double dot(const Vector& a, const Vector& b) { return scalar_product(a, b); }
std::array<double, 3> raw(const Vector& g) { return g.c; }
Vector vec(const std::array<double, 3>& g) { return Vector{g}; }
Vector unit(const Vector& v) { return v / norm(v); }
// a × b, the vector dual to the plane a ∧ b.
Vector cross(const Vector& a, const Vector& b) { return axial(a ^ b); }

// Any unit vector perpendicular to the unit vector a.
Vector perpendicular(const Vector& a) {
  const Vector t = std::abs(a.c[0]) < 0.9 ? vector3(1, 0, 0) : vector3(0, 1, 0);
  return unit(cross(a, t));
}

struct Rows {
  const ParticleModel& pm;
  std::span<const double> y;
  const std::vector<Vector>* forces;
  std::vector<core::ConstraintRow>& out;

  void one(double c, double jdot_qdot, int p, const Vector& g) {
    core::ConstraintRow r;
    r.c = c;
    r.jdot_qdot = jdot_qdot;
    r.n = 1;
    r.particle = {p, p};
    r.grad[0] = raw(g);
    r.j_qdot = dot(g, velocity(y, p));
    r.j_w_q = forces ? pm.inv_mass[p] * dot(g, (*forces)[p]) : 0.0;
    out.push_back(r);
  }
  void two(double c, double jdot_qdot, int a, const Vector& ga, int b, const Vector& gb) {
    core::ConstraintRow r;
    r.c = c;
    r.jdot_qdot = jdot_qdot;
    r.n = 2;
    r.particle = {a, b};
    r.grad[0] = raw(ga);
    r.grad[1] = raw(gb);
    r.j_qdot = dot(ga, velocity(y, a)) + dot(gb, velocity(y, b));
    r.j_w_q = forces ? pm.inv_mass[a] * dot(ga, (*forces)[a]) + pm.inv_mass[b] * dot(gb, (*forces)[b]) : 0.0;
    out.push_back(r);
  }

  void operator()(const PointDistance& k) {
    const Vector d = position(y, k.p) - k.point, v = velocity(y, k.p);
    one(0.5 * (dot(d, d) - k.length * k.length), dot(v, v), k.p, d);
  }
  void operator()(const PairDistance& k) {
    const Vector d = position(y, k.a) - position(y, k.b), v = velocity(y, k.a) - velocity(y, k.b);
    two(0.5 * (dot(d, d) - k.length * k.length), dot(v, v), k.a, d, k.b, -d);
  }
  void operator()(const PlaneConstraint& k) { one(dot(k.normal, position(y, k.p) - k.point), 0.0, k.p, k.normal); }
  void operator()(const LineConstraint& k) {
    const Vector d = position(y, k.p) - k.point;
    one(dot(k.u1, d), 0.0, k.p, k.u1);
    one(dot(k.u2, d), 0.0, k.p, k.u2);
  }
  void operator()(const CircleConstraint& k) {
    const Vector d = position(y, k.p) - k.center, v = velocity(y, k.p);
    one(dot(k.normal, d), 0.0, k.p, k.normal);
    one(0.5 * (dot(d, d) - k.radius * k.radius), dot(v, v), k.p, d);
  }
  // With X = u·d, Y = v·d, Z = axis·d and θ = Z/k: X² + Y² = r² and X sin θ − Y cos θ = 0.
  // C̈ = J q̈ + 2(Ẋ cos θ + Ẏ sin θ) θ̇ + (Y cos θ − X sin θ) θ̇² for the second row.
  void operator()(const HelixConstraint& k) {
    const Vector d = position(y, k.p) - k.center, vp = velocity(y, k.p);
    const double X = dot(k.u, d), Y = dot(k.v, d), th = dot(k.axis, d) / k.k;
    const double Xd = dot(k.u, vp), Yd = dot(k.v, vp), thd = dot(k.axis, vp) / k.k;
    const double s = std::sin(th), c = std::cos(th);
    one(0.5 * (X * X + Y * Y - k.radius * k.radius), Xd * Xd + Yd * Yd, k.p, X * k.u + Y * k.v);
    one(X * s - Y * c, 2 * (Xd * c + Yd * s) * thd + (Y * c - X * s) * thd * thd, k.p,
        s * k.u - c * k.v + ((X * c + Y * s) / k.k) * k.axis);
  }
};

void fill(const ConstraintModel& m, const ParticleModel& pm, std::span<const double> y, const std::vector<Vector>* f) {
  m.rows.clear();
  Rows rows{pm, y, f, m.rows};
  for (const auto& c : m.constraints) std::visit(rows, c);
}

int index_of(const ParticleModel& pm, const std::string& name) {
  for (std::size_t i = 0; i < pm.names.size(); ++i)
    if (pm.names[i] == name) return static_cast<int>(i);
  throw input_error("constraint refers to unknown particle '" + name + "'");
}

ParticleConstraint convert(const core::Constraint& c, const ParticleModel& pm, const std::vector<double>& y0) {
  if (auto* k = std::get_if<core::DistanceToPoint>(&c))
    return PointDistance{index_of(pm, k->particle), vector3(k->point), k->length};
  if (auto* k = std::get_if<core::DistanceBetween>(&c)) return PairDistance{index_of(pm, k->a), index_of(pm, k->b), k->length};
  if (auto* k = std::get_if<core::OnPlane>(&c))
    return PlaneConstraint{index_of(pm, k->particle), vector3(k->point), vector3(k->normal)};
  if (auto* k = std::get_if<core::OnLine>(&c)) {
    const Vector d = vector3(k->direction), u1 = perpendicular(d);
    return LineConstraint{index_of(pm, k->particle), vector3(k->point), u1, cross(d, u1)};
  }
  if (auto* k = std::get_if<core::OnCircle>(&c))
    return CircleConstraint{index_of(pm, k->particle), vector3(k->center), vector3(k->normal), k->radius};
  // The helix's phase comes from the particle's start: choose u, v (u × v = axis)
  // so that the start lies at θ0 = Z0/k. A start off the helix's cylinder is
  // caught by the initial-violation check below.
  const auto& h = std::get<core::OnHelix>(c);
  const int p = index_of(pm, h.particle);
  const double k = h.pitch / (2 * std::numbers::pi);
  const Vector center = vector3(h.center), axis = vector3(h.axis);
  const Vector d0 = position(y0, p) - center;
  const double th0 = dot(axis, d0) / k;
  const Vector off = d0 - dot(axis, d0) * axis;
  const Vector e = norm(off) > 0 ? unit(off) : perpendicular(axis);
  const Vector f = cross(axis, e);
  return HelixConstraint{p, center, std::cos(th0) * e - std::sin(th0) * f, std::sin(th0) * e + std::cos(th0) * f,
                         axis, h.radius, k};
}
}  // namespace

ConstraintModel build_constraints(const core::Scene& scene, const ParticleModel& pm) {
  ConstraintModel m;
  std::vector<double> y0(kParticleState * pm.names.size());
  initial_particle_state(pm, y0);
  ConstraintModel single;  // one constraint at a time, to learn which rows it owns
  for (std::size_t i = 0; i < scene.constraints.size(); ++i) {
    m.constraints.push_back(convert(scene.constraints[i], pm, y0));
    single.constraints = {m.constraints.back()};
    fill(single, pm, y0, nullptr);
    m.owner.insert(m.owner.end(), single.rows.size(), static_cast<int>(i));
  }
  fill(m, pm, y0, nullptr);
  core::check_initial_constraints(scene, m.rows, m.owner, y0);
  return m;
}

void constraint_rows(const ConstraintModel& m, const ParticleModel& pm, std::span<const double> y,
                     const std::vector<Vector>& forces) {
  fill(m, pm, y, &forces);
}

void add_constraint_forces(const ConstraintModel& m, const ParticleModel& pm, std::span<const double> y,
                           std::vector<Vector>& forces, core::ConstraintSolver& solver) {
  fill(m, pm, y, &forces);
  const auto& lambda = solver.solve(m.rows, solver.dynamics_rhs(m.rows));
  for (std::size_t k = 0; k < m.rows.size(); ++k) {
    const auto& r = m.rows[k];
    for (int i = 0; i < r.n; ++i) forces[r.particle[i]] += lambda[k] * vec(r.grad[i]);
  }
}

void project_constraints(const ConstraintModel& m, const ParticleModel& pm, std::span<double> y,
                         core::ConstraintSolver& solver) {
  core::project_onto_constraints(solver, y, kParticleState, [&](std::span<const double> yy) -> const auto& {
    fill(m, pm, yy, nullptr);
    return m.rows;
  });
}

}  // namespace gacompare::cga
