#pragma once
// The scene model: a read-only description of what to simulate, loaded once
// from data/scenes/*.json. Keys and units are the public contract of
// docs/scenes.md; compiled once into the model (core/model/model.hpp) that
// every backend reads.
#include <Eigen/Core>

#include <filesystem>
#include <limits>
#include <memory>
#include <optional>
#include <span>
#include <string>
#include <utility>
#include <variant>
#include <vector>

namespace gacompare::core {

using Vec3 = Eigen::Vector3d;

enum class SolverMethod {
  euler, rk4, rk4_doubling, cash_karp45,
  bs3, dopri5, tsit5, vern6, vern7, vern8, vern9,  // embedded pairs (core/dynamics/tableaus.hpp)
  symplectic_euler, velocity_verlet,
  rkmk4, rkmk45, crouch_grossman4  // Lie-group methods on the bodies' rotations (core/dynamics/lie_group.hpp)
};
std::string_view to_string(SolverMethod m);
std::optional<SolverMethod> solver_method_from_string(std::string_view s);
std::span<const std::string_view> solver_method_names();  // every method's name, in the order above
// rkmk4, rkmk45, crouch_grossman4: each body's rotation steps on its group.
bool is_lie_group(SolverMethod m);

// How an adaptive step's error is measured against the tolerances:
//   physical (default): per body, the errors of the position, the velocity, the
//     rotation (the angle of R⁻¹ δR, whatever stores R) and the angular velocity,
//     each against abs_tol + rel_tol·|its value|; particles per component.
//     Equal tolerance then asks the same accuracy of a matrix, a quaternion and
//     a rotor.
//   component: every stored number against abs_tol + rel_tol·|it| (the report's
//     §B.3.3): 9 matrix entries, 4 quaternion or rotor components, momenta.
enum class ErrorNorm { physical, component };
struct SolverSpec {
  SolverMethod method = SolverMethod::rk4;
  double dt = 1e-3;       // s: the step of fixed-step methods, the first try of adaptive ones
  double abs_tol = 1e-9;  // adaptive methods: absolute tolerance
  double rel_tol = 1e-9;  // adaptive methods: relative tolerance
  ErrorNorm error_norm = ErrorNorm::physical;
};

// --- effects (Table 2 of the report, plus collisions) ---------------------------
struct Gravity { Vec3 g{0, 0, -9.81}; };                 // F = m g
struct LinearDrag { double k = 0; double k_angular = 0; };     // F = -k v; on bodies also τ = -k_angular ω
struct QuadraticDrag { double k = 0; double k_angular = 0; };  // F = -k |v| v; on bodies also τ = -k_angular |ω| ω
// Attractions (Table 2) with an optional Plummer softening length ε ≥ 0:
// F = C m1 m2 r / (r² + ε²)^(3/2), potential −C m1 m2 / √(r² + ε²). ε = 0 is the
// report's exact 1/r² law, singular where two particles meet.
struct AttractionBetweenParticles { double C = 0; double softening = 0; };  // towards each other
struct AttractionToPoint { Vec3 point{0, 0, 0}; double D = 0; double softening = 0; };  // F = D m / r², towards point
// Collision detection and response between rigid bodies (§2.4–2.5).
//   restitution: ε of eq. 53 for every pair, unless a body sets its own; a pair
//     uses the smaller of its two bodies' values.
//   penetration_tolerance (m): §2.4.3's tolerance; a step that ends deeper is
//     retreated (time of impact), shallower contacts get impulses.
//   step (s): the interval at which contacts are checked (the solver takes its
//     own steps inside it); an island with a body that could move more than
//     half the smallest inradius in it is stepped in shorter sub-steps (no
//     tunnelling; core/collision/collision_step.hpp).
//   time_of_impact: how a time of impact is searched for (core/collision/time_of_impact.hpp):
//     "bisection" (§2.5.1, the report's), "illinois" (a bracketing root finder
//     on the separating-axis depth, §4.3's future work), "golden_section"
//     (§4.3.1's line search), "conservative_advancement" (Mirtich's) or
//     "none": no search. An impact is then taken where the step (or a fast
//     island's sub-step) ends, up to one step's travel deep, and the
//     response's correction pushes the pair back (Box2D's and Bullet's way):
//     the penetration tolerance holds at the end of each step's response, not
//     between steps. What accuracy costs in a pile (bench/scale/scale.py).
//   impact_motion: where the search's trial poses come from: "integrate"
//     (default; the island re-integrated to each trial time, §2.5.1) or
//     "interpolate" (each body's pose interpolated between the ends of the
//     sub-step in its backend's algebra, §4.3.2: a quaternion slerp or a rotor
//     power along a line; the island is integrated once, to the time found).
//   method: how contacts are found once the separating-axis test says a pair
//     touches: "manifold" (default; the reference face clipped against the
//     incident face along the axis of minimum penetration, core/collision/manifold.hpp)
//     or "report" (fig. 7's vertex-in-body and edge-through-face detector,
//     which misses faces meeting faces: kept to compare with).
//   broadphase: which pairs get the narrowphase, all methods giving the same
//     pairs (core/collision/broadphase.hpp): "aabb_tree" (default; a dynamic tree of
//     boxes with persistent pairs), "sphere_tree" (the same tree over the
//     backend's spheres, §4.2.2) or "sweep" (sort and sweep on one axis).
enum class TimeOfImpact { bisection, illinois, golden_section, conservative_advancement, none };
enum class ImpactMotion { integrate, interpolate };
enum class ContactMethod { manifold, report };
enum class BroadphaseMethod { sweep, aabb_tree, sphere_tree };
// How the contact solver (core/contact/contact_solver.hpp) solves an island's
// rows: projected Gauss–Seidel sweeps, or the direct solve of their
// complementarity problem (core/contact/lcp.hpp) polished by the sweeps.
enum class ContactSolverMethod { pgs, direct };
// Sleeping (core/collision/sleep.hpp), off unless the scene asks: an island
// whose moving bodies' rim speeds |v| + ρ|ω| all stay at or below `speed`
// for `time` seconds is stopped and no longer integrated, detected or solved,
// until a moving body comes within reach of it or an applied force on it
// switches on. Box2D v3 sleeps at 0.05 m/s after 0.5 s.
struct Sleep {
  bool on = false;
  double speed = 0.01;  // m/s
  double time = 0.5;    // s
};
struct Collisions {
  double restitution = 0.5;
  double penetration_tolerance = 1e-4;
  double step = 1e-3;
  TimeOfImpact time_of_impact = TimeOfImpact::bisection;
  ImpactMotion impact_motion = ImpactMotion::integrate;
  ContactMethod method = ContactMethod::manifold;
  BroadphaseMethod broadphase = BroadphaseMethod::aabb_tree;  // the fastest (bench/broadphase_bench.cpp)
  ContactSolverMethod contact_solver = ContactSolverMethod::direct;
  // Each body's narrowphase geometry built once per detection and each pair's
  // separating axis kept between detections; false rebuilds both
  // bodies for every pair and remembers nothing: the same run, slower (for
  // tests and benchmarks).
  bool reuse = true;
  // A pair's contact manifold kept between detections while the pair's
  // relative pose stays within a bound, its depths measured again
  // (core/collision/kept_contacts.hpp); false tests every pair every time.
  bool reuse_contacts = true;
  Sleep sleep{};
};
// Forces applied at points of bodies (§2.3.1: L̇ = τ): each pushes body `body` at
// `point` (body coordinates, from the centre of mass) with `force` (world, N)
// while from <= t < until, producing the torque (R p) × F — in cga the bivector
// (R p) ∧ F. A switch on or off is integrated to within one step's impulse (an
// RK stage at the switching time sees the new state of the force); put switching
// times on output times so that no step straddles them.
struct AppliedForce {
  std::string body;
  Vec3 point{0, 0, 0};
  Vec3 force{0, 0, 0};
  double from = 0;
  double until = std::numeric_limits<double>::infinity();
};
struct AppliedForces { std::vector<AppliedForce> forces; };
using Effect = std::variant<Gravity, LinearDrag, QuadraticDrag, AttractionBetweenParticles,
                            AttractionToPoint, Collisions, AppliedForces>;
std::string_view effect_name(const Effect& e);  // the scene's "type" string

struct Particle {
  std::string name;
  double mass = 1;
  Vec3 position{0, 0, 0};
  Vec3 velocity{0, 0, 0};
  bool pinned = false;
};

// --- constraints (§2.1.2) ---------------------------------------------------------
struct DistanceToPoint { std::string particle; Vec3 point{0, 0, 0}; double length = 0; };  // eq. 25 (also: on a sphere)
struct DistanceBetween { std::string a, b; double length = 0; };                           // eq. 26
struct OnPlane { std::string particle; Vec3 point{0, 0, 0}; Vec3 normal{0, 0, 1}; };          // normal: unit
struct OnLine { std::string particle; Vec3 point{0, 0, 0}; Vec3 direction{1, 0, 0}; };       // direction: unit
struct OnCircle { std::string particle; Vec3 center{0, 0, 0}; Vec3 normal{0, 0, 1}; double radius = 1; };
// x = c + r(cos θ u + sin θ v) + (pitch/2π) θ axis, (u, v, axis) right-handed; pitch: rise per turn.
struct OnHelix { std::string particle; Vec3 center{0, 0, 0}; Vec3 axis{0, 0, 1}; double radius = 1; double pitch = 1; };
using Constraint = std::variant<DistanceToPoint, DistanceBetween, OnPlane, OnLine, OnCircle, OnHelix>;
std::string_view constraint_name(const Constraint& c);  // the scene's "type" string

// How constraint forces are found and drift is held (§2.1.2): Lagrange multipliers
// from J W Jᵀ λ = −J̇ q̇ − J W Q (eq. 24) by Jacobi-preconditioned conjugate gradient.
enum class Drift { off, baumgarte, projection };
struct ConstraintSolverSpec {
  Drift drift = Drift::off;       // off reproduces the report: drift is left to grow
  double baumgarte_alpha = 10;    // 1/s: C̈ + 2α Ċ + β² C = 0
  double baumgarte_beta = 10;     // 1/s
  double projection_tolerance = 1e-10;  // m: positions projected until every |C|/|∇C| is below it
  double cg_tolerance = 1e-12;    // relative residual of the CG solve
  int cg_max_iterations = 1000;
};

// --- shapes --------------------------------------------------------------------------
class Mesh;  // core/model/mesh.hpp
struct BoxShape { Vec3 size{1, 1, 1}; };                   // full side lengths
struct TetrahedronShape { double edge = 1; };
struct PyramidShape { double base = 1; double height = 1; };  // square base, apex above
struct OctahedronShape { double radius = 1; };             // centre to vertex
struct IcosahedronShape { double radius = 1; };            // centre to vertex
struct SphereShape { double radius = 1; };                 // a round shape (core/model/mesh.hpp, make_sphere)
// A round shape: the points within `radius` of the segment of `length` along
// the body's z axis, centred on its position (core/model/mesh.hpp, make_capsule).
struct CapsuleShape { double radius = 1; double length = 1; };
// Hulls and OBJ meshes are built once, by the loader (which checks them and
// names the JSON path of a bad one); mesh_for() hands out that mesh.
struct HullShape { std::vector<Vec3> points; std::shared_ptr<const Mesh> mesh = nullptr; };
struct MeshShape { std::filesystem::path file; std::shared_ptr<const Mesh> mesh = nullptr; };  // resolved against the scene file's folder
using Shape = std::variant<BoxShape, TetrahedronShape, PyramidShape, OctahedronShape,
                           IcosahedronShape, HullShape, MeshShape, SphereShape, CapsuleShape>;

struct Body {
  std::string name;
  Shape shape;
  std::optional<double> mass;     // exactly one of mass and density is set
  std::optional<double> density;
  Vec3 position{0, 0, 0};
  Eigen::Vector4d orientation{1, 0, 0, 0};  // unit quaternion [w,x,y,z], body -> world
  Vec3 velocity{0, 0, 0};
  Vec3 angular_velocity{0, 0, 0};           // world frame, rad/s
  bool is_static = false;
  std::optional<double> restitution;        // overrides the collisions effect's for this body
  // Coulomb friction coefficient μ ≥ 0 (collisions effect): a pair uses
  // √(μ_a μ_b), Box2D's rule (Bullet's default multiplies; its run is given
  // the same √ by a hook, compare/bullet_world.cpp). 0, the default, adds no
  // friction rows at all: a frictionless scene runs exactly as before.
  double friction = 0;
};

// The rotation matrix of a stored orientation [w, x, y, z], normalised first (a
// sample may carry the run's rotation drift; what it stands for is a rotation).
Eigen::Matrix3d rotation_matrix(const Eigen::Vector4d& q);

// --- generators: expanded into particles and constraints by the dynamics issue --------
struct ParticleNet {          // the hanging net of fig. 4
  std::string name;           // particles are named name[r][c]
  int rows = 2, cols = 2;
  double spacing = 0.1, mass = 1;
  Vec3 origin{0, 0, 0};
  std::vector<std::pair<int, int>> pinned;  // [row, col] pairs
};
struct ParticleChain {
  std::string name;           // particles are named name[i]
  int count = 2;
  double spacing = 0.1, mass = 1;
  Vec3 origin{0, 0, 0};
  Vec3 direction{1, 0, 0};
  std::vector<int> pinned;
};
using Generator = std::variant<ParticleNet, ParticleChain>;

// How rigid bodies keep their rotation (§2.3.1, §2.3.2): the traditional backend's
// representation, and renormalisation, applied alike to every representation.
enum class Rotation { matrix, quaternion };
enum class Renormalise { none, every_step };
struct RigidBodySpec {
  Rotation rotation = Rotation::matrix;      // traditional backend only; cga always uses a rotor
  Renormalise renormalise = Renormalise::none;
};

// What `gacompare check` holds a scene to (scene key "check"). The two
// comparisons every check makes have documented defaults; the invariant bounds
// are checked only where the scene states them.
struct CheckSpec {
  double max_divergence = 1e-6;          // m: largest distance between the backends' positions
  double baseline_tolerance = 1e-9;      // m: largest distance from the stored baseline's final positions
  std::optional<double> max_energy_drift;          // relative, as reports measure it
  std::optional<double> max_constraint_violation;  // m
  std::optional<double> max_rotation_drift;        // ‖RᵀR − I‖, |qq* − 1|, |RR̃ − 1|
  // Where bodies must come to rest (key "rest": {"after", "tolerance", "at"}):
  // from `rest_after` s on, each body named in `at` stays within
  // `rest_tolerance` m of the position given for it (its centre of mass).
  struct RestAt {
    std::string body;
    Vec3 position{0, 0, 0};
  };
  std::vector<RestAt> rest;
  double rest_after = 0, rest_tolerance = 1e-4;
};

// The most output samples a scene may ask for by default (duration /
// output.every): a million samples of a few bodies are already hundreds of
// megabytes of results.
inline constexpr double kMaxSamples = 1e6;

// What a scene may ask of a run (core/model/budget.hpp): checked at load, before any
// work; the command line's --max-samples, --max-steps and --max-memory raise them.
struct Limits {
  double max_samples = kMaxSamples;  // output samples, duration / output.every
  double max_steps = 1e8;            // solver steps of one run (fixed-step count, collision steps; adaptive: at run time)
  double max_memory_mb = 4096;       // the recorded samples of one backend's run, MB
};

struct Scene {
  std::string name;
  std::string description;
  std::filesystem::path file;  // where it was loaded from ("" when built in code)
  std::string sha256;          // of the file's bytes
  double duration = 1;         // s
  double output_every = 0.01;  // s
  SolverSpec solver;
  ConstraintSolverSpec constraint_solver;
  RigidBodySpec rigid_body;
  CheckSpec check;
  std::vector<Effect> effects;  // ONLY these are simulated
  std::vector<Particle> particles;
  std::vector<Constraint> constraints;
  std::vector<Body> bodies;
  std::vector<Generator> generators;
  Limits limits;  // what it was loaded under; the solver's step budget at run time

  template <class T> const T* find_effect() const {
    for (const auto& e : effects)
      if (auto* p = std::get_if<T>(&e)) return p;
    return nullptr;
  }
  template <class T> T* find_effect() { return const_cast<T*>(std::as_const(*this).template find_effect<T>()); }
};

// Loads and validates a scene. Throws gacompare::Error (ErrorKind::input) with one
// line "FILE: JSON/PATH: what was expected" on malformed JSON, an unknown key, a
// wrong type, a missing field, a value out of range, a duplicate name, an
// unknown reference, a bad mesh or more samples than `limits` allow. What
// needs the bodies' meshes (convexity under collisions, magnitudes no physics
// means, steps) is refused by load_compiled (core/model/model.hpp).
Scene load_scene(const std::filesystem::path& file, const Limits& limits = {});
// Same, from text already in memory; `file` is used in messages and to resolve meshes.
Scene parse_scene(const std::string& text, const std::filesystem::path& file, const Limits& limits = {});
// Why the scene cannot take its Lie-group solver.method (particles, no
// bodies), "" when it can or its method is not one: the loader refuses at
// /solver/method, and simulate() refuses a scene built in code. Collisions
// are taken: islands and time-of-impact trials step on the group too
// (core/collision/subsystem.hpp).
std::string lie_group_refusal(const Scene& scene);
// Throws the loader's refusal "FILE: JSON/PATH: what" (for checks made after loading).
[[noreturn]] void refuse_at(const std::filesystem::path& file, const std::string& path, const std::string& what);

// Collision cases (`gacompare collide`): a JSON array of pairs
//   {"name": "...", "a": BODY, "b": BODY}      ("name" optional: "case N")
// where BODY holds exactly one shape key of the scene format ("hull": [[x, y, z],
// ...], "box": [x, y, z], "pyramid": {...}, "mesh": "file.obj", ...), "position":
// [x, y, z] and optionally "orientation": [w, x, y, z] (identity when absent).
// The shape keeps its own coordinates (a hull is not recentred): position and
// orientation place them, x_world = R x + position. Same strict validation as
// scenes; an empty array is an error.
struct PlacedShape {
  Shape shape;
  Vec3 position{0, 0, 0};
  Eigen::Vector4d orientation{1, 0, 0, 0};
};
struct CollisionCaseSpec {
  std::string name;
  PlacedShape a, b;
};
std::vector<CollisionCaseSpec> load_collision_cases(const std::filesystem::path& file);
std::vector<CollisionCaseSpec> parse_collision_cases(const std::string& text, const std::filesystem::path& file);

}  // namespace gacompare::core
