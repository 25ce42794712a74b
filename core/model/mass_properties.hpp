#pragma once
// Mass properties of a uniform solid bounded by a closed mesh (§2.3.3): exact
// polyhedral integrals (the reference), the report's voxel method (approximate,
// kept to show what its accuracy costs), inverse inertia by Gauss–Jordan with
// full pivoting (as the report) and principal axes.
#include "core/model/mesh.hpp"

#include <Eigen/Core>

#include <optional>
#include <string>

namespace gacompare::core {

struct MassProperties {
  double volume = 0;
  double mass = 0;
  Vec3 centre_of_mass = Vec3::Zero();                     // mesh coordinates
  Eigen::Matrix3d inertia = Eigen::Matrix3d::Zero();      // about the centre of mass, mesh axes
};

// Exact for any closed, outward mesh (convex or not): the divergence theorem
// splits the solid into signed tetrahedra (reference point, triangle), each
// integrated in closed form — the covariance form of Blow & Binstock (2004),
// equivalent to Mirtich (1996, "Fast and accurate computation of polyhedral mass
// properties") for triangles. Better than the report, whose voxels only approach it.
MassProperties mass_properties(const Mesh& mesh, double density = 1);

// Inertia about another point (parallel axis theorem): I_q = I_c + m(|r|² 1 − r rᵀ), r = c − q.
Eigen::Matrix3d inertia_about(const MassProperties& props, const Vec3& point);

enum class CellTest { face_planes, parity };  // the report's two tests (§2.3.3)

struct VoxelMassProperties {
  MassProperties properties;
  long cells = 0;         // cells tested (the grid)
  double cells_inside = 0;  // cells counted (boundary centres count half)
};

// §2.3.3 steps 1–5 with cubic cells of side `cell`; step 6 is inverse_inertia().
// face_planes needs a convex mesh (throws input_error otherwise).
VoxelMassProperties voxel_mass_properties(const Mesh& mesh, double cell, double density = 1,
                                          CellTest test = CellTest::face_planes);

struct Inverse {
  std::optional<Eigen::MatrixXd> inverse;  // empty when singular
  std::string failure;                      // one line when singular
};
// §2.3.3 step 6: Gauss–Jordan elimination with full (row and column) pivoting.
// Singular when a pivot is ≤ n·ε·max|a_ij|: there the elimination has lost every
// digit, and a "successful" inverse would be rounding noise.
Inverse gauss_jordan_inverse(const Eigen::MatrixXd& a);
// The inertia tensor's inverse; throws run_error with the failure for a singular tensor.
Eigen::Matrix3d inverse_inertia(const Eigen::Matrix3d& inertia);

struct PrincipalAxes {
  Vec3 moments;           // ascending
  Eigen::Matrix3d axes;   // columns: unit axes, right-handed (det +1); inertia = axes diag(moments) axesᵀ
};
PrincipalAxes principal_axes(const Eigen::Matrix3d& inertia);

}  // namespace gacompare::core
