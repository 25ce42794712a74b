#pragma once
// Closed triangle meshes for rigid bodies (§2.3.3 of the report): the
// built-in shapes of the scene format, convex hulls (Qhull) and OBJ files
// (tinyobjloader), with per-triangle outward normals and the distinct face planes.
//
// A Mesh is always valid: every constructor checks that it is closed (each edge
// in exactly two triangles), consistently oriented (each edge once in each
// direction), outward (positive signed volume) and free of zero-area triangles,
// and throws gacompare::input_error with one line naming the mesh, what failed
// and where. Convexity is checked separately (convexity()): non-convex meshes are
// fine for point-in-body by parity and for mass properties, not for the convex
// narrowphase, which calls require_convex().
#include "core/model/scene.hpp"

#include <Eigen/Core>

#include <array>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace gacompare::core {

using Triangle = std::array<int, 3>;  // vertex indices, counter-clockwise seen from outside

// n·x = offset, n unit and outward.
struct Plane {
  Vec3 normal;
  double offset;
  double distance(const Vec3& p) const { return normal.dot(p) - offset; }  // > 0 outside
};

class Mesh {
 public:
  // Validates (see above) and computes normals and planes. `name` is used in
  // every message about this mesh (a file path, or e.g. "box 1 x 2 x 3").
  static Mesh from_triangles(std::string name, std::vector<Vec3> vertices, std::vector<Triangle> triangles);

  const std::string& name() const { return name_; }
  const std::vector<Vec3>& vertices() const { return vertices_; }
  const std::vector<Triangle>& triangles() const { return triangles_; }
  const std::vector<Vec3>& normals() const { return normals_; }  // per triangle, unit, outward
  // Distinct face planes: coplanar triangles of one polygonal face share one
  // plane (§2.3.3 fn 21), so a box has 6, not 12.
  const std::vector<Plane>& planes() const { return planes_; }
  const std::vector<int>& triangle_plane() const { return triangle_plane_; }  // plane index per triangle
  // Feature edges: the undirected edges whose two triangles lie on different
  // planes (a box has 12; the diagonals that triangulate its faces are not
  // edges of the solid). The narrowphase's edge × edge axes and edge–edge
  // contacts use these. Each as (lower index, higher index).
  const std::vector<std::array<int, 2>>& edges() const { return edges_; }
  // The two distinct planes beside each feature edge: first the plane of the
  // triangle that runs the edge from edges()[i][0] to [1], then the other.
  const std::vector<std::array<int, 2>>& edge_planes() const { return edge_planes_; }
  // Per triangle, the feature edge index of its edge k (vertex k to k+1), or −1
  // for a diagonal inside a polygonal face.
  const std::vector<std::array<int, 3>>& triangle_edges() const { return triangle_edges_; }
  // Per plane, the face's boundary as a loop of vertex indices, counter-clockwise
  // seen from outside (the feature edges of that plane, chained). The contact
  // manifold clips one face against another's (core/collision/manifold.hpp). A planar face
  // of a convex mesh is one convex polygon, so its loop is always there; a face
  // whose boundary is not one loop (a non-convex mesh's face with a hole) gets
  // an empty loop, and such meshes never reach the convex narrowphase.
  const std::vector<std::vector<int>>& faces() const { return faces_; }
  // The solid's edge graph: per vertex, the feature edges that meet
  // there (indices into edges()) and the vertices at their other ends, in the
  // same order. Hill climbing to a support point walks it (core/collision/shape.hpp).
  std::span<const int> neighbours(int v) const {
    return {neighbours_.data() + neighbour_start_[v], neighbours_.data() + neighbour_start_[v + 1]};
  }
  std::span<const int> vertex_edges(int v) const {
    return {vertex_edges_.data() + neighbour_start_[v], vertex_edges_.data() + neighbour_start_[v + 1]};
  }
  // Whether every vertex is a corner of the solid (three or more feature edges
  // meet there). Then a vertex no neighbour is lower than along a direction is
  // the lowest of all (the simplex method's rule, for a convex body); a vertex
  // inside a flat face or on a straight edge has no such guarantee.
  bool corners_only() const { return corners_only_; }
  double size() const { return size_; }  // bounding-box diagonal: the length scale of tolerances

  // Whether `other` is this mesh to the last bit (vertices, triangles,
  // planes, name and round shape; the rest is derived from these): bodies of
  // one shape then share one Mesh (core/model/model.cpp).
  bool identical(const Mesh& other) const;

  // The same solid moved rigidly: x -> R x + t (R a rotation).
  Mesh transformed(const Eigen::Matrix3d& rotation, const Vec3& translation) const;

  // Built convex: a built-in shape or a Qhull hull, convex to ~1e-15 x size,
  // so convexity() need not test every vertex against every plane.
  bool convex_by_construction() const { return convex_; }
  Mesh as_convex() && {
    convex_ = true;
    return std::move(*this);
  }

  // Round shapes. A sphere is carried as a Mesh whose triangles
  // are its proxy, a convex polyhedron with every vertex on the sphere and
  // one at ±r on each axis (make_sphere): so the bounding box and the
  // bounding sphere read off the vertices are the sphere's own, exactly, and
  // everything that only bounds a body (broadphase, static boxes, sizes,
  // plots) works unchanged. What must be exact reads the radius instead:
  // mass properties, the inradius, the narrowphase (core/collision/round.hpp), the
  // referees and Bullet. 0 for a polyhedron.
  //
  // A capsule (make_capsule) is carried the same way: the points within r of
  // a segment, sphere_centre() its midpoint and capsule_half_axis() the
  // vector from there to one end (both moved by transformed()); its proxy's
  // vertices lie on the capsule, at ±r across the axis at both ends and at
  // ±(½L + r) along it. sphere_radius() is the radius of either round shape.
  double sphere_radius() const { return sphere_radius_; }
  const Vec3& sphere_centre() const { return sphere_centre_; }  // moved with the vertices by transformed()
  const Vec3& capsule_half_axis() const { return capsule_half_axis_; }  // zero for a sphere
  bool is_round() const { return sphere_radius_ > 0; }
  // Flags, not a test of the half axis: the narrowphase asks for every pair,
  // and comparing a vector there made sphere–sphere pairs take twice as long.
  bool is_sphere() const { return is_round() && !capsule_; }
  bool is_capsule() const { return capsule_; }

 private:
  Mesh() = default;  // only from_triangles makes one, so every Mesh is valid
  std::string name_;
  std::vector<Vec3> vertices_;
  std::vector<Triangle> triangles_;
  std::vector<Vec3> normals_;
  std::vector<Plane> planes_;
  std::vector<int> triangle_plane_;
  std::vector<std::array<int, 2>> edges_, edge_planes_;
  std::vector<std::array<int, 3>> triangle_edges_;
  std::vector<std::vector<int>> faces_;
  std::vector<int> neighbour_start_, neighbours_, vertex_edges_;
  bool corners_only_ = false;
  double size_ = 0;
  bool convex_ = false;
  double sphere_radius_ = 0;
  Vec3 sphere_centre_ = Vec3::Zero();
  Vec3 capsule_half_axis_ = Vec3::Zero();
  bool capsule_ = false;  // a capsule of length > 0 (make_capsule)
  friend Mesh make_sphere(double radius);
  friend Mesh make_capsule(double radius, double length);
};

// --- the built-in shapes of the scene format (core/model/scene.hpp) --------------------
// Each is centred on its centre of mass (the scene's body position), so the
// mass properties come out with a zero centre of mass.
Mesh make_box(const Vec3& size);         // full side lengths along x, y, z
Mesh make_tetrahedron(double edge);      // regular, centroid at the origin
// Square base of side `base` in the plane z = -height/4, apex at (0, 0, 3 height/4):
// the centre of mass of a solid pyramid lies a quarter of the height above its base.
Mesh make_pyramid(double base, double height);
Mesh make_octahedron(double radius);     // vertices at ±radius on the axes
Mesh make_icosahedron(double radius);    // centre-to-vertex radius
// A sphere of this radius about the origin: its proxy is the hull of the 26
// points ±r on the axes, r(±1, ±1, 0)/√2 (and permutations), r(±1, ±1, ±1)/√3
// (see Mesh::sphere_radius()).
Mesh make_sphere(double radius);
// A capsule of this radius about the segment of this length along z, centred
// on the origin: length 0 is make_sphere(radius). Its proxy is the hull of
// make_sphere's points with z ≥ 0 raised by ½ length and those with z ≤ 0
// lowered by it (see Mesh::capsule_half_axis()).
Mesh make_capsule(double radius, double length);

// The convex hull of a point set, by Qhull (reentrant libqhull_r). Points inside
// or on the hull are not vertices. Throws input_error naming `what` when the
// points span no volume (fewer than 4, coplanar, ...). Not recentred.
Mesh convex_hull(const std::vector<Vec3>& points, const std::string& what = "hull");

// A Wavefront OBJ file, by tinyobjloader (polygons triangulated; all groups
// form one mesh; vertices used by no face dropped). Not recentred.
// Every vertex line must hold finite numbers (tinyobjloader would read a
// word as 0), and every face at most 1,000 corners whose indices name vertices
// the file has (tinyobjloader would wrap one past 2^31): refused naming the
// line. The file is read as core/read_file.hpp reads (a link is not followed).
Mesh load_obj(const std::filesystem::path& file);
// The same from text in memory; `name` is used in messages.
Mesh parse_obj(const std::string& text, const std::string& name);

// Any scene shape. Hull and mesh shapes keep their own coordinates: the caller
// moves them so that the centre of mass (core/model/mass_properties.hpp) is the origin.
Mesh mesh_for(const Shape& shape);

// The radius of the largest ball about `centre` inside the convex body (a
// sphere's own radius about its centre, a capsule's less the distance to its
// segment; a polyhedron's nearest face plane, ≤ 0
// when the centre is outside): the tunnelling rule and the budgets use it.
double inradius(const Mesh& mesh, const Vec3& centre);

// Convexity: every vertex on or behind every face plane, within 1e-6 × size():
// an OBJ file written with 6 significant digits bends a flat face by up to
// ~1e-6 × size either way, and a dent that shallow is far below any penetration
// tolerance the convex narrowphase works with. (Built shapes and Qhull hulls are
// convex to ~1e-15 × size.)
struct Convexity {
  bool convex = true;
  std::string reason;  // one line naming the mesh, the vertex and the plane; empty when convex
};
Convexity convexity(const Mesh& mesh);
void require_convex(const Mesh& mesh);  // throws input_error with convexity().reason

}  // namespace gacompare::core
