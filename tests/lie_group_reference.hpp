#pragma once
// The free asymmetric top for the Lie-group integrator tests
// (tests/rotation_group_cases.hpp, tests/core/dynamics/lie_group_test.cpp), and
// its reference solution by a solver that shares no code with those methods.
#include "core/dynamics/lie_group.hpp"
#include "core/dynamics/ode.hpp"
#include "core/stage.hpp"

#include <Eigen/Geometry>

#include <span>
#include <vector>

namespace gacompare::testing {

// The asymmetric top of the rigid tests (a 0.1 × 0.4 × 0.9 box, 1 kg; principal
// moments largest about x) tumbling at ω = (1, 3, 2) rad/s, and the same body
// with a torque that reads both R and L: a restoring couple about the world z
// axis and a damping −k L.
inline core::lie::FreeBody asymmetric_top(bool torqued) {
  core::lie::FreeBody body{{(0.16 + 0.81) / 12, (0.01 + 0.81) / 12, (0.01 + 0.16) / 12}, {}};
  if (torqued)
    body.torque = [](double, const Eigen::Matrix3d& r, const Eigen::Vector3d& l) {
      return Eigen::Vector3d(0.05 * r.col(2).cross(Eigen::Vector3d::UnitZ()) - 0.1 * l);
    };
  return body;
}
inline Eigen::Vector3d top_momentum(const core::lie::FreeBody& body) {
  return body.inertia.cwiseProduct(Eigen::Vector3d(1, 3, 2));
}
inline const Eigen::Quaterniond& top_start() {
  static const Eigen::Quaterniond q(Eigen::AngleAxisd(0.7, Eigen::Vector3d(1, -2, 0.5).normalized()));
  return q;
}

// The reference: the flat quaternion (q̇ = ½ q ω) and Π through the project's
// Cash–Karp solver (core/dynamics/ode.hpp) at tolerance 1e-13 per component,
// code shared with none of the Lie-group methods. Its global error on these
// runs, ~1e-12, is below every error the convergence tests measure (≥ 1e-10).
struct Reference {
  Eigen::Matrix3d rotation;
  Eigen::Vector3d momentum;
};
inline Reference reference(const core::lie::FreeBody& body, double T) {
  core::OdeSolver solver({core::SolverMethod::cash_karp45, 1e-3, 1e-13, 1e-13, core::ErrorNorm::component}, 7);
  const Eigen::Quaterniond q0 = top_start();
  const Eigen::Vector3d p0 = top_momentum(body);
  std::vector<double> y{q0.w(), q0.x(), q0.y(), q0.z(), p0.x(), p0.y(), p0.z()};
  double t = 0;
  core::Profile profile;
  solver.advance(
      [&](double tt, std::span<const double> s, std::span<double> d) {
        const Eigen::Quaterniond q(s[0], s[1], s[2], s[3]);
        const Eigen::Vector3d pi(s[4], s[5], s[6]);
        const Eigen::Vector3d w = pi.cwiseQuotient(body.inertia);
        Eigen::Vector3d dp = pi.cross(w);
        if (body.torque) {
          const Eigen::Matrix3d r = q.normalized().toRotationMatrix();
          dp += r.transpose() * body.torque(tt, r, r * pi);
        }
        const Eigen::Quaterniond dq = q * Eigen::Quaterniond(0, w.x(), w.y(), w.z());
        d[0] = 0.5 * dq.w(), d[1] = 0.5 * dq.x(), d[2] = 0.5 * dq.y(), d[3] = 0.5 * dq.z();
        d[4] = dp.x(), d[5] = dp.y(), d[6] = dp.z();
      },
      t, T, y, profile);
  return {Eigen::Quaterniond(y[0], y[1], y[2], y[3]).normalized().toRotationMatrix(), {y[4], y[5], y[6]}};
}

template <core::lie::RotationGroup G>
core::lie::State<G> top_state(const core::lie::FreeBody& body) {
  const Eigen::Quaterniond q = top_start();
  // The start through the group's own exp of the angle–axis vector.
  const Eigen::AngleAxisd aa(q);
  return {G::exp(aa.angle() * aa.axis()), top_momentum(body)};
}

// ‖R − R_ref‖_F + |Π − Π_ref| / |Π_ref| after n steps over T.
template <core::lie::RotationGroup G>
double global_error(core::lie::GroupMethod m, const core::lie::FreeBody& body, double T, long n, const Reference& ref) {
  const auto y = core::lie::integrate(m, body, 0.0, T, n, top_state<G>(body));
  return (G::matrix(y.rotation) - ref.rotation).norm() + (y.momentum - ref.momentum).norm() / ref.momentum.norm();
}

}  // namespace gacompare::testing
