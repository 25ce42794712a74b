#pragma once
// What a scene asks of a run, decided at load before any work: a
// scene file from someone else's repository must end with results or a clear
// reason, never a hang, a crash or a machine out of memory. Two kinds of check:
//
// Budgets (raised by the command line's --max-samples, --max-steps,
// --max-memory): output samples (duration / output.every), solver and
// collision steps (duration / the smallest step a fixed-step solver or the
// collision loop may take), and the memory the recorded samples take.
//
// Physical bounds (not raised by any flag): magnitudes at which Newtonian
// rigid-body mechanics in double precision stops meaning anything, so that
// every step would be non-finite or infinitely small: speeds above the speed
// of light (given, reached by a rim turning at the given angular velocity, or
// reached within the scene's duration under its gravity or applied forces),
// lengths beyond the observable universe or below a proton, masses below an
// electron or above the observable universe.
//
// Every refusal names the JSON path whose value is to blame and the numbers.
#include "core/model/model.hpp"
#include "core/model/scene.hpp"

#include <optional>
#include <string>

namespace gacompare::core {

inline constexpr double kSpeedOfLight = 299'792'458.0;  // m/s
inline constexpr double kMaxLength = 1e26;  // m: the observable universe's radius is 4.4e26 m
inline constexpr double kMinLength = 1e-15; // m: a proton's radius is 8.4e-16 m
inline constexpr double kMinMass = 1e-31;   // kg: an electron is 9.1e-31 kg
inline constexpr double kMaxMass = 1e53;    // kg: the observable universe's ordinary matter, 1.5e53 kg

// Peak memory of one backend's run per recorded sample and entity: the samples,
// their results.json tree and its text (the peak resident size of
// `gacompare run` per sample on a particle and a body scene, rounded up).
inline constexpr double kBytesPerParticleSample = 1600;
inline constexpr double kBytesPerBodySample = 3000;

// The first refusal found, as a JSON path and what is wrong there.
struct Refusal {
  std::string path;
  std::string what;
};

// Samples and their memory against `scene.limits`.
std::optional<Refusal> over_sample_budget(const Scene& scene);
// Fixed-step and collision steps against `scene.limits`: a body's inradius
// bounds the collision step. After physically_absurd, whose bounds keep these
// numbers finite.
std::optional<Refusal> over_step_budget(const Scene& scene, const Model& model);

// The physical bounds above.
std::optional<Refusal> physically_absurd(const Scene& scene, const Model& model);

// A body that is not convex, in a scene that lists collisions (§2.4.2: the
// narrowphase is for convex bodies).
std::optional<Refusal> not_convex(const Scene& scene, const Model& model);

// Each body's length scales, read from its model (about its centre of mass).
struct BodyScale {
  double radius = 0;    // farthest vertex from the centre of mass
  double inradius = 0;  // nearest face plane (convex bodies; 0 when the centre is outside one)
  double volume = 0;
  double mass = 0;      // given, or density x volume
};
BodyScale body_scale(const Body& body, const BodyModel& model);

}  // namespace gacompare::core
