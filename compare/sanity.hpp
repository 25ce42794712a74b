#pragma once
// Physical sanity of a collision run: six rules that hold
// for any correct frictionless contact response, checked on the samples a run
// wrote, whatever backend wrote them (traditional, cga, bullet). `check` fails
// on them (exit 1); `compare` prints them as warnings in report.md / report.html.
// A run that goes wrong must not look green because its two backends agree with
// each other and with a baseline stored from the same wrong code.
//
// The rules apply to every run of a scene that lists the `collisions` effect
// (other scenes get no lines) and that did not stop early (that already fails):
//
//  1. Energy never rises (scenes with every restitution ≤ 1 and nothing doing
//     work: no applied forces, no constraints, no attractions; drag only takes
//     energy away). E = kinetic + potential of the samples may rise above its
//     lowest value so far by at most Σ_i m_i |g| tol L_i + 1e-9 · (|E0| + |K0| + |U0|):
//     positional correction may lift a resting body by up to the penetration
//     tolerance above the body it rests on, and a body at level L_i of a stack
//     (L = 1 on a static body, 2 on a body on a static body, ...) by L_i of them.
//  2. No body passes through a static body: at no sample is a dynamic body deeper
//     than 10 · tol in a static one (exact separating-axis depth,
//     collision::sat_reference), nor its centre of mass inside one. A backend
//     that steps without a time of impact (Bullet, which reports its fixed step
//     h in run.metrics, or ours with the scene's time_of_impact "none" and its
//     collision step h) may also dip one step's travel, h · |v|max. Samples
//     only: a body that passes wholly through a thin static body between two
//     samples is not seen here.
//  3. A body at rest does not drift sideways. See lateral_drift_checks below.
//  4. No contact is left approaching: the collider's `unresolved_impacts`
//     counter (contact points approaching faster than the resting speed before
//     the response and still approaching after it) is 0. Absent (older runs,
//     Bullet): "not measured", an info line.
//  5. A body at rest does not keep speeding up (resting_acceleration_check).
//  6. No two moving bodies sink into each other: at no sample do two dynamic
//     bodies overlap by more than rule 2's bound (exact separating-axis depth),
//     for a run without a time of impact 10 · tol + h · (|v_i|max + |v_j|max).
//     A pile or stack whose contacts are not held apart (a heavy box sinking
//     into a light one, a pile squeezed by its own weight) fails here while
//     every wall stays clean.
#include "compare/check.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstddef>
#include <cstdint>
#include <span>
#include <utility>
#include <vector>

namespace gacompare::compare {

// The bounds, each explained where it is used (sanity.cpp).
inline constexpr double kSanityEnergyRounding = 1e-9;      // relative, of |E0| + |K0| + |U0|
inline constexpr double kSanityDeepPenetration = 10;       // × penetration tolerance
inline constexpr double kSanityLateralAcceleration = 1e-6; // m/s per s of rest (at least one second counted)
inline constexpr double kSanityLateralDrift = 1e-6;        // m
inline constexpr double kSanityLevel = 1e-8;               // sin of the tilt below which a face counts as level
inline constexpr int kSanityRestWindow = 3;                // samples in a row at rest vertically
inline constexpr double kSanityRestingSpeedRise = 1e-4;     // m/s over a second of rest, rising throughout

// The rules for one run of `scene` (generators expanded, as
// SceneResult::scene); empty unless the scene lists `collisions` and the run
// has samples and no error. One CheckLine per rule (two for rule 3: velocity
// and displacement), `what` starting with "sanity:"; a rule that does not
// apply to the scene is an info line saying why.
std::vector<CheckLine> sanity_checks(const core::Scene& scene, const core::Model& model, const core::Run& run);
// The same, compiling the scene's model (tests, runs built by hand).
std::vector<CheckLine> sanity_checks(const core::Scene& scene, const core::Run& run);
// Every run of a comparison, in backend order.
std::vector<CheckLine> sanity_checks(const SceneResult& r);

// The rules one by one (the tests call them on runs built by hand).
CheckLine energy_rise_check(const core::Scene& scene, const core::Run& run);
CheckLine penetration_check(const core::Scene& scene, const core::Run& run);
// Rule 3. Frictionless contact pushes only along the contact normal, and gravity
// is vertical, so a body whose every contact has a vertical normal keeps its
// horizontal ("lateral", ⟂ g) velocity, and its horizontal position moves by
// exactly the integral of that velocity. On a slope or against a wall it
// legitimately does not. The rule is checked over stretches of samples where
// a body
//   - is at rest vertically: |v·ĝ| < v_rest = √(2|g| tol) + 2|g| step (the
//     collider's resting speed) at kSanityRestWindow or more samples in a row;
//   - has no applied force acting on it, and the scene has no drag (both push
//     sideways);
//   - at both ends of each sample interval, every other body within its reach
//     (what the two could close in one interval: (speeds + |ω| radii) · Δt +
//     |g| Δt² + 10 tol) touches it across a level face: a face of one of the
//     two, tilted by less than kSanityLevel, with the other body on its outer
//     side to within 10 tol and that body's lowest points over the face's
//     interior by at least the reach (so the contact is not at an edge, where
//     the normal is ambiguous). Other bodies further than the reach are
//     proved far by a face axis of the pair;
//   - and no body within that reach has friction with it (a pair's
//     √(μ_a μ_b) > 0): friction pushes sideways by design.
// Over each stretch [t0, t1]: the lateral velocity changes by at most
// kSanityLateralAcceleration · max(t1 − t0, 1 s) (no body starts sliding on
// its own), and the lateral displacement differs from the trapezoid integral of
// the sampled lateral velocity by at most kSanityLateralDrift (no sideways
// teleport by positional correction).
std::vector<CheckLine> lateral_drift_checks(const core::Scene& scene, const core::Run& run);
CheckLine unresolved_impacts_check(const core::Scene& scene, const core::Run& run);
// Rule 5 (sanity.cpp resting_acceleration): over a second in which every body
// is slower than the resting speed, no body speeds up throughout it by more
// than kSanityRestingSpeedRise.
CheckLine resting_acceleration_check(const core::Scene& scene, const core::Run& run);
// Rule 6: the deepest overlap of two dynamic bodies at any sample, against its
// bound. A non-finite position fails it, naming the body.
CheckLine overlap_check(const core::Scene& scene, const core::Run& run);

// The failing lines, one sentence each ("traditional: energy rose ..."), for
// report.md's warnings.
std::vector<std::string> sanity_warnings(const std::vector<CheckLine>& lines);

// The gap between two spheres (negative where they overlap): every rule's
// sphere test, and SphereGrid's.
inline double sphere_gap(const core::Vec3& a, const core::Vec3& b, double ra, double rb) {
  return (a - b).norm() - ra - rb;
}

// Which of the bodies `which` are near one another: those whose spheres
// (centre, radius), each grown by grow[i] (by nothing where grow is empty),
// meet, |c_i − c_j| − r_i − r_j < grow_i + grow_j (a NaN centre meets
// everything). Every rule above that looks at pairs of bodies asks this,
// never every pair: testing every pair made the checks of a 100,000-body box
// take 25 s for three samples.
//
// A uniform grid per size class (grown radii within a factor of two), of
// cell twice the class's largest, over the centres: a body's partners in a
// class lie in the cells its sphere grown by that largest radius overlaps,
// three a side for a body of the class's size. One grid for all sizes would
// make every cell hold everything once one body is large (a floor, a body
// flung fast); a one-axis sweep would not do either: in a 20-layer pyramid
// each cube's x-interval holds a thousand others. Where a large body's
// query would cover more cells than a class has bodies, it reads the class
// body by body; a body at a non-finite position or of non-finite size has
// no cell and is asked about every body.
class SphereGrid {
 public:
  SphereGrid(std::span<const core::Vec3> centres, std::span<const double> radius, std::span<const std::size_t> which,
             std::span<const double> grow);
  // f(j) for each body j ≠ i of `which` near body i (of `which`), in a fixed
  // order, until f returns false; whether none did.
  template <class F>
  bool near(std::size_t i, F&& f) const {
    const auto call = [&](std::size_t j) { return j == i || !meets(i, j) || f(j); };
    const core::Vec3& c = centres_[i];
    if (lost(i)) return std::all_of(which_.begin(), which_.end(), call);
    for (const Level& l : levels_) {
      // The class's bodies that can meet i have centres within `reach` of
      // c on every axis (widened for the rounding of the sums).
      const double reach = (grown(i) + l.largest) * (1 + 1e-9) + 1e-12 * (1 + c.cwiseAbs().maxCoeff());
      std::array<long, 3> lo{}, hi{};
      double cells = 1;
      for (int a = 0; a < 3; ++a)
        lo[a] = l.index(c[a] - reach), hi[a] = l.index(c[a] + reach), cells *= static_cast<double>(hi[a] - lo[a] + 1);
      if (cells > static_cast<double>(l.cells.size())) {
        for (const auto& entry : l.cells)
          if (!call(entry.second)) return false;
        continue;
      }
      for (long x = lo[0]; x <= hi[0]; ++x)
        for (long y = lo[1]; y <= hi[1]; ++y)
          for (long z = lo[2]; z <= hi[2]; ++z) {
            const std::uint64_t k = key(x, y, z);
            for (auto it = std::lower_bound(l.cells.begin(), l.cells.end(), std::make_pair(k, std::size_t{0}));
                 it != l.cells.end() && it->first == k; ++it)
              if (!call(it->second)) return false;
          }
    }
    return std::all_of(lost_.begin(), lost_.end(), call);
  }
  // Every pair (i < j) near each other, each once, in a fixed order.
  std::vector<std::pair<std::size_t, std::size_t>> pairs() const;

 private:
  // Cells clamped to ±2^20 per axis: a body flung a million cells out shares
  // a boundary cell with others there, which costs tests, not pairs.
  static constexpr long kSpan = 1L << 20;
  static std::uint64_t key(long x, long y, long z) {
    return (static_cast<std::uint64_t>(x + kSpan) << 42) | (static_cast<std::uint64_t>(y + kSpan) << 21) |
           static_cast<std::uint64_t>(z + kSpan);
  }
  struct Level {
    double largest = 0, cell = 1;
    std::vector<std::pair<std::uint64_t, std::size_t>> cells;  // (cell, body), sorted
    long index(double x) const { return std::clamp(static_cast<long>(std::floor(x / cell)), -kSpan + 2, kSpan - 2); }
  };
  double grown(std::size_t i) const { return radius_[i] + (grow_.empty() ? 0.0 : grow_[i]); }
  bool lost(std::size_t i) const { return !centres_[i].allFinite() || !std::isfinite(grown(i)); }
  bool meets(std::size_t i, std::size_t j) const {
    const double g = grow_.empty() ? 0.0 : grow_[i] + grow_[j];
    return !(sphere_gap(centres_[i], centres_[j], radius_[i], radius_[j]) >= g);
  }
  std::span<const core::Vec3> centres_;
  std::span<const double> radius_, grow_;
  std::vector<std::size_t> which_;
  std::vector<Level> levels_;      // by size class, smallest first
  std::vector<std::size_t> lost_;  // bodies at non-finite positions or of non-finite size
};

}  // namespace gacompare::compare
