#pragma once
// Sleeping islands: a step of the collision step (core/collision/collision_step.hpp),
// off unless the collisions effect has "sleep" (core/model/scene.hpp Sleep).
//
// The report has no sleeping: every body is integrated and tested at every
// step, and a settled pile pays full price for standing still. Box2D (Catto)
// and Bullet put an island to sleep once all its bodies have been slow for a
// while; we do the same, with the islands of the collision step
// (core/collision/islands.hpp) as the groups and the rim speed |v| + ρ|ω|
// (ρ the body's arm, the speed bound of Collider::reach) as the measure:
//
//   * Falling asleep. After each collision step, a moving body whose rim
//     speed at t1 is at most `speed` and on which no applied force acts has
//     been still for another step; once every moving body of an island has
//     been still for `time`, the island's bodies are stopped (P = L = 0) and
//     put to sleep together, as one sleeping set. A moving body in no island
//     (nothing within its reach) is a set of its own.
//   * Asleep. A sleeping body counts as static for the broadphase and the
//     islands (it moves nothing it touches: nothing touches it while it
//     sleeps, see waking), its derivative is zero and not computed, and the
//     narrowphase never tests two sleeping or static bodies.
//   * Waking. Before the islands are formed, every sleeping set that an awake
//     moving body can reach within the step (a candidate pair left after
//     unlink_far: it could touch in the step) is woken whole, and the world
//     is detected again with its bodies moving, until nothing more wakes; a
//     set on which an applied force switches on wakes too. A woken body
//     starts from rest where it slept, so the contact solve sees it with its
//     mass, never as a static body.
//
// What it costs in accuracy: a body stopped at up to `speed` has its last
// motion removed, and a woken body missed the gravity of the step in which
// it woke (½ g h² ≈ 5 µm at 1 ms); the error of a sleeping run against the
// awake one is measured in tests/sleep_cases.hpp and by
// bench/scale/sleep.py.
#include <span>
#include <utility>
#include <vector>

namespace gacompare::core {

struct SleepState {
  std::vector<char> asleep;          // per world body
  std::vector<double> still_for;     // s: how long each awake moving body has been still
  std::vector<int> set_of;           // the sleeping set a body sleeps in; −1 awake
  std::vector<std::vector<int>> sets;  // each set's bodies; empty once woken
  std::vector<int> free_sets;        // emptied sets, for reuse
  std::size_t sleeping = 0;          // bodies asleep now

  explicit SleepState(std::size_t n = 0) : asleep(n, 0), still_for(n, 0.0), set_of(n, -1) {}
  bool any() const { return sleeping > 0; }

  // Puts `bodies` (awake moving world bodies) to sleep as one set.
  void fall_asleep(std::span<const int> bodies) {
    int id;
    if (!free_sets.empty()) id = free_sets.back(), free_sets.pop_back();
    else id = static_cast<int>(sets.size()), sets.emplace_back();
    sets[static_cast<std::size_t>(id)].assign(bodies.begin(), bodies.end());
    for (const int b : bodies) asleep[static_cast<std::size_t>(b)] = 1, set_of[static_cast<std::size_t>(b)] = id;
    sleeping += bodies.size();
  }

  // Wakes the set body b sleeps in (false when b is awake); its bodies start
  // their stillness afresh.
  bool wake(int b) {
    const int id = set_of[static_cast<std::size_t>(b)];
    if (id < 0) return false;
    for (const int k : sets[static_cast<std::size_t>(id)]) {
      const auto u = static_cast<std::size_t>(k);
      asleep[u] = 0, set_of[u] = -1, still_for[u] = 0;
    }
    sleeping -= sets[static_cast<std::size_t>(id)].size();
    sets[static_cast<std::size_t>(id)].clear();
    free_sets.push_back(id);
    return true;
  }

  // Wakes every set with a body in a candidate pair with an awake moving
  // body; the number of sets woken.
  int wake_reached(std::span<const char> is_static, std::span<const std::pair<int, int>> candidates) {
    int woken = 0;
    for (const auto& [i, j] : candidates) {
      const auto ui = static_cast<std::size_t>(i), uj = static_cast<std::size_t>(j);
      const bool moving_i = !is_static[ui] && !asleep[ui], moving_j = !is_static[uj] && !asleep[uj];
      if (asleep[ui] && moving_j) woken += wake(i);
      else if (asleep[uj] && moving_i) woken += wake(j);
    }
    return woken;
  }

  // Whether world body k sleeps (false for every body of a run without
  // sleeping, whose vectors are empty).
  bool is_asleep(std::size_t k) const { return sleeping > 0 && asleep[k]; }
};

}  // namespace gacompare::core
