#pragma once
// The stacking family: the hard cases of a contact solver, generated as a
// cross product of sizes, each with its statics answer. Every case starts its
// bodies a millimetre apart (each level 1 mm above the one below, the lowest
// 1 mm above the ground), drops them under gravity and runs 10 simulated
// seconds; the answer is where each body must come to rest:
//
//   column    N = 2, 5, 10, 20, 40 equal cubes (0.2 m, 1 kg); 5, 10, 20
//             unequal boxes (three sizes in turn, one density); 3, 10
//             spheres in a square tube of four static walls that touch them.
//   pyramid   a wall of L = 2, 5, 10, 20 layers (each cube on two below,
//             2 cm gaps in every row); a square pyramid of 3 and 5 layers
//             (each cube on four below); frictionless and dropped without
//             bounce (restitution 0: with a bounce a frictionless pyramid
//             drifts, which is the drop's answer, not the solver's error).
//   ratio     two cubes, 1 : 10^k both ways (k = 0 … 4: heavy on light, light
//             on heavy); a plate of 10^k kg (k = 1 … 4) on three 1 kg cubes.
//   friction  a card house (two plates leaning together, μ = 0.6); a row of
//             ten upright dominoes (μ = 0.5); the wall pyramid of 5 layers
//             and the square one of 3 with μ = 0.5 on every face.
//
// Restitution 0.2 (0 for the frictionless pyramids), rk4 at 1 ms, collision step 1 ms, penetration tolerance
// 1e-4 m (the settings a new user tries first); no friction but in the
// friction cases. The verdict (evaluate) holds every sample to:
//   - lateral drift from the rest position ≤ 1e-4 m, from the start;
//   - after the bodies have landed (t ≥ 1 s): rim speed |v| + ρ|ω| ≤ 1e-4 m/s,
//     and height within [rest − k tol, rest], k the contacts below the body
//     on its way to the ground (each contact may sink by up to tol);
//   - no capped solve (the contact solver's sweep caps) in the whole run.
#include "core/run.hpp"
#include "core/model/scene.hpp"

#include <string>
#include <vector>

namespace gacompare::core {

struct StackVerdict {
  bool pass = true;
  double ratio = 0;          // the worst error / its bound (≤ 1 passes)
  std::string worst;         // which check, body, time and value gave it
  std::string first_failure; // the earliest failing check, or ""
};

struct StackCase {
  std::string name;  // "column/cubes/20"
  Scene scene;       // built in code
  // For each body of the scene: where it must come to rest (its centre) and
  // how many contacts lie below it on its way to the ground; static bodies 0.
  std::vector<Vec3> rest;
  std::vector<int> below;
  bool long_running = false;  // left out when GACOMPARE_QUICK_TESTS=1
  // Minutes per backend (50 moving bodies or more): left out of the tests
  // unless GACOMPARE_SLOW_TESTS=1; the stacking table always runs it.
  bool slow = false;
  // Why the default contact solver does not meet this answer yet, or "" when
  // it must. Tests skip an open case with this reason (GACOMPARE_OPEN_CASES=1
  // runs it); the stacking table runs every case and shows the verdict.
  std::string open;

  StackVerdict evaluate(const Run& run) const;
};

// The whole family, in a fixed order, with the contact solver `method`.
std::vector<StackCase> stacking_family(ContactSolverMethod method);

inline constexpr double kStackDrift = 1e-4;   // m: lateral drift from the rest position
inline constexpr double kStackSpeed = 1e-4;   // m/s: rim speed at rest
inline constexpr double kStackSettle = 1.0;   // s: by then every drop and bounce is over

}  // namespace gacompare::core
