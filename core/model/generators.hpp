#pragma once
// Generators (§2.1.2, fig. 4): scene entries that stand for many particles and the
// distance constraints between them, expanded once before a backend builds.
#include "core/model/scene.hpp"

namespace gacompare::core {

// The scene with every generator replaced by its particles and constraints:
//  particle_net   name[r][c] at origin + (c, r, 0)·spacing, a horizontal grid; a
//                 distance constraint of length `spacing` to the right and the
//                 next row's neighbour (the hanging net of fig. 4 once pinned)
//  particle_chain name[i] at origin + i·spacing·direction/|direction|, linked in order
// Generated particles start at rest. Generated particles come after the scene's own,
// generated constraints before the scene's own (which may refer to them).
Scene expand_generators(const Scene& scene);

}  // namespace gacompare::core
