// The physical-sanity rules of `check` and `compare` (compare/sanity.hpp says
// what each rule is; this file says why each bound is what it is).
#include "compare/sanity.hpp"

#include "core/model/model.hpp"
#include "core/collision/separating_axis.hpp"

#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <limits>
#include <numeric>
#include <span>
#include <utility>
#include <vector>

namespace gacompare::compare {

namespace {
using core::Vec3;
using Mat3 = Eigen::Matrix3d;
constexpr double kInf = std::numeric_limits<double>::infinity();

std::string num(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

// What the rules need to know about a scene, read once from it and its model.
struct SceneFacts {
  const core::Collisions* collisions = nullptr;
  double g = 0;             // |g|
  Vec3 down = Vec3::Zero(); // ĝ; zero without gravity
  double tol = 0, v_rest = 0;
  // The compiled model's meshes (about each centre of mass, so that a
  // sample's position and orientation place them), masses and radii.
  std::vector<std::shared_ptr<const core::Mesh>> meshes;
  std::vector<double> mass, radius;  // radius: of the sphere about the centre of mass holding the mesh
  std::vector<bool> is_static;
  const core::BodyEffects* effects = nullptr;
};

SceneFacts facts_of(const core::Scene& scene, const core::Model& model) {
  SceneFacts w;
  w.collisions = scene.find_effect<core::Collisions>();
  w.effects = &model.effects;
  if (!w.collisions) return w;
  if (const auto* g = scene.find_effect<core::Gravity>(); g && g->g.norm() > 0) {
    w.g = g->g.norm();
    w.down = g->g / w.g;
  }
  w.tol = w.collisions->penetration_tolerance;
  w.v_rest = model.resting_speed;  // the collider's: a contact approaching slower is at rest
  for (std::size_t i = 0; i < scene.bodies.size(); ++i) {
    const core::BodyModel& b = model.bodies[i];
    w.meshes.push_back(b.mesh);
    w.mass.push_back(b.mass);
    w.radius.push_back(b.radius);
    w.is_static.push_back(b.is_static);
  }
  return w;
}

// A body where a sample puts it: vertices and face planes in world coordinates.
struct Posed {
  Vec3 c = Vec3::Zero();
  Mat3 r = Mat3::Identity();
  std::vector<Vec3> v;
  std::vector<core::Plane> planes;
};

std::vector<Posed> pose_all(const SceneFacts& w, const core::Sample& s) {
  std::vector<Posed> out(s.bodies.size());
  for (std::size_t i = 0; i < s.bodies.size() && i < w.meshes.size(); ++i) {
    Posed& p = out[i];
    const auto& q = s.bodies[i].orientation;
    // Normalised: a sample may carry the run's rotation drift, which is
    // reported elsewhere; the geometry is judged on the rotation it stands for.
    p.r = core::rotation_matrix(q);
    p.c = s.bodies[i].position;
    for (const Vec3& x : w.meshes[i]->vertices()) p.v.push_back(p.r * x + p.c);
    for (const auto& pl : w.meshes[i]->planes()) {
      const Vec3 n = p.r * pl.normal;
      p.planes.push_back({n, n.dot(p.c) + pl.offset});
    }
  }
  return out;
}

// The largest gap along a face normal of either body: a lower bound of their
// distance when positive; when negative, −gap is at least the penetration depth
// (the edge × edge axes can only make the depth smaller).
double face_gap(const Posed& a, const Posed& b) {
  double best = -kInf;
  const auto side = [&](const Posed& f, const Posed& o) {
    for (const auto& pl : f.planes) {
      double lo = kInf;
      for (const Vec3& x : o.v) lo = std::min(lo, pl.distance(x));
      best = std::max(best, lo);
    }
  };
  side(a, b);
  side(b, a);
  return best;
}

bool spheres_apart(const SceneFacts& w, const Posed& a, std::size_t ia, const Posed& b, std::size_t ib, double by) {
  return sphere_gap(a.c, b.c, w.radius[ia], w.radius[ib]) >= by;
}

// Each body's centre at a sample, for SphereGrid.
std::vector<Vec3> centres_of(const std::vector<Posed>& posed) {
  std::vector<Vec3> out(posed.size());
  for (std::size_t i = 0; i < posed.size(); ++i) out[i] = posed[i].c;
  return out;
}

// The step a run takes its contacts at, without a time of impact: Bullet's
// fixed step, or our collision step where the scene asks for no search; 0 for
// a run whose impacts are searched.
double step_without_search(const SceneFacts& w, const core::Run& run) {
  const auto fixed = run.metrics.find("bullet_fixed_step_s");
  if (fixed != run.metrics.end()) return fixed->second;
  return w.collisions->time_of_impact == core::TimeOfImpact::none ? w.collisions->step : 0.0;
}

// Each body's highest speed over the run's samples: with the step above, the
// travel a run without a search may end a step with (rules 2 and 6).
std::vector<double> top_speeds(const SceneFacts& w, const core::Run& run) {
  std::vector<double> v(w.mass.size(), 0.0);
  for (const auto& s : run.samples)
    for (std::size_t i = 0; i < v.size() && i < s.bodies.size(); ++i) v[i] = std::max(v[i], s.bodies[i].velocity.norm());
  return v;
}

bool applies(const SceneFacts& w, const core::Run& run) { return w.collisions && !run.error && !run.samples.empty(); }

// What a depth rule (2 and 6) reports. Each pair is judged against its own
// bound; the line carries the pair furthest past its bound where one is, else
// the deepest pair, with its bound. Bounds differ per body in a run without a
// search (one step's travel at each body's top speed), and there the pair
// closest to its bound can be a shallow one between slow bodies: reporting it
// showed a 10,000-body pile as overlapping by 0 while two of its bodies were
// 1.6 mm into each other.
struct DeepestPair {
  struct At {
    double depth = 0, bound = 0, t = 0;
    std::size_t i = 0, j = 0;
  };
  At deepest, worst;
  double worst_margin = -kInf;  // the greatest depth − bound; NaN once a depth is
  explicit DeepestPair(double base) { deepest.bound = worst.bound = base; }
  // Whether a pair at most `upper` deep (−face_gap) could change the line.
  bool matters(double upper, double bound) const {
    return upper > 0 && (upper > deepest.depth || upper - bound > worst_margin);
  }
  void add(double depth, double bound, double t, std::size_t i, std::size_t j) {
    if (std::isnan(worst_margin)) return;
    if (std::isnan(depth)) {
      worst_margin = depth, worst = {depth, bound, t, i, j};
      return;
    }
    depth = std::max(depth, 0.0);  // apart along an axis the faces missed: no overlap
    if (depth > deepest.depth) deepest = {depth, bound, t, i, j};
    if (depth - bound > worst_margin) worst_margin = depth - bound, worst = {depth, bound, t, i, j};
  }
  bool failed() const { return !(worst_margin <= 0); }
  const At& reported() const { return failed() ? worst : deepest; }
};

CheckLine line(const core::Scene& scene, const core::Run& run, const std::string& what, double value, double bound,
               bool ok, std::string note) {
  return {scene.name, run.backend, what, value, bound, ok ? CheckLine::Verdict::pass : CheckLine::Verdict::fail,
          std::move(note)};
}
CheckLine info(const core::Scene& scene, const core::Run& run, const std::string& what, std::string note) {
  return {scene.name, run.backend, what, 0, 0, CheckLine::Verdict::info, std::move(note)};
}

// ---- rule 1: energy -------------------------------------------------------------

// Stack levels at a sample: 1 for a dynamic body touching nothing lower, else
// one more than the highest level among the lower dynamic bodies it touches
// (within the tolerance along every face axis). Positional correction may lift
// a body by one tolerance above what it rests on, which may itself be lifted.
std::vector<int> stack_levels(const SceneFacts& w, const std::vector<Posed>& posed) {
  std::vector<std::size_t> order;
  for (std::size_t i = 0; i < posed.size(); ++i)
    if (!w.is_static[i]) order.push_back(i);
  const auto height = [&](std::size_t i) { return -posed[i].c.dot(w.down); };
  std::sort(order.begin(), order.end(), [&](auto a, auto b) { return height(a) < height(b); });
  // The pairs within the tolerance: grown by half of it each (and a margin
  // for the sum's rounding), a superset of those the test below keeps.
  const std::vector<Vec3> centres = centres_of(posed);
  const std::vector<double> grow(posed.size(), 0.5 * w.tol * (1 + 1e-9) + 1e-15);
  const SphereGrid grid(centres, std::span<const double>(w.radius), order, grow);
  std::vector<int> level(posed.size(), 0);
  for (const std::size_t i : order) {  // every lower body's level is final before a higher one reads it
    level[i] = 1;
    grid.near(i, [&](std::size_t j) {
      if (height(j) < height(i) && !spheres_apart(w, posed[i], i, posed[j], j, w.tol) &&
          face_gap(posed[i], posed[j]) <= w.tol)
        level[i] = std::max(level[i], level[j] + 1);
      return true;
    });
  }
  return level;
}

CheckLine energy(const SceneFacts& w, const core::Scene& scene, const core::Run& run) {
  const std::string what = "sanity: energy rise (J)";
  double max_eps = w.collisions->restitution;
  for (const auto& b : scene.bodies)
    if (b.restitution) max_eps = std::max(max_eps, *b.restitution);
  const auto* pushes = scene.find_effect<core::AppliedForces>();
  if (max_eps > 1) return info(scene, run, what, "not checked: a restitution above 1 adds energy by design");
  if (pushes && !pushes->forces.empty()) return info(scene, run, what, "not checked: applied forces do work");
  if (!scene.constraints.empty()) return info(scene, run, what, "not checked: drift control of constraints does work");
  if (scene.find_effect<core::AttractionBetweenParticles>() || scene.find_effect<core::AttractionToPoint>())
    return info(scene, run, what,
                "not checked: the integration error of an attraction's potential is not bounded by rounding");

  // Rounding: E is a sum of terms of size up to |K0|, |U0|; 1e-9 of them is far
  // above double rounding through a run and far below any injection that matters.
  const auto& s0 = run.samples.front();
  const double e0 = s0.kinetic + s0.potential;
  const double rounding = kSanityEnergyRounding * (std::abs(e0) + std::abs(s0.kinetic) + std::abs(s0.potential));
  // Lift: positional correction may leave a resting body up to one tolerance
  // higher than the lowest it sat (depths stay in (0, tol]), m |g| tol each.
  double lift = 0;
  for (std::size_t i = 0; i < w.mass.size(); ++i)
    if (!w.is_static[i]) lift += w.mass[i] * w.g * w.tol;

  double lowest = e0, t_lowest = s0.t;
  double worst_margin = -kInf, worst_rise = 0, worst_bound = rounding + lift, t_worst = 0, t_from = 0;
  for (const auto& s : run.samples) {
    const double e = s.kinetic + s.potential;
    if (e < lowest) lowest = e, t_lowest = s.t;
    const double rise = e - lowest;
    double bound = rounding + lift;
    if (rise > bound && w.g > 0) {  // stacks: a body on bodies may be lifted by each of them
      const auto level = stack_levels(w, pose_all(w, s));
      double stacked = 0;
      for (std::size_t i = 0; i < w.mass.size(); ++i) stacked += w.mass[i] * w.g * w.tol * level[i];
      bound = rounding + stacked;
    }
    if (rise - bound > worst_margin) {
      worst_margin = rise - bound;
      worst_rise = rise, worst_bound = bound, t_worst = s.t, t_from = t_lowest;
    }
  }
  const bool ok = !(worst_margin > 0);  // NaN fails
  return line(scene, run, what, worst_rise, worst_bound, ok,
              ok ? "" : "energy rose by " + num(worst_rise) + " J from its lowest (t = " + num(t_from) + " s) to t = " +
                            num(t_worst) + " s, above the " + num(worst_bound) + " J positional correction may add");
}

// ---- rule 2: passing through a static body --------------------------------------

CheckLine penetration(const SceneFacts& w, const core::Scene& scene, const core::Run& run) {
  const std::string what = "sanity: penetration into a static body (m)";
  if (std::none_of(w.is_static.begin(), w.is_static.end(), [](bool s) { return s; }))
    return info(scene, run, what, "not checked: no static bodies");
  // 10 tolerances: the time-of-impact search keeps contacts within one
  // tolerance and a resting body sinks less than that between checks, so ten is
  // unreachable by a working collider and still a small fraction of any body.
  // A backend with no time of impact (Bullet: it reports its fixed step) sees a
  // contact only after the step that made it, so its bound adds one step's
  // travel at the body's highest speed: that is its method, not a body passing
  // through (docs/collision-response.md, "Bullet as a whole-simulation reference").
  // Our backends with the scene's time_of_impact "none" take contacts the same
  // way, at the end of each collision step.
  const double step = step_without_search(w, run);
  std::vector<double> bound = top_speeds(w, run);
  for (double& b : bound) b = kSanityDeepPenetration * w.tol + step * b;
  DeepestPair found(kSanityDeepPenetration * w.tol);  // i the body, j the wall
  std::string inside;  // the first centre of mass found inside a static body
  std::vector<std::size_t> statics;  // once: a scene of 10,000 bodies has six walls, not 10,000
  for (std::size_t j = 0; j < w.is_static.size(); ++j)
    if (w.is_static[j]) statics.push_back(j);
  for (const auto& s : run.samples) {
    const auto posed = pose_all(w, s);
    for (std::size_t i = 0; i < posed.size(); ++i) {
      if (w.is_static[i]) continue;
      for (const std::size_t j : statics) {
        if (j >= posed.size() || spheres_apart(w, posed[i], i, posed[j], j, 0)) continue;
        const bool centre_in = std::all_of(posed[j].planes.begin(), posed[j].planes.end(),
                                           [&](const core::Plane& p) { return p.distance(posed[i].c) < 0; });
        // −face_gap bounds a polyhedron's depth from above: the exact (slow)
        // depth is needed only where it could come closest to the bound so
        // far. Not a round body's: its proxy polyhedron is inscribed
        // (core/model/mesh.hpp), and the surface between the proxy's vertices
        // reaches further (up to 11 % of the radius for a sphere); its exact
        // depth is always taken.
        const bool round = w.meshes[i]->is_round() || w.meshes[j]->is_round();
        const double upper = round ? kInf : -face_gap(posed[j], posed[i]);
        if (!centre_in && !found.matters(upper, bound[i])) continue;
        const collision::Placed a{w.meshes[j].get(), {posed[j].r, posed[j].c}}, b{w.meshes[i].get(), {posed[i].r, posed[i].c}};
        found.add(collision::sat_reference(a, b).depth, bound[i], s.t, i, j);
        if (centre_in && inside.empty())
          inside = scene.bodies[i].name + "'s centre of mass is inside " + scene.bodies[j].name + " at t = " + num(s.t) +
                   " s";
      }
    }
  }
  const bool ok = !found.failed() && inside.empty();
  const auto& at = found.reported();
  std::string note;
  if (!ok) {
    note = scene.bodies[at.i].name + " is " + num(at.depth) + " m deep in " + scene.bodies[at.j].name + " at t = " +
           num(at.t) + " s";
    if (!inside.empty()) note += "; " + inside;
  } else if (step > 0) {
    note = "bound: 10 tolerances plus one step without a time of impact (" + num(step) +
           " s) at the body's highest speed";
  }
  return line(scene, run, what, at.depth, at.bound, ok, note);
}

// ---- rule 6: moving bodies in each other ----------------------------------------

CheckLine overlap(const SceneFacts& w, const core::Scene& scene, const core::Run& run) {
  const std::string what = "sanity: overlap of two moving bodies (m)";
  std::vector<std::size_t> moving;
  for (std::size_t i = 0; i < w.is_static.size(); ++i)
    if (!w.is_static[i]) moving.push_back(i);
  if (moving.size() < 2) return info(scene, run, what, "not checked: fewer than two moving bodies");
  // The bound of rule 2, for a pair: 10 tolerances, which a working collider
  // never reaches (a contact is resolved to within one), plus, for a run
  // without a time of impact, one step's travel at each body's highest speed,
  // since such a run sees a contact only after the step that made it.
  const double step = step_without_search(w, run);
  const std::vector<double> v_max = top_speeds(w, run);
  const double base = kSanityDeepPenetration * w.tol;
  DeepestPair found(base);
  // A sample the grid cannot place fails the rule, saying why: a body missing
  // from it, or one at a non-finite position.
  std::string lost;
  for (const auto& s : run.samples) {
    if (s.bodies.size() < w.is_static.size()) {
      lost = "the sample at t = " + num(s.t) + " s has " + std::to_string(s.bodies.size()) + " bodies, the scene " +
             std::to_string(w.is_static.size());
      break;
    }
    const auto posed = pose_all(w, s);
    for (const std::size_t i : moving)
      if (!posed[i].c.allFinite() && lost.empty())
        lost = scene.bodies[i].name + "'s position is not finite at t = " + num(s.t) + " s";
    if (!lost.empty()) break;
    const std::vector<Vec3> centres = centres_of(posed);
    for (const auto& [i, j] : SphereGrid(centres, std::span<const double>(w.radius), moving, {}).pairs()) {
      const double bound = base + step * (v_max[i] + v_max[j]);
      // As in rule 2: −face_gap bounds two polyhedra's depth from above, so
      // the exact depth is taken only where it could change the line.
      const bool round = w.meshes[i]->is_round() || w.meshes[j]->is_round();
      const double upper = round ? kInf : -face_gap(posed[i], posed[j]);
      if (!found.matters(upper, bound)) continue;
      const collision::Placed a{w.meshes[i].get(), {posed[i].r, posed[i].c}}, b{w.meshes[j].get(), {posed[j].r, posed[j].c}};
      found.add(collision::sat_reference(a, b).depth, bound, s.t, i, j);
    }
  }
  if (!lost.empty()) return line(scene, run, what, std::nan(""), base, false, lost);
  const bool ok = !found.failed();
  const auto& at = found.reported();
  std::string note;
  if (at.depth > 0 || !ok)
    note = scene.bodies[at.i].name + " and " + scene.bodies[at.j].name + " overlap by " + num(at.depth) + " m at t = " +
           num(at.t) + " s";
  if (step > 0) note += std::string(note.empty() ? "" : "; ") + "bound: 10 tolerances plus one step without a time of impact (" +
                        num(step) + " s) at each body's highest speed";
  return line(scene, run, what, at.depth, at.bound, ok, note);
}

// ---- rule 3: sideways drift at rest (sanity.hpp states the rule) --------------

Vec3 lateral(const SceneFacts& w, const Vec3& x) { return x - x.dot(w.down) * w.down; }

// Whether a level face of `f` has `o` on its outer side (to within `band`) with
// o's lowest points over the face at least `margin` inside its edges: then every
// contact between the two is on that face, and its normal is vertical.
bool across_level_face(const SceneFacts& w, const Posed& f, const Posed& o, double band, double margin) {
  for (std::size_t k = 0; k < f.planes.size(); ++k) {
    const auto& p = f.planes[k];
    if (p.normal.cross(w.down).norm() > kSanityLevel) continue;
    double lo = kInf;
    for (const Vec3& x : o.v) lo = std::min(lo, p.distance(x));
    if (lo < -band) continue;
    bool inner = true;
    for (const Vec3& x : o.v) {
      if (p.distance(x) > lo + band) continue;  // not among the lowest points over the face
      for (std::size_t m = 0; m < f.planes.size() && inner; ++m)
        if (m != k && f.planes[m].distance(x) > -margin) inner = false;
    }
    if (inner) return true;
  }
  return false;
}

struct Stretch {  // a run of checked intervals of one body
  bool open = false;
  double t0 = 0, t1 = 0;
  Vec3 v0 = Vec3::Zero(), x0 = Vec3::Zero(), integral = Vec3::Zero();
  double dv = 0, drift = 0;
};

std::vector<CheckLine> lateral_drift(const SceneFacts& w, const core::Scene& scene, const core::Run& run) {
  const std::string what_v = "sanity: lateral velocity change at rest (m/s per s)";
  const std::string what_x = "sanity: lateral drift at rest (m)";
  const auto both = [&](const std::string& why) {
    return std::vector<CheckLine>{info(scene, run, what_v, why), info(scene, run, what_x, why)};
  };
  if (w.g == 0) return both("not checked: no gravity, so neither 'at rest' nor 'sideways' is defined");
  const auto* linear = scene.find_effect<core::LinearDrag>();
  const auto* quadratic = scene.find_effect<core::QuadraticDrag>();
  if ((linear && linear->k > 0) || (quadratic && quadratic->k > 0))
    return both("not checked: drag slows a sliding body sideways");
  const core::BodyEffects& fx = *w.effects;
  const double band = kSanityDeepPenetration * w.tol;

  const std::size_t n = run.samples.front().bodies.size(), count = run.samples.size();
  // At rest vertically, for kSanityRestWindow samples in a row: one sample of
  // small vertical speed is every bounce's apex, not rest.
  std::vector<std::vector<char>> resting(n, std::vector<char>(count, 0));
  for (std::size_t i = 0; i < n; ++i) {
    std::size_t k = 0;
    while (k < count) {
      std::size_t e = k;
      while (e < count && std::abs(run.samples[e].bodies[i].velocity.dot(w.down)) < w.v_rest) ++e;
      if (e - k >= static_cast<std::size_t>(kSanityRestWindow))
        std::fill(resting[i].begin() + static_cast<long>(k), resting[i].begin() + static_cast<long>(e), 1);
      k = std::max(e, k + 1);
    }
  }
  const auto speed = [&](const core::Sample& s, std::size_t i) {
    return s.bodies[i].velocity.norm() + s.bodies[i].angular_velocity.norm() * w.radius[i];
  };

  std::vector<Stretch> open(n);
  double worst_rate = 0, worst_drift = 0, rested = 0;
  std::string rate_note, drift_note;
  int stretches = 0;
  const auto close = [&](std::size_t i) {
    Stretch& st = open[i];
    if (!st.open) return;
    st.open = false;
    ++stretches;
    rested += st.t1 - st.t0;
    const double rate = st.dv / std::max(st.t1 - st.t0, 1.0);
    const std::string where = scene.bodies[i].name + " at rest from t = " + num(st.t0) + " to " + num(st.t1) + " s";
    if (rate > worst_rate || std::isnan(rate))
      worst_rate = rate, rate_note = where + ": its lateral velocity changed by " + num(st.dv) + " m/s";
    if (st.drift > worst_drift || std::isnan(st.drift))
      worst_drift = st.drift, drift_note = where + ": it moved sideways " + num(st.drift) + " m more than its velocity explains";
  };

  std::vector<std::size_t> every(n);
  std::iota(every.begin(), every.end(), std::size_t{0});
  std::vector<Posed> here = pose_all(w, run.samples[0]), next;
  std::vector<Vec3> c0 = centres_of(here), c1;
  for (std::size_t k = 0; k + 1 < count; ++k) {
    const auto& s0 = run.samples[k];
    const auto& s1 = run.samples[k + 1];
    next = pose_all(w, s1);
    const double dt = s1.t - s0.t;
    // Each body's partners at each sample: those whose spheres, grown by
    // what the two could close in this interval (the reach below, half to
    // each, with a margin for the sums' rounding), meet. Asked body by body
    // and left at the first that rules the body out: with samples 0.5 s
    // apart, a falling body's reach spans the box.
    std::vector<double> grow(n);
    for (std::size_t i = 0; i < n; ++i)
      grow[i] = (dt * std::max(speed(s0, i), speed(s1, i)) + 0.5 * (w.g * dt * dt + band)) * (1 + 1e-9) + 1e-15;
    c1 = centres_of(next);
    const std::span<const double> radii = std::span<const double>(w.radius);
    const SphereGrid grid0(c0, radii, every, grow), grid1(c1, radii, every, grow);
    for (std::size_t i = 0; i < n; ++i) {
      if (w.is_static[i]) continue;
      bool ok = resting[i][k] && resting[i][k + 1] && dt > 0;
      for (const auto& p : fx.pushes)
        ok = ok && !(p.body == i && p.from < s1.t && p.until > s0.t);
      // Whether j leaves i's rest to be judged at `posed`: apart, or touching
      // it only across a level face, without friction.
      const auto fine = [&](const std::vector<Posed>& posed, std::size_t j) {
        // What the two could close in this interval: both speeds (with the
        // rotation's sweep), gravity's change of velocity, and the band.
        const double reach = dt * (std::max(speed(s0, i), speed(s1, i)) + std::max(speed(s0, j), speed(s1, j))) +
                             w.g * dt * dt + band;
        const Posed &a = posed[i], &b = posed[j];
        if (spheres_apart(w, a, i, b, j, reach) || face_gap(a, b) >= reach) return true;
        if (scene.bodies[i].friction * scene.bodies[j].friction > 0) return false;  // friction pushes sideways
        return across_level_face(w, b, a, band, reach) || across_level_face(w, a, b, band, reach);
      };
      ok = ok && grid0.near(i, [&](std::size_t j) { return fine(here, j); }) &&
           grid1.near(i, [&](std::size_t j) { return fine(next, j); });
      Stretch& st = open[i];
      if (!ok) {
        close(i);
        continue;
      }
      const auto& b0 = s0.bodies[i];
      const auto& b1 = s1.bodies[i];
      if (!st.open) st = {true, s0.t, s0.t, lateral(w, b0.velocity), lateral(w, b0.position), Vec3::Zero(), 0, 0};
      st.integral += 0.5 * dt * (lateral(w, b0.velocity) + lateral(w, b1.velocity));
      st.t1 = s1.t;
      st.dv = std::max(st.dv, (lateral(w, b1.velocity) - st.v0).norm());
      st.drift = std::max(st.drift, (lateral(w, b1.position) - st.x0 - st.integral).norm());
    }
    here.swap(next);
    c0.swap(c1);
  }
  for (std::size_t i = 0; i < n; ++i) close(i);
  if (stretches == 0) return both("not checked: no body rested on level faces alone");
  const std::string checked =
      "checked over " + std::to_string(stretches) + " stretch(es) of rest, " + num(rested) + " s in all";
  const bool rate_ok = worst_rate <= kSanityLateralAcceleration, drift_ok = worst_drift <= kSanityLateralDrift;
  return {line(scene, run, what_v, worst_rate, kSanityLateralAcceleration, rate_ok, rate_ok ? checked : rate_note),
          line(scene, run, what_x, worst_drift, kSanityLateralDrift, drift_ok, drift_ok ? checked : drift_note)};
}

// ---- rule 4: contacts left approaching -----------------------------------------

CheckLine unresolved(const core::Scene& scene, const core::Run& run) {
  const std::string what = "sanity: unresolved impacts";
  const auto it = run.counters.find("unresolved_impacts");
  if (it == run.counters.end())
    return info(scene, run, what, "not measured: this run has no unresolved_impacts counter");
  const double v = static_cast<double>(it->second);
  return line(scene, run, what, v, 0, it->second == 0,
              it->second == 0 ? ""
                              : std::to_string(it->second) +
                                    " contact point(s) still approaching faster than the resting speed after the response");
}

// Rule 5: a body at rest does not keep speeding up. Over every second in
// which a body stays slower than the resting speed (rim speed |v| + ρ|ω|), its
// rim speed at four samples a third of that second apart must not rise at each
// of them and by more than kSanityRestingSpeedRise in all. A resting stack
// whose solve leaves a tilt slides apart with a steady acceleration (a column
// of 20 cubes' top cube: 3.6e-4 m/s at 0.5 s, 3.4e-3 m/s at 4 s) while every
// other rule holds; a body nudged by a neighbour speeds up once, not for a
// second on end; one on a slope steeper than ~0.4° passes the resting speed
// within the second.
CheckLine resting_acceleration(const SceneFacts& w, const core::Scene& scene, const core::Run& run) {
  const std::string what = "sanity: speed-up at rest over 1 s (m/s)";
  if (w.g == 0) return info(scene, run, what, "not checked: no gravity, so nothing rests");
  const auto& samples = run.samples;
  const auto rim_speed = [&](std::size_t k, std::size_t b) {
    const auto& x = samples[k].bodies[b];
    return x.velocity.norm() + w.radius[b] * x.angular_velocity.norm();
  };
  // Only while the whole scene rests: a body struck by a moving neighbour, or
  // nudged by one tipping off a pile, speeds up rightly.
  std::vector<char> all_rest(samples.size(), 1);
  for (std::size_t k = 0; k < samples.size(); ++k)
    for (std::size_t b = 0; b < scene.bodies.size() && all_rest[k]; ++b)
      if (!w.is_static[b] && !(rim_speed(k, b) < w.v_rest)) all_rest[k] = 0;
  double worst = 0;
  std::string where;
  for (std::size_t b = 0; b < scene.bodies.size(); ++b) {
    if (w.is_static[b]) continue;
    std::vector<double> speed(samples.size());
    for (std::size_t k = 0; k < samples.size(); ++k) speed[k] = rim_speed(k, b);
    std::size_t start = 0;  // the first sample of the current resting stretch
    for (std::size_t k = 0; k < samples.size(); ++k) {
      if (!all_rest[k]) {
        start = k + 1;
        continue;
      }
      const double t = samples[k].t;
      if (t - samples[start].t < 1.0) continue;
      // The samples nearest t − 1, t − 2/3 and t − 1/3 s (all in the stretch).
      std::size_t at[4] = {k, k, k, k};
      for (int q = 1; q <= 3; ++q) {
        const double want = t - q / 3.0;
        std::size_t j = k;
        while (j > start && samples[j].t > want) --j;
        at[q] = j;
      }
      const bool rising = speed[at[3]] < speed[at[2]] && speed[at[2]] < speed[at[1]] && speed[at[1]] < speed[at[0]];
      const double rise = speed[at[0]] - speed[at[3]];
      if (rising && rise > worst) {
        worst = rise;
        where = scene.bodies[b].name + " from " + num(speed[at[3]]) + " m/s at t = " + num(samples[at[3]].t) + " s to " +
                num(speed[at[0]]) + " m/s at t = " + num(t) + " s";
      }
    }
  }
  const bool ok = worst <= kSanityRestingSpeedRise;
  return line(scene, run, what, worst, kSanityRestingSpeedRise, ok,
              ok ? "" : "body " + where + ", every body slower than the resting speed throughout");
}

}  // namespace

CheckLine overlap_check(const core::Scene& scene, const core::Run& run) {
  const core::Model model = core::compile(scene);
  const SceneFacts w = facts_of(scene, model);
  if (!applies(w, run)) return info(scene, run, "sanity: overlap of two moving bodies (m)", "not checked: no collisions or no samples");
  return overlap(w, scene, run);
}

CheckLine energy_rise_check(const core::Scene& scene, const core::Run& run) {
  const core::Model model = core::compile(scene);
  const SceneFacts w = facts_of(scene, model);
  if (!applies(w, run)) return info(scene, run, "sanity: energy rise (J)", "not checked: no collisions or no samples");
  return energy(w, scene, run);
}

CheckLine penetration_check(const core::Scene& scene, const core::Run& run) {
  const core::Model model = core::compile(scene);
  const SceneFacts w = facts_of(scene, model);
  if (!applies(w, run))
    return info(scene, run, "sanity: penetration into a static body (m)", "not checked: no collisions or no samples");
  return penetration(w, scene, run);
}

SphereGrid::SphereGrid(std::span<const Vec3> centres, std::span<const double> radius, std::span<const std::size_t> which,
                       std::span<const double> grow)
    : centres_(centres), radius_(radius), grow_(grow), which_(which.begin(), which.end()) {
  // Each body's class: the binary exponent of its grown radius.
  std::vector<std::pair<int, std::size_t>> by_class;
  for (const std::size_t i : which) {
    if (lost(i)) {
      lost_.push_back(i);
      continue;
    }
    int e = 0;
    std::frexp(grown(i), &e);
    by_class.emplace_back(e, i);
  }
  std::stable_sort(by_class.begin(), by_class.end(),
                   [](const auto& a, const auto& b) { return a.first < b.first; });
  for (std::size_t k = 0; k < by_class.size();) {
    std::size_t end = k;
    Level l;
    while (end < by_class.size() && by_class[end].first == by_class[k].first)
      l.largest = std::max(l.largest, grown(by_class[end].second)), ++end;
    l.cell = l.largest > 0 ? 2 * l.largest : 1.0;
    for (std::size_t u = k; u < end; ++u) {
      const Vec3& c = centres[by_class[u].second];
      l.cells.emplace_back(key(l.index(c.x()), l.index(c.y()), l.index(c.z())), by_class[u].second);
    }
    std::sort(l.cells.begin(), l.cells.end());
    levels_.push_back(std::move(l));
    k = end;
  }
}

std::vector<std::pair<std::size_t, std::size_t>> SphereGrid::pairs() const {
  std::vector<std::pair<std::size_t, std::size_t>> out;
  for (const std::size_t i : which_)
    near(i, [&](std::size_t j) {
      if (j > i) out.emplace_back(i, j);
      return true;
    });
  return out;
}

std::vector<CheckLine> lateral_drift_checks(const core::Scene& scene, const core::Run& run) {
  const core::Model model = core::compile(scene);
  const SceneFacts w = facts_of(scene, model);
  if (!applies(w, run)) return {};
  return lateral_drift(w, scene, run);
}

CheckLine unresolved_impacts_check(const core::Scene& scene, const core::Run& run) { return unresolved(scene, run); }

CheckLine resting_acceleration_check(const core::Scene& scene, const core::Run& run) {
  const core::Model model = core::compile(scene);
  const SceneFacts w = facts_of(scene, model);
  if (!applies(w, run)) return info(scene, run, "sanity: speed-up at rest over 1 s (m/s)", "not checked: no collisions or no samples");
  return resting_acceleration(w, scene, run);
}

std::vector<CheckLine> sanity_checks(const core::Scene& scene, const core::Model& model, const core::Run& run) {
  const SceneFacts w = facts_of(scene, model);
  if (!applies(w, run)) return {};
  std::vector<CheckLine> out{energy(w, scene, run), penetration(w, scene, run)};
  for (auto& l : lateral_drift(w, scene, run)) out.push_back(std::move(l));
  out.push_back(unresolved(scene, run));
  out.push_back(resting_acceleration(w, scene, run));
  out.push_back(overlap(w, scene, run));
  return out;
}

std::vector<CheckLine> sanity_checks(const core::Scene& scene, const core::Run& run) {
  return sanity_checks(scene, core::compile(scene), run);
}

std::vector<CheckLine> sanity_checks(const SceneResult& r) {
  std::vector<CheckLine> out;
  for (const auto& b : r.backends) {
    auto lines = sanity_checks(r.scene, *r.model, b.run);
    out.insert(out.end(), lines.begin(), lines.end());
  }
  return out;
}

std::vector<std::string> sanity_warnings(const std::vector<CheckLine>& lines) {
  std::vector<std::string> out;
  for (const auto& l : lines)
    if (l.verdict == CheckLine::Verdict::fail)
      out.push_back(l.backend + ": " + l.what.substr(l.what.find(':') + 2) + " " + num(l.value) + ", bound " +
                    num(l.bound) + (l.note.empty() ? "" : ": " + l.note));
  return out;
}

}  // namespace gacompare::compare
