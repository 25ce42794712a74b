#pragma once
// The broadphase stage's driver: each body's pose once per detection, and
// which pairs of a group go to the narrowphase — the method the scene names
// (core/collision/broadphase.hpp) over the bounding spheres, or an island's
// known candidates, less the pairs whose moving body misses a static body's
// box. Members of the Collider (core/collision/collisions.hpp), defined here.
#include "core/collision/collisions.hpp"
#include "core/parallel.hpp"

namespace gacompare::core {

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::poses(const Model& m, std::span<const double> y, BodyIndices group) const
    -> std::vector<collision::Pose> {
  std::vector<collision::Pose> out(group.size());
  for_each_index(group.size(), [&](std::size_t k) { out[k] = Bodies::pose(m, y, k); }, kGrainBody);
  return out;
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::placed(const std::vector<collision::Pose>& pose, BodyIndices group,
                                                   int k) const -> collision::Placed {
  return {setup.meshes[group[k]].get(), pose[k]};
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::detect(State& state, const Model& m, std::span<const double> y,
                                                   BodyIndices group, std::span<const double> margin,
                                                   Profile& profile) const -> Detection {
  const std::size_t n = group.size();
  Detection d;
  std::vector<std::pair<int, int>> pairs;
  std::vector<collision::Pose> pose;
  {
    ScopedStage timed(profile, Stage::broadphase);
    pose = poses(m, y, group);
    // The method, the state it keeps and the frame the spheres are held in:
    // core/collision/broadphase.hpp. Only the world keeps its broadphase between
    // detections; another group without its candidates (detect_among) is
    // swept afresh.
    const std::vector<Vec3> centres = sphere_centres(pose, group);
    if (group.data() == setup.all_bodies.data()) state.world_centres.assign(centres.begin(), centres.end());
    std::vector<double> radii(n);
    std::vector<char> fixed(n);
    for (std::size_t k = 0; k < n; ++k) {
      radii[k] = setup.sphere_radius[group[k]];
      // A sleeping body is held like a static one (core/collision/sleep.hpp).
      fixed[k] = setup.is_static[group[k]] || state.sleep.is_asleep(static_cast<std::size_t>(group[k]));
    }
    BroadphaseResult found = group.data() == setup.all_bodies.data()
                                 ? state.broadphase.find(centres, radii, fixed, margin)
                                 : Broadphase<Spheres>(BroadphaseMethod::sweep).find(centres, radii, fixed, margin);
    pairs = std::move(found.pairs);
    d.candidates = std::move(found.candidates);
    // Each pair's test on the run's threads (core/parallel.hpp), and the
    // pairs left gathered in order there too.
    const auto drop_away = [&](std::vector<std::pair<int, int>>& list, std::span<const double> grow) {
      std::vector<char> away(list.size());
      for_each_index(
          list.size(), [&](std::size_t k) { away[k] = misses_static(pose, group, centres, list[k], grow); }, kGrainLight);
      erase_flagged(list, away, kGrainLight);
    };
    drop_away(pairs, {});
    drop_away(d.candidates, margin);
    state.counters.broadphase_candidates += static_cast<std::uint64_t>(found.counters.candidates);
    state.counters.broadphase_tree_updates += static_cast<std::uint64_t>(found.counters.tree_updates);
    state.counters.broadphase_pairs_kept += static_cast<std::uint64_t>(found.counters.pairs_kept);
  }
  narrow(state, group, pose, pairs, d, profile, margin);
  return d;
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::detect_among(State& state, const Model& m, std::span<const double> y,
                                                         BodyIndices group,
                                                         std::span<const std::pair<int, int>> candidates,
                                                         Profile& profile, std::size_t grain) const -> Detection {
  const std::size_t n = group.size();
  Detection d;
  std::vector<std::pair<int, int>> pairs;
  // Only the bodies the candidates name are posed: a push-out pass names a
  // few hundred bodies of an island of thousands, and posing them all at
  // every pass was a measurable share of the 10,000-body box's own thread.
  // The other entries of `pose` and `centres` are stale and never read.
  std::vector<collision::Pose>& pose = state.among_pose;
  std::vector<Vec3>& centres = state.among_centres;
  {
    ScopedStage timed(profile, Stage::broadphase);
    std::vector<char> named(n, 0);
    for (const auto& [i, j] : candidates) named[static_cast<std::size_t>(i)] = named[static_cast<std::size_t>(j)] = 1;
    std::vector<int> bodies;
    for (std::size_t k = 0; k < n; ++k)
      if (named[k]) bodies.push_back(static_cast<int>(k));
    // Grown only: a push-out's island of thousands after a small island's
    // detection default-constructed all its poses again.
    if (pose.size() < n) pose.resize(n), centres.resize(n);
    for_each_index(
        bodies.size(),
        [&](std::size_t u) {
          const auto k = static_cast<std::size_t>(bodies[u]);
          pose[k] = Bodies::pose(m, y, k);
          centres[k] = pose[k].apply(setup.sphere_centre[group[k]]);
        },
        kGrainLight);
    // The spheres in a frame at the named bodies' mean centre (summed in body order).
    Vec3 frame = Vec3::Zero();
    for (const int k : bodies) frame += centres[static_cast<std::size_t>(k)];
    if (!bodies.empty()) frame /= static_cast<double>(bodies.size());
    for (const auto& p : candidates) {
      const auto [i, j] = p;
      ++state.counters.broadphase_candidates;
      if (setup.is_static[group[i]] && setup.is_static[group[j]]) continue;
      const double ri = setup.sphere_radius[group[i]], rj = setup.sphere_radius[group[j]];
      if (!Spheres::balls_overlap(Spheres::sphere(centres[static_cast<std::size_t>(i)] - frame, ri), ri,
                                  Spheres::sphere(centres[static_cast<std::size_t>(j)] - frame, rj), rj))
        continue;
      if (misses_static(pose, group, centres, p, {})) continue;
      pairs.emplace_back(i, j);
    }
  }
  narrow(state, group, pose, pairs, d, profile, {}, grain);
  return d;
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::misses_static(const std::vector<collision::Pose>& pose, BodyIndices group,
                                                          const std::vector<Vec3>& centres,
                                                          const std::pair<int, int>& p,
                                                          std::span<const double> grow) const -> bool {
  const auto [i, j] = p;
  const bool si = setup.is_static[group[i]];
  if (si == static_cast<bool>(setup.is_static[group[j]])) return false;
  const int s = si ? i : j, o = si ? j : i;
  const double r = setup.sphere_radius[group[o]] + (grow.empty() ? 0.0 : grow[o]);
  return !reaches_static(pose[s], group[s], centres[o], r);
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::sphere_centres(const std::vector<collision::Pose>& pose,
                                                           BodyIndices group) const -> std::vector<Vec3> {
  std::vector<Vec3> c(group.size());
  for_each_index(group.size(), [&](std::size_t k) { c[k] = pose[k].apply(setup.sphere_centre[group[k]]); }, kGrainBody);
  return c;
}

template <RigidBodies Bodies, class NarrowBody, SphereTreeOps Spheres>
requires collision::NarrowphaseBody<NarrowBody>
auto Collider<Bodies, NarrowBody, Spheres>::reaches_static(const collision::Pose& pose, int s, const Vec3& c,
                                                           double r) const -> bool {
  const Vec3 q = pose.rotation.transpose() * (c - pose.position) - setup.static_mid[s];
  const Vec3 h = setup.static_half[s];
  const Vec3 out = (q.cwiseAbs() - h).cwiseMax(0.0);
  const double pad = collision::kTouchingBand * (r + h.norm()) + 1e-14 * (c - pose.position).norm();
  return out.squaredNorm() <= (r + pad) * (r + pad);
}
}  // namespace gacompare::core
