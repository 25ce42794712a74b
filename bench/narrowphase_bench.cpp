// Narrowphase per pair and per stage: the report's detector and the
// separating-axis fast path in both backends, the exact reference, FCL and
// Bullet, on the same pairs; and the per-feature stages (point in body,
// segment–triangle). Benchmarks are named BM_<op>/<impl> for
// scripts/bench-ratios.py; every item is one pair (or one feature test).
//
//   python3 scripts/bench-ratios.py build/release/bench/narrowphase_bench --reference traditional
//
// The pairs: the overlapping and the separated pairs of data/collision/random.json
// that no library refuses, cycled through in a fixed order.
#include "cga/narrowphase.hpp"
#include "cga/segment_triangle.hpp"
#include "compare/referee.hpp"
#include "answers/collision_cases.hpp"
#include "core/error.hpp"
#include "core/collision/kept_contacts.hpp"
#include "core/collision/separating_axis.hpp"
#include "traditional/narrowphase.hpp"
#include "traditional/segment_triangle.hpp"

#include <benchmark/benchmark.h>

#include <Eigen/Geometry>

#include <array>
#include <random>
#include <string>
#include <utility>
#include <tuple>
#include <vector>

namespace {

using namespace gacompare;

struct Corpus {
  std::vector<collision::CollisionCase> cases;
  std::vector<compare::FclShape> fcl_a, fcl_b;
  std::vector<compare::BulletShape> bullet_a, bullet_b;
};

const Corpus& corpus() {
  static const Corpus c = [] {
    Corpus c;
    for (auto& k : collision::load_cases(std::string(GACOMPARE_DATA_DIR) + "/collision/random.json")) {
      compare::BulletShape ba(*k.mesh_a), bb(*k.mesh_b);
      try {
        compare::bullet_collide(ba, k.pose_a, bb, k.pose_b);
      } catch (const Error&) {
        continue;  // Bullet gives no valid answer on this pair: leave it out for every method
      }
      c.fcl_a.emplace_back(*k.mesh_a);
      c.fcl_b.emplace_back(*k.mesh_b);
      c.bullet_a.push_back(ba);
      c.bullet_b.push_back(bb);
      c.cases.push_back(std::move(k));
    }
    return c;
  }();
  return c;
}

template <class F>
void per_pair(benchmark::State& st, F&& f) {
  const Corpus& c = corpus();
  std::size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(f(c, i));
    if (++i == c.cases.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}

// The contacts of a pair in contact: fig. 7's detector against
// the manifold, each with its separating-axis test, on the overlapping pairs
// of the corpus; and the manifold on the degenerate box pairs the simulation
// meets most (equal cubes face to face: aligned, 1e-9 rad and 45° about the
// normal, offset 1e-3 sideways), where fig. 7 is wrong and so not timed.
const std::vector<std::size_t>& overlapping() {
  static const std::vector<std::size_t> ids = [] {
    std::vector<std::size_t> out;
    const Corpus& c = corpus();
    for (std::size_t i = 0; i < c.cases.size(); ++i)
      if (collision::sat_reference(c.cases[i].a(), c.cases[i].b()).depth > 0) out.push_back(i);
    return out;
  }();
  return ids;
}
template <class Backend>
void contacts(benchmark::State& st, collision::Method method) {
  const Corpus& c = corpus();
  const auto& ids = overlapping();
  std::vector<collision::FeatureContact> found;
  std::size_t i = 0;
  for (auto _ : st) {
    found.clear();
    benchmark::DoNotOptimize(Backend::narrowphase(c.cases[ids[i]].a(), c.cases[ids[i]].b(), method, &found));
    if (++i == ids.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}
// Two cubes resting face to face 1e-5 deep: turned about the normal by 0,
// 1e-9 rad and 45°, offset sideways by 0 and 2e-4 m.
std::vector<std::pair<collision::Placed, collision::Placed>> resting_boxes() {
  static const core::Mesh cube = core::make_box({0.2, 0.2, 0.2});
  std::vector<std::pair<collision::Placed, collision::Placed>> pairs;
  for (const double turn : {0.0, 1e-9, 0.7853981633974483})
    for (const double offset : {0.0, 2e-4}) {
      const Eigen::Matrix3d r = Eigen::AngleAxisd(turn, Eigen::Vector3d::UnitX()).toRotationMatrix();
      pairs.push_back({{&cube, {}}, {&cube, {r, Eigen::Vector3d(0.2 - 1e-5, offset, 0)}}});
    }
  return pairs;
}
template <class Backend>
void manifold_boxes(benchmark::State& st) {
  const auto pairs = resting_boxes();
  std::vector<collision::FeatureContact> found;
  std::size_t i = 0;
  for (auto _ : st) {
    found.clear();
    benchmark::DoNotOptimize(Backend::narrowphase(pairs[i].first, pairs[i].second, collision::Method::manifold, &found));
    if (++i == pairs.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}

// The same resting pairs as a simulation meets them: the whole test on
// shapes placed once (shared by a body's pairs, core/collision/shape.hpp),
// and the kept contacts measured again instead (core/collision/kept_contacts.hpp;
// the refresh is plain vector algebra, the same in every backend).
template <class Body>
void manifold_boxes_shared(benchmark::State& st) {
  std::vector<std::pair<typename Body::Shape, typename Body::Shape>> shapes;
  for (const auto& [a, b] : resting_boxes()) shapes.emplace_back(typename Body::Shape(a), typename Body::Shape(b));
  std::vector<collision::FeatureContact> found;
  std::size_t i = 0;
  for (auto _ : st) {
    found.clear();
    benchmark::DoNotOptimize(
        collision::narrowphase<Body>(shapes[i].first, shapes[i].second, collision::Method::sat_then_manifold, &found));
    if (++i == shapes.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}
void kept_boxes(benchmark::State& st) {
  using Body = traditional::Body;
  const auto pairs = resting_boxes();
  std::vector<collision::KeptContacts> kept(pairs.size());
  for (std::size_t k = 0; k < pairs.size(); ++k) {
    std::vector<collision::FeatureContact> found;
    collision::SatHint hint;
    collision::FaceChoice choice;
    const Body::Shape a(pairs[k].first), b(pairs[k].second);
    const auto sat = collision::narrowphase<Body>(a, b, collision::Method::sat_then_manifold, &found, &hint, &choice);
    if (!collision::keep(kept[k], *pairs[k].first.mesh, *pairs[k].second.mesh, pairs[k].first.pose,
                         pairs[k].second.pose, sat, hint, choice, found)) {
      st.SkipWithError("a resting pair was not kept");
      return;
    }
  }
  const double band = collision::kTouchingBand * pairs[0].first.mesh->size();
  std::vector<collision::FeatureContact> found;
  collision::PairContact sat;
  std::size_t i = 0;
  for (auto _ : st) {
    found.clear();
    const auto& [a, b] = pairs[i];
    benchmark::DoNotOptimize(collision::refresh(kept[i], *a.mesh, *b.mesh, a.pose, b.pose, band, sat, found));
    if (++i == pairs.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}

template <class Backend>
collision::PairContact report(const Corpus& c, std::size_t i) {
  static thread_local std::vector<collision::FeatureContact> contacts;
  contacts.clear();
  return Backend::narrowphase(c.cases[i].a(), c.cases[i].b(), collision::Method::report, &contacts);
}

struct Trad {
  static auto narrowphase(const collision::Placed& a, const collision::Placed& b, collision::Method m,
                          std::vector<collision::FeatureContact>* out) {
    return traditional::narrowphase(a, b, m, out);
  }
};
struct Cga {
  static auto narrowphase(const collision::Placed& a, const collision::Placed& b, collision::Method m,
                          std::vector<collision::FeatureContact>* out) {
    return cga::narrowphase(a, b, m, out);
  }
};

// Feature tests on seeded random inputs, cycled.
struct Segments {
  std::vector<std::array<Eigen::Vector3d, 5>> s;
  Segments() {
    std::mt19937_64 rng(3);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < 1024; ++i) {
      std::array<Eigen::Vector3d, 5> x;
      for (auto& p : x) p = {u(rng), u(rng), u(rng)};
      s.push_back(x);
    }
  }
};
const Segments& segments() {
  static const Segments s;
  return s;
}

// ---- a pair as the simulation meets it (sat_then_manifold) ----
//
// The corpus's pairs split into apart and overlapping (the reference's yes/no);
// each item is one pair:
//   pair_rebuilt: narrowphase on two Placed bodies, their geometry built for
//     the pair alone (new storage each time);
//   pair_placed: both Shapes placed afresh in storage kept between items, no
//     axis remembered (a pair's first detection; `gacompare collide`'s
//     *_manifold columns);
//   pair_cached: the Shapes built once, outside the loop: what a pair costs
//     when its bodies' geometry is shared with other pairs;
//   pair_moving, pair_coherent: every pair's two bodies turning and sliding a
//     little each step (0.2 mrad and 0.1 % of their size), their Shapes placed
//     again each step; without and with the axis remembered from the pair's
//     last step (temporal coherence).
const std::vector<std::size_t>& pairs_of(bool overlapping) {
  static const std::array<std::vector<std::size_t>, 2> ids = [] {
    std::array<std::vector<std::size_t>, 2> out;
    const Corpus& c = corpus();
    for (std::size_t i = 0; i < c.cases.size(); ++i)
      out[collision::sat_reference(c.cases[i].a(), c.cases[i].b()).depth > 0].push_back(i);
    return out;
  }();
  return ids[overlapping];
}
// One item per pair, cycling through the apart or the overlapping ones;
// query(i, pair, found) asks the i-th of them.
template <class Query>
void cycle_pairs(benchmark::State& st, bool overlapping, Query&& query) {
  const auto& ids = pairs_of(overlapping);
  std::vector<collision::FeatureContact> found;
  std::size_t i = 0;
  for (auto _ : st) {
    found.clear();
    benchmark::DoNotOptimize(query(i, corpus().cases[ids[i]], found));
    if (++i == ids.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}
constexpr auto kSimulated = collision::Method::sat_then_manifold;
template <class Body>
void pair_rebuilt(benchmark::State& st, bool overlapping) {
  cycle_pairs(st, overlapping, [](std::size_t, const collision::CollisionCase& k, auto& found) {
    return collision::narrowphase<Body>(k.a(), k.b(), kSimulated, &found);
  });
}
template <class Body>
void pair_placed(benchmark::State& st, bool overlapping) {
  typename Body::Shape a, b;
  cycle_pairs(st, overlapping, [&](std::size_t, const collision::CollisionCase& k, auto& found) {
    a.reset(), b.reset();
    a.place(k.a()), b.place(k.b());
    return collision::narrowphase<Body>(a, b, kSimulated, &found);
  });
}
template <class Body>
void pair_cached(benchmark::State& st, bool overlapping) {
  std::vector<std::pair<typename Body::Shape, typename Body::Shape>> shapes;
  for (const std::size_t id : pairs_of(overlapping)) shapes.emplace_back(corpus().cases[id].a(), corpus().cases[id].b());
  cycle_pairs(st, overlapping, [&](std::size_t i, const collision::CollisionCase&, auto& found) {
    return collision::narrowphase<Body>(shapes[i].first, shapes[i].second, kSimulated, &found);
  });
}
template <class Body>
void pair_moving(benchmark::State& st, bool overlapping, bool coherent) {
  struct Moving {
    typename Body::Shape a, b;
    collision::SatHint hint;
  };
  std::vector<Moving> pairs(pairs_of(overlapping).size());
  std::array<Eigen::Matrix3d, 17> turn;  // by 0 … 16 × 0.2 mrad
  for (int q = 0; q < 17; ++q)
    turn[q] = Eigen::AngleAxisd(2e-4 * q, Eigen::Vector3d(1, 2, 3).normalized()).toRotationMatrix();
  long step = 0;
  cycle_pairs(st, overlapping, [&](std::size_t i, const collision::CollisionCase& k, auto& found) {
    // Step `step` of a back-and-forth motion: 16 steps one way, 16 back.
    const int s = static_cast<int>(step % 32), phase = s < 16 ? s : 32 - s;
    collision::Placed a = k.a(), b = k.b();
    a.pose.rotation = turn[phase] * a.pose.rotation;
    b.pose.position += (1e-3 * phase / 16) * k.mesh_b->size() * Eigen::Vector3d(0.6, 0.0, 0.8);
    pairs[i].a.place(a), pairs[i].b.place(b);
    if (i + 1 == pairs.size()) ++step;
    return collision::narrowphase<Body>(pairs[i].a, pairs[i].b, kSimulated, &found, coherent ? &pairs[i].hint : nullptr);
  });
}
void register_pairs() {
  for (const bool overlapping : {false, true}) {
    const std::string kind = overlapping ? "overlapping" : "apart";
    const auto add = [&](const std::string& what, auto trad, auto cga) {
      benchmark::RegisterBenchmark(("BM_pair_" + kind + "_" + what + "/traditional").c_str(), trad);
      benchmark::RegisterBenchmark(("BM_pair_" + kind + "_" + what + "/cga").c_str(), cga);
    };
    add("rebuilt", [=](benchmark::State& st) { pair_rebuilt<traditional::Body>(st, overlapping); },
        [=](benchmark::State& st) { pair_rebuilt<cga::Body>(st, overlapping); });
    add("placed", [=](benchmark::State& st) { pair_placed<traditional::Body>(st, overlapping); },
        [=](benchmark::State& st) { pair_placed<cga::Body>(st, overlapping); });
    add("cached", [=](benchmark::State& st) { pair_cached<traditional::Body>(st, overlapping); },
        [=](benchmark::State& st) { pair_cached<cga::Body>(st, overlapping); });
    add("moving", [=](benchmark::State& st) { pair_moving<traditional::Body>(st, overlapping, false); },
        [=](benchmark::State& st) { pair_moving<cga::Body>(st, overlapping, false); });
    add("coherent", [=](benchmark::State& st) { pair_moving<traditional::Body>(st, overlapping, true); },
        [=](benchmark::State& st) { pair_moving<cga::Body>(st, overlapping, true); });
  }
}

// Support points (core/collision/shape.hpp): every face of one hull of n vertices
// against another's vertices, by the scan and by hill climbing from the last
// face's support, as the face query runs them; one item = one face. The hulls:
// n random points on a sphere (every one a vertex), the second turned at random.
template <class Body>
void support(benchmark::State& st, int n, bool climb) {
  std::mt19937_64 rng(static_cast<std::uint64_t>(n));
  std::normal_distribution<double> g;
  const auto hull = [&] {
    std::vector<Eigen::Vector3d> p;
    for (int i = 0; i < n; ++i) p.push_back(Eigen::Vector3d(g(rng), g(rng), g(rng)).normalized());
    return core::convex_hull(p);
  };
  const core::Mesh ma = hull(), mb = hull();
  const Eigen::Matrix3d turn = Eigen::Quaterniond(g(rng), g(rng), g(rng), g(rng)).normalized().toRotationMatrix();
  const typename Body::Shape a({&ma, {}}), b({&mb, {turn, Eigen::Vector3d(1.5, 0, 0)}});
  const Body va(a, a.position()), vb(b, b.position());
  const int planes = static_cast<int>(ma.planes().size());
  std::vector<typename Body::Plane> toward;
  for (int k = 0; k < planes; ++k) toward.push_back(va.plane_toward(k, vb));
  int k = 0, arg = 0;
  for (auto _ : st) {
    const auto found = climb ? b.climb(toward[k], arg) : b.scan(toward[k]);
    benchmark::DoNotOptimize(found);
    arg = found.second;
    if (++k == planes) k = 0;
  }
  st.SetItemsProcessed(st.iterations());
  st.counters["vertices"] = static_cast<double>(mb.vertices().size());
}
void register_supports() {
  for (const int n : {8, 12, 16, 24, 32, 48, 64, 128, 256})
    for (const bool climb : {false, true}) {
      const std::string op = "BM_support_" + std::to_string(n) + "/", how = climb ? "_climb" : "_scan";
      benchmark::RegisterBenchmark((op + "traditional" + how).c_str(),
                                   [=](benchmark::State& st) { support<traditional::Body>(st, n, climb); });
      benchmark::RegisterBenchmark((op + "cga" + how).c_str(), [=](benchmark::State& st) { support<cga::Body>(st, n, climb); });
    }
}

template <class Body>
void point_in_body(benchmark::State& st) {
  // A 64-vertex-ish hull against the vertices of another: one vertex per item.
  const auto& k = corpus().cases.front();
  const typename Body::Shape sa(k.a()), sb(k.b());
  const Body a(sa, sa.position()), b(sb, sb.position());
  const int n = static_cast<int>(k.mesh_b->vertices().size());
  int j = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(collision::detail::least_deep_face(a, b, j));
    if (++j == n) j = 0;
  }
  st.SetItemsProcessed(st.iterations());
}

template <class Prepared>
void prepared_segments(benchmark::State& st) {
  const auto& s = segments().s;
  std::vector<Prepared> tris;
  for (const auto& x : s) tris.emplace_back(x[2], x[3], x[4]);
  std::size_t i = 0;
  for (auto _ : st) {
    benchmark::DoNotOptimize(tris[i].through(s[i][0], s[i][1]));
    if (++i == s.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}

// Round pairs (core/collision/round.hpp, core/collision/capsule.hpp): the pairs of a
// round corpus (data/collision/round.json, capsule.json) of one kind, each
// body's shape placed once (as the simulation's cached shapes are), so an
// item is the pair's mathematics alone: sat_then_manifold with its contacts.
enum class RoundPair { sphere_sphere, sphere_polyhedron, capsule_sphere, capsule_capsule, capsule_polyhedron };

RoundPair kind_of(const core::Mesh& a, const core::Mesh& b) {
  const int capsules = a.is_capsule() + b.is_capsule(), spheres = a.is_sphere() + b.is_sphere();
  if (capsules == 2) return RoundPair::capsule_capsule;
  if (capsules == 1) return spheres == 1 ? RoundPair::capsule_sphere : RoundPair::capsule_polyhedron;
  return spheres == 2 ? RoundPair::sphere_sphere : RoundPair::sphere_polyhedron;
}

template <class Body>
void round_pairs(benchmark::State& st, const std::string& corpus, RoundPair kind) {
  const auto cases = collision::load_cases(std::string(GACOMPARE_DATA_DIR) + "/collision/" + corpus);
  std::vector<std::pair<typename Body::Shape, typename Body::Shape>> shapes;
  for (const auto& k : cases)
    if (kind_of(*k.mesh_a, *k.mesh_b) == kind) shapes.emplace_back(k.a(), k.b());
  if (shapes.empty()) {
    st.SkipWithError("no pairs of this kind in the corpus");
    return;
  }
  std::vector<collision::FeatureContact> contacts;
  std::size_t i = 0;
  for (auto _ : st) {
    contacts.clear();
    benchmark::DoNotOptimize(collision::narrowphase<Body>(shapes[i].first, shapes[i].second,
                                                          collision::Method::sat_then_manifold, &contacts));
    if (++i == shapes.size()) i = 0;
  }
  st.SetItemsProcessed(st.iterations());
}

}  // namespace

int main(int argc, char** argv) {
  const std::tuple<const char*, const char*, RoundPair> round_kinds[] = {
      {"sphere_sphere", "round.json", RoundPair::sphere_sphere},
      {"sphere_polyhedron", "round.json", RoundPair::sphere_polyhedron},
      {"capsule_sphere", "capsule.json", RoundPair::capsule_sphere},
      {"capsule_capsule", "capsule.json", RoundPair::capsule_capsule},
      {"capsule_polyhedron", "capsule.json", RoundPair::capsule_polyhedron}};
  for (const auto& round : round_kinds) {
    const std::string name = std::get<0>(round), corpus = std::get<1>(round);
    const RoundPair kind = std::get<2>(round);
    benchmark::RegisterBenchmark(("BM_round_" + name + "/traditional").c_str(),
                                 [corpus, kind](benchmark::State& st) { round_pairs<traditional::Body>(st, corpus, kind); });
    benchmark::RegisterBenchmark(("BM_round_" + name + "/cga").c_str(),
                                 [corpus, kind](benchmark::State& st) { round_pairs<cga::Body>(st, corpus, kind); });
  }
  benchmark::RegisterBenchmark("BM_narrowphase_report/traditional", [](benchmark::State& st) { per_pair(st, report<Trad>); });
  benchmark::RegisterBenchmark("BM_narrowphase_report/cga", [](benchmark::State& st) { per_pair(st, report<Cga>); });
  benchmark::RegisterBenchmark("BM_narrowphase_sat/traditional", [](benchmark::State& st) {
    per_pair(st, [](const Corpus& c, std::size_t i) {
      return traditional::narrowphase(c.cases[i].a(), c.cases[i].b(), collision::Method::sat);
    });
  });
  benchmark::RegisterBenchmark("BM_narrowphase_sat/cga", [](benchmark::State& st) {
    per_pair(st, [](const Corpus& c, std::size_t i) {
      return cga::narrowphase(c.cases[i].a(), c.cases[i].b(), collision::Method::sat);
    });
  });
  benchmark::RegisterBenchmark("BM_narrowphase_sat/sat_reference", [](benchmark::State& st) {
    per_pair(st, [](const Corpus& c, std::size_t i) { return collision::sat_reference(c.cases[i].a(), c.cases[i].b()); });
  });
  benchmark::RegisterBenchmark("BM_narrowphase_sat/fcl", [](benchmark::State& st) {
    per_pair(st, [](const Corpus& c, std::size_t i) {
      return compare::fcl_collide(c.fcl_a[i], c.cases[i].pose_a, c.fcl_b[i], c.cases[i].pose_b);
    });
  });
  benchmark::RegisterBenchmark("BM_narrowphase_sat/bullet", [](benchmark::State& st) {
    per_pair(st, [](const Corpus& c, std::size_t i) {
      return compare::bullet_collide(c.bullet_a[i], c.cases[i].pose_a, c.bullet_b[i], c.cases[i].pose_b);
    });
  });
  benchmark::RegisterBenchmark("BM_contacts_report/traditional",
                               [](benchmark::State& st) { contacts<Trad>(st, collision::Method::report); });
  benchmark::RegisterBenchmark("BM_contacts_report/cga", [](benchmark::State& st) { contacts<Cga>(st, collision::Method::report); });
  benchmark::RegisterBenchmark("BM_contacts_manifold/traditional",
                               [](benchmark::State& st) { contacts<Trad>(st, collision::Method::manifold); });
  benchmark::RegisterBenchmark("BM_contacts_manifold/cga",
                               [](benchmark::State& st) { contacts<Cga>(st, collision::Method::manifold); });
  benchmark::RegisterBenchmark("BM_manifold_boxes/traditional", manifold_boxes<Trad>);
  benchmark::RegisterBenchmark("BM_manifold_boxes/cga", manifold_boxes<Cga>);
  benchmark::RegisterBenchmark("BM_resting_boxes/traditional", manifold_boxes_shared<traditional::Body>);
  benchmark::RegisterBenchmark("BM_resting_boxes/cga", manifold_boxes_shared<cga::Body>);
  benchmark::RegisterBenchmark("BM_resting_boxes/kept", kept_boxes);
  benchmark::RegisterBenchmark("BM_point_in_body/traditional", point_in_body<traditional::Body>);
  benchmark::RegisterBenchmark("BM_point_in_body/cga", point_in_body<cga::Body>);
  benchmark::RegisterBenchmark("BM_segment_triangle/traditional", [](benchmark::State& st) {
    const auto& s = segments().s;
    std::size_t i = 0;
    for (auto _ : st) {
      const auto& x = s[i];
      benchmark::DoNotOptimize(traditional::segment_triangle(x[0], x[1], x[2], x[3], x[4]));
      if (++i == s.size()) i = 0;
    }
    st.SetItemsProcessed(st.iterations());
  });
  benchmark::RegisterBenchmark("BM_segment_triangle/cga", [](benchmark::State& st) {
    const auto& s = segments().s;
    std::size_t i = 0;
    for (auto _ : st) {
      const auto& x = s[i];
      benchmark::DoNotOptimize(cga::segment_triangle(x[0], x[1], x[2], x[3], x[4]));
      if (++i == s.size()) i = 0;
    }
    st.SetItemsProcessed(st.iterations());
  });
  // The narrowphase's form: the triangle prepared once (eq. 41–42 rows; the
  // plane and reciprocal frame of eq. 43–46), then one segment per item.
  benchmark::RegisterBenchmark("BM_segment_through_prepared/traditional", [](benchmark::State& st) {
    prepared_segments<traditional::PreparedTriangle>(st);
  });
  benchmark::RegisterBenchmark("BM_segment_through_prepared/cga", [](benchmark::State& st) {
    prepared_segments<cga::PreparedTriangle>(st);
  });
  register_pairs();
  register_supports();
  benchmark::Initialize(&argc, argv);
  benchmark::RunSpecifiedBenchmarks();
  benchmark::Shutdown();
  return 0;
}
