// The degenerate-contact family: the analytic outcome of
// each kind of case and the verdict on a run. Every outcome is computed from the
// scene handed in (masses from the exact mass properties, ε, initial states), so
// the same code judges a generated case and a bundled scene file.
//
// Tolerances, each with its reason:
//   1e-3 m/s   velocities after slides, rows and bounces: the bound. It
//              also bounds lateral velocity and spin (as the speed of the
//              body's farthest vertex), since an impulse along x between
//              face-aligned boxes has no other component.
//   1e-6       relative change of momentum (and of kinetic energy at ε = 1):
//              the bound; the impulses are equal and opposite, so only
//              the impulse solver's convergence and rounding remain.
//   [0, tol]   the penetration of a resting contact (tol: the scene's
//              penetration tolerance): the issue's "rest heights within the
//              penetration tolerance", read per interface, so box k of a stack
//              rests within k·tol below its analytic height and never above it
//              (1e-9 m of gap is allowed for rounding).
//   tol / d    the tilt of a resting box (d: its bottom face's diagonal): a face
//              whose corners all lie within [0, tol] of the support is tilted
//              by at most that.
//   1e-6 m     lateral drift of a resting box, at every sample: the issue's.
//   1e-6 m/s   speed (and farthest-vertex speed from spin) of a resting box.
#include "answers/contact_family.hpp"
#include "core/model/model.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <algorithm>
#include <cmath>
#include <limits>
#include <optional>
#include <sstream>
#include <stdexcept>

namespace gacompare::core {
namespace {

constexpr double kVelocity = 1e-3;   // m/s
constexpr double kConserved = 1e-6;  // relative
constexpr double kDrift = 1e-6;      // m
constexpr double kRestSpeed = 1e-6;  // m/s
constexpr double kGapAllowed = 1e-9; // m: rounding of positions near 1 m

// Messages by a stream, not by std::string's operator+: GCC 12 misreads a
// chain that starts with a literal as an overlapping memcpy (-Wrestrict, bug 105651).
template <class... T>
std::string cat(const T&... parts) {
  std::ostringstream o;
  o.precision(4);
  (o << ... << parts);
  return o.str();
}

std::string vec(const Vec3& v) { return cat("(", v.x(), ", ", v.y(), ", ", v.z(), ")"); }

// The largest error / tolerance over all checks, and what it was.
class Checks {
 public:
  // error ≥ 0 against tol > 0; `what` is called only when this check is the worst so far.
  template <class What>
  void within(double error, double tol, const char* unit, What&& what) {
    record(std::isnan(error) ? INFINITY : error / tol, error, unit, what);
  }
  // value in [lo, hi]. Inside counts as no error at all (ratio 0); outside, the
  // error is the distance to the interval and the ratio 1 + distance / half width.
  template <class What>
  void inside(double value, double lo, double hi, const char* unit, What&& what) {
    const double out = std::max({0.0, lo - value, value - hi});
    const double ratio = std::isnan(value) ? INFINITY : out > 0 ? 1 + out / (0.5 * (hi - lo)) : 0;
    record(ratio, std::isnan(value) ? value : out, unit, [&] {
      return cat(what(), " = ", value, " ", unit, ", expected in [", lo, ", ", hi, "]");
    });
  }
  ContactVerdict done() {
    v_.pass = v_.ratio <= 1;
    v_.unit = unit_;  // copied once here: assigned in record(), GCC 12 warns falsely (-Wrestrict, bug 105651)
    return v_;
  }

 private:
  template <class What>
  void record(double ratio, double error, const char* unit, What&& what) {
    const bool fails = !(ratio <= 1), worst = first_ || ratio > v_.ratio;
    if (!worst && !(fails && v_.first_failure.empty())) return;
    std::string said = what();
    if (fails && v_.first_failure.empty()) v_.first_failure = said;
    if (!worst) return;
    first_ = false;
    v_.ratio = ratio, v_.error = error, unit_ = unit, v_.reason = std::move(said);
  }
  bool first_ = true;
  const char* unit_ = "";
  ContactVerdict v_;
};

Vec3 half_sides(const Body& b) {
  const auto* box = std::get_if<BoxShape>(&b.shape);
  if (!box) throw std::invalid_argument(cat("body '", b.name, "' is not a box"));
  return box->size / 2;
}
double half_height(const Body& b, const Eigen::Vector4d& q) { return rotation_matrix(q).row(2).cwiseAbs().dot(half_sides(b)); }
// The speed that spin gives the body's farthest vertex.
double rim_speed(const Body& b, const BodySample& s) { return s.angular_velocity.norm() * half_sides(b).norm(); }
double tilt(const BodySample& s) { return std::acos(std::min(1.0, rotation_matrix(s.orientation).row(2).cwiseAbs().maxCoeff())); }

const Collisions& collisions(const Scene& s) {
  const auto* c = s.find_effect<Collisions>();
  if (!c) throw std::invalid_argument("no collisions effect");
  return *c;
}
double restitution(const Scene& s, std::size_t i, std::size_t j) {
  const double e = collisions(s).restitution;
  return std::min(s.bodies[i].restitution.value_or(e), s.bodies[j].restitution.value_or(e));
}
std::vector<std::size_t> bodies(const Scene& s, bool fixed) {
  std::vector<std::size_t> out;
  for (std::size_t k = 0; k < s.bodies.size(); ++k)
    if (s.bodies[k].is_static == fixed) out.push_back(k);
  return out;
}

// --- slide: the 1-D impact law along x --------------------------------------------
struct Slide {
  std::size_t a = 0, b = 0;
  std::optional<std::size_t> floor;
  double va = 0, vb = 0;           // x velocities after the impact
  double spin_a = 0, spin_b = 0;   // allowed farthest-vertex speeds (m/s)
};

Slide slide_answer(const Scene& s) {
  const auto moving = bodies(s, false), fixed = bodies(s, true);
  if (moving.size() != 2 || fixed.size() > 1) throw std::invalid_argument("a slide has two moving bodies and at most a floor");
  Slide r;
  r.a = moving[0], r.b = moving[1];
  if (!fixed.empty()) r.floor = fixed[0];
  const Model model = compile(s);
  const std::vector<BodyModel>& props = model.bodies;
  const double ma = props[r.a].mass, mb = props[r.b].mass, e = restitution(s, r.a, r.b);
  const double ua = s.bodies[r.a].velocity.x(), ub = s.bodies[r.b].velocity.x(), p = ma * ua + mb * ub;
  r.va = (p - e * mb * (ua - ub)) / (ma + mb);
  r.vb = (p + e * ma * (ua - ub)) / (ma + mb);
  // The impulse J acts along x somewhere in the shared face. With b offset
  // laterally by δ, no line along x passes through both centres, so a spin of
  // up to J δ / I_min is physics, not error (δ = 2e-4 m: 5e-3 m/s at the rim).
  const double impulse = ma * std::abs(r.va - ua);
  const Vec3 d = s.bodies[r.b].position - s.bodies[r.a].position;
  const double delta = r.floor ? std::abs(d.y()) : std::hypot(d.y(), d.z());
  auto allowance = [&](std::size_t k) {
    const double i_min = Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d>(props[k].inertia).eigenvalues().minCoeff();
    return kVelocity + impulse * delta / i_min * half_sides(s.bodies[k]).norm();
  };
  r.spin_a = allowance(r.a), r.spin_b = allowance(r.b);
  return r;
}

// Penetration of a box into the floor's or the support's top (positive: into it).
double penetration(const Scene& s, const Sample& x, std::size_t below, std::size_t k) {
  const auto& lo = x.bodies[below];
  const auto& hi = x.bodies[k];
  return (lo.position.z() + half_height(s.bodies[below], lo.orientation)) -
         (hi.position.z() - half_height(s.bodies[k], hi.orientation));
}

void check_slide(const Scene& s, const Run& run, Checks& c) {
  const Slide r = slide_answer(s);
  const Sample& first = run.samples.front();
  const Sample& last = run.samples.back();
  for (const bool is_a : {true, false}) {
    const std::size_t k = is_a ? r.a : r.b;
    const double v = is_a ? r.va : r.vb, spin = is_a ? r.spin_a : r.spin_b;
    const auto& body = last.bodies[k];
    const std::string& name = s.bodies[k].name;
    c.within(std::abs(body.velocity.x() - v), kVelocity, "m/s", [&] {
      return cat(name, " v_x = ", body.velocity.x(), " m/s, expected ", v, " ± ", kVelocity);
    });
    const double lateral = std::hypot(body.velocity.y(), body.velocity.z());
    c.within(lateral, kVelocity, "m/s", [&] { return cat(name, " lateral speed ", lateral, " m/s, expected 0"); });
    c.within(rim_speed(s.bodies[k], body), spin, "m/s",
             [&] { return cat(name, " spins: vertex speed ", rim_speed(s.bodies[k], body), " m/s, allowed ", spin); });
    if (r.floor)
      for (const auto& x : run.samples)
        c.inside(penetration(s, x, *r.floor, k), -kGapAllowed, collisions(s).penetration_tolerance, "m",
                 [&] { return cat(name, " into the floor at t=", x.t); });
  }
  // Momentum along the floor (x, y) is conserved: the floor pushes along z only.
  Vec3 dp = last.linear_momentum - first.linear_momentum;
  if (r.floor) dp.z() = 0;
  const double rel = dp.norm() / first.linear_momentum.norm();
  c.within(rel, kConserved, "relative", [&] { return cat("momentum changed by ", rel, " relative"); });
}

// --- row: ε = 1 passes the first body's velocity to the last -----------------------
void check_row(const Scene& s, const Run& run, Checks& c) {
  const auto moving = bodies(s, false);
  const Model model = compile(s);
  const std::vector<BodyModel>& props = model.bodies;
  if (moving.size() < 2 || !bodies(s, true).empty()) throw std::invalid_argument("a row has two or more free bodies");
  for (std::size_t k = 1; k < moving.size(); ++k)
    if (std::abs(props[moving[k]].mass - props[moving[0]].mass) > 1e-12 || restitution(s, moving[k - 1], moving[k]) != 1)
      throw std::invalid_argument("a row has equal masses and ε = 1");
  const Sample& first = run.samples.front();
  const Sample& last = run.samples.back();
  const Vec3 v0 = s.bodies[moving[0]].velocity;
  for (const std::size_t k : moving) {
    const auto& body = last.bodies[k];
    const Vec3 want = k == moving.back() ? v0 : Vec3::Zero();
    const double err = (body.velocity - want).norm();
    c.within(err, kVelocity, "m/s", [&] {
      return cat(s.bodies[k].name, " v = ", vec(body.velocity), " m/s, expected ", vec(want), " ± ", kVelocity);
    });
    c.within(rim_speed(s.bodies[k], body), kVelocity, "m/s",
             [&] { return cat(s.bodies[k].name, " spins: vertex speed ", rim_speed(s.bodies[k], body), " m/s"); });
  }
  const double dp = (last.linear_momentum - first.linear_momentum).norm() / first.linear_momentum.norm();
  c.within(dp, kConserved, "relative", [&] { return cat("momentum changed by ", dp, " relative"); });
  const double de = std::abs(last.kinetic - first.kinetic) / first.kinetic;
  c.within(de, kConserved, "relative", [&] { return cat("kinetic energy changed by ", de, " relative"); });
}

// --- rest: stacks and a cube on a ridge -----------------------------------------------
// Box k (in scene order) rests on the body before it, the first on the static
// one. The window: the whole run when every box starts at rest in contact
// (nothing should ever move); otherwise the second half (a drop of 1 mm at
// ε = 0.5 is over in a fraction of a second).
double rest_window(const Scene& s) {
  const auto fixed = bodies(s, true), moving = bodies(s, false);
  Sample x;
  for (const auto& b : s.bodies) x.bodies.push_back({b.position, b.orientation, b.velocity, b.angular_velocity});
  std::size_t below = fixed[0];
  for (const std::size_t k : moving) {
    const double p = penetration(s, x, below, k);
    if (p < -kGapAllowed || p > collisions(s).penetration_tolerance || s.bodies[k].velocity.norm() > 0) return s.duration / 2;
    below = k;
  }
  return 0;
}

void check_rest(const Scene& s, const Run& run, Checks& c) {
  const auto fixed = bodies(s, true), moving = bodies(s, false);
  if (fixed.size() != 1 || moving.empty()) throw std::invalid_argument("a rest case has one static support and boxes on it");
  const double tol = collisions(s).penetration_tolerance, from = rest_window(s);
  const Sample& first = run.samples.front();
  for (const auto& x : run.samples) {
    std::size_t below = fixed[0];
    for (const std::size_t k : moving) {
      const auto& body = x.bodies[k];
      const std::string& name = s.bodies[k].name;
      const Vec3 drift = body.position - first.bodies[k].position;
      const double lateral = std::hypot(drift.x(), drift.y());
      c.within(lateral, kDrift, "m", [&] { return cat(name, " drifted ", lateral, " m sideways by t=", x.t); });
      // At every sample, bouncing or not: sunk by half its height, a box has
      // gone through its support (the separating axis flips past that depth).
      const double p = penetration(s, x, below, k), through = half_height(s.bodies[k], first.bodies[k].orientation);
      c.within(p, through, "m", [&] { return cat(name, " sank ", p, " m into ", s.bodies[below].name, " at t=", x.t); });
      if (x.t >= from) {
        c.inside(p, -kGapAllowed, tol, "m", [&] { return cat(name, " into ", s.bodies[below].name, " at t=", x.t); });
        const Vec3 side = 2 * half_sides(s.bodies[k]);
        const double most = tol / std::hypot(side.x(), side.y());
        c.within(tilt(body), most, "rad", [&] { return cat(name, " tilted ", tilt(body), " rad at t=", x.t); });
        const double speed = std::max(body.velocity.norm(), rim_speed(s.bodies[k], body));
        c.within(speed, kRestSpeed, "m/s", [&] { return cat(name, " moves at ", speed, " m/s at t=", x.t); });
      }
      below = k;
    }
  }
}

// --- a free box striking a static one: v' = v − (1 + ε)(v·n) n, n = z --------------
void check_bounce(const Scene& s, const Run& run, Checks& c) {
  const auto fixed = bodies(s, true), moving = bodies(s, false);
  if (fixed.size() != 1 || moving.size() != 1) throw std::invalid_argument("a bounce has one static and one free body");
  const std::size_t k = moving[0];
  const Vec3 v = s.bodies[k].velocity, want = v - (1 + restitution(s, k, fixed[0])) * v.z() * Vec3::UnitZ();
  const auto& body = run.samples.back().bodies[k];
  c.within((body.velocity - want).norm(), kVelocity, "m/s", [&] {
    return cat("v = ", vec(body.velocity), " m/s, expected ", vec(want), " ± ", kVelocity);
  });
  c.within(rim_speed(s.bodies[k], body), kVelocity, "m/s",
           [&] { return cat("spins: vertex speed ", rim_speed(s.bodies[k], body), " m/s"); });
}

}  // namespace

std::string expected_outcome(ContactKind kind, const Scene& s) {
  const double tol = collisions(s).penetration_tolerance;
  switch (kind) {
    case ContactKind::slide: {
      const Slide r = slide_answer(s);
      return cat("1-D impact along x: ", s.bodies[r.a].name, " ", r.va, " m/s, ", s.bodies[r.b].name, " ", r.vb,
                 " m/s (± 1e-3), no lateral velocity, spin only from the lateral offset (vertex speed ≤ ",
                 std::max(r.spin_a, r.spin_b), " m/s), momentum conserved to 1e-6",
                 r.floor ? cat(", both resting on the floor within [0, ", tol, "] m throughout") : "");
    }
    case ContactKind::row:
      return "ε = 1 passes the first body's velocity to the last, the others stop (± 1e-3 m/s); momentum and kinetic "
             "energy conserved to 1e-6";
    case ContactKind::stack:
    case ContactKind::edge_rest:
      return cat(rest_window(s) > 0 ? "after half the run, " : "throughout, ",
                 "each box rests on the one below with a penetration in [0, ", tol,
                 "] m (box k within k·tol of its analytic height), level within tol / diagonal, at rest to 1e-6 m/s; "
                 "lateral drift ≤ 1e-6 m at every sample");
    case ContactKind::edge_bounce:
      return "bounces straight back at ε times its speed (± 1e-3 m/s), without spin";
  }
  return "";
}

ContactVerdict ContactCase::evaluate(const Scene& s, const Run& run) const {
  Checks c;
  try {
    if (run.error) {
      c.within(INFINITY, 1, "", [&] { return cat("the run stopped: ", *run.error); });
      return c.done();
    }
    if (run.samples.empty() || run.samples.back().t < s.duration - 1e-9) {
      c.within(INFINITY, 1, "", [&] { return "the run ended early"; });
      return c.done();
    }
    switch (kind) {
      case ContactKind::slide: check_slide(s, run, c); break;
      case ContactKind::row: check_row(s, run, c); break;
      case ContactKind::stack:
      case ContactKind::edge_rest: check_rest(s, run, c); break;
      case ContactKind::edge_bounce: check_bounce(s, run, c); break;
    }
  } catch (const std::invalid_argument& e) {
    c.within(INFINITY, 1, "", [&] { return cat("the scene does not fit the case: ", e.what()); });
  }
  return c.done();
}

}  // namespace gacompare::core
