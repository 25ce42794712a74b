// Meshes: built-in shapes, Qhull hulls, OBJ loading, and the checks
// that refuse bad meshes with one-line errors.
#include "core/error.hpp"
#include "core/model/mass_properties.hpp"
#include "core/model/mesh.hpp"
#include "core/model/point_in_body.hpp"

#include <Eigen/Geometry>
#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <random>
#include <set>

namespace {

using namespace gacompare::core;
namespace fs = std::filesystem;
const fs::path kMeshes = fs::path(GACOMPARE_TEST_DATA_DIR) / "meshes";

// The message of the input_error `f` throws, checked to be one line.
template <class F> std::string input_error_of(F&& f) {
  try {
    f();
  } catch (const gacompare::Error& e) {
    EXPECT_EQ(e.kind(), gacompare::ErrorKind::input);
    const std::string m = e.what();
    EXPECT_EQ(m.find('\n'), std::string::npos) << m;
    return m;
  }
  ADD_FAILURE() << "no error thrown";
  return "";
}

// Euler's formula V − E + F = 2 for a closed genus-0 triangle mesh: E = 3F/2.
void expect_sphere_topology(const Mesh& m) {
  const long v = static_cast<long>(m.vertices().size()), f = static_cast<long>(m.triangles().size());
  EXPECT_EQ(v - 3 * f / 2 + f, 2) << m.name();
}

TEST(Mesh, BuiltInShapesHaveTheirCountsAndMergedPlanes) {
  struct Case { Mesh mesh; std::size_t vertices, triangles, planes; };
  const Case cases[] = {{make_box({1, 2, 3}), 8, 12, 6},      {make_tetrahedron(1.5), 4, 4, 4},
                        {make_pyramid(2, 3), 5, 6, 5},        {make_octahedron(0.7), 6, 8, 8},
                        {make_icosahedron(1.3), 12, 20, 20}};
  for (const auto& c : cases) {
    EXPECT_EQ(c.mesh.vertices().size(), c.vertices) << c.mesh.name();
    EXPECT_EQ(c.mesh.triangles().size(), c.triangles) << c.mesh.name();
    EXPECT_EQ(c.mesh.planes().size(), c.planes) << c.mesh.name();  // fn 21: a box's 12 triangles, 6 planes
    EXPECT_TRUE(convexity(c.mesh).convex) << convexity(c.mesh).reason;
    expect_sphere_topology(c.mesh);
    // Every normal is unit and points away from the origin (inside every shape).
    for (std::size_t t = 0; t < c.mesh.triangles().size(); ++t) {
      EXPECT_NEAR(c.mesh.normals()[t].norm(), 1, 1e-15);
      EXPECT_GT(c.mesh.normals()[t].dot(c.mesh.vertices()[c.mesh.triangles()[t][0]]), 0);
    }
  }
}

// Face loops (the contact manifold's polygons): one per plane, every vertex
// on its plane, counter-clockwise seen from outside (each corner turns left
// about the normal), and each face's area from its loop (the shoelace sum)
// equal to the area of its triangles. Built shapes, and a Qhull hull whose
// square faces come triangulated. Areas to 1e-12 (sums of a few products).
TEST(Mesh, FaceLoopsAreCounterClockwisePolygonsOfTheirPlanes) {
  std::vector<Vec3> corners = make_box({1, 2, 3}).vertices();
  corners.push_back({0, 0, 0});  // inside: not a hull vertex
  const Mesh meshes[] = {make_box({1, 2, 3}), make_tetrahedron(1.5), make_pyramid(2, 3), make_icosahedron(1.3),
                         convex_hull(corners)};
  for (const Mesh& m : meshes) {
    ASSERT_EQ(m.faces().size(), m.planes().size()) << m.name();
    std::vector<double> area(m.planes().size(), 0);
    for (std::size_t t = 0; t < m.triangles().size(); ++t) {
      const auto [a, b, c] = m.triangles()[t];
      area[m.triangle_plane()[t]] += 0.5 * (m.vertices()[b] - m.vertices()[a]).cross(m.vertices()[c] - m.vertices()[a]).norm();
    }
    for (std::size_t p = 0; p < m.planes().size(); ++p) {
      const auto& loop = m.faces()[p];
      ASSERT_GE(loop.size(), 3u) << m.name() << " plane " << p;
      const Vec3 n = m.planes()[p].normal;
      Vec3 twice = Vec3::Zero();
      for (std::size_t k = 0; k < loop.size(); ++k) {
        const Vec3 u = m.vertices()[loop[k]], v = m.vertices()[loop[(k + 1) % loop.size()]],
                   w = m.vertices()[loop[(k + 2) % loop.size()]];
        EXPECT_NEAR(m.planes()[p].distance(u), 0, 1e-12) << m.name();
        EXPECT_GT(n.dot((v - u).cross(w - v)), 0) << m.name() << " plane " << p;
        twice += u.cross(v);
      }
      EXPECT_NEAR(0.5 * n.dot(twice), area[p], 1e-12) << m.name() << " plane " << p;
    }
  }
}

// The edge graph (hill climbing walks it): each of a box's corners
// meets three feature edges, to the corners that differ from it in one
// coordinate (make_box numbers corner i by the bits x, y, z), each listed with
// the edge that joins them; every built-in shape and a hull has corners only,
// with each feature edge listed at both its ends. A box whose top face has a
// vertex in its middle (as an OBJ file may) is not corners only: that vertex
// meets no feature edge at all.
TEST(Mesh, EdgeGraphJoinsTheCornersOfTheSolid) {
  const Mesh box = make_box({1, 2, 3});
  ASSERT_TRUE(box.corners_only());
  for (int v = 0; v < 8; ++v) {
    const auto next = box.neighbours(v);
    const auto edges = box.vertex_edges(v);
    ASSERT_EQ(next.size(), 3u);
    ASSERT_EQ(edges.size(), 3u);
    std::set<int> bits;
    for (std::size_t k = 0; k < 3; ++k) {
      const auto [e0, e1] = box.edges()[edges[k]];
      EXPECT_TRUE((e0 == v && e1 == next[k]) || (e1 == v && e0 == next[k])) << v;
      bits.insert(v ^ next[k]);
    }
    EXPECT_EQ(bits, (std::set<int>{1, 2, 4})) << v;
  }
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  std::vector<Vec3> points;
  for (int i = 0; i < 50; ++i) points.emplace_back(g(rng), g(rng), g(rng));
  for (const Mesh& m : {make_tetrahedron(1), make_pyramid(1, 2), make_octahedron(1), make_icosahedron(1),
                        convex_hull(points)}) {
    EXPECT_TRUE(m.corners_only()) << m.name();
    std::size_t ends = 0;
    for (int v = 0; v < static_cast<int>(m.vertices().size()); ++v) ends += m.neighbours(v).size();
    EXPECT_EQ(ends, 2 * m.edges().size()) << m.name();
  }
  std::vector<Vec3> v = box.vertices();
  v.emplace_back(0, 0, 1.5);  // the middle of the top face (z = +1.5: corners 4 to 7)
  std::vector<Triangle> t;
  for (const auto& tri : box.triangles())
    if (!((tri[0] & 4) && (tri[1] & 4) && (tri[2] & 4))) t.push_back(tri);
  for (const Triangle& fan : {Triangle{8, 4, 5}, Triangle{8, 5, 7}, Triangle{8, 7, 6}, Triangle{8, 6, 4}}) t.push_back(fan);
  const Mesh dented = Mesh::from_triangles("box with a vertex in a face", v, t);
  EXPECT_EQ(dented.edges().size(), 12u);
  EXPECT_TRUE(dented.neighbours(8).empty());
  EXPECT_FALSE(dented.corners_only());
}

TEST(Mesh, BuiltInShapesHaveTheirSizes) {
  // Independent of the builders: distances measured on the vertices.
  const Mesh box = make_box({1, 2, 3});
  for (const auto& v : box.vertices()) EXPECT_EQ(v.cwiseAbs(), Vec3(0.5, 1, 1.5));
  const Mesh tet = make_tetrahedron(1.5);
  for (std::size_t i = 0; i < 4; ++i)
    for (std::size_t j = i + 1; j < 4; ++j) EXPECT_NEAR((tet.vertices()[i] - tet.vertices()[j]).norm(), 1.5, 1e-15);
  for (const Mesh& m : {make_octahedron(0.7), make_icosahedron(1.3)}) {
    const double r = m.vertices()[0].norm();
    for (const auto& v : m.vertices()) EXPECT_NEAR(v.norm(), r, 1e-15);
  }
  EXPECT_NEAR(make_octahedron(0.7).vertices()[0].norm(), 0.7, 1e-15);
  EXPECT_NEAR(make_icosahedron(1.3).vertices()[0].norm(), 1.3, 1e-15);
  // Pyramid: base side 2 at z = −h/4, apex 3h/4 above the origin (its centroid).
  const Mesh pyr = make_pyramid(2, 3);
  double top = -1e9, bottom = 1e9;
  for (const auto& v : pyr.vertices()) top = std::max(top, v.z()), bottom = std::min(bottom, v.z());
  EXPECT_DOUBLE_EQ(top, 2.25);
  EXPECT_DOUBLE_EQ(bottom, -0.75);
}

TEST(Mesh, MeshForBuildsEveryShape) {
  EXPECT_EQ(mesh_for(BoxShape{{1, 1, 1}}).triangles().size(), 12u);
  EXPECT_EQ(mesh_for(TetrahedronShape{2}).triangles().size(), 4u);
  EXPECT_EQ(mesh_for(PyramidShape{1, 1}).triangles().size(), 6u);
  EXPECT_EQ(mesh_for(OctahedronShape{1}).triangles().size(), 8u);
  EXPECT_EQ(mesh_for(IcosahedronShape{1}).triangles().size(), 20u);
  EXPECT_EQ(mesh_for(HullShape{{{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0, 1}, {0.1, 0.1, 0.1}}}).vertices().size(), 4u);
  EXPECT_EQ(mesh_for(MeshShape{kMeshes / "cube.obj"}).triangles().size(), 12u);
}

TEST(Mesh, HullOfBoxCornersIsTheBox) {
  std::vector<Vec3> corners;
  for (int i = 0; i < 8; ++i) corners.emplace_back(i & 1 ? 1.5 : -1.5, i & 2 ? 0.5 : -0.5, i & 4 ? 2 : -2);
  corners.emplace_back(0.1, 0.2, 0.3);  // an interior point is not a vertex
  corners.emplace_back(1.5, 0, 0);      // nor is a point in the middle of a face
  const Mesh hull = convex_hull(corners);
  EXPECT_EQ(hull.vertices().size(), 8u);
  EXPECT_EQ(hull.triangles().size(), 12u);
  EXPECT_EQ(hull.planes().size(), 6u);
  EXPECT_NEAR(mass_properties(hull).volume, 3.0 * 1 * 4, 1e-14 * 12);
}

TEST(Mesh, HullOfRandomPointsContainsThemAndIsItsOwnHull) {
  std::mt19937_64 rng(5);
  std::normal_distribution<double> g;
  for (int trial = 0; trial < 5; ++trial) {
    std::vector<Vec3> pts(200);
    for (auto& p : pts) p = Vec3(g(rng), 0.5 * g(rng), 2 * g(rng));
    const Mesh hull = convex_hull(pts);
    EXPECT_TRUE(convexity(hull).convex) << convexity(hull).reason;
    // Every input point is inside or on it, within Qhull's merging tolerance
    // (~1e-13 here; 1e-9 × size is the mesh's own coplanarity tolerance).
    for (const auto& p : pts) EXPECT_LE(max_face_distance(hull, p), 1e-9 * hull.size());
    // Each hull vertex is one of the points.
    for (const auto& v : hull.vertices())
      EXPECT_TRUE(std::find(pts.begin(), pts.end(), v) != pts.end());
    const Mesh again = convex_hull(hull.vertices());
    EXPECT_EQ(again.vertices().size(), hull.vertices().size());
    EXPECT_NEAR(mass_properties(again).volume, mass_properties(hull).volume, 1e-13 * mass_properties(hull).volume);
    std::set<std::tuple<double, double, double>> a, b;
    for (const auto& v : hull.vertices()) a.insert({v.x(), v.y(), v.z()});
    for (const auto& v : again.vertices()) b.insert({v.x(), v.y(), v.z()});
    EXPECT_EQ(a, b);
  }
}

TEST(Mesh, HullOfFlatPointsIsRefused) {
  const std::string m = input_error_of([] { convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}, {2, 3, 0}}); });
  EXPECT_NE(m.find("hull of 5 points: Qhull found no 3-d hull"), std::string::npos) << m;
  EXPECT_NE(input_error_of([] { convex_hull({{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}); })
                .find("hull of 3 points: a hull with volume needs at least 4 points"),
            std::string::npos);
}

TEST(Mesh, ObjCubeLoads) {
  const Mesh cube = load_obj(kMeshes / "cube.obj");
  EXPECT_EQ(cube.vertices().size(), 8u);
  EXPECT_EQ(cube.triangles().size(), 12u);
  EXPECT_EQ(cube.planes().size(), 6u);
  EXPECT_TRUE(convexity(cube).convex);
  const MassProperties mp = mass_properties(cube);
  EXPECT_NEAR(mp.volume, 1, 1e-15);
  EXPECT_LT((mp.centre_of_mass - Vec3(0.5, 0.5, 0.5)).norm(), 1e-15);
}

TEST(Mesh, BadObjFilesGiveOneLineErrors) {
  const std::string open = input_error_of([] { load_obj(kMeshes / "open_cube.obj"); });
  EXPECT_NE(open.find((kMeshes / "open_cube.obj").string() + ": not closed: edge ("), std::string::npos) << open;
  const std::string missing = input_error_of([] { load_obj(kMeshes / "nothing.obj"); });
  EXPECT_NE(missing.find((kMeshes / "nothing.obj").string() + ": cannot open the mesh file (OBJ): No such file"), std::string::npos)
      << missing;
}

// The box's 8 corners and 12 triangles, to break one thing at a time.
struct Soup {
  std::vector<Vec3> v;
  std::vector<Triangle> t;
};
Soup box_soup() {
  const Mesh b = make_box({1, 1, 1});
  return {b.vertices(), b.triangles()};
}

TEST(Mesh, BadMeshesGiveOneLineErrors) {
  {
    Soup s = box_soup();
    s.t.pop_back();
    const std::string m = input_error_of([&] { Mesh::from_triangles("open", s.v, s.t); });
    EXPECT_NE(m.find("open: not closed: edge ("), std::string::npos) << m;
    EXPECT_NE(m.find("belongs to 1 triangle(s), expected 2"), std::string::npos) << m;
  }
  {
    Soup s = box_soup();
    s.t.push_back(s.t[0]);  // a duplicated triangle: its edges belong to 3 triangles
    const std::string m = input_error_of([&] { Mesh::from_triangles("doubled", s.v, s.t); });
    EXPECT_NE(m.find("doubled: not manifold: edge ("), std::string::npos) << m;
    EXPECT_NE(m.find("belongs to 3 triangle(s), expected 2"), std::string::npos) << m;
  }
  {
    Soup s = box_soup();
    std::swap(s.t[3][1], s.t[3][2]);
    const std::string m = input_error_of([&] { Mesh::from_triangles("flipped", s.v, s.t); });
    EXPECT_NE(m.find("flipped: inconsistently oriented: triangles "), std::string::npos) << m;
  }
  {
    Soup s = box_soup();
    for (auto& t : s.t) std::swap(t[1], t[2]);
    const std::string m = input_error_of([&] { Mesh::from_triangles("inverted", s.v, s.t); });
    EXPECT_NE(m.find("inverted: inside out: signed volume -1 "), std::string::npos) << m;
  }
  {
    // A vertex exactly midway along an edge, used by a sliver triangle.
    Soup s = box_soup();
    s.v.push_back((s.v[0] + s.v[1]) / 2);
    s.t.push_back({0, 8, 1});
    const std::string m = input_error_of([&] { Mesh::from_triangles("sliver", s.v, s.t); });
    EXPECT_NE(m.find("sliver: degenerate (zero-area) triangle 12 (vertices 0, 8, 1)"), std::string::npos) << m;
  }
  {
    Soup s = box_soup();
    s.t[0][0] = 42;
    EXPECT_NE(input_error_of([&] { Mesh::from_triangles("range", s.v, s.t); }).find("range: triangle 0: vertex index 42"),
              std::string::npos);
  }
  {
    Soup s = box_soup();
    s.v.emplace_back(9, 9, 9);
    EXPECT_NE(input_error_of([&] { Mesh::from_triangles("stray", s.v, s.t); }).find("stray: vertex 8 belongs to no triangle"),
              std::string::npos);
  }
}

TEST(Mesh, NonConvexMeshIsValidButFlagged) {
  // The unit box with its top-centre pushed down: a valid closed mesh with a dent.
  std::vector<Vec3> v = make_box({2, 2, 2}).vertices();
  const Mesh box = make_box({2, 2, 2});
  std::vector<Triangle> t;
  v.emplace_back(0, 0, 0.5);  // vertex 8: the dent, below the top face z = 1
  for (std::size_t i = 0; i < box.triangles().size(); ++i)
    if (box.normals()[i].z() < 0.5) t.push_back(box.triangles()[i]);
  // Top face corners 4..7 (z = +1): a fan around the dent, counter-clockwise from above.
  const int ring[] = {4, 5, 7, 6};
  for (int k = 0; k < 4; ++k) t.push_back({ring[k], ring[(k + 1) % 4], 8});
  const Mesh dented = Mesh::from_triangles("dented box", v, t);
  const Convexity c = convexity(dented);
  EXPECT_FALSE(c.convex);
  EXPECT_NE(c.reason.find("dented box: not convex: vertex "), std::string::npos) << c.reason;
  EXPECT_EQ(c.reason.find('\n'), std::string::npos);
  const std::string m = input_error_of([&] { require_convex(dented); });
  EXPECT_EQ(m, c.reason);
  EXPECT_NO_THROW(require_convex(box));
  // Its volume: the box less the square pyramid of the dent (base 2×2, depth 0.5).
  EXPECT_NEAR(mass_properties(dented).volume, 8 - 4 * 0.5 / 3, 1e-14);
}

// transformed() moves a mesh without rebuilding it (rebuilding a large hull
// would be its cost): its normals, planes and size are, to the last bit,
// what building the moved vertices afresh gives.
TEST(Mesh, TransformedIsTheMovedMeshBuiltAfresh) {
  std::mt19937_64 rng(3);
  std::normal_distribution<double> g;
  std::vector<Vec3> pts(300);
  for (auto& p : pts) p = Vec3(g(rng), g(rng), g(rng));
  const Mesh hull = convex_hull(pts);
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.4, Vec3(1, -1, 2).normalized()).toRotationMatrix();
  const Vec3 t(0.3, -7, 1e3);
  const Mesh moved = hull.transformed(r, t);
  std::vector<Vec3> v;
  for (const auto& p : hull.vertices()) v.push_back(r * p + t);
  const Mesh fresh = Mesh::from_triangles(hull.name(), v, hull.triangles());
  EXPECT_EQ(moved.size(), fresh.size());
  ASSERT_EQ(moved.planes().size(), fresh.planes().size());
  for (std::size_t p = 0; p < fresh.planes().size(); ++p) {
    EXPECT_EQ(moved.planes()[p].normal, fresh.planes()[p].normal) << p;
    EXPECT_EQ(moved.planes()[p].offset, fresh.planes()[p].offset) << p;
  }
  EXPECT_EQ(moved.normals(), fresh.normals());
  EXPECT_EQ(moved.triangle_plane(), fresh.triangle_plane());
  EXPECT_EQ(moved.edges(), fresh.edges());
  EXPECT_EQ(moved.faces(), fresh.faces());
}

// The planes found through the grid of normals are the planes of the rule
// itself, done by brute force: each triangle joins the first plane made whose
// normal and offset are within 1e-9 (and 1e-9 x size) of its own.
TEST(Mesh, PlanesAreTheFirstCoplanarMatch) {
  std::mt19937_64 rng(11);
  std::normal_distribution<double> g;
  std::vector<Vec3> pts(2000);
  for (auto& p : pts) p = Vec3(g(rng), g(rng), g(rng)).normalized();  // many nearly coplanar facets
  for (int i = 0; i < 8; ++i) pts.emplace_back(i & 1 ? 0.6 : -0.6, i & 2 ? 0.6 : -0.6, i & 4 ? 0.6 : -0.6);
  const Mesh m = convex_hull(pts);
  std::vector<Plane> planes;
  for (std::size_t t = 0; t < m.triangles().size(); ++t) {
    const Vec3& n = m.normals()[t];
    const double d = n.dot(m.vertices()[m.triangles()[t][0]]);
    std::size_t p = 0;
    while (p < planes.size() && !((planes[p].normal - n).norm() < 1e-9 && std::abs(planes[p].offset - d) < 1e-9 * m.size())) ++p;
    if (p == planes.size()) planes.push_back({n, d});
    EXPECT_EQ(m.triangle_plane()[t], static_cast<int>(p)) << t;
  }
  EXPECT_EQ(m.planes().size(), planes.size());
}

// A facet of hundreds of corners (a prism over a 300-gon, whose caps Qhull
// merges into one facet each) is triangulated without zero-area triangles
// and in bounded time: its volume is the prism's, area x height.
TEST(Mesh, AHullWithLargeFacetsIsValid) {
  const int n = 300;
  std::vector<Vec3> pts;
  for (int i = 0; i < n; ++i)
    for (double z : {0.0, 0.5}) pts.emplace_back(std::cos(2 * M_PI * i / n), std::sin(2 * M_PI * i / n), z);
  const Mesh prism = convex_hull(pts);
  const double area = 0.5 * n * std::sin(2 * M_PI / n);
  EXPECT_NEAR(mass_properties(prism).volume, area * 0.5, 1e-12);
  std::size_t largest = 0;
  for (const auto& f : prism.faces()) largest = std::max(largest, f.size());
  EXPECT_EQ(largest, static_cast<std::size_t>(n));
}

// A vertex coordinate that is not a finite number is refused naming its line
// (tinyobjloader alone reads it as 0).
TEST(Mesh, ObjVertexCoordinatesMustBeFiniteNumbers) {
  const std::string faces = "f 1 3 2\nf 1 4 3\nf 1 2 4\nf 2 3 4\n";
  EXPECT_EQ(parse_obj("v 0 0 0\nv 1 0 0\nv 0 1 0\nv 0 0 1\n" + faces, "t.obj").vertices().size(), 4u);
  for (const std::string bad : {"x", "1e999", "nan", "0x", "1,5"}) {
    const std::string m = input_error_of([&] { parse_obj("v 0 0 0\nv 1 0 0\n# c\nv 0 " + bad + " 0\nv 0 0 1\n" + faces, "t.obj"); });
    EXPECT_EQ(m, "t.obj: line 4: expected a finite number as a vertex coordinate, got '" + bad + "'");
  }
  EXPECT_NE(input_error_of([&] { parse_obj("v 0 0\n" + faces, "t.obj"); }).find("t.obj: line 1: expected a vertex"), std::string::npos);
}

TEST(Mesh, TransformedMovesEveryVertex) {
  const Eigen::Matrix3d r = Eigen::AngleAxisd(0.7, Vec3(1, 2, 3).normalized()).toRotationMatrix();
  const Mesh a = make_icosahedron(1), b = a.transformed(r, {1, -2, 3});
  for (std::size_t i = 0; i < a.vertices().size(); ++i)
    EXPECT_LT((b.vertices()[i] - (r * a.vertices()[i] + Vec3(1, -2, 3))).norm(), 1e-15);
  EXPECT_EQ(b.planes().size(), a.planes().size());
}

}  // namespace

namespace {
TEST(Mesh, ConvexityToleratesRoundingOfFlatFaces) {
  // A unit cube with one end of its top face's triangulation diagonal lowered by
  // `lift`: the top face folds inward along that diagonal (lowering a corner off
  // the diagonal would fold it outward, still convex). A 1e-8 dent (an OBJ's
  // rounding) passes; a 1e-3 dent does not.
  const Mesh cube = gacompare::core::load_obj(kMeshes / "cube.obj");
  std::vector<int> top;
  for (std::size_t t = 0; t < cube.triangles().size(); ++t)
    if (cube.normals()[t].z() > 0.5) top.insert(top.end(), cube.triangles()[t].begin(), cube.triangles()[t].end());
  ASSERT_EQ(top.size(), 6u);
  int shared = -1;
  for (int k = 3; k < 6; ++k)
    if (std::count(top.begin(), top.begin() + 3, top[k])) shared = top[k];
  ASSERT_GE(shared, 0);
  for (const double lift : {1e-8, 1e-3}) {
    std::vector<gacompare::core::Vec3> v = cube.vertices();
    v[shared].z() -= lift;
    const Mesh bent = Mesh::from_triangles("bent cube", v, cube.triangles());
    EXPECT_EQ(convexity(bent).convex, lift < 1e-6) << lift << ": " << convexity(bent).reason;
  }
}
}  // namespace
