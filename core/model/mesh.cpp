#include "core/model/mesh.hpp"

#include "core/error.hpp"
#include "core/read_file.hpp"

#include <Eigen/Geometry>

extern "C" {
#include <libqhull_r/qhull_ra.h>
}
#include <tiny_obj_loader.h>

#include <algorithm>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <cstdlib>
#include <numbers>
#include <tuple>
#include <unordered_map>
#include <sstream>
#include <utility>

namespace gacompare::core {

namespace {

std::string fmt(const Vec3& v) {
  std::ostringstream s;
  s.precision(9);
  s << '(' << v.x() << ", " << v.y() << ", " << v.z() << ')';
  return s.str();
}

std::string fmt(double x) {
  std::ostringstream s;
  s.precision(6);
  s << x;
  return s.str();
}

// A triangle is degenerate when twice its area is below 1e-12 × (longest edge)²,
// i.e. its largest angle is within ~1e-12 rad of 180° or two corners coincide:
// its normal would then be rounding noise (relative error ~1e-16/1e-12 = 1e-4 and up).
constexpr double kDegenerate = 1e-12;
// Coplanar triangles share a plane (fn 21) when their normals differ by < 1e-9 and
// their offsets by < 1e-9 × size: far above rounding (~1e-15), far below any real
// crease a modeller would make. The report merges by direction alone, which is the
// same for convex bodies; matching offsets as well keeps the parallel but distinct
// faces of a non-convex body apart.
constexpr double kCoplanar = 1e-9;

// Fan-triangulates a convex polygon (vertex loop in either orientation), starting
// at the corner whose fan has the largest smallest triangle: a plain fan from
// corner 0 makes zero-area triangles when that corner lies on the line of another
// side, as Qhull's merged facets and polygons with collinear vertices allow.
// Up to kFanStarts corners, spread evenly, are tried: every corner of a loop
// of n would be n² work, and a facet of a large hull can have thousands.
constexpr int kFanStarts = 32;
void fan(const std::vector<Vec3>& v, const std::vector<int>& loop, std::vector<Triangle>& out) {
  const int n = static_cast<int>(loop.size());
  const int stride = std::max(1, n / kFanStarts);
  int best = 0;
  double best_min = -1;
  for (int s = 0; s < n; s += stride) {
    double m = INFINITY;
    for (int k = 1; k + 1 < n; ++k) {
      const Vec3& a = v[loop[s]];
      m = std::min(m, (v[loop[(s + k) % n]] - a).cross(v[loop[(s + k + 1) % n]] - a).norm());
    }
    if (m > best_min) best_min = m, best = s;
  }
  for (int k = 1; k + 1 < n; ++k) out.push_back({loop[best], loop[(best + k) % n], loop[(best + k + 1) % n]});
}

// For the built-in convex shapes, which contain the origin: faces are listed as
// vertex loops and turned outward here, so no orientation is hand-written.
Mesh convex_from_faces(std::string name, std::vector<Vec3> v, const std::vector<std::vector<int>>& faces) {
  std::vector<Triangle> tris;
  for (const auto& f : faces) {
    std::vector<int> loop = f;
    const Vec3 n = (v[loop[1]] - v[loop[0]]).cross(v[loop[2]] - v[loop[0]]);
    if (n.dot(v[loop[0]]) < 0) std::reverse(loop.begin(), loop.end());
    fan(v, loop, tris);
  }
  return Mesh::from_triangles(std::move(name), std::move(v), std::move(tris)).as_convex();
}

}  // namespace

Mesh Mesh::from_triangles(std::string name, std::vector<Vec3> vertices, std::vector<Triangle> triangles) {
  Mesh m;
  m.name_ = std::move(name);
  const auto fail = [&](const std::string& what) { return input_error(m.name_ + ": " + what); };
  if (triangles.size() < 4) throw fail("a closed mesh needs at least 4 triangles, got " + std::to_string(triangles.size()));
  const int nv = static_cast<int>(vertices.size());
  std::vector<char> used(vertices.size(), 0);
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int i : triangles[t]) {
      if (i < 0 || i >= nv)
        throw fail("triangle " + std::to_string(t) + ": vertex index " + std::to_string(i) + " out of range (" +
                   std::to_string(nv) + " vertices)");
      used[i] = 1;
    }
  for (int i = 0; i < nv; ++i) {
    if (!vertices[i].allFinite()) throw fail("vertex " + std::to_string(i) + " is not finite");
    if (!used[i]) throw fail("vertex " + std::to_string(i) + " belongs to no triangle");
  }
  Eigen::AlignedBox3d box;
  for (const auto& p : vertices) box.extend(p);
  m.size_ = box.diagonal().norm();

  // Degenerate triangles first: their normals would poison every later check.
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const auto [a, b, c] = triangles[t];
    const Vec3 e0 = vertices[b] - vertices[a], e1 = vertices[c] - vertices[b], e2 = vertices[a] - vertices[c];
    const double longest = std::max({e0.squaredNorm(), e1.squaredNorm(), e2.squaredNorm()});
    if (a == b || b == c || a == c || !(e0.cross(-e2).norm() > kDegenerate * longest))
      throw fail("degenerate (zero-area) triangle " + std::to_string(t) + " (vertices " + std::to_string(a) + ", " +
                 std::to_string(b) + ", " + std::to_string(c) + ")");
  }

  // Closed: each undirected edge in exactly two triangles. Oriented: those two use
  // it in opposite directions. Checked in that order so the message names the cause.
  // Every use of an edge, sorted by (lo, hi, triangle): each run of equal
  // (lo, hi) is one undirected edge, in the order a map of them would give.
  struct Use {
    int lo, hi, k;  // k: the triangle's edge from vertex k to k + 1
    std::size_t t;
    bool forward;   // the triangle runs it lo -> hi
  };
  std::vector<Use> uses;
  uses.reserve(3 * triangles.size());
  for (std::size_t t = 0; t < triangles.size(); ++t)
    for (int k = 0; k < 3; ++k) {
      const int a = triangles[t][k], b = triangles[t][(k + 1) % 3];
      uses.push_back({std::min(a, b), std::max(a, b), k, t, a < b});
    }
  std::sort(uses.begin(), uses.end(), [](const Use& x, const Use& y) {
    return std::tie(x.lo, x.hi, x.t) < std::tie(y.lo, y.hi, y.t);
  });
  std::vector<std::size_t> run;  // where each edge's uses begin; run.back() == uses.size()
  for (std::size_t i = 0; i < uses.size(); ++i)
    if (i == 0 || uses[i].lo != uses[i - 1].lo || uses[i].hi != uses[i - 1].hi) run.push_back(i);
  run.push_back(uses.size());
  for (std::size_t r = 0; r + 1 < run.size(); ++r)
    if (const std::size_t n = run[r + 1] - run[r]; n != 2) {
      const Use& u = uses[run[r]];
      throw fail(std::string(n < 2 ? "not closed" : "not manifold") + ": edge (" + std::to_string(u.lo) + ", " +
                 std::to_string(u.hi) + ") belongs to " + std::to_string(n) +
                 " triangle(s), expected 2 (first: triangle " + std::to_string(u.t) + ")");
    }
  for (std::size_t r = 0; r + 1 < run.size(); ++r) {
    const Use &u0 = uses[run[r]], &u1 = uses[run[r] + 1];
    if (u0.forward == u1.forward)
      throw fail("inconsistently oriented: triangles " + std::to_string(u0.t) + " and " + std::to_string(u1.t) +
                 " both run edge " + std::to_string(u0.forward ? u0.lo : u0.hi) + " -> " +
                 std::to_string(u0.forward ? u0.hi : u0.lo));
  }

  // Outward: the signed volume (divergence theorem, apex at the box centre to keep
  // the triple products small) is positive for outward normals.
  const Vec3 o = box.center();
  double six_v = 0;
  for (const auto& [a, b, c] : triangles)
    six_v += (vertices[a] - o).dot((vertices[b] - o).cross(vertices[c] - o));
  if (!(six_v > 0))
    throw fail(std::string(six_v < 0 ? "inside out" : "encloses no volume") + ": signed volume " + fmt(six_v / 6) +
               " (triangles must run counter-clockwise seen from outside)");

  m.normals_.reserve(triangles.size());
  for (const auto& [a, b, c] : triangles)
    m.normals_.push_back((vertices[b] - vertices[a]).cross(vertices[c] - vertices[a]).normalized());
  // Each triangle joins the first plane (in the order planes were made) within
  // kCoplanar of its normal and offset. Planes are filed in a grid of normals
  // with cells 4 kCoplanar wide, so only the one to eight cells a match can be
  // in are searched: linear in the triangles, where a scan of every plane is
  // quadratic (bench/hull_bench.cpp).
  m.triangle_plane_.reserve(triangles.size());
  std::unordered_map<std::uint64_t, std::vector<int>> grid;
  constexpr double kCell = 4 * kCoplanar;
  const auto index = [](double x) { return static_cast<std::int64_t>(std::floor(x / kCell)); };
  const auto key = [](std::int64_t i, std::int64_t j, std::int64_t k) {
    const auto b = [](std::int64_t x) { return static_cast<std::uint64_t>(x) & 0x1fffff; };
    return b(i) << 42 | b(j) << 21 | b(k);
  };
  for (std::size_t t = 0; t < triangles.size(); ++t) {
    const Vec3& n = m.normals_[t];
    const double d = n.dot(vertices[triangles[t][0]]);
    int found = -1;
    // A plane within kCoplanar of n lies in the cells that n ± kCoplanar touch.
    for (auto i = index(n.x() - kCoplanar); i <= index(n.x() + kCoplanar); ++i)
      for (auto j = index(n.y() - kCoplanar); j <= index(n.y() + kCoplanar); ++j)
        for (auto k = index(n.z() - kCoplanar); k <= index(n.z() + kCoplanar); ++k) {
          const auto it = grid.find(key(i, j, k));
          if (it == grid.end()) continue;
          for (int p : it->second)
            if ((found < 0 || p < found) && (m.planes_[p].normal - n).norm() < kCoplanar &&
                std::abs(m.planes_[p].offset - d) < kCoplanar * m.size_)
              found = p;
        }
    if (found < 0) {
      found = static_cast<int>(m.planes_.size());
      m.planes_.push_back({n, d});
      grid[key(index(n.x()), index(n.y()), index(n.z()))].push_back(found);
    }
    m.triangle_plane_.push_back(found);
  }
  m.triangle_edges_.assign(triangles.size(), {-1, -1, -1});
  for (std::size_t r = 0; r + 1 < run.size(); ++r) {
    const Use &u0 = uses[run[r]], &u1 = uses[run[r] + 1];
    const int p0 = m.triangle_plane_[u0.t], p1 = m.triangle_plane_[u1.t];
    if (p0 == p1) continue;  // a diagonal inside a polygonal face
    const int index = static_cast<int>(m.edges_.size());
    m.edges_.push_back({u0.lo, u0.hi});
    m.edge_planes_.push_back(u0.forward ? std::array<int, 2>{p0, p1} : std::array<int, 2>{p1, p0});
    m.triangle_edges_[u0.t][u0.k] = index;
    m.triangle_edges_[u1.t][u1.k] = index;
  }
  // Face loops: plane p0 of a feature edge runs it e0 -> e1, plane p1 the other
  // way. The steps sorted by (plane, from) put each plane's together; a loop
  // starts at its smallest vertex.
  struct Step {
    int plane, from, to;
  };
  std::vector<Step> steps;
  steps.reserve(2 * m.edges_.size());
  for (std::size_t i = 0; i < m.edges_.size(); ++i) {
    const auto [e0, e1] = m.edges_[i];
    const auto [p0, p1] = m.edge_planes_[i];
    steps.push_back({p0, e0, e1});
    steps.push_back({p1, e1, e0});
  }
  std::sort(steps.begin(), steps.end(),
            [](const Step& a, const Step& b) { return std::tie(a.plane, a.from) < std::tie(b.plane, b.from); });
  m.faces_.resize(m.planes_.size());
  for (std::size_t begin = 0, end = 0; begin < steps.size(); begin = end) {
    const int p = steps[begin].plane;
    while (end < steps.size() && steps[end].plane == p) ++end;
    const auto first = steps.begin() + static_cast<std::ptrdiff_t>(begin), last = steps.begin() + static_cast<std::ptrdiff_t>(end);
    const std::size_t n = end - begin;
    bool branching = false;
    for (auto it = first; it + 1 < last; ++it) branching |= it->from == (it + 1)->from;
    if (branching || n < 3) continue;
    std::vector<int>& loop = m.faces_[static_cast<std::size_t>(p)];
    int v = first->from;
    do {
      loop.push_back(v);
      const auto it = std::lower_bound(first, last, v, [](const Step& st, int x) { return st.from < x; });
      v = it != last && it->from == v ? it->to : -1;
    } while (v >= 0 && v != loop.front() && loop.size() <= n);
    if (v != loop.front() || loop.size() != n) loop.clear();  // not one closed loop
  }
  // The edge graph, in compressed rows: vertex v's entries are
  // [neighbour_start_[v], neighbour_start_[v + 1]).
  m.neighbour_start_.assign(vertices.size() + 1, 0);
  for (const auto& [a, b] : m.edges_) ++m.neighbour_start_[a + 1], ++m.neighbour_start_[b + 1];
  for (std::size_t v = 0; v < vertices.size(); ++v) m.neighbour_start_[v + 1] += m.neighbour_start_[v];
  m.neighbours_.resize(2 * m.edges_.size());
  m.vertex_edges_.resize(2 * m.edges_.size());
  std::vector<int> fill(m.neighbour_start_.begin(), m.neighbour_start_.end() - 1);
  for (int e = 0; e < static_cast<int>(m.edges_.size()); ++e)
    for (int end = 0; end < 2; ++end) {
      const int v = m.edges_[e][end], k = fill[v]++;
      m.neighbours_[k] = m.edges_[e][1 - end];
      m.vertex_edges_[k] = e;
    }
  m.corners_only_ = true;
  for (std::size_t v = 0; v < vertices.size(); ++v) m.corners_only_ &= m.neighbour_start_[v + 1] - m.neighbour_start_[v] >= 3;
  m.vertices_ = std::move(vertices);
  m.triangles_ = std::move(triangles);
  return m;
}

namespace {
template <class T>
bool same_bits(const std::vector<T>& a, const std::vector<T>& b) {
  return a.size() == b.size() && (a.empty() || std::memcmp(a.data(), b.data(), a.size() * sizeof(T)) == 0);
}
bool same_bits(double a, double b) { return std::memcmp(&a, &b, sizeof a) == 0; }
bool same_bits(const Vec3& a, const Vec3& b) { return std::memcmp(a.data(), b.data(), sizeof(double) * 3) == 0; }
}  // namespace

// Bit for bit, not ==: -0 and 0 compare equal but need not give the same
// arithmetic downstream. Planes are compared as two fields each, not as raw
// bytes, so that padding never enters.
bool Mesh::identical(const Mesh& o) const {
  if (name_ != o.name_ || !same_bits(vertices_, o.vertices_) || !same_bits(triangles_, o.triangles_) ||
      !same_bits(normals_, o.normals_) || !same_bits(triangle_plane_, o.triangle_plane_) ||
      planes_.size() != o.planes_.size() || convex_ != o.convex_ || capsule_ != o.capsule_ ||
      !same_bits(size_, o.size_) || !same_bits(sphere_radius_, o.sphere_radius_) ||
      !same_bits(sphere_centre_, o.sphere_centre_) || !same_bits(capsule_half_axis_, o.capsule_half_axis_))
    return false;
  for (std::size_t k = 0; k < planes_.size(); ++k)
    if (!same_bits(planes_[k].normal, o.planes_[k].normal) || !same_bits(planes_[k].offset, o.planes_[k].offset))
      return false;
  return true;
}

// A rigid motion keeps everything a valid mesh is, so nothing is checked or
// merged again (that was the cost of a large hull, built once and moved to its
// centre of mass). Normals and planes are computed from the moved vertices as
// from_triangles computes them, each plane from its first triangle: the same
// numbers, to the last bit, as building the moved mesh afresh.
Mesh Mesh::transformed(const Eigen::Matrix3d& rotation, const Vec3& translation) const {
  Mesh m = *this;
  Eigen::AlignedBox3d box;
  for (auto& p : m.vertices_) box.extend(p = rotation * p + translation);
  m.sphere_centre_ = rotation * m.sphere_centre_ + translation;
  m.capsule_half_axis_ = rotation * m.capsule_half_axis_;
  m.size_ = box.diagonal().norm();
  const auto& v = m.vertices_;
  std::vector<char> placed(m.planes_.size(), 0);
  for (std::size_t t = 0; t < m.triangles_.size(); ++t) {
    const auto [a, b, c] = m.triangles_[t];
    m.normals_[t] = (v[b] - v[a]).cross(v[c] - v[a]).normalized();
    const auto p = static_cast<std::size_t>(m.triangle_plane_[t]);
    if (!placed[p]) m.planes_[p] = {m.normals_[t], m.normals_[t].dot(v[a])}, placed[p] = 1;
  }
  return m;
}

// --- built-in shapes ------------------------------------------------------------------

Mesh make_box(const Vec3& size) {
  const Vec3 h = size / 2;
  std::vector<Vec3> v;
  for (int i = 0; i < 8; ++i) v.emplace_back(i & 1 ? h.x() : -h.x(), i & 2 ? h.y() : -h.y(), i & 4 ? h.z() : -h.z());
  // Each face: the four corners with one coordinate bit fixed, as a loop.
  return convex_from_faces("box " + fmt(size.x()) + " x " + fmt(size.y()) + " x " + fmt(size.z()), std::move(v),
                           {{0, 2, 6, 4}, {1, 3, 7, 5}, {0, 1, 5, 4}, {2, 3, 7, 6}, {0, 1, 3, 2}, {4, 5, 7, 6}});
}

Mesh make_tetrahedron(double edge) {
  // Alternate corners of a cube of side 2: edge 2√2, centroid at the origin.
  const double s = edge / (2 * std::numbers::sqrt2);
  std::vector<Vec3> v{{s, s, s}, {s, -s, -s}, {-s, s, -s}, {-s, -s, s}};
  return convex_from_faces("tetrahedron edge " + fmt(edge), std::move(v), {{0, 1, 2}, {0, 1, 3}, {0, 2, 3}, {1, 2, 3}});
}

Mesh make_pyramid(double base, double height) {
  const double b = base / 2, lo = -height / 4;
  std::vector<Vec3> v{{-b, -b, lo}, {b, -b, lo}, {b, b, lo}, {-b, b, lo}, {0, 0, 3 * height / 4}};
  return convex_from_faces("pyramid base " + fmt(base) + " height " + fmt(height), std::move(v),
                           {{0, 1, 2, 3}, {0, 1, 4}, {1, 2, 4}, {2, 3, 4}, {3, 0, 4}});
}

Mesh make_octahedron(double radius) {
  std::vector<Vec3> v;
  for (int axis = 0; axis < 3; ++axis)
    for (double s : {radius, -radius}) v.push_back(s * Vec3::Unit(axis));
  std::vector<std::vector<int>> faces;  // one vertex from each axis pair
  for (int x : {0, 1})
    for (int y : {2, 3})
      for (int z : {4, 5}) faces.push_back({x, y, z});
  return convex_from_faces("octahedron radius " + fmt(radius), std::move(v), faces);
}

Mesh make_icosahedron(double radius) {
  // (0, ±1, ±φ) and its cyclic permutations: edge 2, circumradius √(1 + φ²).
  const double phi = std::numbers::phi, s = radius / std::sqrt(1 + phi * phi);
  std::vector<Vec3> v;
  for (int c = 0; c < 3; ++c)
    for (double a : {1.0, -1.0})
      for (double b : {phi, -phi}) {
        Vec3 p(0, a, b);
        v.push_back(s * Vec3(p[(3 - c) % 3], p[(4 - c) % 3], p[(5 - c) % 3]));
      }
  // Faces are the triples of mutually adjacent vertices (distance = edge).
  const double edge2 = 4 * s * s;
  const auto adjacent = [&](int i, int j) { return std::abs((v[i] - v[j]).squaredNorm() - edge2) < 1e-9 * edge2; };
  std::vector<std::vector<int>> faces;
  for (int i = 0; i < 12; ++i)
    for (int j = i + 1; j < 12; ++j)
      for (int k = j + 1; k < 12; ++k)
        if (adjacent(i, j) && adjacent(j, k) && adjacent(i, k)) faces.push_back({i, j, k});
  return convex_from_faces("icosahedron radius " + fmt(radius), std::move(v), faces);
}

// --- convex hull (Qhull) ------------------------------------------------------------

namespace {
// The 26 directions of make_sphere's proxy at radius r: all (z_sign 0), or
// those with z ≥ 0 (z_sign 1) or z ≤ 0 (−1).
std::vector<Vec3> sphere_points(double radius, int z_sign) {
  std::vector<Vec3> points;
  for (int x = -1; x <= 1; ++x)
    for (int y = -1; y <= 1; ++y)
      for (int z = -1; z <= 1; ++z)
        if ((x != 0 || y != 0 || z != 0) && z * z_sign >= 0) points.push_back(radius * Vec3(x, y, z).normalized());
  return points;
}
}  // namespace

Mesh make_sphere(double radius) {
  std::vector<Vec3> points = sphere_points(radius, 0);
  Mesh m = convex_hull(points, "sphere radius " + fmt(radius));
  m.name_ = "sphere radius " + fmt(radius);
  m.sphere_radius_ = radius;
  return m;
}

// The hemispheres' proxies 26 points apart along z, the equator ring once at
// each end: every vertex on the capsule, ±r across the axis (the rings) and
// ±(½L + r) along it (the poles), so the proxy's box and Welzl's sphere about
// its vertices are the capsule's own (the poles are the farthest pair, and
// every other vertex lies within ½L + r of the centre).
Mesh make_capsule(double radius, double length) {
  if (length == 0) return make_sphere(radius);
  const double h = 0.5 * length;
  std::vector<Vec3> points;
  for (const Vec3& p : sphere_points(radius, 1)) points.push_back(p + Vec3(0, 0, h));
  for (const Vec3& p : sphere_points(radius, -1)) points.push_back(p - Vec3(0, 0, h));
  const std::string name = "capsule radius " + fmt(radius) + " length " + fmt(length);
  Mesh m = convex_hull(points, name);
  m.name_ = name;
  m.sphere_radius_ = radius;
  m.capsule_half_axis_ = Vec3(0, 0, h);
  m.capsule_ = true;
  return m;
}

Mesh convex_hull(const std::vector<Vec3>& points, const std::string& what) {
  const std::string name = what + " of " + std::to_string(points.size()) + " points";
  if (points.size() < 4) throw input_error(name + ": a hull with volume needs at least 4 points");
  std::vector<coordT> coords;
  coords.reserve(3 * points.size());
  for (const auto& p : points) {
    if (!p.allFinite()) throw input_error(name + ": point " + fmt(p) + " is not finite");
    coords.insert(coords.end(), {p.x(), p.y(), p.z()});
  }
  // Qhull reports errors on a FILE*: capture them to quote the first line.
  char* err_text = nullptr;
  std::size_t err_size = 0;
  FILE* err = open_memstream(&err_text, &err_size);
  qhT qh_storage;
  qhT* qh = &qh_storage;
  qh_zero(qh, err);
  // Default options: Qhull merges coplanar facets (a box's faces come back as
  // quadrilaterals, its interior points drop out); we triangulate them ourselves.
  char options[] = "qhull";
  const int code = qh_new_qhull(qh, 3, static_cast<int>(points.size()), coords.data(), False, options, nullptr, err);
  std::vector<Vec3> verts;
  std::vector<Triangle> tris;
  if (code == 0) {
    std::vector<int> index(points.size(), -1);  // Qhull point id -> our vertex
    const auto id = [&](vertexT* vx) {
      const auto pid = static_cast<std::size_t>(qh_pointid(qh, vx->point));
      if (index[pid] < 0) index[pid] = static_cast<int>(verts.size()), verts.push_back(points[pid]);
      return index[pid];
    };
    facetT* facet;
    vertexT *vertex, **vertexp;
    FORALLfacets {
      setT* ordered = qh_facet3vertex(qh, facet);  // the facet's corners in cyclic order
      std::vector<int> loop;
      FOREACHvertex_(ordered) loop.push_back(id(vertex));
      qh_settempfree(qh, &ordered);
      const Vec3 n(facet->normal[0], facet->normal[1], facet->normal[2]);  // Qhull's outward normal
      std::vector<Triangle> part;
      fan(verts, loop, part);
      for (auto& t : part) {
        if ((verts[t[1]] - verts[t[0]]).cross(verts[t[2]] - verts[t[0]]).dot(n) < 0) std::swap(t[1], t[2]);
        tris.push_back(t);
      }
    }
  }
  qh_freeqhull(qh, !qh_ALL);
  int curlong = 0, totlong = 0;
  qh_memfreeshort(qh, &curlong, &totlong);
  std::fclose(err);
  std::string message(err_text ? err_text : "");
  std::free(err_text);
  if (code != 0) {
    // Qhull's first line says why (e.g. "QH6154 ... initial simplex is flat").
    const auto first = message.find_first_not_of(" \n");
    message = first == std::string::npos ? "" : message.substr(first, message.find('\n', first) - first);
    throw input_error(name + ": Qhull found no 3-d hull (error " + std::to_string(code) + ": " + message + ")");
  }
  return Mesh::from_triangles(name, std::move(verts), std::move(tris)).as_convex();
}

// --- OBJ (tinyobjloader) ----------------------------------------------------------

namespace {
// The most corners one OBJ face (or line, or point list) may have, and the
// most of corners² summed over the faces of more than 4: tinyobjloader
// triangulates a polygon in time that grows with the square of its corners
// (measured here: 1,000 corners 2.6 ms, 3,000 86 ms, 10,000 0.64 s; a face
// of 200,000 took over a minute), so these bound one file's triangulation to
// about a quarter of a second. No modeller's polygon comes near them.
constexpr std::size_t kMaxFaceCorners = 1000;
constexpr double kMaxTriangulationWork = 1e8;

std::vector<std::string_view> words(std::string_view line) {
  std::vector<std::string_view> out;
  for (std::size_t i = 0; i < line.size();) {
    const auto a = line.find_first_not_of(" \t\r", i);
    if (a == std::string_view::npos) break;
    const auto b = std::min(line.size(), line.find_first_of(" \t\r", a));
    out.push_back(line.substr(a, b - a));
    i = b;
  }
  return out;
}

// tinyobjloader reads a coordinate that is not a number as 0 (a typo silently
// moved a vertex to the origin) and an index past 2^31 wraps (4294967300 became
// 4), so the lines it would read that way are read here first: "v x y z",
// optionally w or r g b after, every one a finite number; "f", "l" and "p" with
// at most kMaxFaceCorners corners, each "v", "v/t", "v//n" or "v/t/n" of whole
// numbers, not 0, within ±(2^31 − 1), a vertex index naming a vertex the file
// has (a negative one, counted back from the line, one before it).
void check_lines(const std::string& text, const std::string& name) {
  std::size_t line_no = 0, vertices = 0;
  double work = 0;        // Σ corners² over the faces of more than 4
  long long highest = 0;  // the highest positive vertex index, and where
  std::size_t highest_line = 0;
  for (std::size_t begin = 0; begin < text.size();) {
    std::size_t end = text.find('\n', begin);
    if (end == std::string::npos) end = text.size();
    ++line_no;
    const std::string_view line(text.data() + begin, end - begin);
    begin = end + 1;
    const auto first = line.find_first_not_of(" \t");
    if (first == std::string_view::npos || line.size() < first + 2 || (line[first + 1] != ' ' && line[first + 1] != '\t'))
      continue;
    const char keyword = line[first];
    if (keyword != 'v' && keyword != 'f' && keyword != 'l' && keyword != 'p') continue;
    const std::vector<std::string_view> tokens = words(line.substr(first + 1));
    const auto where = name + ": line " + std::to_string(line_no) + ": ";
    if (keyword == 'v') {
      if (tokens.size() != 3 && tokens.size() != 4 && tokens.size() != 6 && tokens.size() != 7)
        throw input_error(where + "expected a vertex \"v x y z\" (then w, or r g b), got " +
                          std::to_string(tokens.size()) + " values");
      for (auto t : tokens) {
        const std::string_view digits = t.size() > 1 && t[0] == '+' ? t.substr(1) : t;
        double x = 0;
        const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
        if (ec != std::errc() || ptr != digits.data() + digits.size() || !std::isfinite(x))
          throw input_error(where + "expected a finite number as a vertex coordinate, got '" +
                            std::string(t.substr(0, 40)) + "'");
      }
      ++vertices;
      continue;
    }
    if (tokens.size() > kMaxFaceCorners)
      throw input_error(where + "expected at most " + std::to_string(kMaxFaceCorners) + " corners on one '" + keyword +
                        "' line, got " + std::to_string(tokens.size()));
    if (keyword == 'f' && tokens.size() > 4) work += static_cast<double>(tokens.size() * tokens.size());
    if (work > kMaxTriangulationWork)
      throw input_error(where + "expected polygons whose corners, squared and summed, come to at most 1e8 (their "
                                "triangulation takes time in that square): split the large polygons");
    for (auto t : tokens) {
      const auto bad = [&](const std::string& what) {
        return input_error(where + what + ", got '" + std::string(t.substr(0, 40)) + "'");
      };
      std::size_t part = 0;
      for (std::size_t a = 0; a <= t.size(); ++part) {
        const std::size_t b = std::min(t.size(), t.find('/', a));
        const std::string_view n = t.substr(a, b - a);
        a = b + 1;
        if (part > 2) throw bad("expected a corner \"v\", \"v/t\", \"v//n\" or \"v/t/n\"");
        if (n.empty() && part > 0) continue;  // "v//n", "v/t/"
        long long x = 0;
        const std::string_view digits = n.size() > 1 && n[0] == '+' ? n.substr(1) : n;
        const auto [ptr, ec] = std::from_chars(digits.data(), digits.data() + digits.size(), x);
        if (ec != std::errc() || ptr != digits.data() + digits.size() || x == 0 || x > 2147483647LL || x < -2147483647LL)
          throw bad("expected indices that are whole numbers from 1 to 2147483647 (or -1 to -2147483647, counted back)");
        if (part != 0) continue;  // texture and normal indices: not used
        if (x < 0 && static_cast<std::size_t>(-x) > vertices)
          throw bad("expected a vertex index counted back over the " + std::to_string(vertices) + " vertices before it");
        if (x > highest) highest = x, highest_line = line_no;
      }
    }
  }
  if (highest > static_cast<long long>(vertices))
    throw input_error(name + ": line " + std::to_string(highest_line) + ": expected vertex indices up to the file's " +
                      std::to_string(vertices) + " vertices, got " + std::to_string(highest));
}
}  // namespace

Mesh load_obj(const std::filesystem::path& file) {
  // Named in a scene file: a link there is not followed (core/read_file.hpp).
  return parse_obj(read_file(file, "mesh file (OBJ)", Links::refuse), file.string());
}

Mesh parse_obj(const std::string& text, const std::string& name) {
  check_lines(text, name);
  tinyobj::ObjReaderConfig config;
  config.triangulate = true;
  config.vertex_color = false;
  tinyobj::ObjReader reader;
  if (!reader.ParseFromString(text, "", config)) {
    std::string why = reader.Error();
    while (!why.empty() && (why.back() == '\n' || why.back() == '\r')) why.pop_back();
    std::replace(why.begin(), why.end(), '\n', ';');
    throw input_error(name + ": not a readable OBJ file: " + (why.empty() ? "unknown error" : why));
  }
  const auto& xyz = reader.GetAttrib().vertices;
  std::vector<int> renumber(xyz.size() / 3, -1);
  std::vector<Vec3> verts;
  std::vector<Triangle> tris;
  for (const auto& shape : reader.GetShapes()) {
    const auto& idx = shape.mesh.indices;
    for (std::size_t f = 0, k = 0; f < shape.mesh.num_face_vertices.size(); ++f) {
      const int nfv = shape.mesh.num_face_vertices[f];
      if (nfv != 3) throw input_error(name + ": face " + std::to_string(f) + " of '" + shape.name + "' has " +
                                      std::to_string(nfv) + " vertices after triangulation");
      Triangle t{};
      for (int j = 0; j < 3; ++j, ++k) {
        const int vi = idx[k].vertex_index;
        if (vi < 0 || static_cast<std::size_t>(vi) >= renumber.size())
          throw input_error(name + ": face " + std::to_string(f) + " refers to vertex " + std::to_string(vi + 1) +
                            ", which does not exist");
        if (renumber[vi] < 0) {
          renumber[vi] = static_cast<int>(verts.size());
          verts.emplace_back(xyz[3 * vi], xyz[3 * vi + 1], xyz[3 * vi + 2]);
        }
        t[j] = renumber[vi];
      }
      tris.push_back(t);
    }
  }
  return Mesh::from_triangles(name, std::move(verts), std::move(tris));
}

Mesh mesh_for(const Shape& shape) {
  struct Build {
    Mesh operator()(const BoxShape& s) const { return make_box(s.size); }
    Mesh operator()(const TetrahedronShape& s) const { return make_tetrahedron(s.edge); }
    Mesh operator()(const PyramidShape& s) const { return make_pyramid(s.base, s.height); }
    Mesh operator()(const OctahedronShape& s) const { return make_octahedron(s.radius); }
    Mesh operator()(const IcosahedronShape& s) const { return make_icosahedron(s.radius); }
    Mesh operator()(const HullShape& s) const { return s.mesh ? *s.mesh : convex_hull(s.points); }
    Mesh operator()(const MeshShape& s) const { return s.mesh ? *s.mesh : load_obj(s.file); }
    Mesh operator()(const SphereShape& s) const { return make_sphere(s.radius); }
    Mesh operator()(const CapsuleShape& s) const { return make_capsule(s.radius, s.length); }
  };
  return std::visit(Build{}, shape);
}

double inradius(const Mesh& mesh, const Vec3& centre) {
  if (mesh.is_sphere()) return mesh.sphere_radius() - (centre - mesh.sphere_centre()).norm();
  if (mesh.is_capsule()) {
    const Vec3 h = mesh.capsule_half_axis(), x = centre - mesh.sphere_centre();
    const double t = std::clamp(x.dot(h) / h.squaredNorm(), -1.0, 1.0);
    return mesh.sphere_radius() - (x - t * h).norm();
  }
  double r = INFINITY;
  for (const auto& p : mesh.planes()) r = std::min(r, -p.distance(centre));
  return r;
}

// --- convexity ------------------------------------------------------------------------

Convexity convexity(const Mesh& mesh) {
  if (mesh.convex_by_construction()) return {};
  const double tol = 1e-6 * mesh.size();  // see mesh.hpp
  for (std::size_t p = 0; p < mesh.planes().size(); ++p) {
    const Plane& plane = mesh.planes()[p];
    for (std::size_t i = 0; i < mesh.vertices().size(); ++i) {
      const double d = plane.distance(mesh.vertices()[i]);
      if (d > tol) {
        const auto t = std::find(mesh.triangle_plane().begin(), mesh.triangle_plane().end(), static_cast<int>(p)) -
                       mesh.triangle_plane().begin();
        return {false, mesh.name() + ": not convex: vertex " + std::to_string(i) + " " + fmt(mesh.vertices()[i]) +
                           " lies " + fmt(d) + " outside the plane of triangle " + std::to_string(t) + " (normal " +
                           fmt(plane.normal) + ")"};
      }
    }
  }
  return {};
}

void require_convex(const Mesh& mesh) {
  if (auto c = convexity(mesh); !c.convex) throw input_error(c.reason);
}

}  // namespace gacompare::core
