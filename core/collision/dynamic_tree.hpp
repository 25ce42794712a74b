#pragma once
// A dynamic bounding-volume tree, written once over a volume
// policy so that the AABB tree and the report's sphere trees (§4.2.2, fig. 13)
// in either algebra are the same code and differ only in V:
//   V::Volume            what a node holds (core::Aabb, or a backend's sphere)
//   V::merge(a, b)       a volume enclosing both (the box union; the smallest
//                        enclosing sphere, traditional or conformal)
//   V::cost(a)           the surface-area measure the tree minimises (half
//                        the box's area; ρ², which the conformal sphere gives
//                        as S² directly)
//   V::overlap(a, b)     whether two volumes share a point (touching counts)
//
// The models are Box2D v3's b2DynamicTree and Bullet's btDbvt; the insertion
// cost and the rotations follow the published algorithms, written afresh:
//   - insertion picks a sibling by the cost it adds to the tree (the
//     surface-area heuristic: a node's cost is the chance that a query
//     volume meets it). A node's children can only cost more than the
//     node's own "inherited" cost (the growth of every ancestor) plus the
//     new leaf's: for spheres that bound prunes a search of the whole tree
//     for the least-cost sibling (branch and bound: Bittner, Hapala and
//     Havran 2013, "Fast insertion-based optimization of bounding volume
//     hierarchies"); for boxes it steers a descent along one path, as
//     Box2D v3 does (best_sibling says why);
//   - every node on the way up from an insertion is refitted and then
//     offered a rotation (after a removal, refitted only, as Box2D v3 does:
//     the reinsertion that follows rotates): one of its children swapped with a grandchild
//     on the other side, kept when it lowers the cost of the two nodes it
//     changes (Kopta et al. 2012, "Fast, effective BVH updates for animated
//     scenes"; Box2D v3's b2RotateNodes). This keeps the tree shallow without
//     AVL balancing. Unlike a box, a parent sphere depends on how its leaves
//     are grouped, so the gain counts the parent's change too (a policy whose
//     merge is grouping-free, the box union, says so and skips it).
// A leaf is never moved in place: the caller removes it and inserts it again
// (core/collision/tree_broadphase.hpp does so only when a body leaves its fat volume).
//
// Nodes live in one vector with a free list, so inserting and removing
// allocate nothing once the tree has grown to its size.
#include <algorithm>
#include <concepts>
#include <cstdint>
#include <span>
#include <string>
#include <utility>
#include <vector>

namespace gacompare::core {

template <class V>
concept TreeVolume = requires(const typename V::Volume& a) {
  { V::merge(a, a) } -> std::convertible_to<typename V::Volume>;
  { V::cost(a) } -> std::convertible_to<double>;
  { V::overlap(a, a) } -> std::convertible_to<bool>;
};

template <TreeVolume V>
class DynamicTree {
 public:
  using Volume = typename V::Volume;
  static constexpr int kNull = -1;
  // A parent that does not depend on how its leaves are grouped (the box
  // union) needs no re-evaluation in a rotation: V::grouping_free.
  static constexpr bool kGroupingFree = requires { requires V::grouping_free; };
  struct Node {
    Volume volume{};
    int parent = kNull, child1 = kNull, child2 = kNull;
    int height = 0;  // a leaf 0, a parent 1 + its taller child's, a free node −1
    int item = -1;   // a leaf's index in the caller's list
    bool leaf() const { return child1 == kNull; }
  };

  // Adds a leaf for `item` with volume v; returns its node (stable until removed).
  int insert(const Volume& v, int item) {
    const int leaf = allocate();
    nodes_[leaf] = Node{v, kNull, kNull, kNull, 0, item};
    ++leaves_;
    if (root_ == kNull) {
      root_ = leaf;
      return leaf;
    }
    const int sibling = best_sibling(v);
    const int above = nodes_[sibling].parent;
    const int parent = allocate();
    nodes_[parent] = Node{V::merge(nodes_[sibling].volume, v), above, sibling, leaf, nodes_[sibling].height + 1, -1};
    nodes_[sibling].parent = parent;
    nodes_[leaf].parent = parent;
    if (above == kNull) root_ = parent;
    else replace_child(above, sibling, parent);
    walk_up(parent);
    return leaf;
  }

  void remove(int leaf) {
    --leaves_;
    const int parent = nodes_[leaf].parent;
    release(leaf);
    if (parent == kNull) {
      root_ = kNull;
      return;
    }
    const int sibling = nodes_[parent].child1 == leaf ? nodes_[parent].child2 : nodes_[parent].child1;
    const int above = nodes_[parent].parent;
    nodes_[sibling].parent = above;
    release(parent);
    if (above == kNull) {
      root_ = sibling;
      return;
    }
    replace_child(above, parent, sibling);
    for (int i = above; i != kNull; i = at(i).parent) refit(i);
  }

  // Calls on_leaf(item) for every leaf whose volume overlaps q. Every node
  // volume tested is counted (volume_tests).
  template <class F>
  void query(const Volume& q, F&& on_leaf) const {
    tests_ += query(q, stack_, on_leaf);
  }
  // The same with the caller's stack, counting nothing in the tree: it reads
  // the tree only, so queries on several threads may run at once (each with
  // its own stack). Returns the volumes tested.
  template <class F>
  std::int64_t query(const Volume& q, std::vector<int>& stack, F&& on_leaf) const {
    if (root_ == kNull) return 0;
    std::int64_t tests = 0;
    stack.clear();
    stack.push_back(root_);
    while (!stack.empty()) {
      const Node& node = nodes_[static_cast<std::size_t>(stack.back())];
      stack.pop_back();
      ++tests;
      if (!V::overlap(node.volume, q)) continue;
      if (node.leaf()) {
        on_leaf(node.item);
      } else {
        stack.push_back(node.child1);
        stack.push_back(node.child2);
      }
    }
    return tests;
  }
  // Adds volume tests counted by the caller (queries with their own stacks).
  void count_volume_tests(std::int64_t tests) const { tests_ += tests; }

  void clear() {
    nodes_.clear();
    root_ = free_ = kNull;
    leaves_ = 0;
  }
  const Volume& volume(int node) const { return nodes_[static_cast<std::size_t>(node)].volume; }
  int leaves() const { return leaves_; }
  int height() const { return root_ == kNull ? 0 : nodes_[static_cast<std::size_t>(root_)].height; }
  int root() const { return root_; }
  std::span<const Node> nodes() const { return nodes_; }
  // Volume tests made by queries since the last call (the broadphase's counter).
  std::int64_t take_volume_tests() const { return std::exchange(tests_, 0); }

  // The structure's invariants, for the tests: links both ways, heights, the
  // number of leaves. Empty when all hold, else what is wrong first.
  std::string check() const {
    if (root_ == kNull) return leaves_ == 0 ? "" : "no root but leaves";
    if (nodes_[static_cast<std::size_t>(root_)].parent != kNull) return "the root has a parent";
    int leaves = 0;
    std::vector<int> todo{root_};
    while (!todo.empty()) {
      const int i = todo.back();
      todo.pop_back();
      const Node& n = nodes_[static_cast<std::size_t>(i)];
      if (n.leaf()) {
        if (n.child2 != kNull || n.height != 0) return "leaf " + std::to_string(i) + " malformed";
        ++leaves;
        continue;
      }
      for (const int c : {n.child1, n.child2})
        if (nodes_[static_cast<std::size_t>(c)].parent != i) return "node " + std::to_string(c) + ": wrong parent";
      const int h = 1 + std::max(nodes_[static_cast<std::size_t>(n.child1)].height,
                                 nodes_[static_cast<std::size_t>(n.child2)].height);
      if (n.height != h) return "node " + std::to_string(i) + ": wrong height";
      todo.push_back(n.child1);
      todo.push_back(n.child2);
    }
    return leaves == leaves_ ? "" : "leaf count " + std::to_string(leaves) + " != " + std::to_string(leaves_);
  }

 private:
  std::vector<Node> nodes_;
  int root_ = kNull, free_ = kNull, leaves_ = 0;
  mutable std::vector<int> stack_;  // query's, kept to allocate once
  mutable std::int64_t tests_ = 0;
  struct Candidate {
    double inherited;  // the growth of every ancestor, were the leaf put below them
    int node;
  };
  std::vector<Candidate> heap_;  // least_cost_sibling's, kept to allocate once

  Node& at(int i) { return nodes_[static_cast<std::size_t>(i)]; }
  int allocate() {
    if (free_ == kNull) {
      nodes_.emplace_back();
      return static_cast<int>(nodes_.size()) - 1;
    }
    const int i = free_;
    free_ = at(i).parent;  // the free list is threaded through `parent`
    return i;
  }
  void release(int i) {
    Node& n = at(i);
    n.child1 = n.child2 = kNull;
    n.height = -1;  // free
    n.item = -1;
    n.parent = free_;
    free_ = i;
  }
  void replace_child(int parent, int old_child, int new_child) {
    Node& p = at(parent);
    (p.child1 == old_child ? p.child1 : p.child2) = new_child;
  }
  void refit(int i) {
    Node& n = at(i);
    n.volume = V::merge(at(n.child1).volume, at(n.child2).volume);
    n.height = 1 + std::max(at(n.child1).height, at(n.child2).height);
  }
  void walk_up(int from) {  // after an insertion
    for (int i = from; i != kNull; i = at(i).parent) {
      refit(i);
      rotate(i);
    }
  }

  // Where a new leaf v goes. Boxes: one path down (descended_sibling). The
  // full search (least_cost_sibling) opened much of a pile's tree at each
  // reinsertion in the 10,000-body box, whose boxes overlap many others, and
  // the descent builds trees that queries read as cheaply (the tests' random
  // edits: 41 node tests per query against 40.5). Spheres keep the full
  // search: a parent sphere depends on how its leaves are grouped, and the
  // descent's bound misled it (the same edits' queries tested half of all
  // leaves, and the height passed 30 for 4,096 random leaves).
  int best_sibling(const Volume& v) {
    if constexpr (kGroupingFree) return descended_sibling(v);
    else return least_cost_sibling(v);
  }

  // The sibling for a new leaf v, by a descent from the root along one path
  // (Box2D v3's insertion, written afresh), for boxes. A node's cost as v's sibling is
  // V::cost(merge(node, v)), the new parent's, plus what v adds to every
  // ancestor ("inherited"). At each node both children are priced as
  // siblings, and the descent goes into the child whose subtree could cost
  // least: its inherited cost plus its own growth plus V::cost(v), a bound
  // no node below it can beat (any parent of v is at least v). It stops
  // when neither child's bound is below the best found. Where both bounds
  // are equal (v inside both children) it takes the smaller child.
  int descended_sibling(const Volume& v) {
    const double leaf_cost = V::cost(v);
    int best = root_;
    double best_cost = V::cost(V::merge(at(root_).volume, v));
    double inherited = 0, direct = best_cost;  // for the node the descent is at
    for (int node = root_; !at(node).leaf();) {
      const Node& n = at(node);
      inherited += direct - V::cost(n.volume);  // what v adds to n, passed on to its children
      int next = kNull;
      double next_bound = 0, next_direct = 0, next_size = 0;
      for (const int child : {n.child1, n.child2}) {
        const Node& c = at(child);
        const double d = V::cost(V::merge(c.volume, v));
        if (d + inherited < best_cost) best_cost = d + inherited, best = child;
        if (c.leaf()) continue;
        const double size = V::cost(c.volume), bound = inherited + d - size + leaf_cost;
        if (next == kNull || bound < next_bound || (bound == next_bound && size < next_size))
          next = child, next_bound = bound, next_direct = d, next_size = size;
      }
      if (next == kNull || next_bound >= best_cost) break;
      node = next, direct = next_direct;
    }
    return best;
  }

  // The sibling whose choice adds the least cost anywhere in the tree, by
  // branch and bound (Bittner et al. 2013): the new parent's cost
  // V::cost(merge(sibling, v)) plus the growth of every ancestor. Children of
  // a node inherit its growth; their subtree costs at least that plus
  // V::cost(v) (any parent of v is at least v), which is the bound.
  int least_cost_sibling(const Volume& v) {
    const double leaf_cost = V::cost(v);
    int best = root_;
    double best_cost = V::cost(V::merge(at(root_).volume, v));
    const auto later = [](const Candidate& a, const Candidate& b) { return a.inherited > b.inherited; };
    heap_.clear();
    heap_.push_back({0.0, root_});
    while (!heap_.empty()) {
      std::pop_heap(heap_.begin(), heap_.end(), later);
      const Candidate c = heap_.back();
      heap_.pop_back();
      if (c.inherited + leaf_cost >= best_cost) break;  // the cheapest left cannot win
      const Node& n = at(c.node);
      const double direct = V::cost(V::merge(n.volume, v));
      if (direct + c.inherited < best_cost) best_cost = direct + c.inherited, best = c.node;
      if (n.leaf()) continue;
      const double inherited = c.inherited + direct - V::cost(n.volume);
      if (inherited + leaf_cost >= best_cost) continue;
      for (const int child : {n.child1, n.child2}) {
        heap_.push_back({inherited, child});
        std::push_heap(heap_.begin(), heap_.end(), later);
      }
    }
    return best;
  }

  // At node a (children b, c): swap b with a child of c, or c with a child of
  // b, if that lowers cost(the changed child) + cost(a) the most.
  void rotate(int a) {
    if (at(a).height < 2) return;
    const int b = at(a).child1, c = at(a).child2;
    const double before = kGroupingFree ? 0.0 : V::cost(at(a).volume);
    double best_gain = 0;
    int move = kNull, nephew = kNull;
    const auto consider = [&](int child, int other) {
      const Node& o = at(other);
      if (o.leaf()) return;
      for (const auto& [up, kept] : {std::pair{o.child1, o.child2}, std::pair{o.child2, o.child1}}) {
        const Volume lowered = V::merge(at(child).volume, at(kept).volume);
        double gain = V::cost(lowered) - V::cost(o.volume);
        if constexpr (!kGroupingFree) gain += V::cost(V::merge(at(up).volume, lowered)) - before;
        if (gain < best_gain) best_gain = gain, move = child, nephew = up;
      }
    };
    consider(b, c);
    consider(c, b);
    if (move == kNull) return;
    const int other = at(nephew).parent;
    replace_child(a, move, nephew);
    replace_child(other, nephew, move);
    at(nephew).parent = a;
    at(move).parent = other;
    refit(other);
    refit(a);
  }
};

}  // namespace gacompare::core
