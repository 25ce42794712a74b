#include "answers/collision_cases.hpp"

#include "core/error.hpp"

#include <Eigen/Geometry>

#include <random>

namespace gacompare::collision {

Pose pose_of(const Vec3& position, const Eigen::Vector4d& wxyz) {
  const Eigen::Quaterniond q(wxyz[0], wxyz[1], wxyz[2], wxyz[3]);
  return {q.normalized().toRotationMatrix(), position};
}

std::vector<CollisionCase> build_cases(const std::vector<core::CollisionCaseSpec>& specs,
                                       const std::filesystem::path& file) {
  std::vector<CollisionCase> out;
  out.reserve(specs.size());
  for (std::size_t i = 0; i < specs.size(); ++i) {
    const auto& s = specs[i];
    const auto build = [&](const core::PlacedShape& p, const char* which) {
      try {
        auto mesh = std::make_shared<const Mesh>(core::mesh_for(p.shape));
        core::require_convex(*mesh);
        return mesh;
      } catch (const Error& e) {
        throw input_error(file.string() + ": /" + std::to_string(i) + "/" + which + " (" + s.name + "): " + e.what());
      }
    };
    out.push_back({s.name, build(s.a, "a"), build(s.b, "b"), pose_of(s.a.position, s.a.orientation),
                   pose_of(s.b.position, s.b.orientation)});
  }
  return out;
}

std::vector<core::CollisionCaseSpec> random_case_specs(std::uint64_t seed, int count, const Vec3& centre) {
  std::mt19937_64 rng(seed);
  std::normal_distribution<double> gauss;
  std::uniform_real_distribution<double> unit(0, 1);
  const auto direction = [&] {
    Vec3 d(gauss(rng), gauss(rng), gauss(rng));
    return Vec3(d.normalized());
  };
  const auto body = [&](const Vec3& position) {
    const int n = 4 + static_cast<int>(unit(rng) * 61);  // 4..64
    const Vec3 axes(0.3 + 0.7 * unit(rng), 0.3 + 0.7 * unit(rng), 0.3 + 0.7 * unit(rng));
    core::HullShape h;
    for (int i = 0; i < n; ++i) h.points.push_back(direction().cwiseProduct(axes) * std::cbrt(unit(rng)));
    Eigen::Vector4d q(gauss(rng), gauss(rng), gauss(rng), gauss(rng));
    return std::pair{core::PlacedShape{h, position, q.normalized()}, axes.maxCoeff()};
  };
  std::vector<core::CollisionCaseSpec> out;
  for (int i = 0; i < count; ++i) {
    auto [a, ra] = body(centre);
    auto [b, rb] = body(Vec3::Zero());
    b.position = centre + direction() * ((0.2 + 1.4 * unit(rng)) * (ra + rb));
    out.push_back({"random " + std::to_string(i), a, b});
  }
  return out;
}

std::vector<CollisionCase> load_cases(const std::filesystem::path& file) {
  return build_cases(core::load_collision_cases(file), file);
}

}  // namespace gacompare::collision
