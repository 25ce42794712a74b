#pragma once
// The narrowphase stage's driver: each pair of a group through the
// narrowphase (core/collision/narrowphase.hpp) on the bodies' shapes placed
// once per detection, the pairs found farther apart than they can move (the
// islands' links), and the deepest depth among given pairs (the time of
// impact's function). Members of the Collider (core/collision/collisions.hpp),
// defined here.
#include "core/collision/collisions.hpp"

namespace gacompare::core {

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::narrow(State& state, BodyIndices group,
                                                   const std::vector<collision::Pose>& pose,
                                                   const std::vector<std::pair<int, int>>& pairs, Detection& d,
                                                   Profile& profile, std::span<const double> margin) const -> void {
  ScopedStage timed(profile, Stage::narrowphase);
  const auto method = setup.settings.method == ContactMethod::report ? collision::Method::sat_then_report
                                                                     : collision::Method::sat_then_manifold;
  ++state.detection;
  if (group.data() == setup.all_bodies.data()) state.hints.next();  // the world's detection: a new round of pairs
  for (const auto& pair : pairs) {
    int i = pair.first, j = pair.second;  // plain ints: lambdas below capture them (clang 14 cannot capture a binding)
    if (setup.is_static[group[i]] && setup.is_static[group[j]]) continue;
    if (group[i] > group[j]) std::swap(i, j);  // a < b in the world: every group sees a pair the same way
    ++state.counters.narrowphase_pairs;
    if (group.data() != setup.all_bodies.data()) ++state.counters.island_narrowphase_pairs;
    PairHit h{i, j, {}, {}};
    if (setup.settings.reuse) {
      const int a = group[i], b = group[j];
      const Shape& sa = shape(state, a, [&] { return pose[i]; });
      const Shape& sb = shape(state, b, [&] { return pose[j]; });
      collision::SatHint& hint = state.hints.at(a, b);
      h.sat = collision::narrowphase<NarrowBody>(sa, sb, method, &h.features, &hint);
      state.counters.narrowphase_axes_kept += hint.kept;
    } else {
      h.sat = collision::narrowphase<NarrowBody>(placed(pose, group, i), placed(pose, group, j), method, &h.features);
      state.counters.narrowphase_shapes += 2;
    }
    // A pair within the touching band is in contact too (it has contacts):
    // its yes/no is rounding's (core/collision/collision.hpp), and a box resting
    // exactly on another fell for a step whenever it rounded to apart.
    if (!h.sat.intersect && h.features.empty()) {
      if (!margin.empty()) note_apart(state, group, pose, h, margin, d);
      continue;
    }
    d.max_depth = std::max(d.max_depth, h.sat.depth);
    d.hits.push_back(std::move(h));
  }
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::note_apart(State& state, BodyIndices group,
                                                       const std::vector<collision::Pose>& pose, const PairHit& h,
                                                       std::span<const double> margin, Detection& d) const -> void {
  const int wa = group[h.a], wb = group[h.b];
  const double reach = margin[h.a] + margin[h.b] +
                       collision::kTouchingBand * collision::pair_scale(*setup.meshes[wa], *setup.meshes[wb]);
  double gap = -h.sat.depth;
  const bool face = h.sat.feature == collision::Feature::face_a || h.sat.feature == collision::Feature::face_b;
  if (!(face && gap > reach))
    gap = on_pair(
        state, wa, wb, [&] { return pose[h.a]; }, [&] { return pose[h.b]; },
        [&](const NarrowBody& va, const NarrowBody& vb) {
          if (collision::round_pair(va, vb)) return gap;  // already exact
          ++state.counters.links_face_tested;
          return collision::face_gap(va, vb, reach);
        });
  if (gap > reach) d.apart.emplace_back(h.a, h.b);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class PoseA, class PoseB, class F>
auto Collider<Bodies, NarrowBody, Spheres>::on_pair(State& state, int wa, int wb, PoseA&& pose_a, PoseB&& pose_b,
                                                    F&& f) const {
  Shape own_a, own_b;
  if (!setup.settings.reuse) {
    own_a.place({setup.meshes[wa].get(), pose_a()}), own_b.place({setup.meshes[wb].get(), pose_b()});
    state.counters.narrowphase_shapes += 2;
  }
  const Shape& a = setup.settings.reuse ? shape(state, wa, pose_a) : own_a;
  const Shape& b = setup.settings.reuse ? shape(state, wb, pose_b) : own_b;
  const Vec3 o = collision::local_origin(a.position(), b.position());
  return f(NarrowBody(a, a.position() - o), NarrowBody(b, b.position() - o));
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
  for (const auto& pair : pairs) {  // few pairs, each body in one or two: their poses only
    const int i = pair.first, j = pair.second;
    g = std::max(g, on_pair(
                        state, group[i], group[j], [&] { return pose_of(i); }, [&] { return pose_of(j); },
                        [](const NarrowBody& va, const NarrowBody& vb) {
                          return (collision::round_pair(va, vb) ? collision::round_narrowphase(va, vb)
                                                                : collision::separating_axis(va, vb))
                              .depth;
                        }));
  }
  return g;
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
template <class PoseOf>
auto Collider<Bodies, NarrowBody, Spheres>::shape(State& state, int b, PoseOf&& pose_of) const -> const Shape& {
  if (state.shapes.size() != setup.meshes.size())
    state.shapes.resize(setup.meshes.size()), state.placed_in.assign(setup.meshes.size(), 0);
  if (state.placed_in[b] != state.detection) {
    state.shapes[b].place({setup.meshes[b].get(), pose_of()});
    state.placed_in[b] = state.detection;
    ++state.counters.narrowphase_shapes;
  }
  return state.shapes[b];
}
}  // namespace gacompare::core
