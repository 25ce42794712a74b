#include "core/model/mass_properties.hpp"

#include "core/error.hpp"
#include "core/model/point_in_body.hpp"

#include <Eigen/Eigenvalues>
#include <Eigen/Geometry>

#include <cmath>
#include <limits>
#include <numbers>
#include <sstream>
#include <utility>

namespace gacompare::core {

namespace {
// Volume, first moment and second moment C = ∫ r rᵀ dV about `o` → mass properties.
// The inertia tensor is I = ρ (tr(C) 1 − C) once C is taken about the centre of mass.
MassProperties from_moments(double volume, const Vec3& first, const Eigen::Matrix3d& second, const Vec3& o,
                            double density) {
  MassProperties m;
  m.volume = volume;
  m.mass = density * volume;
  const Vec3 c = first / volume;  // centre of mass relative to o
  m.centre_of_mass = o + c;
  const Eigen::Matrix3d cc = second - volume * c * c.transpose();
  m.inertia = density * (cc.trace() * Eigen::Matrix3d::Identity() - cc);
  m.inertia = (m.inertia + m.inertia.transpose()) / 2;  // exactly symmetric for the eigen solver
  return m;
}

// A capsule, exact (core/model/mesh.hpp make_capsule): a cylinder of radius r and
// length L and two hemispheres. About the axis the cylinder gives ½ m_c r²
// and the hemispheres together a sphere's 2/5 m_s r². Across it the cylinder
// gives m_c (3r² + L²)/12; each hemisphere (mass ½ m_s) has 2/5 (½ m_s) r²
// about a diameter of its flat face, its centre of mass 3r/8 from that face,
// so about the capsule's centre, ½L + 3r/8 away: 2/5 r² − (3r/8)² +
// (½L + 3r/8)², per unit mass; for both, m_s (2/5 r² + L²/4 + 3Lr/8).
MassProperties capsule_mass_properties(const Mesh& mesh, double density) {
  const double r = mesh.sphere_radius(), l = 2 * mesh.capsule_half_axis().norm();
  const Vec3 u = mesh.capsule_half_axis().normalized();
  const double cylinder = std::numbers::pi * r * r * l, spheres = 4.0 / 3.0 * std::numbers::pi * r * r * r;
  const double mc = density * cylinder, ms = density * spheres;
  const double along = 0.5 * mc * r * r + 0.4 * ms * r * r;
  const double across = mc * (3 * r * r + l * l) / 12 + ms * (0.4 * r * r + 0.25 * l * l + 0.375 * l * r);
  MassProperties m;
  m.volume = cylinder + spheres;
  m.mass = density * m.volume;
  m.centre_of_mass = mesh.sphere_centre();
  m.inertia = across * Eigen::Matrix3d::Identity() + (along - across) * (u * u.transpose());
  return m;
}
}  // namespace

// §2.3.3 asks for volume, centre of mass and inertia; the report integrates on a
// grid (below). Here each triangle (a, b, c) with the reference point o spans a
// tetrahedron of signed volume det/6, det = a·(b×c) (relative to o); over the
// closed surface the signs cancel outside the solid (divergence theorem), so the
// sums are exact for any closed outward mesh. Per tetrahedron (Blow & Binstock
// 2004, the canonical tetrahedron's covariance mapped by [a b c]):
//   ∫ r dV = det/24 (a + b + c),   ∫ r rᵀ dV = det/120 (a aᵀ + b bᵀ + c cᵀ + s sᵀ), s = a + b + c.
// o is the mean of the vertices, not the origin: far from the origin the
// products would otherwise cancel catastrophically (a mesh at 1e6 m would lose
// ~12 digits of its inertia).
MassProperties mass_properties(const Mesh& mesh, double density) {
  if (mesh.is_sphere()) {
    // Exact, not the proxy's (core/model/mesh.hpp): V = 4/3 π r³, I = 2/5 m r².
    const double r = mesh.sphere_radius();
    MassProperties m;
    m.volume = 4.0 / 3.0 * std::numbers::pi * r * r * r;
    m.mass = density * m.volume;
    m.centre_of_mass = mesh.sphere_centre();
    m.inertia = (0.4 * m.mass * r * r) * Eigen::Matrix3d::Identity();
    return m;
  }
  if (mesh.is_capsule()) return capsule_mass_properties(mesh, density);
  const auto& v = mesh.vertices();
  Vec3 o = Vec3::Zero();
  for (const auto& p : v) o += p;
  o /= static_cast<double>(v.size());
  double six_v = 0;
  Vec3 first = Vec3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (const auto& [ia, ib, ic] : mesh.triangles()) {
    const Vec3 a = v[ia] - o, b = v[ib] - o, c = v[ic] - o, s = a + b + c;
    const double det = a.dot(b.cross(c));
    six_v += det;
    first += det / 24 * s;
    second += det / 120 * (a * a.transpose() + b * b.transpose() + c * c.transpose() + s * s.transpose());
  }
  return from_moments(six_v / 6, first, second, o, density);
}

Eigen::Matrix3d inertia_about(const MassProperties& props, const Vec3& point) {
  const Vec3 r = props.centre_of_mass - point;
  return props.inertia + props.mass * (r.squaredNorm() * Eigen::Matrix3d::Identity() - r * r.transpose());
}

// §2.3.3 steps 1–5. Did better than the report in three places, none of which
// changes its O(cell) accuracy: one pass (moments about the box centre, shifted
// to the centre of mass afterwards, instead of a second pass over the grid);
// each cell adds its own inertia (ρ h⁵/6 per axis, the cube's) rather than a
// point mass's zero; a cell whose centre lies on the surface (within 1e-12 ×
// size) counts half, so a grid aligned with a face is not biased to one side.
VoxelMassProperties voxel_mass_properties(const Mesh& mesh, double cell, double density, CellTest test) {
  if (!(cell > 0) || !std::isfinite(cell))
    throw input_error(mesh.name() + ": voxel cell size must be positive and finite");
  if (test == CellTest::face_planes) require_convex(mesh);
  Eigen::AlignedBox3d box;  // step 1
  for (const auto& p : mesh.vertices()) box.extend(p);
  const Vec3 o = box.center();
  Eigen::Array3i n;  // step 2: cells per axis, the grid centred on the box
  for (int k = 0; k < 3; ++k) {
    const double count = std::ceil(box.sizes()[k] / cell);
    if (count > 1e5) throw input_error(mesh.name() + ": voxel cell size too small for the body (over 1e5 cells per axis)");
    n[k] = std::max(1, static_cast<int>(count));
  }
  if (static_cast<double>(n[0]) * n[1] * n[2] > 1e9)
    throw input_error(mesh.name() + ": voxel cell size too small for the body (over 1e9 cells)");
  const double tol = 1e-12 * mesh.size();
  double w_sum = 0;
  Vec3 first = Vec3::Zero();
  Eigen::Matrix3d second = Eigen::Matrix3d::Zero();
  for (int i = 0; i < n[0]; ++i)
    for (int j = 0; j < n[1]; ++j)
      for (int k = 0; k < n[2]; ++k) {
        const Vec3 r = cell * Vec3(i + 0.5 - n[0] / 2.0, j + 0.5 - n[1] / 2.0, k + 0.5 - n[2] / 2.0);
        const Where where = test == CellTest::face_planes ? classify_convex(mesh, o + r, tol)
                                                          : classify_by_parity(mesh, o + r, tol).where;
        if (where == Where::outside) continue;  // step 3
        const double w = where == Where::inside ? 1.0 : 0.5;
        w_sum += w;
        first += w * r;
        second += w * r * r.transpose();
      }
  VoxelMassProperties out;
  out.cells = static_cast<long>(n[0]) * n[1] * n[2];
  out.cells_inside = w_sum;
  if (w_sum == 0)
    throw input_error(mesh.name() + ": voxel cell size " + std::to_string(cell) + " leaves no cell centre inside the body");
  const double dv = cell * cell * cell;
  second = dv * second + dv * w_sum * cell * cell / 12 * Eigen::Matrix3d::Identity();  // + each cube's own ∫ r rᵀ
  out.properties = from_moments(dv * w_sum, dv * first, second, o, density);  // steps 4, 5
  return out;
}

// §2.3.3 step 6 ("Gauss-Jacobi with full pivoting": Gauss–Jordan, as in Numerical
// Recipes' gaussj, §2.1): in place, the largest remaining element as pivot, the
// column swaps undone at the end. For the SPD inertia tensor, Cholesky or Eigen's
// closed-form 3×3 inverse would do; this is kept because the report used it and is
// tested against Eigen.
Inverse gauss_jordan_inverse(const Eigen::MatrixXd& input) {
  const Eigen::Index n = input.rows();
  if (n != input.cols() || n == 0) return {std::nullopt, "not a square matrix"};
  Eigen::MatrixXd a = input;
  const double threshold = static_cast<double>(n) * std::numeric_limits<double>::epsilon() * a.cwiseAbs().maxCoeff();
  std::vector<Eigen::Index> row_of(n), col_of(n);
  std::vector<char> used(n, 0);
  for (Eigen::Index step = 0; step < n; ++step) {
    double big = -1;
    Eigen::Index irow = 0, icol = 0;
    for (Eigen::Index j = 0; j < n; ++j)
      if (!used[j])
        for (Eigen::Index k = 0; k < n; ++k)
          if (!used[k] && std::abs(a(j, k)) > big) big = std::abs(a(j, k)), irow = j, icol = k;
    if (!(big > threshold)) {
      std::ostringstream s;
      s << "singular: largest remaining pivot " << big << " at elimination step " << step + 1 << " of " << n
        << " is below n·eps·max|a| = " << threshold;
      return {std::nullopt, s.str()};
    }
    used[icol] = 1;
    if (irow != icol) a.row(irow).swap(a.row(icol));
    row_of[step] = irow;
    col_of[step] = icol;
    const double inv = 1 / a(icol, icol);
    a(icol, icol) = 1;
    a.row(icol) *= inv;
    for (Eigen::Index r = 0; r < n; ++r)
      if (r != icol) {
        const double f = a(r, icol);
        a(r, icol) = 0;
        a.row(r) -= f * a.row(icol);
      }
  }
  for (Eigen::Index step = n - 1; step >= 0; --step)
    if (row_of[step] != col_of[step]) a.col(row_of[step]).swap(a.col(col_of[step]));
  return {std::move(a), ""};
}

Eigen::Matrix3d inverse_inertia(const Eigen::Matrix3d& inertia) {
  Inverse r = gauss_jordan_inverse(inertia);
  if (!r.inverse) throw run_error("inverse inertia: " + r.failure);
  return *r.inverse;
}

PrincipalAxes principal_axes(const Eigen::Matrix3d& inertia) {
  const Eigen::SelfAdjointEigenSolver<Eigen::Matrix3d> solver(inertia);
  PrincipalAxes p{solver.eigenvalues(), solver.eigenvectors()};
  if (p.axes.determinant() < 0) p.axes.col(2) = -p.axes.col(2);
  return p;
}

}  // namespace gacompare::core
