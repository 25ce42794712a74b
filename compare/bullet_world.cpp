// Bullet as a whole-simulation reference. The scene's bodies go into
// a btDiscreteDynamicsWorld (Bullet 3.24, double precision: bullet-float64) with
// our exact mass properties, and the world is stepped with a fixed step that
// lands on every output time. What follows lists every choice that makes the
// comparison with §2.5 fair, and every Bullet behaviour that still differs from
// it; run.metrics carries the values into results.json.
//
// Bullet's defaults that we keep (btContactSolverInfo, Bullet 3.24):
//   - m_restitutionVelocityThreshold = 0.2 m/s: a contact whose normal approach
//     speed is below it gets restitution 0. This is Bullet's resting rule: a cube
//     dropped on a slab stops bouncing once its impact speed falls below 0.2 m/s
//     (the rebound apex would be ε²·2 mm), where §2.5 would bounce on with ever
//     smaller hops; our backends have their own resting rule.
//   - Restitution is a velocity target, ε times the normal approach speed seen at
//     the start of the step (after gravity's kick), for the contacts found at the
//     start of the step: discrete, no time of impact. A body reverses from
//     wherever the step that finds the contact left it, up to one step's travel
//     |v|·h inside the other body; split impulses then push it out (below).
//   - m_erp2 = 0.2: split-impulse penetration recovery moves 20% of the depth out
//     per step, as a pseudo-velocity that changes positions but no momentum or
//     energy. m_erp = 0.2 (Baumgarte, into the real velocity) would be used for
//     contacts shallower than m_splitImpulsePenetrationThreshold: see below.
//   - m_numIterations = 10 Gauss–Seidel sweeps over the contact points,
//     warm-started (m_warmstartingFactor = 0.85): the impulses of a four-point face
//     contact are iterated, not solved exactly, where eq. 53 solves one contact
//     at a time exactly. (Warm starting made no difference to the bounce test.)
//   - m_linearSlop = 0, m_globalCfm = 0. Contact points are kept while they are
//     within the contact breaking threshold (gContactBreakingThreshold = 0.02 m,
//     scaled by each shape's angular-motion disc) and reused from step to step
//     (persistent manifolds, up to 4 points per pair).
//   - A body's angular speed is clamped to (π/2)/h (btRigidBody::
//     integrateVelocities): 1571 rad/s at h = 1 ms.
//   - Resting contact is a limit cycle, not a fixed point: a cube resting on a
//     slab sits 1e-6 to 1e-5 m deep (split impulses push it out by 20% of the
//     depth per step), and twice in every 14 steps the contact solve leaves it one
//     step's gravity short (|v| = 5.9 mm/s, ω = 0.06 rad/s for that one step),
//     which the next step undoes. Over 20 s: |z − z_rest| ≤ 9.5e-6 m, no drift.
// Two defaults we change, because with them Bullet does not model a bounce at
// all (measured: a 0.2 m cube dropped 0.5 m on a slab with ε = 0.5):
//   - Contact processing threshold 0 on every body (default BT_LARGE_FLOAT).
//     By default every manifold point within the breaking threshold is a
//     "speculative" contact: the solver lets a separated point close its gap d in
//     the step (velocity target −d/h on top of the restitution target), and the
//     gap eats the bounce: the rebound speed becomes ε|v| − d/h < 0 a few steps
//     running, and the cube that hit the slab at 3.1 m/s stopped dead, no bounce.
//     With 0, only touching or penetrating points are solved. (This is the
//     recipe Bullet's author gives for proper restitution:
//     https://github.com/bulletphysics/bullet3/issues/3094.)
//   - m_splitImpulsePenetrationThreshold = 0 (default −0.04 m). By default only
//     contacts deeper than 4 cm get the energy-free split impulse; shallower ones
//     are pushed out by Baumgarte velocity 0.2·depth/h, a kick of up to 0.6 m/s
//     for a 3 mm penetration at 1 ms, which made successive bounce heights rise
//     by 0.30, 0.42, 0.30, 0.33, ... instead of ε² = 0.25 and bounce 6 times.
//     With 0 every penetration is recovered by split impulse: 0.250, 0.249,
//     0.252, 0.234 (tests/compare/bullet_world_test.cpp).
// Our settings:
//   - Friction: each body's μ (the scene's "friction", default 0: §2.5 is
//     frictionless), combined per pair as our √(μ_a μ_b) through Bullet's hook
//     gCalculateCombinedFrictionCallback (Bullet's default multiplies, as for
//     restitution below); rolling and spinning friction 0 (our backends have
//     neither). Bullet's Coulomb model differs from ours (core/collision/collisions.hpp):
//     its friction rows are solved per contact point of the persistent manifold,
//     after the normal rows in each of its 10 sweeps, each bounded by
//     ±μ times that point's current normal impulse: one row along the relative
//     sliding velocity (SOLVER_USE_2_FRICTION_DIRECTIONS is off by default; a
//     point that does not slip gets btPlaneSpace1's first tangent), so a box
//     per point and direction, where ours holds both tangents in one disc
//     |λ_t| ≤ μ λ_n converged to 1e-11 m/s. Its friction anchor
//     (CF_HAS_FRICTION_ANCHOR, off by default) would keep a contact point where
//     it was made; without it points are refreshed each step. Bullet integrates
//     positions after the contact solve (semi-implicit Euler: v += g h, solve,
//     x += v h): no creep of our kind (ours integrates first and displaces
//     resting contacts by ½ h Δv, core/collision/collisions.hpp friction_displacement),
//     but positions ½ a h t off the exact parabola (short when braking: a
//     stopping distance ½ v₀ h short).
//     Damping 0. Sleeping disabled (DISABLE_DEACTIVATION on every dynamic body),
//     unless the scene's collisions effect asks for it: then Bullet's island
//     deactivation with the scene's speed and time (core/collision/sleep.hpp).
//   - Margin 0 on every hull: the hull is the mesh, not the mesh grown by Bullet's
//     0.04 m skin. With margin 0 GJK alone would give one contact point per step;
//     initializePolyhedralFeatures() turns on Bullet's polyhedral face clipping,
//     which gives a face-on-face contact its full manifold (up to 4 points) at once.
//   - btDispatcherInfo::m_enableSatConvex = true (default false): the clipping
//     takes its separating axis from the separating-axis test over the hulls' face
//     normals and edge pairs, not from GJK/EPA. With GJK/EPA, a 0.2 m cube landing
//     flat at (0.05, −0.03) got EPA's own interior point (near its centre) into
//     the 4-point manifold in place of a corner; the impulses, all on one side,
//     sent it off the slab spinning at 3.5 rad/s to land on another face, and the
//     bundled cube_drop_flat bounced 0.245, then rocked (0.76, 0.29, 0.94, ...).
//     With SAT: the four corners, no spin, 0.249, 0.245, 0.242, 0.249, as when it
//     lands centred. (It is also faster: 27 boxes in a box, 1.8 s against 2.9 s.)
//   - Restitution: ours is min(ε_a, ε_b) per pair, ε_x the body's own
//     "restitution" or the collisions effect's. Bullet multiplies the two bodies'
//     values by default; a product can equal every pair's minimum only in special
//     cases (one common ε: √ε each). Bullet 2.83+ has a hook for exactly this,
//     gCalculateCombinedRestitutionCallback (btManifoldResult.h), called when a
//     contact point is created; we point it at min() while the world steps and
//     give each body its own ε_x, so every pair gets our value exactly, whatever
//     the per-body values. The hook is process-wide: simulate_bullet is not
//     reentrant (the harness runs one simulation at a time).
//   - Applied forces (the applied_forces effect, core/model/scene.hpp): before each
//     step, every force active at the step's midpoint is handed to Bullet with
//     btRigidBody::applyForce(F, R·p), R the body's rotation at the start of the
//     step (body -> world; the Bullet basis times Aᵀ, see Inertia below). Bullet
//     adds it to the body's force and torque accumulators (the torque is
//     (R p) × F, as in our backends), its velocity update (integrateVelocities)
//     gives v += F·h/m and ω += I_w⁻¹·τ·h with I_w at the step's start, and
//     stepSimulation ends with clearForces() unconditionally (btDiscreteDynamics-
//     World has no setting that keeps forces), so each force is applied anew
//     before every step. How this differs from our backends: there a force is a
//     term of the derivative, evaluated at every RK stage at the stage's own time
//     and orientation, so a switch on or off lands within one step's impulse, and
//     R p turns with the body within the step. Here the force and the lever arm
//     R p are constant over a step, taken at its start (the arm) and its midpoint
//     (whether the force is on). The midpoint makes a switch on a step boundary
//     exact (every output time is one: the scene comment asks for switches on
//     output times) whatever the rounding of the step's start time; a switch
//     inside a step moves to the nearest boundary, an impulse error of at most
//     |F|·h/2 per switch. The torque's arm is first order in h: a body turning at
//     ω is pushed with the arm it had up to ω·h rad ago.
//   - No collisions effect: the bodies are added with collision mask 0, so they
//     fly through each other as in our backends, and no collision routine runs.
//   - CCD: off in effect. Each body's CCD motion threshold is half its inradius
//     (the distance from its centre of mass to its nearest face), the bound at
//     which our backends halve their contact interval; Bullet sweeps a sphere of
//     the inradius only for a step that moves a body farther than that, i.e.
//     only where a step could tunnel. At the scenes' speeds (|v|·h ≪ inradius) it
//     never triggers.
//   - Gyroscopic term: BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY (Bullet's
//     default since 2.83), one implicit step of Euler's equations in the body
//     frame per step. Measured on a free 0.1 × 0.4 × 0.9 box tumbling at 6.2 rad/s
//     for 4 s (max |L − L₀|/|L₀|): implicit body 2.5e-2 at h = 1 ms, 6.4e-3 at
//     0.25 ms (first order: implicit Euler loses energy, 4.2e-2 and 1.1e-2);
//     IMPLICIT_WORLD gave the same figures, EXPLICIT 2.6e-2 and 6.4e-3 (with more
//     energy lost, 4.4e-2); none (flags 0) keeps ω fixed in the world frame,
//     which holds |L| and the energy exactly but turns L itself by 128%: no
//     gyroscopic term is wrong for any body whose ω is not a principal axis.
//   - Inertia: Bullet takes a diagonal inertia in the body's frame. Where our
//     tensor about the centre of mass is not diagonal in body coordinates (a hull,
//     a mesh, a rotated shape), the Bullet body is the same solid in its principal
//     frame: the hull's points are p = Aᵀx (x about the centre of mass) with
//     A = core::principal_axes (columns: the principal axes in body coordinates,
//     det +1), the Bullet basis is R·A, and we read R back as basis·Aᵀ. A tensor
//     whose off-diagonal terms are below 1e-12 of its largest moment (a box:
//     rounding of the polyhedral integrals) is taken as diagonal, A = 1, so a box
//     keeps its own axes. (This replaces a btCompoundShape with the hull as a
//     child under the principal transform: the same solid, without the compound
//     collision algorithm in between.)
//   - Stage timing: Bullet's step (gravity, broadphase, narrowphase, solver,
//     integration) is one call we cannot split into our stages; all of it is
//     timed as Stage::integrate. Handing Bullet the applied forces before each
//     step is timed as Stage::forces.
#include "compare/bullet_world.hpp"

#include "core/error.hpp"
#include "core/dynamics/invariants.hpp"
#include "core/model/model.hpp"
#include "core/dynamics/simulator.hpp"
#include "core/stage.hpp"

#include <btBulletCollisionCommon.h>
#include <btBulletDynamicsCommon.h>
#include <BulletCollision/CollisionDispatch/btManifoldResult.h>
#include <BulletCollision/NarrowPhaseCollision/btPersistentManifold.h>

#include <Eigen/Geometry>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <limits>
#include <memory>
#include <optional>
#include <sstream>
#include <variant>
#include <vector>

static_assert(sizeof(btScalar) == sizeof(double), "the Bullet reference needs the double build (bullet-float64)");

namespace gacompare::compare {

using core::Vec3;

namespace {

constexpr const char* kBackend = "bullet";
// The fixed step when the scene has no collisions effect (pybullet's default).
constexpr double kDefaultStep = 1.0 / 240.0;

btVector3 to_bullet(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Vec3 to_eigen(const btVector3& v) { return {v.x(), v.y(), v.z()}; }
btMatrix3x3 to_bullet(const Eigen::Matrix3d& r) {
  return {r(0, 0), r(0, 1), r(0, 2), r(1, 0), r(1, 1), r(1, 2), r(2, 0), r(2, 1), r(2, 2)};
}
Eigen::Matrix3d to_eigen(const btMatrix3x3& m) {
  Eigen::Matrix3d r;
  for (int a = 0; a < 3; ++a)
    for (int b = 0; b < 3; ++b) r(a, b) = m[a][b];
  return r;
}

bool finite(const btVector3& v) { return std::isfinite(v.x()) && std::isfinite(v.y()) && std::isfinite(v.z()); }

// ε_pair = min(ε_a, ε_b) and μ_pair = √(μ_a μ_b) (core/model/scene.hpp's rules),
// installed while the world steps.
btScalar min_restitution(const btCollisionObject* a, const btCollisionObject* b) {
  return std::min(a->getRestitution(), b->getRestitution());
}
btScalar root_friction(const btCollisionObject* a, const btCollisionObject* b) {
  return std::sqrt(a->getFriction() * b->getFriction());
}
class MaterialHooks {
 public:
  MaterialHooks()
      : restitution_(gCalculateCombinedRestitutionCallback), friction_(gCalculateCombinedFrictionCallback) {
    gCalculateCombinedRestitutionCallback = &min_restitution;
    gCalculateCombinedFrictionCallback = &root_friction;
  }
  ~MaterialHooks() {
    gCalculateCombinedRestitutionCallback = restitution_;
    gCalculateCombinedFrictionCallback = friction_;
  }
  MaterialHooks(const MaterialHooks&) = delete;
  MaterialHooks& operator=(const MaterialHooks&) = delete;

 private:
  CalculateCombinedCallback restitution_, friction_;
};

struct BulletBody {
  std::unique_ptr<btCollisionShape> shape;
  std::unique_ptr<btRigidBody> body;
  Eigen::Matrix3d principal = Eigen::Matrix3d::Identity();  // A: principal frame -> body frame
};

// Members are destroyed in reverse order: the bodies (after the destructor has
// taken them out of the world) before the world, the world before its parts.
struct World {
  btDefaultCollisionConfiguration configuration;
  btCollisionDispatcher dispatcher{&configuration};
  btDbvtBroadphase broadphase;
  btSequentialImpulseConstraintSolver solver;
  btDiscreteDynamicsWorld world{&dispatcher, &broadphase, &solver, &configuration};
  std::vector<BulletBody> bodies;
  ~World() {
    for (auto& b : bodies) world.removeRigidBody(b.body.get());
  }
};

// Bullet's own shape for the body: btSphereShape for a sphere, btCapsuleShapeZ
// for a capsule (whose margins are their radius, so they keep Bullet's
// default; a capsule's inertia is diagonal about its axis, so the principal
// frame is the body's and the axis z; its `height` is the length between the
// hemispheres' centres, as ours), else the hull of the vertices in the
// principal frame with no margin (top of file).
std::unique_ptr<btCollisionShape> bullet_shape(const core::Mesh& mesh, const Eigen::Matrix3d& principal) {
  if (mesh.is_sphere()) return std::make_unique<btSphereShape>(mesh.sphere_radius());
  if (mesh.is_capsule()) {
    const Vec3 h = principal.transpose() * mesh.capsule_half_axis();
    if (h.head<2>().norm() > 1e-12 * h.norm())
      throw input_error(mesh.name() + ": bullet: a capsule's axis must be a principal axis of the body (z)");
    return std::make_unique<btCapsuleShapeZ>(mesh.sphere_radius(), 2 * h.norm());
  }
  auto hull = std::make_unique<btConvexHullShape>();
  for (const Vec3& v : mesh.vertices()) hull->addPoint(to_bullet(Vec3(principal.transpose() * v)), false);
  hull->setMargin(0);
  hull->recalcLocalAabb();
  hull->initializePolyhedralFeatures();
  return hull;
}

void observe(const World& w, core::Sample& s) {
  s.bodies.resize(w.bodies.size());
  s.rotation_drift = 0;
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const btRigidBody& rb = *w.bodies[b].body;
    const btTransform& tr = rb.getCenterOfMassTransform();
    const Eigen::Matrix3d basis = to_eigen(tr.getBasis());
    const Eigen::Matrix3d r = basis * w.bodies[b].principal.transpose();  // body -> world
    const Eigen::Quaterniond q = Eigen::Quaterniond(r).normalized();
    auto& out = s.bodies[b];
    out.position = to_eigen(tr.getOrigin());
    out.orientation = Eigen::Vector4d(q.w(), q.x(), q.y(), q.z());
    out.velocity = to_eigen(rb.getLinearVelocity());
    out.angular_velocity = to_eigen(rb.getAngularVelocity());
    s.rotation_drift = std::max(s.rotation_drift, (basis.transpose() * basis - Eigen::Matrix3d::Identity()).norm());
  }
}

// "" when every dynamic body's state is finite, else "body 'name'".
std::string first_nonfinite(const World& w, const core::Scene& scene) {
  for (std::size_t b = 0; b < w.bodies.size(); ++b) {
    const btRigidBody& rb = *w.bodies[b].body;
    const btTransform& tr = rb.getCenterOfMassTransform();
    bool ok = finite(tr.getOrigin()) && finite(rb.getLinearVelocity()) && finite(rb.getAngularVelocity());
    for (int k = 0; k < 3; ++k) ok = ok && finite(tr.getBasis()[k]);
    if (!ok) return "body '" + scene.bodies[b].name + "'";
  }
  return "";
}

}  // namespace

std::string bullet_unsupported(const core::Scene& scene, const core::Model* model) {
  if (!scene.generators.empty() || !scene.particles.empty())
    return "the scene has particles" +
           (scene.particles.empty() ? std::string(" (from generators)") : " ('" + scene.particles.front().name + "', ...)") +
           "; the Bullet reference simulates rigid bodies only";
  if (!scene.constraints.empty())
    return "the scene has constraints ('" + std::string(core::constraint_name(scene.constraints.front())) +
           "', ...); the Bullet reference simulates free rigid bodies only";
  for (const auto& e : scene.effects)
    if (!std::holds_alternative<core::Gravity>(e) && !std::holds_alternative<core::Collisions>(e) &&
        !std::holds_alternative<core::AppliedForces>(e))
      return "the '" + std::string(core::effect_name(e)) +
             "' effect; the Bullet reference applies only gravity, collisions and applied forces (Bullet's damping is "
             "not our drag law)";
  if (scene.bodies.empty()) return "the scene has no bodies";
  if (scene.find_effect<core::Collisions>() && model)
    for (std::size_t i = 0; i < scene.bodies.size(); ++i)
      if (!model->bodies[i].convex)
        return "body '" + scene.bodies[i].name + "' is not convex; Bullet would collide with its convex hull";
  return "";
}

std::string bullet_unsupported(const core::Scene& scene) {
  std::optional<core::Model> model;
  try {
    model = core::compile(scene);
  } catch (const Error&) {
    // A shape that cannot be built is the scene's error, not Bullet's:
    // simulate_bullet reports it as the backends do.
  }
  return bullet_unsupported(scene, model ? &*model : nullptr);
}

core::Run simulate_bullet(const core::Scene& scene) {
  if (const std::string why = bullet_unsupported(scene); !why.empty())
    throw input_error(scene.file.string() + ": bullet: " + why);
  return simulate_bullet(scene, core::compile(scene));
}

core::Run simulate_bullet(const core::Scene& scene, const core::Model& model) {
  if (const std::string why = bullet_unsupported(scene, &model); !why.empty())
    throw input_error(scene.file.string() + ": bullet: " + why);

  // As core::check_implemented says for the backends: a static body cannot be pushed.
  if (const auto* a = scene.find_effect<core::AppliedForces>())
    for (const auto& f : a->forces)
      for (const auto& b : scene.bodies)
        if (b.name == f.body && b.is_static)
          throw input_error(scene.file.string() + ": applied force on static body '" + b.name + "', which cannot move");

  core::Run run;
  run.backend = kBackend;
  core::require_volumes(scene, model);
  const core::Collisions* collisions = scene.find_effect<core::Collisions>();
  const core::BodyEffects& effects = model.effects;
  const Vec3 gravity = effects.gravity;  // zero without a gravity effect
  const double step = collisions ? collisions->step : kDefaultStep;

  const MaterialHooks hooks;
  // Bullet reads its sleeping time from a global; every run sets it, so no
  // run inherits another's (2 s, Bullet's own default, when the scene does
  // not ask for sleeping: every body then has deactivation disabled anyway).
  gDeactivationTime = collisions && collisions->sleep.on ? collisions->sleep.time : 2.0;
  auto world = std::make_unique<World>();
  btContactSolverInfo& info = world->world.getSolverInfo();
  info.m_splitImpulsePenetrationThreshold = 0;  // every penetration by split impulse (top of file)
  world->world.getDispatchInfo().m_enableSatConvex = true;  // SAT axis for hull clipping (top of file)
  world->world.setGravity(to_bullet(gravity));  // before adding bodies: addRigidBody copies it into each

  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    const core::Body& body = scene.bodies[b];
    const core::BodyModel& bm = model.bodies[b];
    const core::Mesh& mesh = *bm.mesh;  // about the centre of mass
    BulletBody bb;
    bb.principal = bm.principal;
    const Vec3& moments = bm.moments;
    bb.shape = bullet_shape(mesh, bb.principal);

    const bool fixed = body.is_static;
    const double mass = fixed ? 0.0 : bm.mass;
    btRigidBody::btRigidBodyConstructionInfo ci(mass, nullptr, bb.shape.get(),
                                                fixed ? btVector3(0, 0, 0) : to_bullet(moments));
    ci.m_friction = collisions ? body.friction : 0.0;
    ci.m_rollingFriction = 0;
    ci.m_spinningFriction = 0;
    ci.m_linearDamping = 0;
    ci.m_angularDamping = 0;
    ci.m_additionalDamping = false;
    ci.m_restitution = collisions ? bm.restitution : 0.0;
    const Eigen::Quaterniond q(body.orientation[0], body.orientation[1], body.orientation[2], body.orientation[3]);
    ci.m_startWorldTransform = btTransform(to_bullet(Eigen::Matrix3d(q.toRotationMatrix() * bb.principal)),
                                           to_bullet(body.position));
    bb.body = std::make_unique<btRigidBody>(ci);
    btRigidBody& rb = *bb.body;
    rb.setContactProcessingThreshold(0);  // no speculative contacts (top of file)
    if (!fixed) {
      rb.setLinearVelocity(to_bullet(body.velocity));
      rb.setAngularVelocity(to_bullet(body.angular_velocity));
      if (collisions && collisions->sleep.on) {
        // The scene's sleeping in Bullet's terms: |v| below the speed and
        // |ω| below it over the bounding radius, so that |v| + ρ|ω| stays
        // within twice it (ours bounds the sum by it); the time is Bullet's
        // global gDeactivationTime, set below.
        double rho = 0;
        for (const Vec3& v : mesh.vertices()) rho = std::max(rho, v.norm());
        rb.setSleepingThresholds(collisions->sleep.speed, collisions->sleep.speed / std::max(rho, 1e-12));
      } else {
        rb.setActivationState(DISABLE_DEACTIVATION);
      }
      rb.setFlags(BT_ENABLE_GYROSCOPIC_FORCE_IMPLICIT_BODY);
      if (collisions) {
        const double r = bm.inradius;
        rb.setCcdMotionThreshold(0.5 * r);
        rb.setCcdSweptSphereRadius(r);
      }
    }
    if (collisions)
      world->world.addRigidBody(&rb);
    else
      world->world.addRigidBody(&rb, btBroadphaseProxy::DefaultFilter, 0);  // collides with nothing
    world->bodies.push_back(std::move(bb));
  }

  // The contact settings (see the top of this file), for results.json.
  run.metrics["bullet_contact_processing_threshold_m"] = 0;
  run.metrics["bullet_sat_convex"] = world->world.getDispatchInfo().m_enableSatConvex ? 1 : 0;
  run.metrics["bullet_restitution_velocity_threshold_m_per_s"] = info.m_restitutionVelocityThreshold;
  run.metrics["bullet_contact_breaking_threshold_m"] = gContactBreakingThreshold;
  run.metrics["bullet_erp"] = info.m_erp;
  run.metrics["bullet_erp2"] = info.m_erp2;
  run.metrics["bullet_split_impulse"] = info.m_splitImpulse;
  run.metrics["bullet_split_impulse_penetration_threshold_m"] = info.m_splitImpulsePenetrationThreshold;
  run.metrics["bullet_linear_slop_m"] = info.m_linearSlop;
  run.metrics["bullet_global_cfm"] = info.m_globalCfm;
  run.metrics["bullet_solver_iterations"] = info.m_numIterations;
  run.metrics["bullet_warmstarting_factor"] = info.m_warmstartingFactor;

  auto record = [&](double t) {
    core::Sample s;
    s.t = t;
    observe(*world, s);
    core::fill_invariants(scene, model, s);
    run.samples.push_back(std::move(s));
  };

  // The applied forces' points in each body's principal frame (Aᵀ p), so that
  // R p = basis · (Aᵀ p) with the Bullet basis R·A.
  std::vector<Vec3> push_points;
  for (const auto& push : effects.pushes)
    push_points.push_back(world->bodies[push.body].principal.transpose() * push.point);
  // Hands Bullet the forces active at time t; it clears them after the step.
  auto apply_forces = [&](double t) {
    const core::ScopedStage timed(run.profile, core::Stage::forces);
    for (std::size_t k = 0; k < effects.pushes.size(); ++k) {
      const auto& push = effects.pushes[k];
      if (!(t >= push.from && t < push.until)) continue;
      btRigidBody& rb = *world->bodies[push.body].body;
      rb.applyForce(to_bullet(push.force), rb.getCenterOfMassTransform().getBasis() * to_bullet(push_points[k]));
    }
  };

  std::uint64_t steps = 0, manifolds = 0, points = 0, asleep_steps = 0;
  const bool sleeping = collisions && collisions->sleep.on;
  const auto times = core::output_times(scene);
  run.samples.reserve(times.size());
  const auto start = std::chrono::steady_clock::now();
  record(0);
  for (std::size_t k = 1; k < times.size() && !run.error; ++k) {
    // Whole fixed steps from one output time to the next: n = ⌈interval/step⌉
    // steps of interval/n ≤ step (a hair of slack so that an interval that is a
    // multiple of the step up to rounding is not given one step more).
    const double interval = times[k] - times[k - 1];
    const auto n = std::max<long long>(1, static_cast<long long>(std::ceil(interval / step * (1 - 1e-12))));
    const double h = interval / static_cast<double>(n);
    if (k == 1) run.metrics["bullet_fixed_step_s"] = h;
    run.solver.min_step = std::min(run.solver.min_step, h);
    run.solver.max_step = std::max(run.solver.max_step, h);
    for (long long i = 0; i < n; ++i) {
      const double t0 = times[k - 1] + static_cast<double>(i) * h, t1 = t0 + h;
      if (!effects.pushes.empty()) apply_forces(t0 + 0.5 * h);  // on or off at the step's midpoint (top of file)
      int taken = 0;
      {
        const core::ScopedStage timed(run.profile, core::Stage::integrate);
        // One fixed step of h: Bullet's accumulator goes 0 → h → 0 exactly, so
        // each call takes exactly one step (checked below), never 0 or 2.
        taken = world->world.stepSimulation(h, 1, h);
      }
      steps += static_cast<std::uint64_t>(taken);
      for (int m = 0; m < world->dispatcher.getNumManifolds(); ++m) {
        const int c = world->dispatcher.getManifoldByIndexInternal(m)->getNumContacts();
        if (c > 0) ++manifolds, points += static_cast<std::uint64_t>(c);
      }
      if (sleeping)
        for (const auto& bb : world->bodies)  // a static body is always ISLAND_SLEEPING in Bullet
          asleep_steps += !bb.body->isStaticObject() && bb.body->getActivationState() == ISLAND_SLEEPING;
      if (taken != 1) {
        std::ostringstream msg;
        msg << "bullet took " << taken << " steps instead of 1, stage integrate, between t=" << t0 << " and t=" << t1;
        run.error = msg.str();
        break;
      }
      if (const std::string bad = first_nonfinite(*world, scene); !bad.empty()) {
        std::ostringstream msg;
        msg << "non-finite state: " << bad << ", stage integrate, between t=" << t0 << " and t=" << t1;
        run.error = msg.str();
        break;
      }
    }
    if (!run.error) record(times[k]);
  }
  run.wall_seconds = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  run.solver.steps_accepted = steps;
  run.solver.derivative_evaluations = steps;  // Bullet evaluates the forces once per step
  run.counters["bullet_steps"] = steps;
  // Per step, the contact manifolds (body pairs) holding at least one point, and
  // their points, summed over the steps.
  run.counters["bullet_contact_manifolds"] = manifolds;
  run.counters["bullet_contact_points"] = points;
  // As our sleeping_body_steps (core/collision/sleep.hpp): bodies asleep, summed over the steps.
  if (sleeping) run.counters["sleeping_body_steps"] = asleep_steps;
  return run;
}

}  // namespace gacompare::compare
