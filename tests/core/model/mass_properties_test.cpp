// Mass properties (§2.3.3): the exact integrals against closed forms and rigid
// motions, the voxel method against its own error bound, Gauss–Jordan against
// Eigen, principal axes.
#include "core/error.hpp"
#include "core/model/mass_properties.hpp"
#include "core/model/mesh.hpp"

#include <Eigen/Geometry>
#include <Eigen/Eigenvalues>
#include <Eigen/LU>
#include <gtest/gtest.h>

#include <cmath>
#include <numbers>
#include <random>

namespace {

using namespace gacompare::core;
using Eigen::Matrix3d;

// Rounding: a few hundred floating-point operations per triangle on O(1)
// numbers, summed over ≤ 20 triangles: relative error ≲ 1e-14.
constexpr double kExact = 1e-13;

double rel(const Matrix3d& a, const Matrix3d& b) { return (a - b).norm() / b.norm(); }

struct ClosedForm {
  Mesh mesh;
  double volume;
  Matrix3d inertia_per_mass;  // about the centre of mass, the shape's own axes
};

std::vector<ClosedForm> closed_forms() {
  const double a = 1.3, b = 0.7, c = 2.1;
  const double phi = std::numbers::phi;
  std::vector<ClosedForm> out;
  // Box: I = m/12 (b² + c², a² + c², a² + b²).
  out.push_back({make_box({a, b, c}), a * b * c,
                 Eigen::Vector3d(b * b + c * c, a * a + c * c, a * a + b * b).asDiagonal() * (1.0 / 12)});
  // Regular tetrahedron of edge e: V = e³/(6√2), I = m e²/20 about every axis.
  const double e = 1.7;
  out.push_back({make_tetrahedron(e), e * e * e / (6 * std::numbers::sqrt2), Matrix3d::Identity() * e * e / 20});
  // Square pyramid, base s, height h: V = s²h/3, I_xx = I_yy = m(s²/20 + 3h²/80), I_zz = m s²/10.
  const double s = 1.2, h = 0.9;
  out.push_back({make_pyramid(s, h), s * s * h / 3,
                 Eigen::Vector3d(s * s / 20 + 3 * h * h / 80, s * s / 20 + 3 * h * h / 80, s * s / 10).asDiagonal()});
  // Octahedron |x| + |y| + |z| ≤ r: V = 4r³/3, I = m r²/5 (= m e²/10 with e = r√2).
  const double r = 0.8;
  out.push_back({make_octahedron(r), 4 * r * r * r / 3, Matrix3d::Identity() * r * r / 5});
  // Icosahedron of circumradius R: edge e = R / sin(2π/5), V = 5(3 + √5)e³/12,
  // I = m e² φ²/10 about every axis.
  const double R = 1.1, ei = R / std::sin(2 * std::numbers::pi / 5);
  out.push_back({make_icosahedron(R), 5 * (3 + std::sqrt(5.0)) * ei * ei * ei / 12,
                 Matrix3d::Identity() * ei * ei * phi * phi / 10});
  return out;
}

TEST(MassProperties, ExactMatchesClosedForms) {
  const double density = 2.5;
  for (const auto& cf : closed_forms()) {
    const MassProperties mp = mass_properties(cf.mesh, density);
    EXPECT_NEAR(mp.volume, cf.volume, kExact * cf.volume) << cf.mesh.name();
    EXPECT_NEAR(mp.mass, density * cf.volume, kExact * density * cf.volume) << cf.mesh.name();
    EXPECT_LT(mp.centre_of_mass.norm(), kExact * cf.mesh.size()) << cf.mesh.name();  // built centred
    EXPECT_LT(rel(mp.inertia, mp.mass * cf.inertia_per_mass), kExact) << cf.mesh.name() << "\n" << mp.inertia;
  }
}

TEST(MassProperties, RotatedAndTranslatedCopyTransformsAsTensor) {
  const Matrix3d rot = Eigen::AngleAxisd(1.1, Eigen::Vector3d(0.3, -1, 2).normalized()).toRotationMatrix();
  const Vec3 t(4, -3, 12);
  for (const auto& cf : closed_forms()) {
    const MassProperties a = mass_properties(cf.mesh, 3);
    const MassProperties b = mass_properties(cf.mesh.transformed(rot, t), 3);
    // Far from the origin the tolerance grows with |t|/size (the vertices carry
    // rounding of ~eps |t|), hence 1e-12 rather than kExact.
    EXPECT_NEAR(b.volume, a.volume, 1e-12 * a.volume) << cf.mesh.name();
    EXPECT_LT((b.centre_of_mass - (rot * a.centre_of_mass + t)).norm(), 1e-12 * t.norm()) << cf.mesh.name();
    EXPECT_LT(rel(b.inertia, rot * a.inertia * rot.transpose()), 1e-12) << cf.mesh.name();
    // Parallel axis theorem, against the closed form moved by hand:
    // about the origin, I = I_c + m(|t|² 1 − t tᵀ).
    const Matrix3d about_origin = rot * (a.mass * cf.inertia_per_mass) * rot.transpose() +
                                  a.mass * (t.squaredNorm() * Matrix3d::Identity() - t * t.transpose());
    EXPECT_LT(rel(inertia_about(b, Vec3::Zero()), about_origin), 1e-12) << cf.mesh.name();
  }
}

TEST(MassProperties, NonConvexAndOffCentreMeshes) {
  // Two unit cubes side by side as one hull-free mesh would be convex; instead an
  // L of three unit cubes, built from a box mesh by parity-independent sums:
  // mass properties are additive, so the L equals the sum of its cubes.
  const Mesh l = load_obj(std::filesystem::path(GACOMPARE_TEST_DATA_DIR) / "meshes" / "l_shape.obj");
  EXPECT_FALSE(convexity(l).convex);
  const MassProperties mp = mass_properties(l);
  const Vec3 centres[] = {{0.5, 0.5, 0.5}, {1.5, 0.5, 0.5}, {0.5, 1.5, 0.5}};
  Vec3 c = Vec3::Zero();
  for (const auto& x : centres) c += x / 3;
  Matrix3d i = Matrix3d::Zero();
  for (const auto& x : centres) {
    const Vec3 r = x - c;
    i += Matrix3d::Identity() / 6 + (r.squaredNorm() * Matrix3d::Identity() - r * r.transpose());
  }
  EXPECT_NEAR(mp.volume, 3, kExact);
  EXPECT_LT((mp.centre_of_mass - c).norm(), kExact);
  EXPECT_LT(rel(mp.inertia, i), kExact);
}

// The voxel method's error bound. The cells whose weight differs from the
// solid's indicator all meet the surface, so they lie in the shell of points
// within ρ = √3 h (a cell's diagonal) of it. By Steiner's formula for the convex
// body K, that shell has volume W ≤ V(K + ρB) − V(K ⊖ ρB) ≤ 2Aρ + Mρ² + 4πρ³/3
// with M = ½ Σ_edges ℓ (π − dihedral) ≤ (π/2) Σ ℓ. Then |ΔV| ≤ W; the first
// moment about the exact centre changes by ≤ W (R + ρ), R the largest vertex
// distance from it, so |Δc| ≤ W (R + ρ)/V'; the second moment changes by
// ≤ W (R + ρ)² (the norm of |r|² 1 − r rᵀ is |r|²), and re-centring adds ≤ V'|Δc|².
TEST(MassProperties, VoxelMethodConvergesWithinItsBound) {
  const Matrix3d rot = Eigen::AngleAxisd(0.3, Eigen::Vector3d(1, 2, 2).normalized()).toRotationMatrix();
  const Mesh shapes[] = {make_box({1, 2, 3}), make_tetrahedron(1.5), make_octahedron(0.8),
                         make_icosahedron(1.1).transformed(rot, Vec3::Zero()), make_pyramid(1.2, 0.9)};
  for (const Mesh& m : shapes) {
    const MassProperties exact = mass_properties(m);
    double area = 0, edges = 0, radius = 0;
    for (const auto& [a, b, c] : m.triangles()) {
      const auto& v = m.vertices();
      area += (v[b] - v[a]).cross(v[c] - v[a]).norm() / 2;
      edges += ((v[b] - v[a]).norm() + (v[c] - v[b]).norm() + (v[a] - v[c]).norm()) / 2;  // each edge twice
    }
    for (const auto& v : m.vertices()) radius = std::max(radius, (v - exact.centre_of_mass).norm());
    Eigen::AlignedBox3d box;
    for (const auto& v : m.vertices()) box.extend(v);
    double first_error = -1, last_error = -1;
    for (int n : {8, 16, 32, 64}) {
      const double h = box.sizes().maxCoeff() / n, rho = std::sqrt(3.0) * h;
      const double w = 2 * area * rho + std::numbers::pi / 2 * edges * rho * rho + 4 * std::numbers::pi / 3 * rho * rho * rho;
      const VoxelMassProperties vox = voxel_mass_properties(m, h);
      const MassProperties& p = vox.properties;
      EXPECT_EQ(vox.cells, static_cast<long>(std::ceil(box.sizes().x() / h)) * static_cast<long>(std::ceil(box.sizes().y() / h)) *
                               static_cast<long>(std::ceil(box.sizes().z() / h)));
      EXPECT_NEAR(p.volume, vox.cells_inside * h * h * h, 1e-12 * p.volume);
      EXPECT_LE(std::abs(p.volume - exact.volume), w) << m.name() << " n=" << n;
      const double dc = w * (radius + rho) / p.volume;
      EXPECT_LE((p.centre_of_mass - exact.centre_of_mass).norm(), dc) << m.name() << " n=" << n;
      const double di = w * (radius + rho) * (radius + rho) + p.volume * dc * dc;
      EXPECT_LE((p.inertia - exact.inertia).operatorNorm(), di) << m.name() << " n=" << n;
      const double err = std::abs(p.volume - exact.volume) / exact.volume + rel(p.inertia, exact.inertia);
      if (first_error < 0) first_error = err;
      last_error = err;
    }
    // 8× finer cells: the bound falls 8×; the error falls at least 4× (often more,
    // as the signed errors of centre sampling cancel along flat faces).
    EXPECT_LE(last_error, first_error / 4 + 1e-12) << m.name();
  }
}

TEST(MassProperties, VoxelParityAgreesWithFacePlanes) {
  const Mesh m = make_icosahedron(1);
  const VoxelMassProperties a = voxel_mass_properties(m, 0.1, 2, CellTest::face_planes);
  const VoxelMassProperties b = voxel_mass_properties(m, 0.1, 2, CellTest::parity);
  EXPECT_EQ(a.cells, b.cells);
  EXPECT_EQ(a.cells_inside, b.cells_inside);
  EXPECT_NEAR(a.properties.mass, b.properties.mass, 1e-12);
  // The face-plane test needs a convex body.
  const Mesh l = load_obj(std::filesystem::path(GACOMPARE_TEST_DATA_DIR) / "meshes" / "l_shape.obj");
  EXPECT_THROW(voxel_mass_properties(l, 0.1), gacompare::Error);
  EXPECT_NEAR(voxel_mass_properties(l, 0.1, 1, CellTest::parity).properties.volume, 3, 1e-9);  // cells align with the faces
  EXPECT_THROW(voxel_mass_properties(m, 0), gacompare::Error);
}

Eigen::MatrixXd random_spd(std::mt19937_64& rng, int n) {
  std::normal_distribution<double> g;
  Eigen::MatrixXd b(n, n);
  for (int i = 0; i < n; ++i)
    for (int j = 0; j < n; ++j) b(i, j) = g(rng);
  return b * b.transpose() + 0.1 * Eigen::MatrixXd::Identity(n, n);
}

TEST(MassProperties, GaussJordanMatchesEigen) {
  std::mt19937_64 rng(7);
  for (int trial = 0; trial < 200; ++trial) {
    const int n = trial % 2 ? 3 : 6;
    const Eigen::MatrixXd a = random_spd(rng, n);
    const Inverse gj = gauss_jordan_inverse(a);
    ASSERT_TRUE(gj.inverse) << gj.failure;
    const Eigen::MatrixXd eigen = a.partialPivLu().inverse();
    // Both are backward stable: each differs from the true inverse by ~cond·eps.
    const double cond = a.norm() * eigen.norm();
    EXPECT_LT((*gj.inverse - eigen).norm() / eigen.norm(), 50 * cond * std::numeric_limits<double>::epsilon());
    EXPECT_LT((*gj.inverse * a - Eigen::MatrixXd::Identity(n, n)).norm(), 50 * cond * std::numeric_limits<double>::epsilon());
  }
  // A zero diagonal needs the pivoting.
  Eigen::MatrixXd perm(3, 3);
  perm << 0, 2, 0, 0, 0, 3, 4, 0, 0;
  EXPECT_EQ(*gauss_jordan_inverse(perm).inverse, Eigen::MatrixXd(perm.inverse()));
  // Inertia from an actual body, through the Matrix3d entry point.
  const Matrix3d inertia = mass_properties(make_pyramid(1, 2).transformed(
                                               Eigen::AngleAxisd(0.5, Vec3(1, 1, 0).normalized()).toRotationMatrix(), Vec3::Zero()))
                               .inertia;
  EXPECT_LT(rel(inverse_inertia(inertia), inertia.inverse()), 1e-14);
}

TEST(MassProperties, GaussJordanRefusesSingular) {
  Eigen::MatrixXd s(3, 3);
  s << 1, 2, 3, 2, 4, 6, 1, 0, 1;  // row 2 = 2 × row 1, exactly
  const Inverse r = gauss_jordan_inverse(s);
  EXPECT_FALSE(r.inverse);
  EXPECT_NE(r.failure.find("singular: largest remaining pivot 0 at elimination step 3 of 3"), std::string::npos) << r.failure;
  Matrix3d flat = Matrix3d::Zero();
  flat.diagonal() << 1, 1, 0;  // a rod's tensor: no inverse
  try {
    inverse_inertia(flat);
    ADD_FAILURE() << "no error";
  } catch (const gacompare::Error& e) {
    EXPECT_EQ(e.kind(), gacompare::ErrorKind::run);
    EXPECT_NE(std::string(e.what()).find("inverse inertia: singular"), std::string::npos) << e.what();
  }
  EXPECT_FALSE(gauss_jordan_inverse(Eigen::MatrixXd(2, 3)).inverse);
}

TEST(MassProperties, PrincipalAxesDiagonalise) {
  const Matrix3d rot = Eigen::AngleAxisd(0.9, Vec3(2, -1, 1).normalized()).toRotationMatrix();
  const MassProperties mp = mass_properties(make_box({1, 2, 3}).transformed(rot, {1, 2, 3}));
  const PrincipalAxes p = principal_axes(mp.inertia);
  // Box 1×2×3, mass 6: moments m/12 (b² + c², ...) = 6.5, 5, 2.5, ascending.
  EXPECT_NEAR(p.moments[0], 2.5, 1e-13);
  EXPECT_NEAR(p.moments[1], 5, 1e-13);
  EXPECT_NEAR(p.moments[2], 6.5, 1e-13);
  EXPECT_NEAR(p.axes.determinant(), 1, 1e-14);
  EXPECT_LT(rel(p.axes * p.moments.asDiagonal() * p.axes.transpose(), mp.inertia), 1e-14);
  // The smallest moment is about the box's long (z) axis, rotated.
  EXPECT_NEAR(std::abs(p.axes.col(0).dot(rot.col(2))), 1, 1e-13);
}

}  // namespace
