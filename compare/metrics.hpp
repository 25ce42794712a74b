#pragma once
// How far apart two states are, and how much a run's energy changed: the
// measures every comparison uses (sweep errors against a reference, check
// against baselines and between backends, the divergence figures, the energy
// change in reports), written once so they all measure alike.
#include "compare/runner.hpp"
#include "core/run.hpp"

#include <Eigen/Core>

#include <array>
#include <optional>
#include <string_view>
#include <vector>

namespace gacompare::compare {

// The angle (rad, in [0, π]) of the rotation q⁻¹q′ that takes orientation q to
// q′ (quaternions [w,x,y,z], each normalised first: a sample may carry rotation
// drift, and the angle is that of the rotations they stand for). With q′'s sign
// chosen so that q·q′ ≥ 0 (q and −q are one rotation), q·q′ = cos(θ/4)² − sin(θ/4)²
// and the angle is θ = 4 atan2(|q − q′|, |q + q′|): twice Kahan's angle between
// the two 4-vectors, which is half the rotation's. Accurate to rounding for
// every angle (~1e-16 rad absolute near 0), where 2 acos|q·q′| reads 0 for any
// angle below 2.1e-8 rad (acos of 1 − ulp) and loses half the digits near it.
double rotation_angle(const Eigen::Vector4d& q, const Eigen::Vector4d& q2);

// The four things a state is measured by, with their units.
enum class Measure { position, orientation, velocity, angular_velocity };
inline constexpr std::array<Measure, 4> kMeasures = {Measure::position, Measure::orientation, Measure::velocity,
                                                     Measure::angular_velocity};
std::string_view measure_name(Measure m);  // "position", "orientation", "velocity", "angular_velocity"
std::string_view measure_unit(Measure m);  // "m", "rad", "m/s", "rad/s"
std::string_view measure_words(Measure m); // "position", "orientation", "velocity", "angular velocity"
std::optional<Measure> measure_from_string(std::string_view name);
// Orientation and angular velocity are measured on bodies only.
bool body_only(Measure m);

// Each scene body's radius about its centre of mass: the largest distance of a
// vertex of its mesh from it (m). A turn by θ moves no point of the body by more
// than radius × θ.
std::vector<double> body_radii(const core::Model& model);

// One value per measure.
struct StateErrors {
  std::array<double, 4> value{0, 0, 0, 0};
  double& operator[](Measure m) { return value[static_cast<std::size_t>(m)]; }
  double operator[](Measure m) const { return value[static_cast<std::size_t>(m)]; }
  // Each measure the worse of this and o's (worse() below: a NaN wins).
  void take(const StateErrors& o);
};

// The larger of `worst` and `x`, where a NaN wins (a plain std::max drops a NaN
// against 0, and a diverged run would then read as perfect).
double worse(double worst, double x);

// One particle's or one body's differences: |x − x′| (m), the rotation angle of
// q⁻¹q′ (rad, bodies), |v − v′| (m/s) and |ω − ω′| (rad/s, world frame, bodies);
// a measure an object does not have is 0.
StateErrors particle_difference(const core::ParticleSample& a, const core::ParticleSample& b);
StateErrors body_difference(const core::BodySample& a, const core::BodySample& b);

// Between two samples of the same scene, the largest over particles and bodies
// of each measure: |x − x′| (m), the rotation angle of q⁻¹q′ (rad), |v − v′|
// (m/s) and |ω − ω′| (rad/s, world frame).
StateErrors state_difference(const core::Sample& a, const core::Sample& b);

// The two measures of state_difference the divergence figures and the summary use.
double position_difference(const core::Sample& a, const core::Sample& b);
double orientation_difference(const core::Sample& a, const core::Sample& b);

// Largest state_difference between the backends over all samples (0 with fewer
// than two backends); Bullet is left out (a reference with another integrator
// and contact model, compared in its own table).
StateErrors max_state_divergence(const SceneResult& r);
double max_divergence(const SceneResult& r);              // position (m)
double max_orientation_divergence(const SceneResult& r);  // rad

// The energy a run's change is measured against: |E₀| = |K₀ + U₀| at t = 0, or,
// where E₀ is less than 1e-6 of |K₀| + |U₀| (a datum that makes the total
// cancel), that sum. From the first sample alone, so every backend and solver
// setting of a scene is measured by the same yardstick. 0 when every energy at
// t = 0 is 0 (a body at rest at the datum: bead_on_helix, hanging_net,
// cube_pyramid_point).
double energy_scale(const core::Sample& first);

// max over samples of |E(t) − E₀| / energy_scale: the energy drift, or the
// energy dissipated where drag or restitution acts. Never saturates: a blow-up
// from −0.5 J to 1.9e6 J reads 3.8e6. Where energy_scale is 0 there is no
// scale at t = 0 and the largest |K| + |U| seen in the run stands in (only
// there can the value not exceed 1). A NaN energy reads NaN.
double energy_drift(const core::Run& run);

}  // namespace gacompare::compare
