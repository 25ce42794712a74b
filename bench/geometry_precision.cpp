// Precision far from the origin: the error of each geometric operation
// at distances D = 1, 1e2, 1e4, 1e6 from the origin, for the traditional twin,
// the conformal backend, and the conformal backend in a local origin
// (cga/geometry/local_origin.hpp). Prints a markdown table.
//
// Each case is a feature of size ~1 (points, spheres of radius 0.3–1.5, planes
// and lines through it) placed at distance D. The inputs are doubles; the
// reference answer for those same double inputs is computed in __float128
// (113-bit significand, libquadmath) by straightforward formulas that share no
// code with either backend. The error is the largest deviation of any returned
// point or radius from the reference, divided by the answer's own scale
// max(1, radius, distance of the answer from the feature): the features have
// size ~1, but a random case can be ill-conditioned (nearly coplanar points, a
// nearly parallel line) and put its answer far away. Maximum over the cases;
// cases where a backend's kind differs from the reference's are counted apart.
//
// Also measured: the report's eq. 38 circumcentre (2D frame, absolute
// coordinates squared), to show why the twin does not use it.
//
//   ./geometry_precision [cases per cell, default 1000]
#include "cga/geometry/geometry.hpp"
#include "traditional/geometry.hpp"

#include <quadmath.h>

#include <cstdio>
#include <cstdlib>
#include <functional>
#include <random>
#include <string>
#include <vector>

namespace {

using gacompare::geometry::Kind;
using Vec3 = Eigen::Vector3d;
namespace C = gacompare::cga;
namespace L = gacompare::cga::local;
namespace T = gacompare::traditional;
using q = __float128;

// ---- a minimal quad-precision vector, for the reference answers ----
struct Q3 {
  q x, y, z;
};
Q3 Q(const Vec3& v) { return {v.x(), v.y(), v.z()}; }
Q3 operator+(Q3 a, Q3 b) { return {a.x + b.x, a.y + b.y, a.z + b.z}; }
Q3 operator-(Q3 a, Q3 b) { return {a.x - b.x, a.y - b.y, a.z - b.z}; }
Q3 operator*(q s, Q3 a) { return {s * a.x, s * a.y, s * a.z}; }
q dot(Q3 a, Q3 b) { return a.x * b.x + a.y * b.y + a.z * b.z; }
Q3 cross(Q3 a, Q3 b) { return {a.y * b.z - a.z * b.y, a.z * b.x - a.x * b.z, a.x * b.y - a.y * b.x}; }
q norm(Q3 a) { return sqrtq(dot(a, a)); }
// The answer's scale (see above), set per case from the feature's site.
Q3 g_site;
q g_scale = 1;
double err(const Vec3& got, Q3 want) {
  const q s = fmaxq(g_scale, norm(want - g_site));
  return static_cast<double>(norm(Q(got) - want) / s);
}
double err(double got, q want) { return static_cast<double>(fabsq(q(got) - want) / g_scale); }

// ---- the cases ----
struct Case {
  Vec3 a, b, c, d;      // points of the feature
  Vec3 s1, s2;          // sphere centres
  double r1, r2;        // radii
  Vec3 n1, n2;          // plane normals (unit)
  double o1, o2;        // plane offsets
  Vec3 x;               // a point to reflect
  Vec3 site;
};

struct Rng {
  std::mt19937_64 g{2003};
  double u(double lo, double hi) { return std::uniform_real_distribution<double>(lo, hi)(g); }
  Vec3 p(double r) { return {u(-r, r), u(-r, r), u(-r, r)}; }
  Vec3 unit() {
    for (;;) {
      const Vec3 v = p(1);
      if (v.norm() > 0.1 && v.norm() <= 1) return v.normalized();
    }
  }
};

Case make_case(Rng& rng, double D) {
  Case k;
  k.site = D * rng.unit();
  const auto at = [&](double r) { return Vec3(k.site + rng.p(r)); };
  k.a = at(1), k.b = at(1), k.c = at(1), k.d = at(1), k.x = at(1);
  k.s1 = at(0.7), k.s2 = at(0.7);
  k.r1 = rng.u(0.3, 1.5), k.r2 = rng.u(0.3, 1.5);
  k.n1 = rng.unit(), k.n2 = rng.unit();
  k.o1 = k.n1.dot(k.site) + rng.u(-0.5, 0.5), k.o2 = k.n2.dot(k.site) + rng.u(-0.5, 0.5);
  return k;
}

// ---- one operation: reference, and the error of each backend ----
struct Errors {
  double trad = 0, cga = 0, local = 0;
  int wrong_kind[3] = {0, 0, 0};
};
struct Op {
  std::string name;
  // Fills e with this case's errors (max-accumulated by the caller).
  std::function<void(const Case&, double e[3], bool bad[3])> run;
};

// Max error over a circle-like result against the reference centre and radius.
template <class R>
void circle_errors(const R& r, Kind want, Q3 centre, q radius, double& e, bool& bad) {
  if (r.kind != want) { bad = true; return; }
  g_scale = fmaxq(1, radius);
  e = std::max(err(r.centre, centre), err(r.radius, radius));
  g_scale = 1;
}

std::vector<Op> operations() {
  std::vector<Op> ops;
  ops.push_back({"circumcircle", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, v = Q(k.c) - a, w = cross(u, v);
    const Q3 off = (1 / (2 * dot(w, w))) * cross(dot(u, u) * v - dot(v, v) * u, w);
    const Q3 c = a + off;
    const q r = norm(off);
    circle_errors(T::circumcircle(k.a, k.b, k.c), Kind::circle, c, r, e[0], bad[0]);
    circle_errors(C::circumcircle(k.a, k.b, k.c), Kind::circle, c, r, e[1], bad[1]);
    circle_errors(L::circumcircle(k.a, k.b, k.c), Kind::circle, c, r, e[2], bad[2]);
  }});
  ops.push_back({"circumcircle, eq. 38 (report)", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, v = Q(k.c) - a, w = cross(u, v);
    const Q3 c = a + (1 / (2 * dot(w, w))) * cross(dot(u, u) * v - dot(v, v) * u, w);
    // §2.4.1 eq. 38: a frame in the plane, absolute 2D coordinates, determinants.
    const Vec3 e1 = (k.b - k.a).normalized();
    const Vec3 nrm = (k.b - k.a).cross(k.c - k.a).normalized();
    const Vec3 e2 = nrm.cross(e1);
    const double x1 = k.a.dot(e1), y1 = k.a.dot(e2), x2 = k.b.dot(e1), y2 = k.b.dot(e2), x3 = k.c.dot(e1),
                 y3 = k.c.dot(e2);
    const double s1 = x1 * x1 + y1 * y1, s2 = x2 * x2 + y2 * y2, s3 = x3 * x3 + y3 * y3;
    const double n1 = (s2 - s1) * (y3 - y1) - (s3 - s1) * (y2 - y1);
    const double n2 = (x2 - x1) * (s3 - s1) - (x3 - x1) * (s2 - s1);
    const double dd = (x2 - x1) * (y3 - y1) - (x3 - x1) * (y2 - y1);
    const Vec3 centre = 0.5 * n1 / dd * e1 + 0.5 * n2 / dd * e2 + k.a.dot(nrm) * nrm;
    g_scale = fmaxq(1, norm(c - a));
    e[0] = err(centre, c);
    g_scale = 1;
    e[1] = e[2] = 0;
    bad[1] = bad[2] = false;
  }});
  ops.push_back({"sphere_through", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, v = Q(k.c) - a, w = Q(k.d) - a;
    const Q3 off = (1 / (2 * dot(u, cross(v, w)))) *
                   (dot(u, u) * cross(v, w) + dot(v, v) * cross(w, u) + dot(w, w) * cross(u, v));
    const Q3 c = a + off;
    const q r = norm(off);
    circle_errors(T::sphere_through(k.a, k.b, k.c, k.d), Kind::sphere, c, r, e[0], bad[0]);
    circle_errors(C::sphere_through(k.a, k.b, k.c, k.d), Kind::sphere, c, r, e[1], bad[1]);
    circle_errors(L::sphere_through(k.a, k.b, k.c, k.d), Kind::sphere, c, r, e[2], bad[2]);
  }});
  ops.push_back({"meet_sphere_sphere", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 c1 = Q(k.s1), dc = Q(k.s2) - c1;
    const q d = norm(dc), r1 = k.r1, r2 = k.r2;
    const q a = (d * d + r1 * r1 - r2 * r2) / (2 * d), h2 = r1 * r1 - a * a;
    const Kind want = h2 > 0 ? Kind::circle : Kind::none;
    const Q3 c = c1 + (a / d) * dc;
    const q r = h2 > 0 ? sqrtq(h2) : 0;
    circle_errors(T::meet_sphere_sphere(T::sphere(k.s1, k.r1), T::sphere(k.s2, k.r2)), want, c, r, e[0], bad[0]);
    circle_errors(C::meet_sphere_sphere(C::sphere(k.s1, k.r1), C::sphere(k.s2, k.r2)), want, c, r, e[1], bad[1]);
    circle_errors(L::meet_sphere_sphere(k.s1, k.r1, k.s2, k.r2), want, c, r, e[2], bad[2]);
    if (want == Kind::none) e[0] = e[1] = e[2] = 0;
  }});
  ops.push_back({"meet_sphere_plane", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 c0 = Q(k.s1), nn = Q(k.n1);
    const q h = dot(nn, c0) - q(k.o1), r0 = k.r1, h2 = r0 * r0 - h * h;
    const Kind want = h2 > 0 ? Kind::circle : Kind::none;
    const Q3 c = c0 - h * nn;
    const q r = h2 > 0 ? sqrtq(h2) : 0;
    circle_errors(T::meet_sphere_plane(T::sphere(k.s1, k.r1), T::plane(k.n1, k.o1)), want, c, r, e[0], bad[0]);
    circle_errors(C::meet_sphere_plane(C::sphere(k.s1, k.r1), C::plane(k.n1, k.o1)), want, c, r, e[1], bad[1]);
    circle_errors(L::meet_sphere_plane(k.s1, k.r1, k.n1, k.o1), want, c, r, e[2], bad[2]);
    if (want == Kind::none) e[0] = e[1] = e[2] = 0;
  }});
  ops.push_back({"meet_line_plane", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, nn = Q(k.n1);
    const Q3 p = a - ((dot(nn, a) - q(k.o1)) / dot(nn, u)) * u;
    const auto one = [&](const gacompare::geometry::PointResult& r, double& ei, bool& b) {
      if (r.kind != Kind::point) { b = true; return; }
      ei = err(r.point, p);
    };
    one(T::meet_line_plane(*T::line_through(k.a, k.b), T::plane(k.n1, k.o1)), e[0], bad[0]);
    one(C::meet_line_plane(*C::line_through(k.a, k.b), C::plane(k.n1, k.o1)), e[1], bad[1]);
    one(L::meet_line_plane(k.a, k.b, k.n1, k.o1), e[2], bad[2]);
  }});
  ops.push_back({"meet_line_sphere", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, c = Q(k.s1);
    const Q3 f = a - (dot(a - c, u) / dot(u, u)) * u;
    const q d2 = dot(f - c, f - c), r = k.r1, h2 = r * r - d2;
    const Kind want = h2 > 0 ? Kind::point_pair : Kind::none;
    const Q3 step = h2 > 0 ? (sqrtq(h2) / norm(u)) * u : Q3{0, 0, 0};
    const auto one = [&](const gacompare::geometry::PairResult& p, double& ei, bool& b) {
      if (p.kind != want) { b = true; return; }
      ei = want == Kind::none ? 0 : std::max(err(p.first, f - step), err(p.second, f + step));
    };
    one(T::meet_line_sphere(*T::line_through(k.a, k.b), T::sphere(k.s1, k.r1)), e[0], bad[0]);
    one(C::meet_line_sphere(*C::line_through(k.a, k.b), C::sphere(k.s1, k.r1)), e[1], bad[1]);
    one(L::meet_line_sphere(k.a, k.b, k.s1, k.r1), e[2], bad[2]);
  }});
  ops.push_back({"meet_plane_plane", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 n1 = Q(k.n1), n2 = Q(k.n2), u = cross(n1, n2);
    const Q3 p = (1 / dot(u, u)) * cross(q(k.o1) * n2 - q(k.o2) * n1, u);
    // Compare the lines by the point of each nearest the case's site (the
    // world-origin foot is ~D away for both, so it is not the feature).
    const Q3 s = Q(k.site);
    const Q3 want = p + (dot(s - p, u) / dot(u, u)) * u;
    const auto one = [&](const gacompare::geometry::LineResult& l, double& ei, bool& b) {
      if (l.kind != Kind::line) { b = true; return; }
      const Q3 lp = Q(l.point), ld = Q(l.direction);
      ei = static_cast<double>(norm(lp + dot(s - lp, ld) * ld - want));
    };
    one(T::meet_plane_plane(T::plane(k.n1, k.o1), T::plane(k.n2, k.o2)), e[0], bad[0]);
    one(C::meet_plane_plane(C::plane(k.n1, k.o1), C::plane(k.n2, k.o2)), e[1], bad[1]);
    one(L::meet_plane_plane(k.n1, k.o1, k.n2, k.o2, k.site), e[2], bad[2]);
  }});
  ops.push_back({"reflect_in_plane", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 x = Q(k.x), nn = Q(k.n1);
    const Q3 want = x - (2 * (dot(nn, x) - q(k.o1))) * nn;
    e[0] = err(T::reflect_in_plane(k.x, T::plane(k.n1, k.o1)), want);
    e[1] = err(C::reflect_in_plane(k.x, C::plane(k.n1, k.o1)), want);
    e[2] = err(L::reflect_in_plane(k.x, k.n1, k.o1), want);
    bad[0] = bad[1] = bad[2] = false;
  }});
  ops.push_back({"reflect_in_sphere", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 x = Q(k.x), c = Q(k.s1), w = x - c;
    const q r = k.r1;
    const Q3 want = c + (r * r / dot(w, w)) * w;
    const auto one = [&](const gacompare::geometry::PointResult& p, double& ei, bool& b) {
      if (p.kind != Kind::point) { b = true; return; }
      ei = err(p.point, want);
    };
    one(T::reflect_in_sphere(k.x, T::sphere(k.s1, k.r1)), e[0], bad[0]);
    one(C::reflect_in_sphere(k.x, C::sphere(k.s1, k.r1)), e[1], bad[1]);
    one(L::reflect_in_sphere(k.x, k.s1, k.r1), e[2], bad[2]);
  }});
  ops.push_back({"reflect_in_line", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, x = Q(k.x);
    const Q3 f = a + (dot(x - a, u) / dot(u, u)) * u;
    const Q3 want = 2 * f - x;
    e[0] = err(T::reflect_in_line(k.x, *T::line_through(k.a, k.b)), want);
    e[1] = err(C::reflect_in_line(k.x, *C::line_through(k.a, k.b)), want);
    e[2] = err(L::reflect_in_line(k.x, k.a, k.b), want);
    bad[0] = bad[1] = bad[2] = false;
  }});
  ops.push_back({"nearest_on_line", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 a = Q(k.a), u = Q(k.b) - a, x = Q(k.x);
    const Q3 want = a + (dot(x - a, u) / dot(u, u)) * u;
    e[0] = err(T::nearest_on_line(k.x, *T::line_through(k.a, k.b)), want);
    e[1] = err(C::nearest_on_line(k.x, *C::line_through(k.a, k.b)), want);
    e[2] = err(L::nearest_on_line(k.x, k.a, k.b), want);
    bad[0] = bad[1] = bad[2] = false;
  }});
  ops.push_back({"side (inside < 0)", [](const Case& k, double e[3], bool bad[3]) {
    const Q3 w = Q(k.x) - Q(k.s1);
    const q r = k.r1, want = (dot(w, w) - r * r) / 2;
    e[0] = err(T::side(T::sphere(k.s1, k.r1), k.x), want);
    e[1] = err(C::side(C::sphere(k.s1, k.r1), k.x), want);
    e[2] = err(L::side(k.s1, k.r1, k.x), want);
    bad[0] = bad[1] = bad[2] = false;
  }});
  return ops;
}

}  // namespace

int main(int argc, char** argv) {
  int n = 1000;
  if (argc > 2 || (argc == 2 && (std::sscanf(argv[1], "%d", &n) != 1 || n < 1))) {
    std::fprintf(stderr, "usage: geometry_precision [cases per cell, a whole number >= 1; default 1000]\n");
    return 2;
  }
  const double distances[] = {1, 1e2, 1e4, 1e6};
  const char* backends[] = {"traditional", "cga", "cga, local origin"};
  const auto ops = operations();
  std::printf("Max error over %d cases per cell, relative to max(1, radius, distance of the answer\n"
              "from the feature), against a __float128 reference for the same double inputs;\n"
              "\"k✗\" = cases whose kind was wrong (counted, not in the error).\n\n",
              n);
  std::printf("| operation | backend | D = 1 | D = 1e2 | D = 1e4 | D = 1e6 |\n|---|---|---|---|---|---|\n");
  for (const Op& op : ops) {
    Errors cells[4];
    for (int di = 0; di < 4; ++di) {
      Rng rng;  // the same cases for every operation, scaled to each distance
      for (int i = 0; i < n; ++i) {
        Case k = make_case(rng, distances[di]);
        if ((k.b - k.a).norm() < 0.1 || (k.c - k.a).norm() < 0.1 || (k.c - k.b).norm() < 0.1) continue;
        g_site = Q(k.site);
        double e[3] = {0, 0, 0};
        bool bad[3] = {false, false, false};
        op.run(k, e, bad);
        double* acc[3] = {&cells[di].trad, &cells[di].cga, &cells[di].local};
        for (int b = 0; b < 3; ++b) {
          if (bad[b]) ++cells[di].wrong_kind[b];
          else *acc[b] = std::max(*acc[b], e[b]);
        }
      }
    }
    const int nb = op.name.find("eq. 38") != std::string::npos ? 1 : 3;
    for (int b = 0; b < nb; ++b) {
      std::printf("| %s | %s |", op.name.c_str(), nb == 1 ? "traditional, eq. 38" : backends[b]);
      for (int di = 0; di < 4; ++di) {
        const double v = b == 0 ? cells[di].trad : b == 1 ? cells[di].cga : cells[di].local;
        if (cells[di].wrong_kind[b]) std::printf(" %.1e (%d k✗) |", v, cells[di].wrong_kind[b]);
        else std::printf(" %.1e |", v);
      }
      std::printf("\n");
    }
  }
  return 0;
}
