#pragma once
// Collision cases made ready to query: the meshes built and checked
// convex, the poses as rotation matrices. The file format is in core/model/scene.hpp
// (load_collision_cases); `gacompare collide`, the tests and the benchmarks all
// read the same files under data/collision/.
#include "core/collision/collision.hpp"
#include "core/model/scene.hpp"

#include <cstdint>
#include <filesystem>
#include <memory>
#include <string>
#include <vector>

namespace gacompare::collision {

struct CollisionCase {
  std::string name;
  std::shared_ptr<const Mesh> mesh_a, mesh_b;
  Pose pose_a, pose_b;
  Placed a() const { return {mesh_a.get(), pose_a}; }
  Placed b() const { return {mesh_b.get(), pose_b}; }
};

// Builds each shape (core::mesh_for) and requires it convex; an error names the
// file, the case and the body ("FILE: case 3 (edge-edge) /a: ...").
std::vector<CollisionCase> build_cases(const std::vector<core::CollisionCaseSpec>& specs,
                                       const std::filesystem::path& file);
std::vector<CollisionCase> load_cases(const std::filesystem::path& file);

// The seeded random corpus (data/collision/random.json is this with seed 2026
// and 200 pairs): hulls of 4–64 points drawn in an ellipsoid with random
// semi-axes 0.3–1, uniform random orientations (normalised 4D Gaussians), b
// placed along a random direction at 0.2–1.6 × the sum of the hulls' radii
// from a, so that about half the pairs overlap; centred at `centre`.
std::vector<core::CollisionCaseSpec> random_case_specs(std::uint64_t seed, int count,
                                                       const Vec3& centre = Vec3::Zero());

Pose pose_of(const Vec3& position, const Eigen::Vector4d& wxyz);

}  // namespace gacompare::collision
