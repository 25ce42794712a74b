#pragma once
// The contact solver: the response stage of a collision step (§2.5), written
// once over a backend's rigid bodies (their Motion: arm,
// inverse_effective_mass — eq. 53 or eq. 54 —, normal_velocity, push, store,
// displace). It is given the contacts of one group of bodies at the accepted
// time (core/collision/collision_step.hpp decides when) and changes their momenta and,
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
// Coulomb friction (beyond the report, whose response is
// frictionless): only for pairs with μ = √(μ_a μ_b) > 0, two tangent rows per
// contact in the same Gauss–Seidel, acting in the pair's contact plane
// (in_plane_of), held in the disc |λ_t| ≤ μ λ̄_n (λ̄_n its
// pair's mean normal impulse, friction_limit) and warm
// started (Friction below), and resting contacts displaced by ½ h of their
// impulses' velocity change (friction_displacement). The direct solve's
// answer is made exact for the disc by Newton's method where its box rounds
// leave it short (polish; core/contact/coulomb.hpp). With μ = 0 no friction
// row exists and every run is as before, bit for bit.
#include "core/collision/collision_setup.hpp"
#include "core/contact/coulomb.hpp"
#include "core/contact/lcp.hpp"
#include "core/parallel.hpp"
#include "core/stage.hpp"

#include <Eigen/SparseCore>

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdint>
#include <limits>
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
// The direct solve's rounds of friction bounds (±μ λ̄_n from the normal
// impulses of the round before, friction_limit); the sweeps after it finish
// what is left.
inline constexpr int kFrictionRounds = 8;
// Lines per block of the direct solve's groups on the run's threads: the
// piles' groups are a few lines each, 1.4 µs on average on the 10,000-body
// box, so a block of this many holds about the 100 µs a chunk needs
// (core/parallel.hpp).
inline constexpr std::size_t kLinesPerBlock = 256;
// A frictionless warm start whose residual is at most this share of the
// tolerance is kept without a solve (direct). A kept answer's residual stays
// in the velocities step after step: kept at the tolerance itself, a 20-cube
// column's worst error against its statics answer grew from 1e-9 to 1e-6 of
// its bounds over 10 s; at a thousandth it stays at 1e-9, and the column and
// the ten-layer wall pyramid keep 97 % and 99 % of their warm starts.
inline constexpr double kKeepWarmStart = 1e-3;
// A resting pair whose points' depths differ by at most this share of the
// penetration tolerance counts as level: while every resting pair is level
// and none is deeper than tol/2, the position projection is skipped
// (project_positions). A spread s tilts a face of size L by s/L, and its
// load then pushes the body above sideways by (s/L)|g| per second; at 1e-12 m
// on 0.2 m cubes that is 5e-11 m/s², 3e-9 m over 10 s. At rest the spread
// left by the last projection stays below this (the stacking family skips
// the same steps with a bound of 1e-12 m or 1e-8 m), so the bound sends only
// a disturbed stack back to the projection.
inline constexpr double kProjectSpread = 1e-8;
// The friction rows' weight in the direct solve's regularisation (lcp.hpp):
// among the impulses that give the same velocities (a face's corners, a body
// on two supports), the solve takes the one with the least friction. With
// the normal rows' weight, the least-norm answer of a wall pyramid held
// itself up partly by friction that squeezed each cube between its two
// supports (it evens out their normal loads), that friction sat on its
// bounds, the bounds moved with it, and the rounds did not settle.
inline constexpr double kFrictionWeight = 1e4;

template <class Bodies>
class ContactSolver {
 public:
  using Model = typename Bodies::Model;
  using BodyIndices = std::span<const int>;

  // §2.5: impulses at every contact of `hits` (pairs of the group), solved
  // together, then the positional correction (see the top of this file). `dt`
  // is the time since the group's last accepted state: warm-started impulses
  // scale with it.
  void respond(const CollisionSetup& setup, CollisionCounters& counters, const Model& m, std::span<double> y,
               BodyIndices world, std::span<const PairHit> hits, double dt, Profile& profile) {
    Solve{setup, counters, cache_, live_from_}.respond(m, y, world, hits, dt, profile);
  }

  // The positional correction alone: each pair of `hits` deeper than the
  // tolerance pushed to tol/4, the others held from approaching; no impulse.
  // For pairs a response left too deep (core/collision/push_out_step.hpp).
  void push_out(const CollisionSetup& setup, CollisionCounters& counters, const Model& m, std::span<double> y,
                BodyIndices world, std::span<const PairHit> hits, Profile& profile) {
    Solve{setup, counters, cache_, live_from_}.push_out(m, y, world, hits, profile);
  }

  // Forgets warm-start impulses older than the previous collision step (a
  // pair that stopped touching; a contact is only warm started from the step
  // before). Once per collision step; `step` counts the collision steps. An
  // older entry is only ignored from then on (warm_start reads it as
  // missing) and erased every kEraseEvery steps: a pass over the whole cache
  // at every step, all of it on the run's own thread, averaged 0.1 ms a step
  // over the 10,000-body box's second on two threads (0.37 ms, about 1 %,
  // once it has piled up).
  void forget_old_contacts(std::uint64_t step) {
    live_from_ = step;
    if (step % kEraseEvery == 0) std::erase_if(cache_, [&](const auto& kv) { return !live(kv.second, step); });
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
  static constexpr std::uint64_t kEraseEvery = 64;
  std::uint64_t live_from_ = 0;  // the step of the last forget_old_contacts
  // Whether r was stored at the collision step before `from` (the last
  // forget_old_contacts' step), or since.
  static bool live(const Remembered& r, std::uint64_t from) { return r.step + 1 >= from; }
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
    std::uint64_t live_from;  // an entry not live from then (ContactSolver::live) is as good as missing

    struct Row {
      int a, b;
      std::size_t sa, sb;    // the bodies' slots in the response's Motions
      std::size_t hit;       // which pair of the detection
      Vec3 n, ra, rb;        // the normal (a to b); the point from each centre
      typename Bodies::Arm arm_a, arm_b;
      double k, target, lambda, before, depth;  // 1/effective mass, target n·Δv, impulse, n·Δv before, depth
      std::ptrdiff_t friction = -1;  // its friction rows in the solve's Frictions, or −1 (μ = 0)
    };
    // Coulomb friction at one contact: two rows along the tangents
    // t[0], t[1] of the contact plane, their accumulated impulses λ_t held in the
    // disc |λ_t| ≤ μ λ̄_n of its pair's mean normal impulse (friction_limit). A disc, not
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
      std::size_t pair_begin = 0, pair_end = 0;  // its pair's normal rows [begin, end): the bound's load
    };
    // A contact's friction bound μ λ̄_n: λ̄_n the mean normal impulse of its
    // pair's points, not its own point's. How a rigid face's load divides
    // among its corners is not determined (the corners are redundant), and a
    // solve's division shifts with the friction: bounded by each corner's own
    // share, the direct solve's rounds did not settle on a five-layer wall
    // pyramid with μ = 0.5, and the sweeps after them ended on their cap at
    // every step. The pair's load is determined, and a face that slides still
    // feels μ times its whole load. (The report has no friction; this is
    // the patch friction of PhysX, kept at the points.)
    // `normal(k)` is normal row k's impulse: the rows' own, or a direct
    // solve's impulses of this round.
    template <class Normal>
    static double friction_limit(const Friction& f, Normal normal) {
      double sum = 0;
      for (std::size_t k = f.pair_begin; k < f.pair_end; ++k) sum += normal(k);
      return f.mu * std::max(0.0, sum) / static_cast<double>(f.pair_end - f.pair_begin);
    }
    static double friction_limit(const Friction& f, const std::vector<Row>& rows) {
      return friction_limit(f, [&](std::size_t k) { return rows[k].lambda; });
    }
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

    // A contact point moved along n into its pair's contact plane (through the
    // pair's points' centroid, normal to n), where its friction rows act.
    // The points of a face contact lie off that plane by the clipped depths
    // and the face's tilt; a tangent row at such a point picks up n-motion
    // (a pitching face's corners then "slip" by tilt × speed), and four
    // corners that all stick over-determine the three in-plane freedoms: on a
    // square pyramid's landing the sweeps' fixed point did not exist (the best
    // answer left 3.4e-9 m/s, Newton's method found), and the sweeps cycled. In
    // the plane, a tangent row sees only the in-plane motion and the twist
    // about n, which any set of sticking points can share.
    static Vec3 in_plane_of(const Vec3& point, const Vec3& n, const Vec3& centre) {
      return point - n * n.dot(point - centre);
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
    // stop its slip, then the pair projected onto the disc |λ_t| ≤ μ λ̄_n, λ̄_n
    // its pair's mean accumulated normal impulse (static friction inside the disc,
    // dynamic on its rim). Returns the largest velocity change.
    static double relax(const std::vector<Row>& rows, Friction& f, Motions& motion) {
      const Row& r = rows[f.row];
      std::array<double, 2> next{};
      for (int d = 0; d < 2; ++d) next[d] = f.lambda[d] - tangent_velocity(r, f, d, motion) / f.k[d];
      const double limit = friction_limit(f, rows), size = std::hypot(next[0], next[1]);
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
    // Returns the last sweep's largest velocity change (the residual at exit).
    double solve(std::vector<Row>& rows, Motions& motion, double converged, std::uint64_t& cap_hits,
                 std::span<Friction> frictions = {}) const {
      if (rows.empty()) return 0;
      ++counters.solves;
      double last = 0;  // the last sweep's largest change: the residual at a capped exit
      for (int sweep = 0;; ++sweep) {
        double worst = 0;
        if (sweep == kMaxSweeps) {
          ++cap_hits;
          counters.add_sweeps(sweep);
          return last;
        }
        ++counters.sweeps;
        for (auto& r : rows) {
          const double next = std::max(0.0, r.lambda + (r.target - normal_velocity(r, motion)) / r.k);
          const double dl = next - r.lambda;
          if (dl == 0) continue;
          worst = std::max(worst, std::abs(dl) * r.k);
          r.lambda = next;
          push(r, motion, dl);
        }
        for (auto& f : frictions) worst = std::max(worst, relax(rows, f, motion));
        if (worst <= converged) {
          counters.add_sweeps(sweep + 1);
          return worst;
        }
        last = worst;
      }
    }

    // --- The direct solve (core/contact/lcp.hpp) ---
    // One row as the direct solve sees it: a normal row, or one tangent of a
    // friction row, between its two bodies' slots.
    struct Line {
      std::size_t sa, sb;
      const typename Bodies::Arm* arm_a;
      const typename Bodies::Arm* arm_b;
      Vec3 dir;
    };
    // The normal rows first (line k is row k), then each friction's two tangents.
    static std::vector<Line> lines_of(const std::vector<Row>& rows, const std::vector<Friction>& frictions) {
      std::vector<Line> lines;
      lines.reserve(rows.size() + 2 * frictions.size());
      for (const auto& r : rows) lines.push_back({r.sa, r.sb, &r.arm_a, &r.arm_b, r.n});
      for (const auto& f : frictions)
        for (int d = 0; d < 2; ++d) lines.push_back({rows[f.row].sa, rows[f.row].sb, &f.arm_a[d], &f.arm_b[d], f.t[d]});
      return lines;
    }
    // Each moving slot's lines, in line order, with the sign of their impulse
    // on it (−1 on a line's first body, +1 on its second): slot s's are
    // items[first[s], first[s + 1]), one list for all (a vector per slot was
    // an allocation per body of a pile's island at every solve).
    struct LinesAt {
      std::vector<std::size_t> first;
      std::vector<std::pair<std::size_t, double>> items;
      std::span<const std::pair<std::size_t, double>> operator[](std::size_t s) const {
        return {items.data() + first[s], items.data() + first[s + 1]};
      }
    };
    static LinesAt lines_at(const std::vector<Line>& lines, std::size_t slots, const std::vector<char>& moving) {
      LinesAt at;
      at.first.assign(slots + 1, 0);
      for (const Line& l : lines) {
        if (moving[l.sa]) ++at.first[l.sa + 1];
        if (moving[l.sb]) ++at.first[l.sb + 1];
      }
      for (std::size_t s = 0; s < slots; ++s) at.first[s + 1] += at.first[s];
      at.items.resize(at.first[slots]);
      std::vector<std::size_t> next(at.first.begin(), at.first.end() - 1);
      for (std::size_t k = 0; k < lines.size(); ++k) {
        if (moving[lines[k].sa]) at.items[next[lines[k].sa]++] = {k, -1.0};
        if (moving[lines[k].sb]) at.items[next[lines[k].sb]++] = {k, 1.0};
      }
      return at;
    }
    // A line's arm on the body its impulse has `sign` on.
    static const typename Bodies::Arm& arm(const Line& l, double sign) { return sign > 0 ? *l.arm_b : *l.arm_a; }
    // The Delassus matrix A = J M⁻¹ Jᵀ of the lines, from the backend's own
    // algebra: column j is what a unit impulse along line j (pushed into a
    // body at rest, as the sweeps push) does to every line's velocity
    // (normal_velocity). Only a body both lines share couples them; static
    // bodies are skipped (they take no impulse). Written column by column
    // into the compressed storage (no triplets to sort): column j's rows are
    // the lines at its two bodies, each list in line order, merged, with the
    // two bodies' parts summed where line i shares both; every such entry is
    // stored, zeros too, so the pattern (and the factorisation's ordering)
    // is the same whatever the values.
    Eigen::SparseMatrix<double> delassus(const std::vector<Line>& lines, const Motions& motion,
                                         const std::vector<char>& moving) const {
      const auto at = lines_at(lines, motion.size(), moving);
      // Line j's column part through slot s (where j has sign sj): (line, value), in line order.
      using Part = std::vector<std::pair<Eigen::Index, double>>;
      const auto part = [&](std::size_t s, std::size_t j, double sj, Part& out) {
        out.clear();
        if (!moving[s]) return;
        Motion unit = Bodies::at_rest(motion[s]);
        Bodies::push(unit, arm(lines[j], sj), lines[j].dir, sj);
        for (const auto& [i, si] : at[s])
          out.emplace_back(static_cast<Eigen::Index>(i), si * Bodies::normal_velocity(unit, arm(lines[i], si), lines[i].dir));
      };
      const auto n = static_cast<Eigen::Index>(lines.size());
      // Column j's entries: the lines of its two bodies, merged by line.
      // Counted first, so that the columns are then written on the run's
      // threads, each where its count puts it (a pile's island has
      // thousands of lines).
      Eigen::SparseMatrix<double> a(n, n);
      int* outer = a.outerIndexPtr();
      outer[0] = 0;
      for_each_index(lines.size(), [&](std::size_t j) {
        const auto pa = at[lines[j].sa], pb = at[lines[j].sb];  // empty for a static slot
        std::size_t u = 0, v = 0, c = 0;
        for (; u < pa.size() && v < pb.size(); ++c) {
          const std::size_t i = std::min(pa[u].first, pb[v].first);
          u += pa[u].first == i, v += pb[v].first == i;
        }
        outer[j + 1] = static_cast<int>(c + (pa.size() - u) + (pb.size() - v));
      }, kGrainPair);
      for (Eigen::Index j = 0; j < n; ++j) outer[j + 1] += outer[j];
      a.resizeNonZeros(outer[n]);
      for_each_block(lines.size(), kGrainPair, [&](std::size_t, std::size_t begin, std::size_t end) {
        Part pa, pb;
        for (std::size_t j = begin; j < end; ++j) {
          const Line& l = lines[j];
          auto nz = static_cast<Eigen::Index>(outer[j]);
          part(l.sa, j, -1.0, pa), part(l.sb, j, 1.0, pb);
          const bool a_first = l.sa < l.sb;  // the parts summed in slot order
          std::size_t u = 0, v = 0;
          while (u < pa.size() || v < pb.size()) {
            Eigen::Index i;
            double x;
            if (v == pb.size() || (u < pa.size() && pa[u].first < pb[v].first)) {
              i = pa[u].first, x = pa[u].second, ++u;
            } else if (u == pa.size() || pb[v].first < pa[u].first) {
              i = pb[v].first, x = pb[v].second, ++v;
            } else {
              i = pa[u].first, x = a_first ? pa[u].second + pb[v].second : pb[v].second + pa[u].second, ++u, ++v;
            }
            a.innerIndexPtr()[nz] = static_cast<int>(i), a.valuePtr()[nz] = x, ++nz;
          }
        }
      });
      return a;
    }
    // A's factor by body, A = G Gᵀ (contact::Blcp::G): slot s's part of A,
    // the velocities of its lines from unit impulses through s alone (the
    // parts delassus sums), is positive semi-definite of rank at most six (a
    // rigid body's freedoms), factorised as G_s G_sᵀ by pivoted Cholesky
    // (contact::psd_factor). In the backend's own algebra, as A is: no basis
    // of the bodies' motions is needed. Its exact zeros are kept as entries:
    // the augmented system's pattern is then the lines' and the ranks' alone,
    // not where rounding left a zero, and a resting stack's projections meet
    // the pattern the last one analysed (lcp.cpp keeps the analysis of each
    // pattern). Dropping them, every projection of a resting 385-cube pyramid
    // had a pattern of its own and was ordered again (AMD, some 6 % of the
    // run); kept, 165 of its 174 factorisations in a second reuse an
    // analysis, for some 2 % more entries.
    Eigen::SparseMatrix<double, Eigen::RowMajor> body_factor(const std::vector<Line>& lines, const Motions& motion,
                                                           const std::vector<char>& moving) const {
      const auto at = lines_at(lines, motion.size(), moving);
      std::vector<Eigen::Triplet<double, Eigen::Index>> t;
      Eigen::Index columns = 0;
      for (std::size_t s = 0; s < motion.size(); ++s) {
        const auto k = static_cast<Eigen::Index>(at[s].size());
        if (k == 0) continue;
        Eigen::MatrixXd part(k, k);
        for (Eigen::Index v = 0; v < k; ++v) {
          const auto& [j, sj] = at[s][static_cast<std::size_t>(v)];
          Motion unit = Bodies::at_rest(motion[s]);
          Bodies::push(unit, arm(lines[j], sj), lines[j].dir, sj);
          for (Eigen::Index u = 0; u < k; ++u) {
            const auto& [i, si] = at[s][static_cast<std::size_t>(u)];
            part(u, v) = si * Bodies::normal_velocity(unit, arm(lines[i], si), lines[i].dir);
          }
        }
        const Eigen::MatrixXd gs = contact::psd_factor(part, 6);
        for (Eigen::Index c = 0; c < gs.cols(); ++c, ++columns)
          for (Eigen::Index u = 0; u < k; ++u)
            t.emplace_back(static_cast<Eigen::Index>(at[s][static_cast<std::size_t>(u)].first), columns, gs(u, c));
      }
      Eigen::SparseMatrix<double, Eigen::RowMajor> g(static_cast<Eigen::Index>(lines.size()), columns);
      g.setFromTriplets(t.begin(), t.end());
      return g;
    }
    // Every line's velocity less its target (lines: normal rows' targets; friction: 0).
    Eigen::VectorXd line_velocities(const std::vector<Row>& rows, const std::vector<Friction>& frictions,
                                    const Motions& motion) const {
      Eigen::VectorXd v(static_cast<Eigen::Index>(rows.size() + 2 * frictions.size()));
      Eigen::Index k = 0;
      for (const auto& r : rows) v[k++] = normal_velocity(r, motion) - r.target;
      for (const auto& f : frictions)
        for (int d = 0; d < 2; ++d) v[k++] = tangent_velocity(rows[f.row], f, d, motion);
      return v;
    }
    // The lines' groups: lines whose bodies are joined through moving bodies,
    // in the order of their first line; a static body joins nothing.
    static std::vector<std::vector<Eigen::Index>> groups_of(const std::vector<Line>& lines, const std::vector<char>& moving) {
      std::vector<std::size_t> root(moving.size());
      for (std::size_t k = 0; k < root.size(); ++k) root[k] = k;
      const auto find = [&](std::size_t x) {
        while (root[x] != x) x = root[x] = root[root[x]];
        return x;
      };
      for (const auto& l : lines)
        if (moving[l.sa] && moving[l.sb]) root[find(l.sa)] = find(l.sb);
      std::vector<std::vector<Eigen::Index>> groups;
      std::vector<std::ptrdiff_t> group_of(moving.size(), -1);
      for (std::size_t k = 0; k < lines.size(); ++k) {
        const std::size_t r = find(moving[lines[k].sa] ? lines[k].sa : lines[k].sb);
        if (group_of[r] < 0) group_of[r] = static_cast<std::ptrdiff_t>(groups.size()), groups.emplace_back();
        groups[static_cast<std::size_t>(group_of[r])].push_back(static_cast<Eigen::Index>(k));
      }
      return groups;
    }
    // The rows' complementarity problem solved at once: every row's impulse
    // λ ≥ 0 and velocity ≥ its target, one of them tight; friction rows in the
    // box ±μ λ̄_n of the normal impulses found (solve_group: solved again
    // until those settle, at most kFrictionRounds times). Starts from the impulses the
    // rows hold (warm starting) and leaves their new values pushed into
    // `motion`; the sweeps that follow then hold friction in its disc and
    // meet `converged` (a converged solve leaves them one sweep to check).
    // Rows with pull[k] set are bilateral (their impulse may be negative: the
    // position projection below). `known` (optional): the Delassus matrix of
    // the same rows, bodies and arms, from an earlier solve of this response
    // (its normal rows first: friction lines after them are left out), used
    // instead of building it again; or, empty, where this solve leaves its own.
    // Returns whether every round was solved.
    bool direct(std::vector<Row>& rows, std::vector<Friction>& frictions, Motions& motion,
                const std::vector<char>& moving, double converged, const std::vector<char>& pull = {},
                Eigen::SparseMatrix<double>* known = nullptr, double* left = nullptr) const {
      if (rows.empty()) return true;
      // Without friction: a warm start already well within the tolerance
      // (kKeepWarmStart) is kept. At rest it usually is, and the solve's
      // factorisation is most of a resting stack's step. The check reads the
      // rows' velocities with the warm start already in them (A λ + b), so
      // it needs no Delassus matrix either.
      if (frictions.empty() && pull.empty() && held_residual(rows, motion) <= kKeepWarmStart * converged)
        return ++counters.exact_starts, true;
      bool solved = true;
      const std::vector<Line> lines = lines_of(rows, frictions);
      const auto n = static_cast<Eigen::Index>(lines.size()), nr = static_cast<Eigen::Index>(rows.size());
      contact::Blcp p;
      if (known && known->rows() == n) p.A = *known;
      else if (known && known->rows() > n && frictions.empty()) p.A = known->topLeftCorner(n, n);
      else p.A = delassus(lines, motion, moving);
      if (known && known->rows() == 0) *known = p.A;
      Eigen::VectorXd held(n);
      for (Eigen::Index k = 0; k < nr; ++k) held[k] = rows[static_cast<std::size_t>(k)].lambda;
      for (std::size_t q = 0; q < frictions.size(); ++q)
        for (int d = 0; d < 2; ++d) held[nr + static_cast<Eigen::Index>(2 * q) + d] = frictions[q].lambda[d];
      p.b = line_velocities(rows, frictions, motion) - p.A * held;  // the velocities with no impulse at all
      p.weight = Eigen::VectorXd::Ones(n);
      p.weight.tail(n - nr).setConstant(kFrictionWeight);
      p.lo = Eigen::VectorXd::Zero(n);
      p.hi = Eigen::VectorXd::Constant(n, std::numeric_limits<double>::infinity());
      for (std::size_t k = 0; k < pull.size(); ++k)
        if (pull[k]) p.lo[static_cast<Eigen::Index>(k)] = -std::numeric_limits<double>::infinity();
      Eigen::VectorXd lambda = held;
      // With friction: a warm start that is already the sweeps' fixed point
      // (a stack at rest, its load carried over) is kept as it is. The box's
      // rounds would move a contact held on its disc's rim into the box's
      // corner, for Newton's method to bring back at every step.
      const bool coulomb = !frictions.empty() && pull.empty();
      const contact::CoulombProblem c = coulomb ? coulomb_problem(p, nr, frictions) : contact::CoulombProblem{};
      const double held_residual = coulomb ? contact::coulomb_residual(c, held) : 0.0;
      if (coulomb && held_residual <= converged) return ++counters.coulomb_exact_starts, true;
      contact::BlcpSettings how;
      how.velocity_tolerance = converged;
      // The lines fall into groups that share no moving body (a static body
      // couples nothing), each solved on its own: smaller factorisations, and a
      // pair's answer does not depend on an unrelated body that shares its island.
      std::vector<Eigen::Index> local(static_cast<std::size_t>(n), -1);
      const std::vector<std::vector<Eigen::Index>> groups = groups_of(lines, moving);
      // A's factor by body, only where a group is large enough to be
      // factorised in the augmented form (lcp.cpp).
      if (std::ranges::any_of(groups, [&](const auto& g) { return static_cast<Eigen::Index>(g.size()) >= how.augmented_from; }))
        p.G = body_factor(lines, motion, moving);
      if (groups.size() == 1) {  // one group holds every line, in order: the problem itself
        for (Eigen::Index i = 0; i < n; ++i) local[static_cast<std::size_t>(i)] = i;
        GroupCounts counts;
        solve_group(p, lambda, groups[0], local, nr, frictions, how, counts);
        solved = add(counts);
      } else {
        // The groups on the run's threads (core/parallel.hpp), in blocks of
        // consecutive groups of kLinesPerBlock lines or more: a group reads
        // only its own lines of p and writes only its own entries of lambda
        // and local, and each block counts into its own slot, added in block
        // order after. The answer is the same for any number of threads.
        std::vector<std::size_t> first{0};  // each block's first group
        for (std::size_t k = 0, lines_in = 0; k < groups.size(); ++k)
          if ((lines_in += groups[k].size()) >= grain_of(kLinesPerBlock) && k + 1 < groups.size())
            first.push_back(k + 1), lines_in = 0;
        first.push_back(groups.size());
        std::vector<GroupCounts> counts(first.size() - 1);
        for_each_index(counts.size(), [&](std::size_t q) {
          for (std::size_t k = first[q]; k < first[q + 1]; ++k) solve_one(p, lambda, groups[k], local, nr, frictions, how, counts[q]);
        }, 1);
        for (const GroupCounts& c : counts) solved = add(c) && solved;
      }
      if (const double exact = coulomb ? polish(c, lambda, held, held_residual, converged) : -1; left) *left = exact;
      for (Eigen::Index k = 0; k < nr; ++k) {
        Row& r = rows[static_cast<std::size_t>(k)];
        if (const double dl = lambda[k] - held[k]; dl != 0) push(r, motion, dl);
        r.lambda = lambda[k];
      }
      for (std::size_t q = 0; q < frictions.size(); ++q)
        for (int d = 0; d < 2; ++d) {
          Friction& f = frictions[q];
          const Eigen::Index k = nr + static_cast<Eigen::Index>(2 * q) + d;
          if (const double dl = lambda[k] - held[k]; dl != 0) push(rows[f.row], f, d, motion, dl);
          f.lambda[d] = lambda[k];
        }
      return solved;
    }
    // The worst violation of the frictionless rows' conditions by the
    // impulses they hold (blcp_residual's measure with lo = 0, hi = ∞): a row
    // that pushes must not move, one that does not must not approach.
    static double held_residual(const std::vector<Row>& rows, const Motions& motion) {
      double worst = 0;
      for (const auto& r : rows) {
        const double w = normal_velocity(r, motion) - r.target;
        worst = std::max(worst, r.lambda > 0 ? std::abs(w) : std::max(0.0, -w));
      }
      return worst;
    }
    // The Coulomb problem of the direct solve's lines (coulomb.hpp): its
    // normal rows first, each friction's two tangents after them.
    static contact::CoulombProblem coulomb_problem(const contact::Blcp& p, Eigen::Index nr,
                                                   const std::vector<Friction>& frictions) {
      contact::CoulombProblem c{p.A, p.b, nr, {}};
      c.discs.reserve(frictions.size());
      for (std::size_t q = 0; q < frictions.size(); ++q)
        c.discs.push_back({nr + static_cast<Eigen::Index>(2 * q), frictions[q].mu,
                           static_cast<Eigen::Index>(frictions[q].pair_begin),
                           static_cast<Eigen::Index>(frictions[q].pair_end)});
      return c;
    }
    // The rounds' answer made exact for Coulomb's disc where it is not yet
    // the sweeps' fixed point (a box's corner outside its disc, rounds whose
    // bounds did not settle), by Newton's method from the rounds' answer or
    // the warm start, whichever is nearer. Kept only if it lowers the
    // residual; the sweeps then finish from whichever answer is better.
    // Returns the residual of Newton's answer where it ran and met the
    // tolerance, else −1.
    double polish(const contact::CoulombProblem& c, Eigen::VectorXd& lambda, const Eigen::VectorXd& held,
                double held_residual, double converged) const {
      const double before = contact::coulomb_residual(c, lambda);
      if (before <= converged) return -1;
      Eigen::VectorXd x = held_residual < before ? held : lambda;
      contact::CoulombSettings how;
      how.velocity_tolerance = converged;
      const contact::CoulombResult r = contact::solve_coulomb(c, x, how);
      ++counters.coulomb_solves;
      counters.coulomb_newton_steps += static_cast<std::uint64_t>(r.iterations);
      if (!r.solved) ++counters.coulomb_unsolved;
      if (r.residual < before) lambda = x;
      return r.solved ? r.residual : -1;
    }
    // What one group's solve adds to the counters, apart from them so that
    // groups can be solved on several threads (direct).
    struct GroupCounts {
      std::uint64_t rounds = 0, pivots = 0, factorisations = 0, updates = 0, augmented = 0, held = 0, proximal = 0,
                    unsolved = 0;
    };
    // Adds c to the counters; whether every round it counts was solved.
    bool add(const GroupCounts& c) const {
      counters.direct_rounds += c.rounds, counters.direct_pivots += c.pivots;
      counters.direct_factorisations += c.factorisations, counters.direct_updates += c.updates;
      counters.direct_augmented += c.augmented, counters.direct_held += c.held;
      counters.direct_proximal += c.proximal, counters.direct_unsolved += c.unsolved;
      return c.unsolved == 0;
    }
    // One group of several (direct): its own problem, the rows and columns of
    // p's lines in it, solved from and into its entries of lambda.
    void solve_one(const contact::Blcp& p, Eigen::VectorXd& lambda, const std::vector<Eigen::Index>& group,
                   std::vector<Eigen::Index>& local, Eigen::Index nr, const std::vector<Friction>& frictions,
                   const contact::BlcpSettings& how, GroupCounts& counts) const {
      const auto m = static_cast<Eigen::Index>(group.size());
      for (Eigen::Index i = 0; i < m; ++i) local[static_cast<std::size_t>(group[static_cast<std::size_t>(i)])] = i;
      // A's block on the group's lines, copied from its compressed storage (no
      // triplets to sort: most groups are a row or two, and sorting was a
      // good part of their solve). Every row of such a column is a line of
      // the group (lines couple only through a moving body they share), and
      // `local` numbers them in line order.
      contact::Blcp g;
      g.A = contact::principal_block(p.A, group, local);
      g.b = p.b(group), g.lo = p.lo(group), g.hi = p.hi(group), g.weight = p.weight(group);
      if (p.G.rows() > 0 && m >= how.augmented_from) {  // the group's rows of G (its bodies' columns)
        std::vector<Eigen::Triplet<double>> gt;
        for (Eigen::Index u = 0; u < m; ++u)
          for (Eigen::SparseMatrix<double, Eigen::RowMajor>::InnerIterator it(p.G, group[static_cast<std::size_t>(u)]); it; ++it)
            gt.emplace_back(u, it.col(), it.value());
        g.G.resize(m, p.G.cols());
        g.G.setFromTriplets(gt.begin(), gt.end());
      }
      Eigen::VectorXd x = lambda(group);
      solve_group(g, x, group, local, nr, frictions, how, counts);
      lambda(group) = x;
    }
    // One group's rounds (see direct): each friction row's box ±μ λ̄_n from
    // the normal impulses of the round before (friction_limit: its pair's
    // mean), solved again until the bounds of the rows that reach them
    // settle, at most kFrictionRounds times.
    void solve_group(contact::Blcp& g, Eigen::VectorXd& x, const std::vector<Eigen::Index>& group,
                     const std::vector<Eigen::Index>& local, Eigen::Index nr, const std::vector<Friction>& frictions,
                     const contact::BlcpSettings& how, GroupCounts& counts) const {
      struct Rub {
        Eigen::Index at;  // a friction line (local)
        const Friction* f;
      };
      std::vector<Rub> rubs;
      for (Eigen::Index i = 0; i < static_cast<Eigen::Index>(group.size()); ++i)
        if (const Eigen::Index line = group[static_cast<std::size_t>(i)]; line >= nr)
          rubs.push_back({i, &frictions[static_cast<std::size_t>((line - nr) / 2)]});
      const auto limit_of = [&](const Rub& u) {
        return friction_limit(*u.f, [&](std::size_t k) { return x[local[k]]; });
      };
      for (int round = 0; round < kFrictionRounds; ++round) {
        // How far the bounds of the rows on them moved (as velocity: Δbound
        // A_ii). A bound matters only where the friction reaches it, and the
        // others need not settle: where friction can move load between
        // supports, λ̄_n is not unique either and wanders at the
        // regularisation's level.
        double moved = 0;
        for (const Rub& u : rubs) {
          const double bound = limit_of(u);
          if (round > 0 && std::abs(x[u.at]) >= g.hi[u.at] * (1 - 1e-9))
            moved = std::max(moved, std::abs(bound - g.hi[u.at]) * g.A.coeff(u.at, u.at));
          // A row inside its old bound that the new one cuts off moved too.
          if (round > 0) moved = std::max(moved, (std::abs(x[u.at]) - bound) * g.A.coeff(u.at, u.at));
          g.lo[u.at] = -bound, g.hi[u.at] = bound;
        }
        if (round > 0 && moved <= how.velocity_tolerance) break;
        const contact::BlcpResult r = contact::solve_blcp(g, x, how);
        ++counts.rounds;
        counts.pivots += static_cast<std::uint64_t>(r.pivots);
        counts.factorisations += static_cast<std::uint64_t>(r.factorisations);
        counts.updates += static_cast<std::uint64_t>(r.updates);
        counts.augmented += static_cast<std::uint64_t>(r.augmented);
        counts.held += static_cast<std::uint64_t>(r.held);
        counts.proximal += static_cast<std::uint64_t>(r.proximal);
        counts.unsolved += !r.solved;
        if (rubs.empty()) break;
      }
    }
    // Slot k's body moves (a static body takes no impulse).
    std::vector<char> moving(BodyIndices world, const std::vector<int>& body_of) const {
      std::vector<char> out(body_of.size());
      for (std::size_t k = 0; k < body_of.size(); ++k) out[k] = !setup.is_static[world[static_cast<std::size_t>(body_of[k])]];
      return out;
    }

    // Warm starting: a contact found again (the same pair, its point within 1 %
    // of the smaller body's size of where it was relative to both centres)
    // starts from the impulse it had, scaled from that step's length to this
    // one's (a resting contact's impulse is its load times the step). A stack
    // then needs a sweep or two per step, not a fresh solve through every box.
    // A friction row starts from the remembered friction impulse's parts along
    // its tangents, held in the disc of its pair's warm-started normal impulses.
    void warm_start(std::vector<Row>& rows, std::vector<Friction>& frictions, Motions& motion, double dt) const {
      if (cache_.empty() || !(dt > 0)) return;
      std::vector<const Cached*> found(rows.size(), nullptr);  // each row's remembered impulses
      auto pair = cache_.end();  // the pair of the row before: a pair's rows are consecutive
      std::uint64_t looked = 0;
      for (std::size_t k = 0; k < rows.size(); ++k) {
        Row& r = rows[k];
        if (k == 0 || key(r.a, r.b) != looked) looked = key(r.a, r.b), pair = cache_.find(looked);
        if (pair == cache_.end() || !live(pair->second, live_from)) continue;
        const double near = 1e-2 * std::min(setup.meshes[r.a]->size(), setup.meshes[r.b]->size());
        double closest = near;
        for (const auto& c : pair->second.at) {
          const double dist = std::max((c.ra - r.ra).norm(), (c.rb - r.rb).norm());
          if (dist < closest) closest = dist, found[k] = &c;
        }
        if (!found[k]) continue;
        r.lambda = found[k]->rate * dt;
        push(r, motion, r.lambda);
        ++counters.warm_started;
      }
      // Friction after every normal row: its disc is its pair's (friction_limit).
      for (Friction& f : frictions) {
        const Cached* best = found[f.row];
        if (!best) continue;
        const Vec3 j = best->friction_rate * dt;
        std::array<double, 2> l{j.dot(f.t[0]), j.dot(f.t[1])};
        const double size = std::hypot(l[0], l[1]), limit = friction_limit(f, rows);
        if (size > limit) l[0] *= limit / size, l[1] *= limit / size;
        for (int d = 0; d < 2; ++d) f.lambda[d] = l[d], push(rows[f.row], f, d, motion, l[d]);
        counters.friction_warm_started += size > 0;
      }
    }
    // The impulses of this solve replace what its pairs had; other pairs (other
    // islands) keep theirs until forget_old_contacts. A pair's entry is
    // emptied, not erased, so that its storage serves the next step (an
    // empty entry warm starts nothing, as a missing one).
    void remember(std::span<const PairHit> hits, BodyIndices world, const std::vector<Row>& rows,
                  const std::vector<Friction>& frictions, double dt) const {
      for (const auto& h : hits)
        if (const auto it = cache_.find(key(world[h.a], world[h.b])); it != cache_.end()) it->second.at.clear();
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
    //
    // That force acted through the whole step only if the contact was closed
    // from its start. A body that began the step above its support (by up to
    // ½ g h², 4.9e-6 m at 1 ms) fell onto it within the step, and the force
    // acted only after that: displaced by the whole ½ dt Δv it went back up
    // to where it began, above the support, and hovered there at rest, step
    // after step, since every height up to ½ g h² above the support is a
    // fixed point of that scheme. So where the displacement would leave a
    // resting pair of a moving body and a static one apart at every point,
    // the moving body is lowered along the normal until its deepest point
    // touches: where a body that fell onto its support and stopped there
    // ends. (Between two moving bodies that is left alone: which of the two
    // should give way is the whole stack's question, and no family member
    // has needed it.) `correct`: the pairs the projection moved, whose
    // detected depths are no longer theirs.
    void friction_displacement(const Model& m, std::span<double> y, const std::vector<Row>& rows,
                               const std::vector<Friction>& frictions, const Motions& motion,
                               const std::vector<int>& body_of, const std::vector<char>& correct, double dt) const {
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
      struct Lowering {
        std::size_t slot;
        Vec3 by;
      };
      std::vector<Lowering> lower;
      for (const auto& f : frictions) {
        if (f.row != f.pair_begin) continue;  // once per pair: its rows are [pair_begin, pair_end), all with friction
        const Row& first = rows[f.pair_begin];
        const bool a_static = setup.is_static[static_cast<std::size_t>(first.a)];
        bool resting = a_static != setup.is_static[static_cast<std::size_t>(first.b)] && !correct[first.hit];
        double end = -std::numeric_limits<double>::infinity();  // the deepest point's depth after the displacement
        for (std::size_t j = f.pair_begin; j < f.pair_end && resting; ++j) {
          const Row& r = rows[j];
          resting = r.friction >= 0 && !frictions[static_cast<std::size_t>(r.friction)].impact;
          end = std::max(end, r.depth - normal_velocity(r, pseudo));
        }
        // The hover's range only: above rounding, and at most ½ g h². A landing's
        // impulse leaves larger gaps (up to ½ dt v_rest); lowering those too
        // changed every friction pyramid's landings, and Newton's method then
        // stalled on some (docs/collision-response.md).
        const double size = std::max(setup.meshes[static_cast<std::size_t>(first.a)]->size(),
                                     setup.meshes[static_cast<std::size_t>(first.b)]->size());
        if (!resting || !(-end > 1e-12 * size) || !(-end <= 0.5 * setup.gravity * dt * dt)) continue;
        // n runs from a to b: b comes down along −n, a along +n.
        if (a_static) lower.push_back({first.sb, Vec3(end * first.n)});
        else lower.push_back({first.sa, Vec3(-end * first.n)});
      }
      for (const Lowering& l : lower) {
        const double by = l.by.norm();
        const Vec3 along = l.by / by;
        const auto arm = Bodies::arm(motion[l.slot], Bodies::position(motion[l.slot]), along);  // through the centre
        const double w = Bodies::inverse_effective_mass(motion[l.slot], arm);  // 1/M
        if (w > 0) Bodies::push(pseudo[l.slot], arm, along, by / w);  // a translation by `by`
      }
      counters.friction_lowerings += lower.size();
      displace(m, y, body_of, pseudo);
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
    // `moves` (the direct method's moving slots, or empty): the rows solved
    // at once before the sweeps (push_out).
    void correct_positions(const Model& m, std::span<double> y, const std::vector<Row>& rows, const Motions& motion,
                           const std::vector<int>& body_of, const std::vector<char>& correct,
                           const std::vector<char>& moves = {}, const std::vector<Row>& pivots = {}) const {
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
      for (Row p : pivots) {  // each a vertex of its own, with its arms
        p.lambda = 0;
        p.target = std::max(0.0, p.depth - 0.25 * tol);
        fix.push_back(p);
      }
      Motions pseudo;
      pseudo.reserve(motion.size());
      for (const auto& mo : motion) pseudo.push_back(Bodies::at_rest(mo));
      if (!moves.empty()) {
        std::vector<Friction> none;
        direct(fix, none, pseudo, moves, 1e-9 * tol);  // well within the sweeps' tolerance, as the projection's
      }
      solve(fix, pseudo, 1e-6 * tol, counters.correction_cap_hits);  // m: a millionth of the tolerance, see above
      displace(m, y, body_of, pseudo);
      for (std::size_t hi = 0; hi < correct.size(); ++hi) counters.corrections += correct[hi];
    }

    // Each slot's body moved by its pseudo-motion: on the run's threads, each
    // slot writing its own body's state (a pair's grain, as gather's motions).
    static void displace(const Model& m, std::span<double> y, const std::vector<int>& body_of, const Motions& pseudo) {
      for_each_index(pseudo.size(), [&](std::size_t k) {
        Bodies::displace(m, y, static_cast<std::size_t>(body_of[k]), pseudo[k]);
      }, kGrainPair);
    }
    // Whether a projection would only lift resting pairs back to tol/4 as a
    // whole: no pair to correct, and each resting pair's points at one depth
    // (within kProjectSpread tol). The projection is what keeps a face's
    // corners level (lcp.hpp: a spread tilts the face, and the load then
    // pushes sideways); a depth common to a pair's points tilts nothing and
    // the band (0, tol/2] allows it. A stack at rest sinks as a whole, by
    // ½|g|h² a step, so it is projected once in a few steps, not at every one.
    static bool projection_idle(const std::vector<Row>& rows, const std::vector<char>& correct,
                                const std::vector<char>& resting, double tol) {
      if (std::find(correct.begin(), correct.end(), 1) != correct.end()) return false;
      std::vector<double> lo(correct.size(), INFINITY), hi(correct.size(), -INFINITY);
      for (const auto& r : rows) lo[r.hit] = std::min(lo[r.hit], r.depth), hi[r.hit] = std::max(hi[r.hit], r.depth);
      for (std::size_t h = 0; h < correct.size(); ++h)
        if (resting[h] && hi[h] - lo[h] > kProjectSpread * tol) return false;
      return true;
    }
    // The positional correction of the direct solver: a projection, at every
    // step that is not idle (projection_idle), of every frictionless pair in resting contact (a row with an
    // impulse in the velocity solve, the pair not parting) to the depth tol/4 at each of its
    // points, pulling as well as pushing (bilateral rows), with the other rows
    // of a pair deeper than tol/2 pushed to tol/4 and every other row kept
    // from getting deeper. A tolerance band lets a resting contact sit
    // anywhere in (0, tol]; a body on two supports whose depths differ in the
    // band is tilted by up to tol / size, a tilted face's normal pushes
    // sideways, and a frictionless wall pyramid spread apart at 3.5 mm/s in
    // 10 s with the pushing correction alone. Projected, every resting face
    // of a stack sits at the same depth, level. The bodies move; their momenta
    // do not (pseudo-velocities, as in the split impulse).
    // A projection is a small move: no point of any body further than twice
    // the tolerance (a resting depth is at most tol; a body on a point may turn
    // a little more), each bilateral row within tol/4 of its target. Where the resting pairs ask
    // for what no rigid move gives (a body on supports that are not level
    // with each other), the least-squares answer can be large; it is then
    // dropped for the pushing correction alone, and counted
    // (projections_refused).
    // `a`: the velocity solve's Delassus matrix (direct), whose normal rows
    // are these rows with the same arms: the projection's matrix, not built
    // again; or empty where that solve kept its warm start without one, and
    // then built here.
    void project_positions(const Model& m, std::span<double> y, BodyIndices world, const std::vector<Row>& rows,
                           const Motions& motion, const std::vector<int>& body_of, const std::vector<char>& correct,
                           const std::vector<char>& parting, const std::vector<char>& moves,
                           Eigen::SparseMatrix<double>& a) const {
      const double tol = setup.settings.penetration_tolerance, settle = 0.25 * tol;
      // Frictionless pairs only: friction holds a body against the sideways
      // push a tilt gives, and projecting a pair with friction moved what its
      // friction holds still (a box sticking on an incline crept 2e-5 m).
      std::vector<char> resting(correct.size(), 0), rubbing(correct.size(), 0);
      for (const auto& r : rows) rubbing[r.hit] |= r.friction >= 0;
      for (const auto& r : rows) resting[r.hit] |= r.lambda > 0 && !parting[r.hit] && !rubbing[r.hit];
      std::vector<Row> fix;
      std::vector<char> pull, touched(correct.size(), 0);
      fix.reserve(rows.size()), pull.reserve(rows.size());
      for (const auto& r : rows) {
        Row p = r;
        p.lambda = 0;
        p.target = resting[r.hit] ? r.depth - settle : correct[r.hit] ? std::max(0.0, r.depth - settle) : 0.0;
        touched[r.hit] |= resting[r.hit] || correct[r.hit];
        pull.push_back(resting[r.hit]);
        fix.push_back(p);
      }
      if (std::find(touched.begin(), touched.end(), 1) == touched.end()) return;
      if (projection_idle(rows, correct, resting, tol)) return ++counters.projections_skipped, void();
      const auto project = [&](const std::vector<char>& bilateral) {
        Motions pseudo;
        pseudo.reserve(motion.size());
        for (const auto& mo : motion) pseudo.push_back(Bodies::at_rest(mo));
        for (auto& f : fix) f.lambda = 0;
        std::vector<Friction> none;
        // Solved to a billionth of the tolerance; the sweeps cannot pull, so
        // they only finish a solve the direct method left unsolved (counted).
        if (!direct(fix, none, pseudo, moves, 1e-9 * tol, bilateral, &a))
          solve(fix, pseudo, 1e-6 * tol, counters.correction_cap_hits);
        return pseudo;
      };
      Motions pseudo = project(pull);
      bool small = true;
      for (std::size_t k = 0; k < fix.size(); ++k) {
        const double moved = normal_velocity(fix[k], pseudo);
        small &= std::abs(moved) <= 2 * tol && (!pull[k] || std::abs(moved - fix[k].target) <= 0.25 * tol);
      }
      for (std::size_t k = 0; k < pseudo.size(); ++k) {  // no point of any body moved by more than 2 tol
        const double half = 0.5 * setup.meshes[static_cast<std::size_t>(world[static_cast<std::size_t>(body_of[k])])]->size();
        small &= Bodies::speed(pseudo[k]) + half * Bodies::angular_speed(pseudo[k]) <= 2 * tol;
      }
      if (!small) {
        ++counters.projections_refused;
        pseudo = project(std::vector<char>(fix.size(), 0));
      }
      displace(m, y, body_of, pseudo);
      for (const char t : touched) counters.corrections += t;
    }

    // The bodies of `hits` read once, in slots the rows index (no lookup in
    // the solver's sweeps), and a row per contact point with its geometry:
    // normal, arms, effective mass and depth; `point` holds each row's point.
    // The velocity and friction parts are the response's.
    struct Gathered {
      Motions motion;
      std::vector<int> body_of;  // slot → body of the group
      std::vector<Row> rows;
      std::vector<Vec3> point;
    };
    Gathered gather(const Model& m, std::span<const double> y, BodyIndices world, std::span<const PairHit> hits) const {
      constexpr std::size_t kNone = std::numeric_limits<std::size_t>::max();
      Gathered g;
      // Body of the group → slot: a table per thread, kept between calls and
      // cleared where it was written. A fresh table the size of the group at
      // every call filled 80 KB for each island's response in a 10,000-body
      // world, where the island has a few bodies.
      thread_local std::vector<std::size_t> slot_of;
      if (slot_of.size() < world.size()) slot_of.resize(world.size(), kNone);
      struct Cleared {  // on the way out of the block below, an exception's too
        std::vector<std::size_t>& table;
        const std::vector<int>& written;
        ~Cleared() {
          for (const int b : written) table[static_cast<std::size_t>(b)] = kNone;
        }
      };
      // Slots in the order the hits first name their bodies, and each hit's
      // first row, on this thread; the motions and rows, a few hundred
      // nanoseconds each, on the run's threads (a pile's island has
      // thousands), each into its own slot.
      std::vector<std::size_t> sa(hits.size()), sb(hits.size()), first(hits.size() + 1, 0);
      {
        const Cleared cleared{slot_of, g.body_of};
        const auto slot = [&](int b) {
          std::size_t& s = slot_of[static_cast<std::size_t>(b)];
          if (s == kNone) s = g.body_of.size(), g.body_of.push_back(b);
          return s;
        };
        for (std::size_t hi = 0; hi < hits.size(); ++hi) {
          sa[hi] = slot(hits[hi].a), sb[hi] = slot(hits[hi].b);
          first[hi + 1] = first[hi] + hits[hi].features.size();
        }
      }
      g.motion.resize(g.body_of.size());
      // A pair's grain, not a body's: a pile's push-out names a thousand or
      // two bodies at each pass, which kGrainBody left on one thread; on the
      // 10,000-body box's pile at 0.9 s (two threads, three alternated runs)
      // the response stage went from 1.51-1.85 s to 1.39-1.73 s.
      for_each_index(g.body_of.size(), [&](std::size_t s) {
        g.motion[s] = Bodies::motion(m, y, static_cast<std::size_t>(g.body_of[s]));
      }, kGrainPair);
      g.rows.resize(first.back());
      g.point.resize(first.back());
      std::vector<char> kept(first.back());
      for_each_index(hits.size(), [&](std::size_t hi) {
        const auto& h = hits[hi];
        const Motion& ma = g.motion[sa[hi]];
        const Motion& mb = g.motion[sb[hi]];
        for (std::size_t f = 0; f < h.features.size(); ++f) {
          const auto& c = h.features[f];
          Row& r = g.rows[first[hi] + f];
          r = Row{world[h.a], world[h.b], sa[hi], sb[hi], hi, c.normal, c.point - Bodies::position(ma),
                  c.point - Bodies::position(mb), Bodies::arm(ma, c.point, c.normal), Bodies::arm(mb, c.point, c.normal),
                  0, 0, 0, 0, c.depth};
          r.k = Bodies::inverse_effective_mass(ma, r.arm_a) + Bodies::inverse_effective_mass(mb, r.arm_b);
          kept[first[hi] + f] = r.k > 0;
          g.point[first[hi] + f] = c.point;
        }
      }, kGrainPair);
      // A row with no effective mass (two static bodies' contact) is left out.
      if (std::ranges::find(kept, char{0}) != kept.end()) {
        std::size_t w = 0;
        for (std::size_t k = 0; k < kept.size(); ++k)
          if (kept[k]) g.rows[w] = g.rows[k], g.point[w] = g.point[k], ++w;
        g.rows.resize(w), g.point.resize(w);
      }
      return g;
    }

    // A pair pushed out through one or two points pivots about them: the
    // correction lifts the point, a turn does most of that (a small body's
    // turn costs less than its translation), and the turn lowers the body's
    // other vertices into the other body. The manifold holds only what
    // touches, so nothing held them: in the 10,000-body box without a search
    // a vertex 1.7 mm into a wall was left 0.85 mm deep, the next pass halved
    // that again, and pairs stayed millimetres deep after the last pass; an
    // edge–edge pair likewise. So each vertex that the turn could bring into
    // the pair's overlap gets a row of its own, at its depth in the slab
    // the two bodies overlap in along n: the part of a past the lowest point
    // of b, n·p − (n·x − d/2), and of b below the highest of a,
    // (n·x + d/2) − n·q (x the contact point, midway, d its depth). Pushed
    // to tol/4 where it is in, held from approaching where it is not (the
    // slab is wider than b, so this asks more than the bodies need, never
    // what no move gives: lifting the whole body along n meets every row).
    // A vertex contact's own body is left out for the face's: the face is
    // flat, and its corners lie in the slab without touching anything.
    std::vector<Row> pivot_rows(const Model& m, std::span<const double> y, std::span<const PairHit> hits,
                                const Gathered& g, const std::vector<char>& correct) const {
      const double tol = setup.settings.penetration_tolerance;
      std::vector<std::size_t> first(hits.size(), g.rows.size());
      for (std::size_t k = g.rows.size(); k-- > 0;) first[g.rows[k].hit] = k;
      std::vector<Row> out;
      for (std::size_t hi = 0; hi < hits.size(); ++hi) {
        const auto& fs = hits[hi].features;
        if (!correct[hi] || fs.empty() || fs.size() >= 3 || first[hi] == g.rows.size()) continue;
        const collision::Feature kind = fs[0].feature;
        if (kind == collision::Feature::none || std::ranges::any_of(fs, [&](const auto& f) { return f.feature != kind; }))
          continue;
        const Row& r = g.rows[first[hi]];
        const auto deepest = std::ranges::max_element(fs, {}, [](const auto& f) { return f.depth; });
        const Vec3 n = deepest->normal;  // from a to b
        const double mid = n.dot(deepest->point), d = deepest->depth, reach = 2 * d + tol;
        const auto& ma = g.motion[r.sa];
        const auto& mb = g.motion[r.sb];
        // The vertices of one body (on_a: a's) with their depths in the slab.
        const auto scan = [&](bool on_a) {
          const auto& mesh = *setup.meshes[static_cast<std::size_t>(on_a ? r.a : r.b)];
          if (mesh.is_round()) return;
          const collision::Pose pose = Bodies::pose(m, y, static_cast<std::size_t>(g.body_of[on_a ? r.sa : r.sb]));
          for (const Vec3& local : mesh.vertices()) {
            const Vec3 u = pose.apply(local);
            const double depth = on_a ? n.dot(u) - (mid - 0.5 * d) : (mid + 0.5 * d) - n.dot(u);
            if (!(depth > -reach)) continue;
            // A vertex of the manifold (half its depth behind its point) has its row.
            const bool held = kind != collision::Feature::edge_edge && std::ranges::any_of(fs, [&](const auto& f) {
              return (f.point + (on_a ? 0.5 : -0.5) * f.depth * n - u).norm() <= 1e-9 * mesh.size();
            });
            if (held) continue;
            Row p{r.a, r.b, r.sa, r.sb, hi, n, u - Bodies::position(ma), u - Bodies::position(mb),
                  Bodies::arm(ma, u, n), Bodies::arm(mb, u, n), 0, 0, 0, 0, depth};
            p.k = Bodies::inverse_effective_mass(ma, p.arm_a) + Bodies::inverse_effective_mass(mb, p.arm_b);
            if (p.k > 0) out.push_back(p);
          }
        };
        if (kind != collision::Feature::face_a) scan(true);   // a's vertices: in b's face, or an edge's
        if (kind != collision::Feature::face_b) scan(false);  // b's
      }
      return out;
    }

    // The positional correction alone, for pairs a response left deeper than
    // the tolerance (core/collision/push_out_step.hpp): each such pair pushed
    // to tol/4, every other pair of `hits` held from approaching. No impulse
    // and no warm start: the velocities are the response's.
    // With the direct method the correction is solved at once, as the
    // response's projection is, and the sweeps only check it: in a pile the
    // correction's rows hold each other through thousands of bodies, and the
    // sweeps ran to their cap of 1,000 on them (70 times in a second of the
    // 10,000-body box, where nine tenths of the sweeps' row updates were in
    // solves of 1,000 to 4,000 rows). Both reach the
    // same motion of the bodies, to the tolerance: every solution λ of the
    // problem moves them alike (A = J M⁻¹ Jᵀ is positive semi-definite, so
    // A λ, and with it M⁻¹ Jᵀ λ, is the same for all).
    void push_out(const Model& m, std::span<double> y, BodyIndices world, std::span<const PairHit> hits,
                  Profile& profile) const {
      ScopedStage timed(profile, Stage::response);
      const Gathered g = gather(m, y, world, hits);
      std::vector<char> correct(hits.size(), 0);
      for (std::size_t hi = 0; hi < hits.size(); ++hi) correct[hi] = hits[hi].sat.depth > setup.settings.penetration_tolerance;
      const bool direct_solve = setup.settings.contact_solver == ContactSolverMethod::direct;
      correct_positions(m, y, g.rows, g.motion, g.body_of, correct, direct_solve ? moving(world, g.body_of) : std::vector<char>{},
                        pivot_rows(m, y, hits, g, correct));
    }

    void respond(const Model& m, std::span<double> y, BodyIndices world, std::span<const PairHit> hits, double dt,
                 Profile& profile) const {
      ScopedStage timed(profile, Stage::response);
      Gathered g = gather(m, y, world, hits);
      Motions& motion = g.motion;
      const std::vector<int>& body_of = g.body_of;
      std::vector<Row>& rows = g.rows;
      std::vector<Friction> frictions;  // none unless a pair has μ > 0
      std::vector<char> resting_pair(hits.size(), 0);
      // Each pair's contact plane: through its points' centroid, normal to n.
      std::vector<Vec3> centre(hits.size(), Vec3::Zero());
      for (std::size_t hi = 0; hi < hits.size(); ++hi) {
        for (const auto& c : hits[hi].features) centre[hi] += c.point;
        if (!hits[hi].features.empty()) centre[hi] /= static_cast<double>(hits[hi].features.size());
      }
      for (std::size_t k = 0; k < rows.size(); ++k) {
        Row& r = rows[k];
        const double eps = std::min(setup.restitution[r.a], setup.restitution[r.b]);
        // Box2D's mixing rule, √(μ_a μ_b) (Bullet multiplies by default; its run
        // is hooked to the same √, compare/bullet_world.cpp).
        const double mu = std::sqrt(setup.friction[r.a] * setup.friction[r.b]);
        r.before = normal_velocity(r, motion);
        const bool resting = r.before < 0 && -r.before <= setup.resting_speed;
        counters.resting_contacts += resting;
        resting_pair[r.hit] |= resting;
        r.target = r.before < 0 ? -(resting ? 0.0 : eps) * r.before : 0.0;
        if (mu > 0) r.friction = static_cast<std::ptrdiff_t>(frictions.size()),
                    frictions.push_back(friction_row(k, r, in_plane_of(g.point[k], r.n, centre[r.hit]), mu, motion));
      }
      for (std::size_t k = 0, begin = 0; k < rows.size(); ++k)  // each pair's rows are consecutive
        if (k + 1 == rows.size() || rows[k + 1].hit != rows[k].hit) {
          for (std::size_t j = begin; j <= k; ++j)
            if (rows[j].friction >= 0) frictions[static_cast<std::size_t>(rows[j].friction)].pair_begin = begin,
                                       frictions[static_cast<std::size_t>(rows[j].friction)].pair_end = k + 1;
          begin = k + 1;
        }
      counters.contacts += rows.size();
      counters.friction_contacts += frictions.size();
      warm_start(rows, frictions, motion, dt);
      double scale = 0;
      for (const auto& r : rows) scale = std::max(scale, std::abs(r.target));
      for (const auto& f : frictions) scale = std::max(scale, std::hypot(f.slip[0], f.slip[1]));
      const double converged = kVelocityTolerance * (1 + scale);
      const bool direct_solve = setup.settings.contact_solver == ContactSolverMethod::direct;
      const std::vector<char> moves = direct_solve ? moving(world, body_of) : std::vector<char>{};
      Eigen::SparseMatrix<double> a;  // the direct solve's Delassus matrix, for its projection
      // Where Newton's method made the direct solve's answer exact (coulomb.hpp),
      // its residual as the sweeps measure it; else −1. Such an answer is the
      // sweeps' fixed point and they are not run: near a contact between
      // sticking and sliding that fixed point can repel Gauss–Seidel (from
      // answers 1e-12 inside the tolerance the sweeps drifted out and ran to
      // their cap on the friction pyramids). Every other answer is finished
      // by the sweeps as before.
      double left = -1;
      if (direct_solve) direct(rows, frictions, motion, moves, converged, {}, &a, &left);
      if (left >= 0) counters.add_residual(left);
      else counters.add_residual(solve(rows, motion, converged, counters.sweep_cap_hits, frictions));
      // Sliding: friction on the rim of its disc and the contact still slipping
      // after the solve. (On the rim alone is not sliding: the corners of a face
      // that sticks share its load in no unique way, and the direct solve may
      // leave a lightly loaded corner's friction on its rim.)
      for (const auto& f : frictions) {
        const Row& r = rows[f.row];
        const double limit = friction_limit(f, rows);
        const bool rim = std::hypot(f.lambda[0], f.lambda[1]) >= limit * (1 - 1e-9) && limit > 0;
        const double slip = std::hypot(tangent_velocity(r, f, 0, motion), tangent_velocity(r, f, 1, motion));
        counters.sliding_contacts += rim && slip > converged;
      }
      for (const auto& r : rows) {
        counters.impulses += r.lambda > 0;
        // An impact whose approach the solve did not stop (to 0.1 % of its speed).
        if (r.before < -setup.resting_speed && normal_velocity(r, motion) < 1e-3 * r.before) ++counters.unresolved_impacts;
      }
      remember(hits, world, rows, frictions, dt);
      // The pairs whose depth is corrected: deeper than tol/2, and resting or
      // not parting by themselves; and every pair deeper than tol. A pair in
      // the band that parts after an impact is left alone: the impact
      // conserves momenta exactly, and the depth goes with it. A pair beyond
      // the band was not found by a search (a body an impulse made faster than
      // its reach met one it was not linked to, collision_step.hpp): parting
      // slowly, it stayed millimetres deep for many steps.
      const double tol = setup.settings.penetration_tolerance;
      std::vector<char> correct(hits.size(), 0), parting(hits.size(), 1);
      for (const auto& r : rows) parting[r.hit] &= normal_velocity(r, motion) > setup.resting_speed;
      for (std::size_t hi = 0; hi < hits.size(); ++hi)
        correct[hi] = hits[hi].sat.depth > tol || (hits[hi].sat.depth > 0.5 * tol && (resting_pair[hi] || !parting[hi]));
      for (std::size_t k = 0; k < motion.size(); ++k) Bodies::store(m, y, static_cast<std::size_t>(body_of[k]), motion[k]);
      if (direct_solve) project_positions(m, y, world, rows, motion, body_of, correct, parting, moves, a);
      else correct_positions(m, y, rows, motion, body_of, correct);
      friction_displacement(m, y, rows, frictions, motion, body_of, correct, dt);
    }
  };
};

}  // namespace gacompare::core
