#pragma once
// The recorded motion, for people to look at and for other tools to read:
// replay.html (every backend's run side by side in 3-D, with a time slider,
// play/pause and an orbiting camera) and trajectories.csv, both from the
// samples a comparison keeps (the first repeat's: every output.every).
#include "compare/runner.hpp"

#include <cstddef>
#include <filesystem>
#include <string>
#include <vector>

namespace gacompare::compare {

// One row per sample, backend and object:
// t,backend,kind,name,x,y,z,qw,qx,qy,qz,vx,vy,vz,wx,wy,wz
// kind "body" or "particle"; a particle's orientation and angular velocity
// fields are empty. Orientation [w,x,y,z] body → world, angular velocity in the
// world frame, as in results.json. Every digit (%.17g).
std::string trajectories_csv(const SceneResult& r);

// A replay draws at most this many frames, every k-th sample and the last (a
// scene may keep up to a million samples; a browser cannot hold that many).
inline constexpr std::size_t kMaxReplayFrames = 2000;

// The sample indices a replay shows: all of them when there are at most
// `max_frames`, else every k-th (k = ⌈(n − 1) / (max_frames − 2)⌉) and the last.
std::vector<std::size_t> replay_frames(std::size_t samples, std::size_t max_frames = kMaxReplayFrames);

// Where the page's three.js comes from: Debian's libjs-three (the non-module
// build, three.min.js), read when a page is written and inlined, so the page
// works with no network. Set at configure time (GACOMPARE_THREE_JS).
std::filesystem::path three_js_path();

// replay.html: one self-contained page. Each backend gets its own view of the
// same scene from the same camera: the bodies' meshes (results.json's
// scene.bodies, placed by each sample's position and orientation), particles
// as spheres with their recorded paths, distance constraints as rods. Throws
// run_error when three.js cannot be read (scripts/install-deps.sh installs
// libjs-three). The page exposes window.replay (frames, times, views, show(k),
// pause()) for the headless-browser test and for scripting it; a URL ending in
// #t=SECONDS opens paused at that time.
std::string replay_html(const SceneResult& r);

}  // namespace gacompare::compare
