// The equivalence suite: bundled rigid-body scenes through every backend, whose
// trajectories must agree to within what the solver's tolerance allows. Each
// accepted Cash–Karp step may err by its tolerance (abs + rel·|y| ≤ 2·tol for
// |y| ≤ 1 m or rad), so two correct integrations of the same free flight — one
// on a matrix, one on a rotor — differ by at most ~2·tol per step taken:
// bound = 2·tol·(steps of both runs). An orientation is a phase: an error ε in ω
// at time t turns into an angle ε·(T − t) by the end, so the angle's bound carries
// the factor 1 + |ω₀|·T (|ω₀| the fastest initial spin, T the duration).
#include "compare/results.hpp"
#include "compare/runner.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

namespace gacompare::compare {
namespace {

class Equivalence : public ::testing::TestWithParam<const char*> {};

TEST_P(Equivalence, BackendsAgreeWithinTheSolverTolerance) {
  const auto scene = core::load_scene(std::string(GACOMPARE_DATA_DIR) + "/scenes/" + GetParam() + ".json");
  const SceneResult all = compare_scene(scene, backend_names(), 1);
  // traditional (the matrix), its quaternion twin, cga, pga: Bullet runs collision scenes only.
  ASSERT_EQ(all.backends.size(), 4u);
  EXPECT_EQ(all.backends[1].run.backend, "traditional-quaternion");
  for (const auto& b : all.backends) ASSERT_FALSE(b.run.error.has_value()) << *b.run.error;
  double spin = 0;
  for (const auto& b : scene.bodies) spin = std::max(spin, b.angular_velocity.norm());
  // Each geometric algebra against the matrix backend, the bound from the
  // steps the pair took.
  for (std::size_t k = 1; k < all.backends.size(); ++k) {
    SceneResult r = all;
    r.backends = {all.backends[0], all.backends[k]};
    const double steps = static_cast<double>(r.backends[0].run.solver.steps_accepted + r.backends[1].run.solver.steps_accepted);
    const double bound = 2 * scene.solver.rel_tol * steps;
    EXPECT_LT(max_divergence(r), bound) << r.backends[1].run.backend;
    EXPECT_LT(max_orientation_divergence(r), bound * (1 + spin * scene.duration)) << r.backends[1].run.backend;
    EXPECT_GT(max_orientation_divergence(r), 0.0) << r.backends[1].run.backend;  // the algebras differ: not the same code twice
  }
}

INSTANTIATE_TEST_SUITE_P(RigidScenes, Equivalence, ::testing::Values("tumbling_box", "spinning_top"));

}  // namespace
}  // namespace gacompare::compare
