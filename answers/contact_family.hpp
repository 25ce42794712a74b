#pragma once
// The degenerate-contact family: scenes built in code, each
// with its analytic outcome and a verdict on a run of it. Faces meeting faces,
// edges lying on faces, vertices exactly on edges: the configurations that the
// report's vertex-in-body / edge-through-face detector (fig. 7) sees as
// degenerate and that real scenes are full of. The family is generated as a
// cross product of the parameters the issue names, never hand-picked, so a case
// that fails cannot have been left out because it failed.
//
//   slide   two boxes, a at 1 m/s along x into b at rest, ε = 0.9: equal
//           (0.2 m cubes, 1 kg) or unequal (b 0.3 × 0.3 × 0.2 m, 2 kg); free or
//           resting on a frictionless static floor under gravity; b turned about
//           x (the contact normal) or z by 0, 90° or 1e-9 rad; b offset along y
//           or z by 0, 1e-9 or 1e-3 of a's size (on the floor: along y only).
//   row     2–5 equal cubes 1 cm apart along x, the first at 1 m/s, ε = 1.
//   stack   2, 3, 5 or 10 equal cubes on a static slab under gravity, ε = 0.5,
//           10 s, exactly touching or each dropped from 1 mm above the one below.
//   edge    a cube on the top edge of a static box turned 45° about x (a ridge
//           0.1, 0.2 or 0.4 m long: inside the cube's bottom face, ending exactly
//           on its edges, crossing them): resting on it under gravity, or
//           striking it at 1 m/s without gravity, ε = 0.5.
//
// Every case states its outcome in `expected`; `evaluate` computes that outcome
// again from the scene it is given (masses, velocities, sizes, ε), so a bundled
// scene file (data/scenes/contact_*.json) is judged by its own numbers, and the
// tests check separately that those numbers are the family's (same_setup).
#include "core/run.hpp"
#include "core/model/scene.hpp"

#include <string>
#include <vector>

namespace gacompare::core {

enum class ContactKind { slide, row, stack, edge_rest, edge_bounce };

// The outcome of one run against the analytic answer. Every check compares a
// measured error with its tolerance; `ratio` is the largest error / tolerance
// (≤ 1 passes), `error` and `unit` that check's error, `reason` says which
// quantity it was, its value and what was expected. `first_failure` is the
// first check that failed, in the order they are made (for the checks made at
// every sample: the earliest in time), where the worst one is often only the
// consequence (a box thrown off at 80 m/s had first fallen into the slab).
struct ContactVerdict {
  bool pass = true;
  double ratio = 0;
  double error = 0;
  std::string unit;
  std::string reason;
  std::string first_failure;
};

struct ContactCase {
  std::string name;      // "slide/equal/free/turn=z:1e-9rad/offset=y:1e-3"
  ContactKind kind;
  Scene scene;           // built in code (scene.file empty)
  std::string expected;  // the analytic outcome, in words and numbers
  std::string bundled;   // "" or the data/scenes file stem that holds this case
  // The 10 s stacks but two (two boxes touching, the three dropped
  // 1 mm) and the bundled 5-stack: GACOMPARE_QUICK_TESTS=1 leaves them out
  // of `ctest -L contact`.
  bool long_running = false;

  ContactVerdict evaluate(const Scene& scene, const Run& run) const;
  ContactVerdict evaluate(const Run& run) const { return evaluate(scene, run); }
};

// The analytic outcome of a scene of this kind, in words and numbers, computed
// from the scene as evaluate() computes it.
std::string expected_outcome(ContactKind kind, const Scene& scene);

// The whole family, in a fixed order (slides, rows, stacks, edges).
const std::vector<ContactCase>& contact_family();

// "" when the two scenes set up the same simulation (effects, solver, duration,
// output, rotation, bodies with their shapes, masses and initial states, to
// 1e-12); else the first difference. Names, descriptions and files are ignored.
std::string same_setup(const Scene& a, const Scene& b);

// The case name as a test name: every character outside [A-Za-z0-9] becomes '_'.
std::string identifier(const std::string& case_name);

}  // namespace gacompare::core
