#pragma once
// A scene's bodies stepped by the Lie-group solver methods (rkmk4, rkmk45,
// crouch_grossman4: core/dynamics/lie_bodies.hpp and each backend's
// group_step), through one backend and representation: the rotation stays
// normalised without renormalising, the step is the module's own
// (core/dynamics/lie_group.hpp), and each method converges at its order
// against a reference by another solver. Instantiated per backend (and for
// the traditional quaternion) by tests/{traditional,cga,pga}/rigid_body_test.cpp;
// `Variant` supplies the backend, the scene's "rigid_body" options and the
// representation's RotationGroup.
#include "core/dynamics/lie_group.hpp"
#include "core/dynamics/simulator.hpp"
#include "core/model/model.hpp"
#include "rigid_cases.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <cstdio>
#include <string>
#include <tuple>
#include <utility>
#include <vector>

namespace gacompare::testing {

// The tumbling box of the free-flight case (0.1 × 0.4 × 0.9 m, 2 kg, principal
// body axes), with every effect a body feels without collisions: gravity, a
// linear drag on v and on ω (a torque that reads R and L), and a force applied
// at a body point (a torque that reads R, and a force that reads t).
inline constexpr double kLieMass = 2, kLieDrag = 0.1, kLieSpinDrag = 0.01;
inline const Eigen::Vector3d kLiePoint(0.05, 0.1, 0.2), kLieForce(0.3, -0.2, 0.5), kLieGravity(0, 0, -9.81);
inline const Eigen::Vector3d kLieX0(1, 2, 3), kLieV0(1, 0, 5), kLieW0(3, -2, 5);
inline const Eigen::Quaterniond kLieQ0(0.9238795325112867, 0.3826834323650898, 0, 0);

inline core::Scene lie_scene(const std::string& rigid_options, double duration, double every,
                             const std::string& solver) {
  return rigid_scene(
      R"({"name": "box", "shape": {"box": [0.1, 0.4, 0.9]}, "mass": 2.0, "position": [1, 2, 3],
          "orientation": [0.9238795325112867, 0.3826834323650898, 0, 0], "velocity": [1, 0, 5],
          "angular_velocity": [3, -2, 5]})",
      R"(, "effects": [{"type": "gravity", "g": [0, 0, -9.81]}, {"type": "linear_drag", "k": 0.1, "k_angular": 0.01},
          {"type": "applied_forces", "forces": [{"body": "box", "point": [0.05, 0.1, 0.2], "force": [0.3, -0.2, 0.5]}]}])",
      rigid_options, duration, every, solver);
}
inline std::string fixed_step(const char* method, double dt) {
  std::string s = R"({"method": ")";
  s += method;
  s += R"(", "dt": )";
  s += std::to_string(dt);
  s += "}";
  return s;
}
inline std::string adaptive(const char* method, double tol) {
  char buf[160];
  std::snprintf(buf, sizeof buf, R"({"method": "%s", "dt": 1e-3, "abs_tol": %.0e, "rel_tol": %.0e})", method, tol, tol);
  return buf;
}
// The angle between two samples' orientations: 2 asin |vec(q̄₁ q₂)|, exact for
// small angles (an acos of the dot product resolves only 3e-8 rad).
inline double angle_between(const core::BodySample& a, const core::BodySample& b) {
  const Eigen::Quaterniond qa(a.orientation[0], a.orientation[1], a.orientation[2], a.orientation[3]);
  const Eigen::Quaterniond qb(b.orientation[0], b.orientation[1], b.orientation[2], b.orientation[3]);
  return 2 * std::asin(std::min(1.0, (qa.conjugate() * qb).vec().norm()));
}
// The largest distance of a stored rotation from the group over the run's samples.
inline double largest_drift(const core::Run& run) {
  double worst = 0;
  for (const auto& s : run.samples) worst = std::max(worst, s.rotation_drift);
  return worst;
}
template <class Backend>
core::Run run_or_fail(const core::Scene& scene) {
  core::Run run = core::simulate<Backend>(scene);
  EXPECT_FALSE(run.error.has_value()) << *run.error;
  return run;
}

template <class Variant>
class LieBodiesCases : public ::testing::Test {};
TYPED_TEST_SUITE_P(LieBodiesCases);

// 10⁴ steps of 1 ms (10 s, about ten turns), renormalise "none": each step
// composes the rotation with 1 (RKMK) or 5 (Crouch–Grossman 4) exps that are
// rotations to rounding, so the stored rotation's distance from the group
// (‖RᵀR − I‖_F, |q q* − 1|, |R R̃ − 1|) grows by a few 1e-16 a composition:
// a random walk of 1e-14·√c over 10⁴ steps; 1e-13·√c leaves a factor 10
// (measured: see the printed drifts). The backend's own rk4 on the stored
// numbers, on the same scene, leaves the group by more than 1e-12 (O(h⁵) a
// step: 4.7e-12 for a quaternion, rotor or motor, 4.3e-11 for the matrix),
// so the bound tells the two apart.
TYPED_TEST_P(LieBodiesCases, RotationStaysNormalisedWithoutRenormalising) {
  using B = typename TypeParam::Backend;
  for (const auto& [method, compositions] : {std::pair{"rkmk4", 1}, {"crouch_grossman4", 5}}) {
    const core::Run run = run_or_fail<B>(lie_scene(TypeParam::options, 10, 1, fixed_step(method, 1e-3)));
    std::printf("%s %s: drift after 1e4 steps %.2e\n", TypeParam::Group::name.data(), method, largest_drift(run));
    EXPECT_LE(largest_drift(run), 1e-13 * std::sqrt(compositions)) << method;
  }
  // rkmk45 at 1e-10 takes ~1,200 steps of one composition each over the same 10 s.
  const core::Run pair = run_or_fail<B>(lie_scene(TypeParam::options, 10, 1, adaptive("rkmk45", 1e-10)));
  std::printf("%s rkmk45: drift after %llu steps %.2e\n", TypeParam::Group::name.data(),
              static_cast<unsigned long long>(pair.solver.steps_accepted), largest_drift(pair));
  EXPECT_LE(largest_drift(pair), 1e-13);
  const core::Run flat = run_or_fail<B>(lie_scene(TypeParam::options, 10, 1, fixed_step("rk4", 1e-3)));
  std::printf("%s rk4 (flat): drift %.2e\n", TypeParam::Group::name.data(), largest_drift(flat));
  EXPECT_GT(largest_drift(flat), 1e-12);
}

// The scene's step is the module's: 100 steps of 10 ms of rkmk4 and of
// crouch_grossman4 against core::lie::integrate on the same group, the torque
// written here from the scene's effects (−k_ω ω + (R p) × F, ω = R I⁻¹ Rᵀ L)
// and the box's principal moments by formula. They differ only in the order
// of roundings (I⁻¹ as a matrix or as three quotients, L = R Π read and
// written at every step): 1e-12 rad and 1e-12 relative in ω, a hundred steps
// of roundings of size-1 numbers. The centre follows the drag's closed form,
// v(t) = v∞ + (v0 − v∞) e^(−kt/m), v∞ = (m g + F)/k: the 4th-order step's
// error (kh/m)⁵ is 1e-17 a step, so 1e-12 m is rounding.
TYPED_TEST_P(LieBodiesCases, StepIsTheModulesOwn) {
  using B = typename TypeParam::Backend;
  using G = typename TypeParam::Group;
  const Eigen::Vector3d moments = kLieMass / 12 * Eigen::Vector3d(0.16 + 0.81, 0.01 + 0.81, 0.01 + 0.16);
  core::lie::FreeBody body{moments, [moments](double, const Eigen::Matrix3d& r, const Eigen::Vector3d& l) {
                             const Eigen::Vector3d w = r * (r.transpose() * l).cwiseQuotient(moments);
                             return Eigen::Vector3d(-kLieSpinDrag * w + (r * kLiePoint).cross(kLieForce));
                           }};
  const Eigen::AngleAxisd start(kLieQ0);
  const core::lie::State<G> y0{G::exp(start.angle() * start.axis()),
                               moments.cwiseProduct(kLieQ0.conjugate() * kLieW0)};  // Π = I ω_body
  const double T = 1;
  for (const auto& [method, group] : {std::pair{"rkmk4", core::lie::GroupMethod::rkmk4},
                                      {"crouch_grossman4", core::lie::GroupMethod::crouch_grossman4}}) {
    const core::Run run = run_or_fail<B>(lie_scene(TypeParam::options, T, T, fixed_step(method, 0.01)));
    ASSERT_EQ(run.solver.steps_accepted, 100u);
    const core::BodySample& got = run.samples.back().bodies[0];
    const auto y = core::lie::integrate(group, body, 0.0, T, 100, y0);
    const Eigen::Matrix3d r = G::matrix(y.rotation);
    core::BodySample want;
    const Eigen::Quaterniond q(r);
    want.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    const Eigen::Vector3d w = r * y.momentum.cwiseQuotient(moments);
    std::printf("%s %s: against the module %.2e rad, %.2e in ω\n", G::name.data(), method, angle_between(got, want),
                (got.angular_velocity - w).norm() / w.norm());
    EXPECT_LT(angle_between(got, want), 1e-12) << method;
    EXPECT_LT((got.angular_velocity - w).norm(), 1e-12 * w.norm()) << method;
    const double k = kLieDrag / kLieMass, decay = std::exp(-k * T);
    const Eigen::Vector3d v_inf = (kLieMass * kLieGravity + kLieForce) / kLieDrag;
    const Eigen::Vector3d v = v_inf + (kLieV0 - v_inf) * decay;
    const Eigen::Vector3d x = kLieX0 + v_inf * T + (kLieV0 - v_inf) * (1 - decay) / k;
    EXPECT_LT((got.position - x).norm(), 1e-12) << method;
    EXPECT_LT((got.velocity - v).norm(), 1e-12) << method;
  }
}

// Each method's order, its global error at T = 1 s (about a turn) against a
// reference by another solver (vern8 at 1e-13 on the same backend, whose
// error, ~1e-12, is below every error measured here, ≥ 1e-9), the angle
// between the final orientations:
//   rkmk4, crouch_grossman4: scenes of 20, 40 and 80 steps; the slope of the
//     finer halving, log2(e(40)/e(80)), within ±0.3 of 4 (as the module's
//     tests ask);
//   rkmk45 at the same fixed steps, through the backend's group_step (the
//     scene's solver would choose its own steps): the kept solution's slope
//     within ±0.3 of 5, and the pair's error estimate of one step from the
//     start, |err| over the state, falling as h⁵ (the embedded solution's
//     local error): log2 of a halving within ±0.3 of 5;
//   rkmk45 as the scene's adaptive solver at 1e-6, 1e-8 and 1e-10: each
//     error within 10× its tolerance, and falling with it.
TYPED_TEST_P(LieBodiesCases, EachMethodConvergesAtItsOrder) {
  using B = typename TypeParam::Backend;
  const double T = 1;
  const core::Run ref = run_or_fail<B>(lie_scene(TypeParam::options, T, T, adaptive("vern8", 1e-13)));
  const core::BodySample& want = ref.samples.back().bodies[0];
  const char* name = TypeParam::Group::name.data();
  for (const char* method : {"rkmk4", "crouch_grossman4"}) {
    double e[3];
    for (int k = 0; k < 3; ++k)
      e[k] = angle_between(
          run_or_fail<B>(lie_scene(TypeParam::options, T, T, fixed_step(method, T / (20 << k)))).samples.back().bodies[0],
          want);
    const double slope = std::log2(e[1] / e[2]);
    std::printf("%s %s: errors %.2e %.2e %.2e, slopes %.2f %.2f\n", name, method, e[0], e[1], e[2],
                std::log2(e[0] / e[1]), slope);
    EXPECT_GT(e[2], 1e-9) << method;
    EXPECT_NEAR(slope, 4, 0.3) << method;
  }

  const core::Scene scene = lie_scene(TypeParam::options, T, T, adaptive("rkmk45", 1e-6));
  const auto model = B::build(scene);
  std::vector<double> y0(B::state_size(model)), out(y0.size()), err(y0.size());
  B::initial_state(model, y0);
  double e[3], estimate[3];
  for (int k = 0; k < 3; ++k) {
    const long n = 20L << k;
    const double h = T / static_cast<double>(n);
    std::vector<double> y = y0;
    for (long i = 0; i < n; ++i) {
      B::group_step(model, core::SolverMethod::rkmk45, static_cast<double>(i) * h, h, y, out, err);
      y.swap(out);
    }
    core::Sample s;
    B::observe(model, y, s);
    e[k] = angle_between(s.bodies[0], want);
    B::group_step(model, core::SolverMethod::rkmk45, 0, 0.04 / (1 << k), y0, out, err);
    double sum = 0;
    for (const double d : err) sum += d * d;
    estimate[k] = std::sqrt(sum);
  }
  const double slope = std::log2(e[1] / e[2]), estimate_slope = std::log2(estimate[1] / estimate[2]);
  std::printf("%s rkmk45 (fixed steps): errors %.2e %.2e %.2e, slopes %.2f %.2f; one step's estimate %.2e %.2e %.2e, "
              "slope %.2f\n",
              name, e[0], e[1], e[2], std::log2(e[0] / e[1]), slope, estimate[0], estimate[1], estimate[2],
              estimate_slope);
  EXPECT_GT(e[2], 1e-9);
  EXPECT_NEAR(slope, 5, 0.3);
  EXPECT_NEAR(estimate_slope, 5, 0.3);

  double previous = INFINITY;
  for (const double tol : {1e-6, 1e-8, 1e-10}) {
    const core::Run run = run_or_fail<B>(lie_scene(TypeParam::options, T, T, adaptive("rkmk45", tol)));
    const double error = angle_between(run.samples.back().bodies[0], want);
    std::printf("%s rkmk45 at %.0e: error %.2e in %llu steps\n", name, tol, error,
                static_cast<unsigned long long>(run.solver.steps_accepted));
    EXPECT_LT(error, 10 * tol) << tol;
    EXPECT_LT(error, previous) << tol;
    previous = error;
  }
}

// A body whose axes are not principal (an irregular hull: its inertia has
// off-diagonal terms) takes I⁻¹ as it is, in each backend's terms (cga's on
// bivector components, turned back to axial ones): rkmk45 at 1e-11 against
// vern8 at 1e-13 over 2 s of tumbling with the drag and a force applied off
// the centre, 1e-9 rad and 1e-9 relative in ω (the tolerance's 1e-11 a step
// over a few hundred steps, with room; measured 4e-12 and 3e-12).
TYPED_TEST_P(LieBodiesCases, BodyAxesNeedNotBePrincipal) {
  using B = typename TypeParam::Backend;
  const auto scene = [](const std::string& solver) {
    return rigid_scene(
        R"({"name": "rock", "shape": {"hull": [[0, 0, 0], [0.5, 0.1, 0], [0.1, 0.3, 0.05], [0.2, 0.1, 0.6],
            [0.4, 0.35, 0.3], [-0.1, 0.2, 0.25]]}, "mass": 1.5, "position": [0, 0, 1],
            "velocity": [0.5, 0, 1], "angular_velocity": [2, -1, 4]})",
        R"(, "effects": [{"type": "linear_drag", "k": 0.1, "k_angular": 0.01},
            {"type": "applied_forces", "forces": [{"body": "rock", "point": [0.1, 0, 0.1], "force": [0, 0.4, 0]}]}])",
        TypeParam::options, 2, 2, solver);
  };
  const core::Scene lie = scene(adaptive("rkmk45", 1e-11));
  const Eigen::Matrix3d inertia = core::compile(lie).bodies[0].inertia;
  ASSERT_GT(std::abs(inertia(0, 1)) + std::abs(inertia(0, 2)) + std::abs(inertia(1, 2)), 1e-3 * inertia.trace());
  const core::Run run = run_or_fail<B>(lie), ref = run_or_fail<B>(scene(adaptive("vern8", 1e-13)));
  const core::BodySample &got = run.samples.back().bodies[0], &want = ref.samples.back().bodies[0];
  std::printf("%s: non-principal body, rkmk45 against vern8 %.2e rad, %.2e in ω\n", TypeParam::Group::name.data(),
              angle_between(got, want), (got.angular_velocity - want.angular_velocity).norm() / want.angular_velocity.norm());
  EXPECT_LT(angle_between(got, want), 1e-9);
  EXPECT_LT((got.angular_velocity - want.angular_velocity).norm(), 1e-9 * want.angular_velocity.norm());
  EXPECT_LT((got.position - want.position).norm(), 1e-9);
}

// A box (0.1 × 0.2 × 0.3 m, 1 kg: three different principal moments, so it
// tumbles) dropped from 0.4 m turning at ω = (4, −3, 6) rad/s onto a static
// slab, restitution 0.5, friction 0.3, for `duration` s: corner and edge
// impacts, each found by a time-of-impact search on the box's island stepped
// alone, then sliding and rocking contacts. `sleep`: the collisions effect
// sleeps at its defaults (0.01 m/s for 0.5 s).
inline core::Scene lie_drop(const std::string& rigid_options, double duration, const std::string& solver,
                            bool sleep = false) {
  return rigid_scene(
      R"({"name": "slab", "shape": {"box": [4, 4, 0.2]}, "mass": 100, "position": [0, 0, -0.1], "static": true,
          "friction": 0.3},
         {"name": "box", "shape": {"box": [0.1, 0.2, 0.3]}, "mass": 1, "position": [0, 0, 0.4],
          "orientation": [0.9238795325112867, 0.3826834323650898, 0, 0], "velocity": [0.3, 0, 0],
          "angular_velocity": [4, -3, 6], "friction": 0.3})",
      std::string(R"(, "effects": [{"type": "gravity", "g": [0, 0, -9.81]}, {"type": "collisions", "restitution": 0.5,
          "penetration_tolerance": 1e-4, "step": 1e-3)") +
          (sleep ? R"(, "sleep": {})" : "") + "}]",
      rigid_options, duration, 0.01, solver);
}
// The drop's |ω0| = |(4, −3, 6)| rad/s and the box's half diagonal
// ½|(0.1, 0.2, 0.3)| m, and the bound on two 4th-order runs' parting over T
// seconds at step h, (ωh)⁴ ωT in angle (CollisionsStepOnTheGroup).
inline constexpr double kDropOmega = 7.8102496759066544, kDropRho = 0.18708286933869706;
inline double drop_bound(double h, double T) { return std::pow(kDropOmega * h, 4) * kDropOmega * T; }
// The largest distance between the box's centres and angle between its
// orientations, sample by sample, of two runs of one scene.
inline std::pair<double, double> apart(const core::Run& a, const core::Run& b) {
  double dx = 0, angle = 0;
  EXPECT_EQ(a.samples.size(), b.samples.size());
  for (std::size_t k = 0; k < a.samples.size() && k < b.samples.size(); ++k) {
    const core::BodySample &p = a.samples[k].bodies[1], &q = b.samples[k].bodies[1];
    dx = std::max(dx, (p.position - q.position).norm());
    angle = std::max(angle, angle_between(p, q));
  }
  return {dx, angle};
}

// The Lie-group methods take the collisions effect: the islands stepped
// alone and the time-of-impact trials integrate through the backend's
// group_step too (core/collision/subsystem.hpp; before, such a subsystem had
// no group step and the run stopped), so the whole run steps on the group.
// On the tumbling drop (lie_drop, 1 s), rkmk4 and crouch_grossman4 at steps
// h = 1 ms and h/2, rkmk45 at 1e-10:
//   - each run completes with contacts responded to and impacts found by the
//     time-of-impact search on the box's island stepped alone, its trials
//     re-integrating the box (islands_stepped_alone, impact_bodies_integrated);
//   - it agrees with the same scene under rk4 at the same step, sample by
//     sample. Every method here is of order 4 (rkmk45 of 5, at a tolerance
//     far below rk4's error), so the two runs part by their global errors,
//     C (ωh)⁴ ωT in angle: with the leading constant C ≤ 1 (RK4's on a
//     rotation is 1/120), ω = |ω0| = 7.8 rad/s, h = 1 ms and T = 1 s, the
//     bound is 2.9e-8 rad, and ρ = 0.19 m (the box's half diagonal) times it,
//     5.6e-9 m, for the centre, which moves off only through the contacts.
//     That the difference is the methods' truncation error, and not a
//     different motion, is checked by its order: halving h divides it by
//     2⁴, log2 of the ratio within ±0.3 of 4 (as the module's tests ask),
//     in angle and in the centre;
//   - the rotation's drift stays at rounding without renormalising: about a
//     thousand compositions with rotations (steps and positional
//     corrections), a random walk of 1e-14, under the 1e-13 of
//     RotationStaysNormalisedWithoutRenormalising; rk4's own drift on the
//     same run is above it (8.5e-13 for a quaternion, rotor or motor,
//     2.7e-10 for the matrix), so the bound tells the two apart.
TYPED_TEST_P(LieBodiesCases, CollisionsStepOnTheGroup) {
  using B = typename TypeParam::Backend;
  const char* name = TypeParam::Group::name.data();
  constexpr double h = 1e-3;
  const double bound = drop_bound(h, 1);
  const core::Run flat[2] = {run_or_fail<B>(lie_drop(TypeParam::options, 1, fixed_step("rk4", h))),
                             run_or_fail<B>(lie_drop(TypeParam::options, 1, fixed_step("rk4", h / 2)))};
  std::printf("%s rk4: drift %.2e, %llu contacts, %llu impact searches\n", name, largest_drift(flat[0]),
              static_cast<unsigned long long>(flat[0].count("contacts")),
              static_cast<unsigned long long>(flat[0].count("impact_searches")));
  EXPECT_GT(largest_drift(flat[0]), 1e-13);
  for (const char* method : {"rkmk4", "crouch_grossman4", "rkmk45"}) {
    const bool pair = std::string(method) == "rkmk45";
    double dx[2], angle[2];
    for (int k = 0; k < 2; ++k) {
      const core::Run run =
          run_or_fail<B>(lie_drop(TypeParam::options, 1, pair ? adaptive(method, 1e-10) : fixed_step(method, h / (1 << k))));
      std::tie(dx[k], angle[k]) = apart(run, flat[k]);
      std::printf("%s %s (h/%d): from rk4 %.2e m, %.2e rad; drift %.2e; %llu contacts, %llu impact searches, %llu "
                  "islands alone, %llu bodies integrated by trials, %llu steps\n",
                  name, method, 1 << k, dx[k], angle[k], largest_drift(run),
                  static_cast<unsigned long long>(run.count("contacts")),
                  static_cast<unsigned long long>(run.count("impact_searches")),
                  static_cast<unsigned long long>(run.count("islands_stepped_alone")),
                  static_cast<unsigned long long>(run.count("impact_bodies_integrated")),
                  static_cast<unsigned long long>(run.solver.steps_accepted));
      EXPECT_GT(run.count("contacts"), 0u) << method;
      EXPECT_GT(run.count("impact_searches"), 0u) << method;
      EXPECT_GT(run.count("islands_stepped_alone"), 0u) << method;
      EXPECT_GT(run.count("impact_bodies_integrated"), 0u) << method;
      EXPECT_LE(largest_drift(run), 1e-13) << method;
    }
    std::printf("%s %s: order of the difference %.2f (angle), %.2f (centre)\n", name, method,
                std::log2(angle[0] / angle[1]), std::log2(dx[0] / dx[1]));
    EXPECT_LT(angle[0], bound) << method;
    EXPECT_LT(dx[0], kDropRho * bound) << method;
    EXPECT_NEAR(std::log2(angle[0] / angle[1]), 4, 0.3) << method;
    EXPECT_NEAR(std::log2(dx[0] / dx[1]), 4, 0.3) << method;
  }
}

// A sleeping body does not move under a Lie-group method either: its step
// copies it, as its derivative is zero under the flat methods (the world's
// group step takes the mask of sleeping bodies, core/dynamics/simulation.hpp
// advance). The drop of 2.5 s with sleeping on settles and sleeps; from then
// on every sample holds the box exactly where it fell asleep, at rest, and
// it sleeps where the same scene under rk4 sleeps, within the bound of
// CollisionsStepOnTheGroup over the run's 2.5 s.
TYPED_TEST_P(LieBodiesCases, SleepingBodiesStayWhereTheySleep) {
  using B = typename TypeParam::Backend;
  const core::Run flat = run_or_fail<B>(lie_drop(TypeParam::options, 2.5, fixed_step("rk4", 1e-3), true));
  const core::Run run = run_or_fail<B>(lie_drop(TypeParam::options, 2.5, fixed_step("rkmk4", 1e-3), true));
  const auto [dx, angle] = apart(run, flat);
  std::printf("%s rkmk4 asleep: %llu islands slept, %llu body-steps asleep; from rk4 %.2e m, %.2e rad\n",
              TypeParam::Group::name.data(), static_cast<unsigned long long>(run.count("sleep_islands")),
              static_cast<unsigned long long>(run.count("sleeping_body_steps")), dx, angle);
  ASSERT_EQ(run.count("sleep_islands"), 1u);
  ASSERT_EQ(flat.count("sleep_islands"), 1u);
  EXPECT_EQ(run.count("sleeping_body_steps"), flat.count("sleeping_body_steps"));
  // Its gravity terms skipped as rk4 skips them: both evaluate the forces 4
  // times a step, at the same steps, none on the box while it sleeps.
  EXPECT_EQ(run.solver.derivative_evaluations, flat.solver.derivative_evaluations);
  EXPECT_EQ(run.count("effect_gravity_terms"), flat.count("effect_gravity_terms"));
  EXPECT_LT(run.count("effect_gravity_terms"), run.solver.derivative_evaluations / 2);
  // The samples taken asleep: the last sleeping_body_steps collision steps of 1 ms.
  const auto asleep = static_cast<std::size_t>(run.count("sleeping_body_steps") / 10);
  ASSERT_GE(asleep, 2u);
  const core::BodySample& last = run.samples.back().bodies[1];
  for (std::size_t k = run.samples.size() - asleep; k < run.samples.size(); ++k) {
    const core::BodySample& b = run.samples[k].bodies[1];
    EXPECT_EQ(b.position, last.position) << "t=" << run.samples[k].t;
    EXPECT_EQ(b.orientation, last.orientation) << "t=" << run.samples[k].t;
    EXPECT_EQ(b.velocity.norm() + b.angular_velocity.norm(), 0.0) << "t=" << run.samples[k].t;
  }
  EXPECT_LT(angle, drop_bound(1e-3, 2.5));
  EXPECT_LT(dx, kDropRho * drop_bound(1e-3, 2.5));
}

REGISTER_TYPED_TEST_SUITE_P(LieBodiesCases, RotationStaysNormalisedWithoutRenormalising, StepIsTheModulesOwn,
                            EachMethodConvergesAtItsOrder, BodyAxesNeedNotBePrincipal, CollisionsStepOnTheGroup,
                            SleepingBodiesStayWhereTheySleep);

}  // namespace gacompare::testing
