#pragma once
// The narrowphase stage's driver: each pair of a group through the
// narrowphase (core/collision/narrowphase.hpp) on the bodies' shapes placed
// once per detection, the pairs found farther apart than they can move (the
// islands' links), and the deepest depth among given pairs (the time of
// impact's function). Members of the Collider (core/collision/collisions.hpp),
// defined here.
#include "core/collision/collisions.hpp"
#include "core/parallel.hpp"

#include <array>
#include <atomic>
#include <cstdint>

namespace gacompare::core {

// How many pairs ahead the narrowphase's lookups ask the cache for their
// records: the lookups miss it at scale, and asked for ahead, the 10,000-body
// pile's narrowphase took 0.94 of its time on one thread and 0.92 on two
// (twelve alternated runs of each build of collision_step_bench --settle 0.08
// on the box restarted at 0.9 s, bench/scale/restart_scene.py). With two
// tables to look up it had gained too little to tell from the noise.
inline constexpr std::size_t kPrefetchAhead = 8;

// The placed shapes' table and the detection each was placed in, one entry
// per body of the world, sized on first use (narrow, depth_at, shape).
template <class State>
void size_shape_tables(State& state, std::size_t bodies) {
  if (state.shapes.size() != bodies) state.shapes.resize(bodies), state.placed_in.assign(bodies, 0);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::narrow(State& state, BodyIndices group,
                                                   const std::vector<collision::Pose>& pose,
                                                   const std::vector<std::pair<int, int>>& pairs, Detection& d,
                                                   Profile& profile, std::span<const double> margin,
                                                   std::size_t grain) const -> void {
  ScopedStage timed(profile, Stage::narrowphase);
  const auto method = setup.settings.method == ContactMethod::report ? collision::Method::sat_then_report
                                                                     : collision::Method::sat_then_manifold;
  const bool reuse = setup.settings.reuse;
  // Kept contacts (core/collision/kept_contacts.hpp) for the manifold method.
  const bool keep = setup.settings.reuse_contacts && method == collision::Method::sat_then_manifold;
  ++state.detection;
  if (group.data() == setup.all_bodies.data()) state.pairs.next(), state.kept.next();  // a new round of pairs
  // Each pair gets a slot of its own, so that the pairs can be tested on the
  // run's threads and come out the same for any number of them
  // (core/parallel.hpp):
  //   1. on this thread, the pairs to test (a < b in the world); their
  //      slots are written on the run's threads, in step 2 (a 10,000-body
  //      world's slots are megabytes, and writing them on one thread was a
  //      measurable share of the run's own thread);
  //   2. in parallel, each pair's own lookups: its record (its remembered
  //      axis and the state of its kept contacts), and its kept contacts
  //      where that state says they are current, measured again where its
  //      relative pose has stayed within their bound
  //      (core/collision/kept_contacts.hpp: those pairs are not tested, and
  //      their bodies not placed for them); and each
  //      body a tested pair needs placed, once, by the pair that claims it
  //      first (an atomic exchange of the detection it was placed in);
  //   3. in parallel, the tests, each writing back its pair's remembered axis
  //      and kept contacts where its pair had them;
  //   4. on this thread, in pair order, the pairs new to the memories, the
  //      hits, the links apart and the counters.
  // The memories are only read and rewritten in place (PairMemory::find)
  // until step 4 adds the new pairs, so the entries found in step 2 stay
  // where they are. Their lookups miss the cache at scale (the tables of
  // 10,000 bodies' pairs are megabytes): on one thread, with each pair's
  // axis looked up twice, they were a seventh of the 10,000-body box's run.
  using Slot = NarrowSlot;
  std::vector<std::pair<int, int>>& tests = state.tests;
  tests.clear();
  if (reuse) size_shape_tables(state, setup.meshes.size());
  for (const auto& pair : pairs) {
    int i = pair.first, j = pair.second;
    if (setup.is_static[group[i]] && setup.is_static[group[j]]) continue;
    if (group[i] > group[j]) std::swap(i, j);  // a < b in the world: every group sees a pair the same way
    tests.emplace_back(i, j);
  }
  // The slots kept between detections (a slot beyond this detection's pairs is stale).
  if (state.slots.size() < tests.size()) state.slots.resize(tests.size());
  const std::span<Slot> slots(state.slots.data(), tests.size());
  state.counters.narrowphase_pairs += slots.size();
  if (group.data() != setup.all_bodies.data()) state.counters.island_narrowphase_pairs += slots.size();
  // PairMemory::find on several threads at once: each writes only its own pair's entry.
  const bool shared = runs_parallel(slots.size(), grain);
  const bool report = method == collision::Method::sat_then_report;
  for_each_index(
      slots.size(),
      [&](std::size_t u) {
        Slot& s = slots[u];
        if (u + kPrefetchAhead < slots.size() && (reuse || keep))
          state.pairs.prefetch(group[tests[u + kPrefetchAhead].first], group[tests[u + kPrefetchAhead].second]);
        s = Slot{PairHit{tests[u].first, tests[u].second, {}, {}}, {}, {}};
        const int wa = group[s.h.a], wb = group[s.h.b];
        s.record = reuse || keep ? state.pairs.find(wa, wb) : nullptr;
        if (s.record) s.remembered = *s.record, s.held = s.remembered.kept;
        if (keep && s.held.wait > 0) {
          s.hold = --s.held.wait > 0;  // kept again after the test that ends the wait
        } else if (keep && s.held.valid) {
          // A current state's manifold was met at the pair's last test, as
          // its record was, so it is in the table (were it not, the pair
          // would read as having none).
          if (collision::KeptContacts* k = state.kept.find(wa, wb)) {
            if (collision::refresh(*k, *setup.meshes[wa], *setup.meshes[wb], pose[s.h.a], pose[s.h.b],
                                   collision::kTouchingBand *
                                       collision::pair_scale(*setup.meshes[wa], *setup.meshes[wb]),
                                   s.h.sat, s.h.features)) {
              s.held.refused = 0;
              if (s.held != s.remembered.kept) s.record->kept = s.held;
              s.kept = true;
              return;
            }
            s.hold = !collision::refuse(s.held);
            s.kept_entry = k;
          }
        }
        if (!reuse) return;
        if (s.record) s.hint = s.remembered.axis;
        // Each body a tested pair needs is placed once in this detection, by
        // the first pair to claim it. Which pair, or thread, that is changes
        // nothing: a shape is a function of its mesh and pose alone.
        for (const int k : {s.h.a, s.h.b}) {
          const int w = group[k];
          // Read before the exchange: most of a body's pairs find it placed,
          // and an exchange writes, taking the line from the other core's cache.
          std::atomic_ref<std::uint64_t> placed(state.placed_in[w]);
          if (placed.load(std::memory_order_relaxed) == state.detection ||
              placed.exchange(state.detection, std::memory_order_relaxed) == state.detection)
            continue;
          ++s.shapes;
          auto& shape = state.shapes[w];
          shape.place({setup.meshes[w].get(), pose[k]});
          // The report's detector reads prepared triangles, built on first
          // use by a thread that may not be alone: built here instead.
          if (shared && report && !shape.is_sphere() && !shape.is_capsule() &&
              !setup.meshes[w]->triangles().empty()) shape.triangle(0);
        }
      },
      grain);
  // Whether a tested pair's contacts are kept (collision::keep, into its entry).
  const auto keeps = [&](const Slot& s) { return keep && !s.kept && s.choice.made && !s.h.features.empty(); };
  for_each_index(
      slots.size(),
      [&](std::size_t u) {
        Slot& s = slots[u];
        if (s.kept) return;
        PairHit& h = s.h;
        collision::FaceChoice* choice = keep ? &s.choice : nullptr;
        if (reuse) {
          h.sat = collision::narrowphase<NarrowBody>(state.shapes[group[h.a]], state.shapes[group[h.b]], method,
                                                     &h.features, &s.hint, choice);
        } else {
          // The shapes placed for this pair alone; the hint only written (an
          // empty one is read as none), for the kept contacts.
          const typename NarrowBody::Shape sa(placed(pose, group, h.a)), sb(placed(pose, group, h.b));
          h.sat = collision::narrowphase<NarrowBody>(sa, sb, method, &h.features, keep ? &s.hint : nullptr, choice);
        }
        const int wa = group[h.a], wb = group[h.b];
        // The manifold kept where the test gives one and the pair does not
        // wait: into its entry where it has one (a pair new to the table gets
        // it in pair order, below).
        s.held.valid = false;
        if (keeps(s) && !s.hold) {
          if (!s.kept_entry) s.kept_entry = state.kept.find(wa, wb);
          if (s.kept_entry)
            s.held.valid = collision::keep(*s.kept_entry, *setup.meshes[wa], *setup.meshes[wb], pose[h.a], pose[h.b],
                                           h.sat, s.hint, s.choice, h.features);
        }
        // The record written back only where it changed, as most do not: a
        // store to every pair's record, whose line the tests since had
        // evicted, cost the 10,000-body pile's narrowphase 5 % (the two
        // versions alternated, six runs each of collision_step_bench on the
        // pile restarted at 0.9 s, bench/scale/restart_scene.py).
        if (s.record)
          if (const PairRecord now{reuse ? s.hint : s.remembered.axis, s.held}; !(now == s.remembered)) *s.record = now;
        // A pair within the touching band is in contact too (it has contacts):
        // its yes/no is rounding's (core/collision/collision.hpp), and a box resting
        // exactly on another fell for a step whenever it rounded to apart.
        if (!h.sat.intersect && h.features.empty() && !margin.empty())
          s.apart = apart_beyond_reach(state, group, pose, h, margin, s.face_tested, s.shapes);
      },
      grain);
  // Step 4 in three parts, so that the slots (some 400 bytes each, written
  // on the run's threads) are read there too: read on this thread alone,
  // a 10,000-body world's were 1.8 % of its run's own thread.
  //   a. in parallel, each block of slots' counts, counters and deepest
  //      hit, and its pairs new to the memories;
  //   b. on this thread, in pair order, those pairs into the memories (an
  //      insertion can move the tables' entries);
  //   c. in parallel, each block's hits, gaps and links apart written where
  //      the counts before it put them: every list in pair order.
  const auto apart = [](const Slot& s) { return !s.h.sat.intersect && s.h.features.empty(); };
  // A pair new to the kept manifolds, or to the records (without reuse a
  // record is kept only for a state other than the empty one).
  const auto manifold_new = [&](const Slot& s) { return keeps(s) && !s.hold && !s.kept_entry; };
  const auto record_new = [&](const Slot& s) { return !s.record && (reuse || s.held != collision::KeptState{}); };
  const auto fresh = [&](const Slot& s) { return !s.kept && (manifold_new(s) || record_new(s)); };
  struct Block {
    std::size_t hits = 0, gaps = 0, far = 0;
    std::uint64_t face_tested = 0, shapes = 0, kept = 0, axes = 0;
    double deepest = -INFINITY;
    std::vector<std::size_t> fresh;
  };
  // Blocks of kGrainBody slots (a few nanoseconds each here): a push-out's
  // few hundred pairs stay on this thread.
  const std::size_t blocks = blocks_of(slots.size(), kGrainBody);
  std::vector<Block> block(blocks);
  for_each_block(slots.size(), kGrainBody, [&](std::size_t b, std::size_t begin, std::size_t end) {
    Block& k = block[b];
    for (std::size_t u = begin; u < end; ++u) {
      const Slot& s = slots[u];
      k.face_tested += s.face_tested, k.shapes += s.shapes;
      if (s.kept) ++k.kept;
      else k.shapes += reuse ? 0 : 2, k.axes += reuse ? s.hint.kept : 0;  // without reuse, the pair's own shapes
      if (fresh(s)) k.fresh.push_back(u);
      if (apart(s)) ++k.gaps, k.far += s.apart;
      else ++k.hits, k.deepest = std::max(k.deepest, s.h.sat.depth);
    }
  });
  std::size_t hits = d.hits.size(), gaps = d.gaps.size(), far = d.apart.size();
  std::vector<std::array<std::size_t, 3>> at(blocks);
  for (std::size_t b = 0; b < blocks; ++b) {
    const Block& k = block[b];
    state.counters.links_face_tested += k.face_tested;
    state.counters.narrowphase_shapes += k.shapes;
    state.counters.contacts_kept += k.kept;
    state.counters.narrowphase_axes_kept += k.axes;
    d.max_depth = std::max(d.max_depth, k.deepest);
    at[b] = {hits, gaps, far};
    hits += k.hits, gaps += k.gaps, far += k.far;
    for (const std::size_t u : k.fresh) {
      Slot& s = slots[u];
      if (!manifold_new(s)) continue;
      const int wa = group[s.h.a], wb = group[s.h.b];
      s.held.valid = collision::keep(state.kept.at(wa, wb), *setup.meshes[wa], *setup.meshes[wb], pose[s.h.a],
                                     pose[s.h.b], s.h.sat, s.hint, s.choice, s.h.features);
      if (s.record) s.record->kept = s.held;
    }
  }
  // The pairs new to the records last: an insertion can move the records,
  // which the loop above writes through the slots' pointers.
  for (const Block& k : block)
    for (const std::size_t u : k.fresh)
      if (const Slot& s = slots[u]; record_new(s))
        state.pairs.at(group[s.h.a], group[s.h.b]) = {reuse ? s.hint : collision::SatHint{}, s.held};
  d.hits.resize(hits), d.gaps.resize(gaps), d.apart.resize(far);
  for_each_block(slots.size(), kGrainBody, [&](std::size_t b, std::size_t begin, std::size_t end) {
    auto [h, gap, a] = at[b];
    for (std::size_t u = begin; u < end; ++u) {
      Slot& s = slots[u];
      if (!apart(s)) {
        d.hits[h++] = std::move(s.h);
        continue;
      }
      if (s.apart) d.apart[a++] = {s.h.a, s.h.b};
      d.gaps[gap++] = {s.h.a, s.h.b, s.h.sat.depth};
    }
  });
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::apart_beyond_reach(const State& state, BodyIndices group,
                                                               const std::vector<collision::Pose>& pose,
                                                               const PairHit& h, std::span<const double> margin,
                                                               std::uint64_t& face_tested,
                                                               std::uint64_t& shapes) const -> bool {
  const int wa = group[h.a], wb = group[h.b];
  const double reach = margin[h.a] + margin[h.b] +
                       collision::kTouchingBand * collision::pair_scale(*setup.meshes[wa], *setup.meshes[wb]);
  const double gap = -h.sat.depth;
  const bool face = h.sat.feature == collision::Feature::face_a || h.sat.feature == collision::Feature::face_b;
  if (face && gap > reach) return true;
  const auto beyond = [&](const NarrowBody& va, const NarrowBody& vb) {
    if (collision::round_pair(va, vb)) return gap > reach;  // already exact
    ++face_tested;
    return collision::face_gap(va, vb, reach) > reach;
  };
  // The bodies' shapes of this detection (placed above), or their own.
  if (setup.settings.reuse) return in_pair_frame(state.shapes[wa], state.shapes[wb], beyond);
  return on_own_shapes(placed(pose, group, h.a), placed(pose, group, h.b), shapes, beyond);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class F>
auto Collider<Bodies, NarrowBody, Spheres>::on_own_shapes(const collision::Placed& a, const collision::Placed& b,
                                                          std::uint64_t& shapes, F&& f) {
  // Constructed only here: two Shapes are some 4 KB, and building them,
  // unused, for every pair found apart with reuse on was 2.8 % of the samples
  // of a 10,000-body pile's collision step.
  Shape own_a, own_b;
  own_a.place(a), own_b.place(b), shapes += 2;
  return in_pair_frame(own_a, own_b, f);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class F>
auto Collider<Bodies, NarrowBody, Spheres>::in_pair_frame(const Shape& a, const Shape& b, F&& f) {
  const Vec3 o = collision::local_origin(a.position(), b.position());
  return f(NarrowBody(a, a.position() - o), NarrowBody(b, b.position() - o));
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class PoseA, class PoseB, class F>
auto Collider<Bodies, NarrowBody, Spheres>::on_pair(State& state, int wa, int wb, PoseA&& pose_a, PoseB&& pose_b,
                                                    F&& f) const {
  if (setup.settings.reuse) return in_pair_frame(shape(state, wa, pose_a), shape(state, wb, pose_b), f);
  return on_own_shapes({setup.meshes[wa].get(), pose_a()}, {setup.meshes[wb].get(), pose_b()},
                       state.counters.narrowphase_shapes, f);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::depth_of(State& state, const Model& m, std::span<const double> y,
                                                     BodyIndices group, const std::vector<std::pair<int, int>>& pairs,
                                                     Profile& profile) const -> double {
  return depth_at(
      state, group, pairs, [&](int k) { return Bodies::pose(m, y, static_cast<std::size_t>(k)); }, profile);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class PoseOf>
auto Collider<Bodies, NarrowBody, Spheres>::depth_at(State& state, BodyIndices group,
                                                     const std::vector<std::pair<int, int>>& pairs, PoseOf&& pose_of,
                                                     Profile& profile) const -> double {
  ScopedStage timed(profile, Stage::narrowphase);
  double g = -INFINITY;
  ++state.detection;
  const auto depth = [](const NarrowBody& va, const NarrowBody& vb) {
    return (collision::round_pair(va, vb) ? collision::round_narrowphase(va, vb) : collision::separating_axis(va, vb))
        .depth;
  };
  if (!setup.settings.reuse || !runs_parallel(pairs.size(), kGrainDepthPair)) {
    for (const auto& pair : pairs) {  // their bodies' poses only, each body placed once
      const int i = pair.first, j = pair.second;
      g = std::max(g, on_pair(state, group[i], group[j], [&] { return pose_of(i); }, [&] { return pose_of(j); }, depth));
    }
    return g;
  }
  // Many pairs (a pile's resting contacts that sank below the tolerance in
  // a sub-step, searched together): on the run's threads, each body placed
  // once by its own item, then each pair tested in its own slot. The bodies
  // and the count placed are those of the loop above (the first pair that
  // names a body places it); the deepest is the same in any order.
  std::vector<int> place;  // the group's bodies to place, in the order the pairs name them
  size_shape_tables(state, setup.meshes.size());
  for (const auto& [i, j] : pairs)
    for (const int k : {i, j})
      if (std::uint64_t& at = state.placed_in[static_cast<std::size_t>(group[k])]; at != state.detection)
        at = state.detection, place.push_back(k);
  state.counters.narrowphase_shapes += place.size();
  for_each_index(place.size(), [&](std::size_t u) {
    const int k = place[u];
    state.shapes[static_cast<std::size_t>(group[k])].place({setup.meshes[group[k]].get(), pose_of(k)});
  }, kGrainDepthPair);
  std::vector<double> each(pairs.size());
  for_each_index(pairs.size(), [&](std::size_t q) {
    const auto [i, j] = pairs[q];
    each[q] = in_pair_frame(state.shapes[static_cast<std::size_t>(group[i])], state.shapes[static_cast<std::size_t>(group[j])],
                            depth);
  }, kGrainDepthPair);
  for (const double d : each) g = std::max(g, d);
  return g;
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class PoseOf>
auto Collider<Bodies, NarrowBody, Spheres>::shape(State& state, int b, PoseOf&& pose_of) const -> const Shape& {
  size_shape_tables(state, setup.meshes.size());
  if (state.placed_in[b] != state.detection) {
    state.shapes[b].place({setup.meshes[b].get(), pose_of()});
    state.placed_in[b] = state.detection;
    ++state.counters.narrowphase_shapes;
  }
  return state.shapes[b];
}
}  // namespace gacompare::core
