#pragma once
// Islands: the bodies that may touch one another within a
// collision step, grouped so that a time-of-impact search, a shortened step
// and a contact solve involve one group and not the whole world.
//
// The report (§2.5.1, fig. 11) ends every body's step at the time of impact of
// whichever pair went too deep, and rewinds and re-integrates the whole system
// for each trial time; §4.3 notes that this "requires the entire systems state
// to be evaluated a large number of times". Bodies that cannot reach each other
// within the step cannot exchange an impulse in it, so their motions are
// independent and each group may be searched, shortened and solved alone. Two
// bodies are linked when their bounding spheres, each grown by how far the body
// can move in the step, overlap (the candidates of the broadphase), unless the
// narrowphase found them farther apart than that (core/collision/collision_step.hpp,
// unlink_far); the islands are the connected components of the moving bodies
// under those links. Static
// bodies take part in every island that touches them but never link two
// islands: an impulse on a static body moves nothing.
//
// Union–find with union by size and path halving (Tarjan 1975): O(n + k α(n))
// for n bodies and k links.
#include <algorithm>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

namespace gacompare::core {

class UnionFind {
 public:
  explicit UnionFind(std::size_t n) : parent_(n), size_(n, 1) { std::iota(parent_.begin(), parent_.end(), 0); }
  int find(int x) {
    while (parent_[x] != x) {
      parent_[x] = parent_[parent_[x]];
      x = parent_[x];
    }
    return x;
  }
  void unite(int a, int b) {
    a = find(a), b = find(b);
    if (a == b) return;
    if (size_[a] < size_[b]) std::swap(a, b);
    parent_[b] = a;
    size_[a] += size_[b];
  }

 private:
  std::vector<int> parent_, size_;
};

struct Island {
  std::vector<int> bodies;   // world indices, ascending: the moving bodies, then (ascending) the static ones
  std::size_t moving = 0;    // bodies[0, moving) move
  std::vector<std::size_t> pairs;  // indices into the candidate list whose bodies are in this island
};

// The islands of the moving bodies that take part in at least one candidate
// pair (a moving body with no candidate touches nothing this step and is left
// out), in order of their smallest body. `pairs` holds (i, j), i < j.
inline std::vector<Island> islands_of(std::size_t n, std::span<const char> is_static,
                                      std::span<const std::pair<int, int>> pairs) {
  UnionFind sets(n);
  for (const auto& [i, j] : pairs)
    if (!is_static[i] && !is_static[j]) sets.unite(i, j);
  // The moving bodies some pair names; then, walking the bodies in order, an
  // island for each root at its smallest such body, and its moving bodies
  // ascending as they come: no sort of the islands or of their moving
  // bodies (both were a share of the 10,000-body box's own thread, with
  // some 1,150 islands a step).
  std::vector<char> listed(n, 0);
  for (const auto& [i, j] : pairs) listed[i] |= !is_static[i], listed[j] |= !is_static[j];
  std::vector<int> island_of(n, -1);  // by root
  std::vector<Island> out;
  for (std::size_t b = 0; b < n; ++b) {
    if (!listed[b]) continue;
    const int root = sets.find(static_cast<int>(b));
    if (island_of[root] < 0) island_of[root] = static_cast<int>(out.size()), out.emplace_back();
    out[static_cast<std::size_t>(island_of[root])].bodies.push_back(static_cast<int>(b));
  }
  for (auto& is : out) is.moving = is.bodies.size();
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    const auto [i, j] = pairs[k];
    const int mover = is_static[i] ? j : i;
    if (is_static[mover]) continue;  // two static bodies never meet
    out[static_cast<std::size_t>(island_of[sets.find(mover)])].pairs.push_back(k);
  }
  // Then each island's static bodies, ascending.
  for (auto& is : out) {
    for (const std::size_t k : is.pairs)
      for (const int b : {pairs[k].first, pairs[k].second})
        if (is_static[b] && listed[b] != 2) listed[b] = 2, is.bodies.push_back(b);
    std::sort(is.bodies.begin() + static_cast<long>(is.moving), is.bodies.end());
    for (std::size_t k = is.moving; k < is.bodies.size(); ++k) listed[is.bodies[k]] = 0;  // a static body joins many islands
  }
  return out;
}

}  // namespace gacompare::core
