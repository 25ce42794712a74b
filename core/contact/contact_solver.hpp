#pragma once
// The contact solver: the response stage of a collision step (§2.5), written
// once over a backend's rigid bodies (their Motion: arm,
// inverse_effective_mass — eq. 53 or eq. 54 —, normal_velocity, push, store,
// displace). It is given the contacts of one group of bodies at the accepted
// time (core/collision_step.hpp decides when) and changes their momenta and,
// for the positional correction, their positions.
//
//
// Resting contact (the report has none; fn 29 only asks that all contacts meet
// the tolerance before any response):
//   - a contact whose approach speed is below v_rest = √(2 |g| tol) + 2 |g| h
//     (the speed a body gains falling through the tolerance, plus two steps of
//     gravity) gets restitution 0: it stops instead of bouncing ever smaller;
//   - simultaneous contacts are solved together by projected Gauss–Seidel
//     with accumulated clamping (sequential impulses: each contact's total
//     impulse λ ≥ 0, targets v_n⁺ ≥ −ε v_n⁻; a cube landing flat on four
//     corners bounces straight, one contact at a time would spin it), at most
//     kMaxSweeps sweeps (the cap hits are counted);
//   - contacts found again in the next step start from their last impulse
//     (warm starting), so a stack's load is carried from step to step instead
//     of being solved afresh through every box;
//   - a pair deeper than tol/2 after the impulses is brought to tol/4 by a
//     split impulse (pseudo-velocities that move the bodies along the contact
//     normals without touching their momenta), so a resting body never creeps down to the
//     tolerance and forces a time-of-impact search that can make no progress.
//     The lift does work against gravity of at most m g tol/4 per correction;
//     the counters say how many there were. Pairs that part after an impact
//     are never corrected: a translation changes the angular momentum about
//     the origin (x × m v), which an elastic impact must conserve.
//
// Coulomb friction (issue #17; beyond the report, whose response is
// frictionless): only for pairs with μ = √(μ_a μ_b) > 0, two tangent rows per
// contact in the same Gauss–Seidel, held in the disc |λ_t| ≤ μ λ_n and warm
// started (Friction below), and resting contacts displaced by ½ h of their
// impulses' velocity change (friction_displacement). With μ = 0 no friction
// row exists and every run is as before, bit for bit.
#include "core/collision_setup.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <span>
#include <unordered_map>
#include <vector>

namespace gacompare::core {


// Gauss–Seidel sweeps per solve: a safety stop, counted when reached. A chain
// of n bodies converges at about cos²(π/(n+1)) per sweep, so the first solve
// of a stack of ten, before warm starting has anything to start from, needs
// ~300 sweeps to reach kVelocityTolerance; with a cap of 200 its residual
// leaves the boxes sinking and the stack falls (measured), with 500 it stands.
inline constexpr int kMaxSweeps = 1000;
// The velocity solve stops when no sweep changes a contact's velocity by more
// than this (m/s), times 1 + the fastest approach. It is tight because a
// frictionless stack turns any residual into drift: the corners of a face
// contact form a redundant set (four rows, three degrees of freedom) on which
// Gauss–Seidel converges slowly, a residual leaves a tilt, a tilted face's
// normal has a sideways part, and every step's load then pushes sideways. A
// stack of ten 0.2 m cubes over 10 s drifts sideways 9e-6 m at 1e-9,
// 2.6e-6 m at 1e-10, 6e-7 m at 1e-11 and 2.4e-7 m at 1e-12, for 0.41, 0.51,
// 0.59 and 0.78 s of run time (traditional; warm starting keeps it to
// ~35 sweeps a step).
inline constexpr double kVelocityTolerance = 1e-11;

template <class Bodies>
class ContactSolver {
 public:
  using Model = typename Bodies::Model;
  using World = std::span<const int>;

  // §2.5: impulses at every contact of `hits` (pairs of the group), solved
  // together, then the positional correction (see the top of this file). `dt`
  // is the time since the group's last accepted state: warm-started impulses
  // scale with it.
  void respond(const CollisionSetup& setup, CollisionCounters& counters, const Model& m, std::span<double> y,
               World world, std::span<const PairHit> hits, double dt, Profile& profile) {
    Solve{setup, counters, cache_}.respond(m, y, world, hits, dt, profile);
  }

  // Forgets warm-start impulses older than the previous collision step (a
  // pair that stopped touching; a contact is only warm started from the step
  // before). Once per collision step; `step` counts the collision steps.
  void forget_old_contacts(std::uint64_t step) {
    std::erase_if(cache_, [&](const auto& kv) { return kv.second.step + 1 < step; });
  }

 private:
  struct Cached {
    Vec3 ra, rb;
    double rate;  // impulse per second
    Vec3 friction_rate = Vec3::Zero();  // the friction impulse per second (world), zero without friction
  };
  struct Remembered {
    std::uint64_t step = 0;  // the collision step that stored them
    std::vector<Cached> at;
  };
  // By world pair (a, b), a < b: an island and the world see a pair the same way round.
  std::unordered_map<std::uint64_t, Remembered> cache_;
  static std::uint64_t key(int a, int b) {
    return (static_cast<std::uint64_t>(a) << 32) | static_cast<std::uint32_t>(b);
  }

  // One response: the setup and counters it reads and adds to, the warm-start
  // cache it reads and rewrites.
  struct Solve {
    using Motion = typename Bodies::Motion;
    using Motions = std::vector<Motion>;
    const CollisionSetup& setup;
    CollisionCounters& counters;
    std::unordered_map<std::uint64_t, Remembered>& cache_;

    struct Row {
      int a, b;
      std::size_t sa, sb;    // the bodies' slots in the response's Motions
      std::size_t hit;       // which pair of the detection
      Vec3 n, ra, rb;        // the normal (a to b); the point from each centre
      typename Bodies::Arm arm_a, arm_b;
      double k, target, lambda, before, depth;  // 1/effective mass, target n·Δv, impulse, n·Δv before, depth
      std::ptrdiff_t friction = -1;  // its friction rows in the solve's Frictions, or −1 (μ = 0)
    };
    // Coulomb friction at one contact (issue #17): two rows along the tangents
    // t[0], t[1] of the contact plane, their accumulated impulses λ_t held in the
    // disc |λ_t| ≤ μ λ_n of the contact's accumulated normal impulse. A disc, not
    // a pyramid: the cone is isotropic, so the friction a sliding body feels does
    // not depend on how its sliding lines up with the basis (a four-sided pyramid
    // |λ_1|, |λ_2| ≤ μ λ_n lets a body sliding at 45° to t[0] feel √2 μ). t[0] is
    // the direction of the relative sliding velocity when there is one (as
    // Bullet's first friction direction), so a sliding contact's friction lies
    // along t[0] and each row's own effective mass (Gauss–Seidel uses no 2 × 2
    // block) does not turn it off the slip; at rest t[0] is any tangent.
    struct Friction {
      std::size_t row;             // its normal row
      std::array<Vec3, 2> t;       // unit tangents (backend: in_plane, quarter_turn)
      std::array<typename Bodies::Arm, 2> arm_a, arm_b;
      std::array<double, 2> k, lambda, slip;  // 1/effective mass, impulse, relative velocity before
      double mu;
      bool impact;  // its normal row approached faster than v_rest: no friction_displacement
    };
    static double normal_velocity(const Row& r, const Motions& of) {
      return Bodies::normal_velocity(of[r.sb], r.arm_b, r.n) - Bodies::normal_velocity(of[r.sa], r.arm_a, r.n);
    }
    static void push(const Row& r, Motions& of, double dl) {
      Bodies::push(of[r.sb], r.arm_b, r.n, dl);
      Bodies::push(of[r.sa], r.arm_a, r.n, -dl);
    }
    static double tangent_velocity(const Row& r, const Friction& f, int d, const Motions& of) {
      return Bodies::normal_velocity(of[r.sb], f.arm_b[d], f.t[d]) - Bodies::normal_velocity(of[r.sa], f.arm_a[d], f.t[d]);
    }
    static void push(const Row& r, const Friction& f, int d, Motions& of, double dl) {
      Bodies::push(of[r.sb], f.arm_b[d], f.t[d], dl);
      Bodies::push(of[r.sa], f.arm_a[d], f.t[d], -dl);
    }

    // The friction rows of normal row r (index `row`) at contact point p: the
    // tangents from the relative velocity's part in the contact plane (the
    // backend's in_plane and quarter_turn), or from the coordinate axis least
    // along n when the contact does not slip.
    Friction friction_row(std::size_t row, const Row& r, const Vec3& p, double mu, const Motions& of) const {
      const Vec3 slip = Bodies::point_velocity(of[r.sb], p) - Bodies::point_velocity(of[r.sa], p);
      Vec3 t = Bodies::in_plane(r.n, slip);
      if (!(t.norm() > 1e-12 * (1 + slip.norm()))) {
        Eigen::Index axis = 0;
        r.n.cwiseAbs().minCoeff(&axis);
        t = Bodies::in_plane(r.n, Vec3::Unit(axis));
      }
      t.normalize();
      Friction f{row, {t, Bodies::quarter_turn(r.n, t)}, {}, {}, {}, {0, 0}, {}, mu, r.before < -setup.resting_speed};
      for (int d = 0; d < 2; ++d) {
        f.arm_a[d] = Bodies::arm(of[r.sa], p, f.t[d]);
        f.arm_b[d] = Bodies::arm(of[r.sb], p, f.t[d]);
        f.k[d] = Bodies::inverse_effective_mass(of[r.sa], f.arm_a[d]) + Bodies::inverse_effective_mass(of[r.sb], f.arm_b[d]);
        f.slip[d] = tangent_velocity(r, f, d, of);
      }
      return f;
    }

    // One Gauss–Seidel update of a contact's friction: each row's impulse to
    // stop its slip, then the pair projected onto the disc |λ_t| ≤ μ λ_n, λ_n
    // the normal row's accumulated impulse (static friction inside the disc,
    // dynamic on its rim). Returns the largest velocity change.
    static double relax(const Row& r, Friction& f, Motions& motion) {
      std::array<double, 2> next{};
      for (int d = 0; d < 2; ++d) next[d] = f.lambda[d] - tangent_velocity(r, f, d, motion) / f.k[d];
      const double limit = f.mu * r.lambda, size = std::hypot(next[0], next[1]);
      if (size > limit) {
        const double s = size > 0 ? limit / size : 0.0;
        next[0] *= s, next[1] *= s;
      }
      double worst = 0;
      for (int d = 0; d < 2; ++d) {
        const double dl = next[d] - f.lambda[d];
        if (dl == 0) continue;
        worst = std::max(worst, std::abs(dl) * f.k[d]);
        f.lambda[d] = next[d];
        push(r, f, d, motion, dl);
      }
      return worst;
    }

    // Projected Gauss–Seidel with accumulated clamping: each row's total impulse
    // λ stays ≥ 0 while a sweep may lower it (Catto's sequential impulses; eq. 53
    // / eq. 54 are the rows' effective masses). Stops when no row changes its
    // velocity by more than `converged` in a sweep, or after kMaxSweeps (counted
    // in `cap_hits`).
    // Friction rows (if any) are relaxed after the normal rows in every sweep,
    // against the normal impulses of that sweep.
    void solve(std::vector<Row>& rows, Motions& motion, double converged, std::uint64_t& cap_hits,
               std::span<Friction> frictions = {}) const {
      if (rows.empty()) return;
      for (int sweep = 0;; ++sweep) {
        if (sweep == kMaxSweeps) {
          ++cap_hits;
          return;
        }
        ++counters.sweeps;
        double worst = 0;
        for (auto& r : rows) {
          const double next = std::max(0.0, r.lambda + (r.target - normal_velocity(r, motion)) / r.k);
          const double dl = next - r.lambda;
          if (dl == 0) continue;
          worst = std::max(worst, std::abs(dl) * r.k);
          r.lambda = next;
          push(r, motion, dl);
        }
        for (auto& f : frictions) worst = std::max(worst, relax(rows[f.row], f, motion));
        if (worst <= converged) return;
      }
    }

    // Warm starting: a contact found again (the same pair, its point within 1 %
    // of the smaller body's size of where it was relative to both centres)
    // starts from the impulse it had, scaled from that step's length to this
    // one's (a resting contact's impulse is its load times the step). A stack
    // then needs a sweep or two per step, not a fresh solve through every box.
    // A friction row starts from the remembered friction impulse's parts along
    // its tangents, held in the disc of its warm-started normal impulse.
    void warm_start(std::vector<Row>& rows, std::vector<Friction>& frictions, Motions& motion, double dt) const {
      if (cache_.empty() || !(dt > 0)) return;
      for (auto& r : rows) {
        const auto pair = cache_.find(key(r.a, r.b));
        if (pair == cache_.end()) continue;
        const double near = 1e-2 * std::min(setup.meshes[r.a]->size(), setup.meshes[r.b]->size());
        const Cached* best = nullptr;
        double closest = near;
        for (const auto& c : pair->second.at) {
          const double dist = std::max((c.ra - r.ra).norm(), (c.rb - r.rb).norm());
          if (dist < closest) closest = dist, best = &c;
        }
        if (!best) continue;
        r.lambda = best->rate * dt;
        push(r, motion, r.lambda);
        ++counters.warm_started;
        if (r.friction < 0) continue;
        Friction& f = frictions[static_cast<std::size_t>(r.friction)];
        const Vec3 j = best->friction_rate * dt;
        std::array<double, 2> l{j.dot(f.t[0]), j.dot(f.t[1])};
        const double size = std::hypot(l[0], l[1]), limit = f.mu * r.lambda;
        if (size > limit) l[0] *= limit / size, l[1] *= limit / size;
        for (int d = 0; d < 2; ++d) f.lambda[d] = l[d], push(r, f, d, motion, l[d]);
        counters.friction_warm_started += size > 0;
      }
    }
    // The impulses of this solve replace what its pairs had; other pairs (other
    // islands) keep theirs until forget_old_contacts.
    void remember(std::span<const PairHit> hits, World world, const std::vector<Row>& rows,
                  const std::vector<Friction>& frictions, double dt) const {
      for (const auto& h : hits) cache_.erase(key(world[h.a], world[h.b]));
      if (!(dt > 0)) return;
      for (const auto& r : rows)
        if (r.lambda > 0) {
          auto& e = cache_[key(r.a, r.b)];
          e.step = counters.steps;
          e.at.push_back({r.ra, r.rb, r.lambda / dt});
          if (r.friction < 0) continue;
          const Friction& f = frictions[static_cast<std::size_t>(r.friction)];
          e.at.back().friction_rate = (f.lambda[0] * f.t[0] + f.lambda[1] * f.t[1]) / dt;
        }
    }

    // The impulses of a resting contact with friction stand for forces that
    // acted through the step, but the step's integration moved the bodies
    // without them: a box held on an incline slid ½ g sin θ h² down it in every
    // step, which the friction impulse then stopped (a creep of ½ g sin θ h,
    // 1.7 mm/s at h = 1 ms, 20°), and a sliding box went ½ μ g h² too far per
    // step. Each such contact's normal and friction impulse λ (one wrench, so
    // that the friction's torque about the centre is balanced by the normal's)
    // moves the bodies by ½ dt of the velocity change it made, as a constant
    // force through the step would have: pseudo-velocities as in the split
    // impulse, so no momentum changes. Impacts (approach faster than v_rest)
    // are instants, not forces, and are left alone. Only contacts with friction
    // (μ > 0): a frictionless scene is unchanged.
    void friction_displacement(const Model& m, std::span<double> y, const std::vector<Row>& rows,
                               const std::vector<Friction>& frictions, const Motions& motion,
                               const std::vector<int>& body_of, double dt) const {
      if (frictions.empty() || !(dt > 0)) return;
      Motions pseudo;
      pseudo.reserve(motion.size());
      for (const auto& mo : motion) pseudo.push_back(Bodies::at_rest(mo));
      for (const auto& f : frictions) {
        if (f.impact) continue;
        const Row& r = rows[f.row];
        push(r, pseudo, 0.5 * dt * r.lambda);
        for (int d = 0; d < 2; ++d) push(r, f, d, pseudo, 0.5 * dt * f.lambda[d]);
      }
      for (std::size_t k = 0; k < pseudo.size(); ++k) Bodies::displace(m, y, static_cast<std::size_t>(body_of[k]), pseudo[k]);
    }

    // Positional correction by split impulse (pseudo-velocities, as Bullet's
    // split impulse does): the same rows, solved together for a displacement of
    // each body instead of a velocity, with targets bringing every contact of
    // the pairs to correct to tol/4 deep (the other rows only keep their pairs
    // from getting deeper, so a correction in a stack is not passed on as
    // penetration to the next box). The bodies move; their momenta do not
    // change, so the correction injects none (the old correction translated one
    // pair's centres along its normal: a teleport that ignored the rest of a
    // stack). The rows of a face contact (three or more points) act at the
    // centres: with their arms, the four corners of a face form a redundant set
    // that Gauss–Seidel leaves with a residual tilt, and a tilted face's normal
    // pushes sideways (a stack of ten drifted 6e-4 m in 10 s that way; 6e-8 m
    // without the turn). The rows of an edge or a vertex contact keep their
    // arms: a cube pivoting on an edge sinks by turning, and lifting its centre
    // instead raised its energy by 0.24 mJ per correction (caught by check's
    // energy rule on cube_drop_edge: +1.8 mJ against 1 mJ allowed). Solved to
    // a millionth of the tolerance: at a thousandth, an edge contact's two rows
    // left a turn of ~1e-6 rad, which a cube balanced on a ridge (an unstable
    // equilibrium growing at 7.7 /s) turned into 1.3e-6 m/s within a second.
    void correct_positions(const Model& m, std::span<double> y, const std::vector<Row>& rows, const Motions& motion,
                           const std::vector<int>& body_of, const std::vector<char>& correct) const {
      const double tol = setup.settings.penetration_tolerance;
      std::vector<Row> fix;
      if (std::find(correct.begin(), correct.end(), 1) == correct.end()) return;
      std::vector<int> points(correct.size(), 0);
      for (const auto& r : rows) ++points[r.hit];
      // A face's rows act at the centres along one normal: the same row, whose
      // target is the deepest corner's (four copies with their own targets are
      // the same problem, solved slowly: the copies fight over one degree of
      // freedom, and no exact step can satisfy them all).
      std::vector<int> face_row(correct.size(), -1);
      for (const auto& r : rows) {
        const double target = correct[r.hit] ? std::max(0.0, r.depth - 0.25 * tol) : 0.0;
        if (points[r.hit] >= 3) {  // a face: at the centres, no turn
          if (face_row[r.hit] >= 0) {
            Row& q = fix[static_cast<std::size_t>(face_row[r.hit])];
            q.target = std::max(q.target, target);
            continue;
          }
          face_row[r.hit] = static_cast<int>(fix.size());
        }
        Row p = r;
        if (points[r.hit] >= 3) {
          const auto& ma = motion[r.sa];
          const auto& mb = motion[r.sb];
          p.arm_a = Bodies::arm(ma, Bodies::position(ma), r.n);
          p.arm_b = Bodies::arm(mb, Bodies::position(mb), r.n);
          p.k = Bodies::inverse_effective_mass(ma, p.arm_a) + Bodies::inverse_effective_mass(mb, p.arm_b);
        }
        p.lambda = 0;
        p.target = target;
        fix.push_back(p);
      }
      Motions pseudo;
      pseudo.reserve(motion.size());
      for (const auto& mo : motion) pseudo.push_back(Bodies::at_rest(mo));
      solve(fix, pseudo, 1e-6 * tol, counters.correction_cap_hits);  // m: a millionth of the tolerance, see above
      for (std::size_t k = 0; k < pseudo.size(); ++k) Bodies::displace(m, y, static_cast<std::size_t>(body_of[k]), pseudo[k]);
      for (std::size_t hi = 0; hi < correct.size(); ++hi) counters.corrections += correct[hi];
    }

    void respond(const Model& m, std::span<double> y, World world, std::span<const PairHit> hits, double dt,
                 Profile& profile) const {
      ScopedStage timed(profile, Stage::response);
      // The bodies in contact, read once, in slots the rows index (no lookup in
      // the solver's sweeps).
      Motions motion;
      std::vector<int> body_of;  // slot → body of the group
      std::unordered_map<int, std::size_t> slot_of;
      const auto slot = [&](int b) {
        const auto [it, fresh] = slot_of.emplace(b, motion.size());
        if (fresh) motion.push_back(Bodies::motion(m, y, static_cast<std::size_t>(b))), body_of.push_back(b);
        return it->second;
      };
      std::vector<Row> rows;
      std::vector<Friction> frictions;  // none unless a pair has μ > 0
      std::vector<char> resting_pair(hits.size(), 0);
      for (std::size_t hi = 0; hi < hits.size(); ++hi) {
        const auto& h = hits[hi];
        const int wa = world[h.a], wb = world[h.b];
        const double eps = std::min(setup.restitution[wa], setup.restitution[wb]);
        // Box2D's mixing rule, √(μ_a μ_b) (Bullet multiplies by default; its run
        // is hooked to the same √, compare/bullet_world.cpp).
        const double mu = std::sqrt(setup.friction[wa] * setup.friction[wb]);
        const std::size_t sa = slot(h.a), sb = slot(h.b);
        const Motion& ma = motion[sa];
        const Motion& mb = motion[sb];
        for (const auto& c : h.features) {
          Row r{wa, wb, sa, sb, hi, c.normal, c.point - Bodies::position(ma), c.point - Bodies::position(mb),
                Bodies::arm(ma, c.point, c.normal), Bodies::arm(mb, c.point, c.normal), 0, 0, 0, 0, c.depth};
          r.k = Bodies::inverse_effective_mass(ma, r.arm_a) + Bodies::inverse_effective_mass(mb, r.arm_b);
          if (!(r.k > 0)) continue;
          r.before = normal_velocity(r, motion);
          const bool resting = r.before < 0 && -r.before <= setup.resting_speed;
          counters.resting_contacts += resting;
          resting_pair[hi] |= resting;
          r.target = r.before < 0 ? -(resting ? 0.0 : eps) * r.before : 0.0;
          if (mu > 0) r.friction = static_cast<std::ptrdiff_t>(frictions.size()),
                      frictions.push_back(friction_row(rows.size(), r, c.point, mu, motion));
          rows.push_back(r);
        }
      }
      counters.contacts += rows.size();
      counters.friction_contacts += frictions.size();
      warm_start(rows, frictions, motion, dt);
      double scale = 0;
      for (const auto& r : rows) scale = std::max(scale, std::abs(r.target));
      for (const auto& f : frictions) scale = std::max(scale, std::hypot(f.slip[0], f.slip[1]));
      solve(rows, motion, kVelocityTolerance * (1 + scale), counters.sweep_cap_hits, frictions);
      for (const auto& f : frictions)
        counters.sliding_contacts += std::hypot(f.lambda[0], f.lambda[1]) >= f.mu * rows[f.row].lambda * (1 - 1e-9) &&
                                     rows[f.row].lambda > 0;
      for (const auto& r : rows) {
        counters.impulses += r.lambda > 0;
        // An impact whose approach the solve did not stop (to 0.1 % of its speed).
        if (r.before < -setup.resting_speed && normal_velocity(r, motion) < 1e-3 * r.before) ++counters.unresolved_impacts;
      }
      remember(hits, world, rows, frictions, dt);
      // The pairs whose depth is corrected: deeper than tol/2, and resting or
      // not parting by themselves. A pair that parts after an impact is left
      // alone: the impact conserves momenta exactly, and the depth goes with it.
      const double tol = setup.settings.penetration_tolerance;
      std::vector<char> correct(hits.size(), 0), parting(hits.size(), 1);
      for (const auto& r : rows) parting[r.hit] &= normal_velocity(r, motion) > setup.resting_speed;
      for (std::size_t hi = 0; hi < hits.size(); ++hi)
        correct[hi] = hits[hi].sat.depth > 0.5 * tol && (resting_pair[hi] || !parting[hi]);
      for (std::size_t k = 0; k < motion.size(); ++k) Bodies::store(m, y, static_cast<std::size_t>(body_of[k]), motion[k]);
      correct_positions(m, y, rows, motion, body_of, correct);
      friction_displacement(m, y, rows, frictions, motion, body_of, dt);
    }
  };
};

}  // namespace gacompare::core
