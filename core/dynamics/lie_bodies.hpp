#pragma once
// A scene's bodies stepped by a Lie-group solver.method (rkmk4, rkmk45,
// crouch_grossman4; core/dynamics/lie_group.hpp body_step): what every
// backend's group_step shares, the method and the scene's forces and torques
// on one body as the module reads them. Each backend packs and unpacks its
// own rotation (matrix, quaternion, rotor, motor) around the step.
#include "core/dynamics/lie_group.hpp"
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

#include <algorithm>
#include <cstddef>
#include <span>

namespace gacompare::core {

// rkmk4 → RKMK on RK4, rkmk45 → RKMK on Dormand–Prince 5(4) (the pair's
// error estimate kept), crouch_grossman4 → Crouch–Grossman 4.
lie::GroupMethod group_method(SolverMethod m);

// Body `body`'s world force F(t, P) and torque τ(t, R, L) from the scene's
// effects, as every backend's derivative applies them: gravity m g, the drags
// on v = P/m and on ω = R I⁻¹ Rᵀ L, and the applied forces, F at the body
// point p, τ = (R p) × F, while from ≤ t < until.
struct BodyForces {
  const BodyEffects* effects;
  std::size_t body;
  double mass;
  Eigen::Matrix3d inv_inertia;  // body frame, on axial vectors
  Eigen::Vector3d force(double t, const Eigen::Vector3d& momentum) const;
  Eigen::Vector3d torque(double t, const Eigen::Matrix3d& rotation, const Eigen::Vector3d& momentum) const;
  // Whether any effect turns the body (an angular drag, a force applied to it).
  bool turns() const;
  // The module's body: I⁻¹ as it is (body axes need not be principal) and
  // τ when anything turns the body. The torque refers to *this.
  lie::FreeBody free_body() const;
};

// What the step reads of a backend's body: 1/m (0: static), m, and I⁻¹ in the
// body frame on axial vectors.
struct GroupBody {
  double inv_mass, mass;
  Eigen::Matrix3d inv_inertia;
};

// A Lie-group step of every body of a backend's state (its group_step),
// written once: body b's block is [b·stride, (b + 1)·stride); body_of(b)
// gives its GroupBody, read(y, b) unpacks its BodyState<G> (Π = R⁻¹ L) and
// write(s, b, state) packs one (L = R Π). A static body, and one flagged in
// `asleep` (empty, or a flag per body: core/collision/sleep.hpp), is copied,
// its err zero: it does not move, as its derivative is zero. With rkmk45, err
// gets out less the embedded solution, in the stored numbers.
template <lie::RotationGroup G, class BodyOf, class Read, class Write>
void group_step_bodies(const BodyEffects& effects, std::size_t count, std::size_t stride, SolverMethod method, double t,
                       double h, std::span<const double> y, std::span<double> out, std::span<double> err,
                       std::span<const char> asleep, BodyOf&& body_of, Read&& read, Write&& write) {
  const lie::GroupMethod group = group_method(method);
  const bool pair = method == SolverMethod::rkmk45;
  // Each body's slices of out and err are its own: bodies in parallel (core/parallel.hpp).
  for_each_index(count, [&](std::size_t b) {
    const GroupBody body = body_of(b);
    const std::size_t at = b * stride;
    if (body.inv_mass == 0 || (!asleep.empty() && asleep[b])) {
      std::copy_n(y.begin() + static_cast<long>(at), stride, out.begin() + static_cast<long>(at));
      if (pair) std::fill_n(err.begin() + static_cast<long>(at), stride, 0.0);
      return;
    }
    const BodyForces forces{&effects, b, body.mass, body.inv_inertia};
    const lie::FreeBody free = forces.free_body();
    const auto force = [&](double tt, const Eigen::Vector3d& p) { return forces.force(tt, p); };
    lie::BodyState<G> low;
    write(out, b, lie::body_step<G>(group, free, body.inv_mass, force, t, read(y, b), h, pair ? &low : nullptr));
    if (!pair) return;
    write(err, b, low);
    for (std::size_t k = at; k < at + stride; ++k) err[k] = out[k] - err[k];
  });
}

}  // namespace gacompare::core
