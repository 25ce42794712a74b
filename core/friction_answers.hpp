#pragma once
// The analytic answers of the friction scenes (issue #17, data/scenes/friction_*.json)
// and a run measured against them: for tests/friction_cases.hpp (both
// backends), tests/compare/bullet_world_test.cpp and bench/friction_table
// (README "Friction"). A scene is one dynamic body on one static body whose
// top face (its body +z) is the contact plane, with gravity g and the pair's
// Coulomb coefficient μ = √(μ_a μ_b); θ is the plane's tilt against g:
//   - at rest with tan θ < μ: it sticks, displacement 0;
//   - at rest with tan θ ≥ μ: it slides down the slope with
//     a = |g| (sin θ − μ cos θ): speed a t, distance ½ a t² at the end;
//   - launched with v₀ along the plane (down the slope or on the level) with
//     tan θ < μ: it decelerates at |g| (μ cos θ − sin θ) and stops after
//     v₀² / (2 (μ cos θ − sin θ) |g|) at time v₀ / ((μ cos θ − sin θ) |g|).
#include "core/run.hpp"
#include "core/scene.hpp"

#include <string>
#include <vector>

namespace gacompare::core {

struct FrictionFigure {
  std::string quantity, unit;
  double analytic = 0, measured = 0;
  // |measured − analytic| / |analytic|, or the absolute difference where the answer is 0.
  double error() const;
};

// The scene's figures measured in `run` (input_error if the scene is not of
// the kind above). A body counts as stopped once its speed is below 1e-3 v₀:
// from there it has (1e-3)² = 1e-6 of its stopping distance left, and a
// solver whose resting contact jitters (Bullet's: ~1e-5 m/s) is not timed by
// its jitter.
std::vector<FrictionFigure> friction_figures(const Scene& scene, const Run& run);

}  // namespace gacompare::core
