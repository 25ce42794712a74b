#pragma once
// Point in body (§2.4.3 and §2.3.3): by face planes for convex bodies, by
// ray-crossing parity for any closed mesh. Both say `boundary` for points within
// `tolerance` (absolute, metres) of the surface, so callers decide how a touching
// point counts; §2.4.3's penetration tolerance is a caller's use of max_face_distance.
#include "core/model/mesh.hpp"

#include <optional>

namespace gacompare::core {

enum class Where { inside, boundary, outside };

// §2.4.3: the largest signed distance n·p − d over the distinct face planes. For
// a convex body it is ≤ 0 exactly inside, −(depth) inside, and a lower bound of
// the distance to the body outside. Meaningless for non-convex meshes.
double max_face_distance(const Mesh& mesh, const Vec3& p);

// Convex bodies only (the caller checks convexity(); this does not).
Where classify_convex(const Mesh& mesh, const Vec3& p, double tolerance);

struct ParityResult {
  Where where = Where::outside;
  int crossings = 0;       // along the accepted ray (0 for boundary points)
  int directions_tried = 0;
  Vec3 direction = Vec3::Zero();  // the accepted ray's direction
};

// Any closed mesh (§2.3.3's second method). Instead of the report's segment to
// a far point with de-duplicated hits (fn 20) we reject any ray that passes
// within a relative 1e-9 (barycentric) of an edge or vertex, or within 1e-9 rad
// of parallel to a triangle it could touch, and try the next direction of a fixed
// seeded sequence. Every crossing that is counted is then a clean transversal
// crossing of one triangle's interior, far (relative to rounding) from every
// ambiguity, so the parity is decided by well-conditioned signs. De-duplication
// cannot do this: a ray grazing a silhouette edge touches two triangles without
// entering, and counting it once is wrong. `first` lets a caller (or a test)
// choose the first direction; later ones come from the sequence. Points within
// `tolerance` of a triangle are `boundary` before any ray is cast.
ParityResult classify_by_parity(const Mesh& mesh, const Vec3& p, double tolerance,
                                std::optional<Vec3> first = std::nullopt);

// Distance from p to the closed triangle (a, b, c) (Ericson, Real-Time Collision
// Detection §5.1.5, by Voronoi regions).
double distance_to_triangle(const Vec3& p, const Vec3& a, const Vec3& b, const Vec3& c);

}  // namespace gacompare::core
