#pragma once
// The analytic answers of the friction scenes (data/scenes/friction_*.json)
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
//     v₀² / (2 (μ cos θ − sin θ) |g|) at time v₀ / ((μ cos θ − sin θ) |g|);
//   - a solid sphere at rest with tan θ ≤ 7/2 μ rolls without slipping:
//     a = 5/7 |g| sin θ (speed and distance as above);
//   - a solid sphere launched on the level without spin slides, slowed by
//     μ|g| and spun up by 5μ|g|/(2r), until ω r = v at t* = 2 v₀/(7 μ|g|);
//     then it rolls at 5/7 v₀ (speed while sliding, t*, the rolling speed).
#include "core/run.hpp"
#include "core/model/scene.hpp"

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

// A spinning top on a floor (data/scenes/top_on_floor.json): one dynamic
// polyhedron standing on its lowest vertex (the apex) on one static body,
// symmetric about the line from the apex to its centre of mass (I3 along it,
// I1 about the centre across it), spun at ω3 about that axis, tilted θ from
// the vertical. While friction holds the apex (needs μ ≥ Ω² l sin θ / |g|,
// checked) it is Lagrange's heavy top about a fixed point, which precesses
// steadily where I1' Ω² cos θ − I3 ω3 Ω + m|g|l = 0, I1' = I1 + m l²; the slow
// root, written without the cancellation of (I3 ω3 − √D)/(2 I1' cos θ):
// Ω = 2 m|g|l / (I3 ω3 + √D), D = (I3 ω3)² − 4 I1' cos θ m|g|l. Figures: the
// mean precession rate (the axis's azimuth about the vertical at the end over
// the time), the tilt farthest from its start, and how far the apex moved.
std::vector<FrictionFigure> top_figures(const Scene& scene, const Run& run);

// A pile settling (data/scenes/mixed_pile.json): static and dynamic
// axis-aligned boxes and spheres, each dynamic body expected to come to rest
// straight below where it starts, on the highest thing under it — a box on a
// box (their footprints overlap) or on a sphere (its centre over the box), a
// sphere on a box's top face, edge or corner (at horizontal distance d < r
// from the top face: r² = d² + height²) or on another sphere. Figures: the
// highest body's rest height, every body's height error relative to its own
// rest height (the largest), the largest horizontal drift (m) and the largest
// speed and angular speed at the end.
std::vector<FrictionFigure> pile_figures(const Scene& scene, const Run& run);

// The figures of whichever of the three kinds the scene is: more than two
// bodies, a pile; a spinning polyhedron, a top; otherwise friction_figures.
std::vector<FrictionFigure> analytic_figures(const Scene& scene, const Run& run);

}  // namespace gacompare::core
