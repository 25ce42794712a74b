#pragma once
// Constraints on particles (§2.1.2), written once over a backend's vector algebra.
// Each constraint gives rows of C, ∇C and J̇q̇ at the current state; the
// multipliers come from core::ConstraintSolver and the forces Jᵀλ go back to the
// particles. The formulas are the same whatever represents a vector — the report
// (§2.2) expects nothing else for particles — so they live here once, and each
// backend supplies only its algebra as an `Ops` policy (traditional/constraint.hpp:
// Eigen dot and cross; cga/constraint.hpp: scalar product and the dual of a ∧ b).
//
// Ops: using Vector; static Vector position(y, i), velocity(y, i), from(Eigen 3-vector);
//      static double dot(a, b); static Vector cross(a, b), unit(a);
//      static std::array<double, 3> raw(a); static Vector vec(std::array<double, 3>).
#include "core/dynamics/particle_constraint_solver.hpp"
#include "core/dynamics/particle_vector.hpp"
#include "core/error.hpp"
#include "core/model/scene.hpp"

#include <cmath>
#include <numbers>
#include <span>
#include <string>
#include <variant>
#include <vector>

namespace gacompare::core {

template <class V> struct PointDistance { int p; V point; double length; };  // C = ½(|x − o|² − L²)   (eq. 25)
template <class V> struct PairDistance { int a, b; double length; };         // C = ½(|xa − xb|² − L²) (eq. 26)
template <class V> struct PlaneConstraint { int p; V point, normal; };       // C = n·(x − o)
template <class V> struct LineConstraint { int p; V point, u1, u2; };        // C_i = u_i·(x − o), u_i ⊥ line
template <class V> struct CircleConstraint { int p; V center, normal; double radius; };  // plane row + sphere row
template <class V> struct HelixConstraint { int p; V center, u, v, axis; double radius, k; };  // k = pitch / 2π

template <ParticleVectorOps Ops>
struct ParticleConstraints {
  using V = typename Ops::Vector;
  using Constraint = std::variant<PointDistance<V>, PairDistance<V>, PlaneConstraint<V>, LineConstraint<V>,
                                  CircleConstraint<V>, HelixConstraint<V>>;
  struct Model {
    std::vector<Constraint> constraints;
    std::vector<int> owner;                         // per row: the constraint (scene order) it belongs to
    mutable std::vector<ConstraintRow> rows;        // scratch, refilled on every evaluation
  };

  // Resolves particle names, builds each constraint's frame, and throws
  // input_error when the initial state y0 does not satisfy a constraint.
  static Model build(const Scene& scene, const std::vector<std::string>& names, std::span<const double> y0) {
    Model m, single;  // single: one constraint at a time, to learn which rows it owns
    for (std::size_t i = 0; i < scene.constraints.size(); ++i) {
      m.constraints.push_back(convert(scene.constraints[i], names, y0));
      single.constraints = {m.constraints.back()};
      fill(single, {}, y0, nullptr);
      m.owner.insert(m.owner.end(), single.rows.size(), static_cast<int>(i));
    }
    fill(m, {}, y0, nullptr);
    check_initial_constraints(scene, m.rows, m.owner, y0);
    return m;
  }

  // m.rows at state y; with `forces` (the applied forces) J W Q is filled too.
  static void fill(const Model& m, std::span<const double> inv_mass, std::span<const double> y,
                   const std::vector<V>* forces) {
    m.rows.clear();
    Rows rows{inv_mass, y, forces, m.rows};
    for (const auto& c : m.constraints) std::visit(rows, c);
  }

  // forces += Jᵀλ with λ from eq. 24 (and Baumgarte's terms when chosen).
  static void add_forces(const Model& m, std::span<const double> inv_mass, std::span<const double> y,
                         std::vector<V>& forces, ConstraintSolver& solver) {
    fill(m, inv_mass, y, &forces);
    const auto& lambda = solver.solve(m.rows, solver.dynamics_rhs(m.rows));
    for (std::size_t k = 0; k < m.rows.size(); ++k) {
      const auto& r = m.rows[k];
      for (int i = 0; i < r.n; ++i) forces[r.particle[i]] += lambda[k] * Ops::vec(r.grad[i]);
    }
  }

  // drift = projection, after a step (see project_onto_constraints).
  static void project(const Model& m, std::span<double> y, ConstraintSolver& solver) {
    project_onto_constraints(solver, y, 6, [&](std::span<const double> yy) -> const std::vector<ConstraintRow>& {
      fill(m, {}, yy, nullptr);
      return m.rows;
    });
  }

 private:
  static double dot(const V& a, const V& b) { return Ops::dot(a, b); }

  // Any unit vector perpendicular to the unit vector a.
  static V perpendicular(const V& a) {
    const V t = Ops::from(std::abs(Ops::raw(a)[0]) < 0.9 ? Vec3(1, 0, 0) : Vec3(0, 1, 0));
    return Ops::unit(Ops::cross(a, t));
  }

  struct Rows {
    std::span<const double> inv_mass;  // empty when forces are not given
    std::span<const double> y;
    const std::vector<V>* forces;
    std::vector<ConstraintRow>& out;

    void one(double c, double jdot_qdot, int p, const V& g) {
      ConstraintRow r;
      r.c = c;
      r.jdot_qdot = jdot_qdot;
      r.n = 1;
      r.particle = {p, p};
      r.grad[0] = Ops::raw(g);
      r.j_qdot = dot(g, Ops::velocity(y, p));
      r.j_w_q = forces ? inv_mass[p] * dot(g, (*forces)[p]) : 0.0;
      out.push_back(r);
    }
    void two(double c, double jdot_qdot, int a, const V& ga, int b, const V& gb) {
      ConstraintRow r;
      r.c = c;
      r.jdot_qdot = jdot_qdot;
      r.n = 2;
      r.particle = {a, b};
      r.grad[0] = Ops::raw(ga);
      r.grad[1] = Ops::raw(gb);
      r.j_qdot = dot(ga, Ops::velocity(y, a)) + dot(gb, Ops::velocity(y, b));
      r.j_w_q = forces ? inv_mass[a] * dot(ga, (*forces)[a]) + inv_mass[b] * dot(gb, (*forces)[b]) : 0.0;
      out.push_back(r);
    }

    void operator()(const PointDistance<V>& k) {
      const V d = Ops::position(y, k.p) - k.point, v = Ops::velocity(y, k.p);
      one(0.5 * (dot(d, d) - k.length * k.length), dot(v, v), k.p, d);
    }
    void operator()(const PairDistance<V>& k) {
      const V d = Ops::position(y, k.a) - Ops::position(y, k.b), v = Ops::velocity(y, k.a) - Ops::velocity(y, k.b);
      two(0.5 * (dot(d, d) - k.length * k.length), dot(v, v), k.a, d, k.b, -d);
    }
    void operator()(const PlaneConstraint<V>& k) { one(dot(k.normal, Ops::position(y, k.p) - k.point), 0.0, k.p, k.normal); }
    void operator()(const LineConstraint<V>& k) {
      const V d = Ops::position(y, k.p) - k.point;
      one(dot(k.u1, d), 0.0, k.p, k.u1);
      one(dot(k.u2, d), 0.0, k.p, k.u2);
    }
    void operator()(const CircleConstraint<V>& k) {
      const V d = Ops::position(y, k.p) - k.center, v = Ops::velocity(y, k.p);
      one(dot(k.normal, d), 0.0, k.p, k.normal);
      one(0.5 * (dot(d, d) - k.radius * k.radius), dot(v, v), k.p, d);
    }
    // With X = u·d, Y = v·d, Z = axis·d and θ = Z/k: X² + Y² = r² and X sin θ − Y cos θ = 0.
    // C̈ = J q̈ + 2(Ẋ cos θ + Ẏ sin θ) θ̇ + (Y cos θ − X sin θ) θ̇² for the second row.
    void operator()(const HelixConstraint<V>& k) {
      const V d = Ops::position(y, k.p) - k.center, vp = Ops::velocity(y, k.p);
      const double X = dot(k.u, d), Y = dot(k.v, d), th = dot(k.axis, d) / k.k;
      const double Xd = dot(k.u, vp), Yd = dot(k.v, vp), thd = dot(k.axis, vp) / k.k;
      const double s = std::sin(th), c = std::cos(th);
      one(0.5 * (X * X + Y * Y - k.radius * k.radius), Xd * Xd + Yd * Yd, k.p, V(X * k.u + Y * k.v));
      one(X * s - Y * c, 2 * (Xd * c + Yd * s) * thd + (Y * c - X * s) * thd * thd, k.p,
          V(s * k.u - c * k.v + ((X * c + Y * s) / k.k) * k.axis));
    }
  };

  static int index_of(const std::vector<std::string>& names, const std::string& name) {
    for (std::size_t i = 0; i < names.size(); ++i)
      if (names[i] == name) return static_cast<int>(i);
    throw input_error("constraint refers to unknown particle '" + name + "'");
  }

  static Constraint convert(const core::Constraint& c, const std::vector<std::string>& names,
                            std::span<const double> y0) {
    if (auto* k = std::get_if<DistanceToPoint>(&c))
      return PointDistance<V>{index_of(names, k->particle), Ops::from(k->point), k->length};
    if (auto* k = std::get_if<DistanceBetween>(&c))
      return PairDistance<V>{index_of(names, k->a), index_of(names, k->b), k->length};
    if (auto* k = std::get_if<OnPlane>(&c))
      return PlaneConstraint<V>{index_of(names, k->particle), Ops::from(k->point), Ops::from(k->normal)};
    if (auto* k = std::get_if<OnLine>(&c)) {
      const V d = Ops::from(k->direction), u1 = perpendicular(d), u2 = Ops::cross(d, u1);
      LineConstraint<V> line{index_of(names, k->particle), Ops::from(k->point), u1, u2};
      return line;
    }
    if (auto* k = std::get_if<OnCircle>(&c))
      return CircleConstraint<V>{index_of(names, k->particle), Ops::from(k->center), Ops::from(k->normal), k->radius};
    // The helix's phase comes from the particle's start: choose u, v (u × v = axis)
    // so that the start lies at θ0 = Z0/k. A start off the helix's cylinder is
    // caught by the initial-violation check.
    const auto& h = std::get<OnHelix>(c);
    const int p = index_of(names, h.particle);
    const double k = h.pitch / (2 * std::numbers::pi);
    const V center = Ops::from(h.center), axis = Ops::from(h.axis);
    const V d0 = Ops::position(y0, p) - center;
    const double th0 = dot(axis, d0) / k;
    const V off = d0 - dot(axis, d0) * axis;
    const V e = dot(off, off) > 0 ? Ops::unit(off) : perpendicular(axis);
    const V f = Ops::cross(axis, e);
    const V u = std::cos(th0) * e - std::sin(th0) * f, v = std::sin(th0) * e + std::cos(th0) * f;
    HelixConstraint<V> helix{p, center, u, v, axis, h.radius, k};
    return helix;
  }
};

}  // namespace gacompare::core
