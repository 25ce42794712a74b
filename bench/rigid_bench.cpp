// Rigid-body stages, traditional matrix vs quaternion vs rotor vs motor:
//   derivative  one body's dy/dt (ω from L, the rotation's rate, forces)
//   step        one RK4 step of one body through the simulator's backend (four
//               derivatives, each with its `forces` stage timer, and the update)
//   vertices    moving a 1,000-vertex mesh into the world: R v + x for each vertex,
//               with R a matrix, a quaternion, a rotor sandwich, or the rotor's
//               matrix built once per body (the outermorphism, docs/architecture.md "Fair
//               comparison"); for the motor, its closed-form sandwich on each point
//               (pga/algebra/cl301.hpp apply: the translation included)
// Names BM_<stage>/<representation>; scripts/bench-ratios.py --reference matrix
// prints the ratio table of docs/results/rigid-bodies.md.
#include "cga/backend.hpp"
#include "core/dynamics/ode.hpp"
#include "pga/backend.hpp"
#include "traditional/backend.hpp"

#include <benchmark/benchmark.h>

#include <random>

namespace {
using namespace gacompare;

core::Scene body_scene(const char* rotation) {
  return core::parse_scene(std::string(R"({"name": "b", "duration": 1, "output": {"every": 1},
      "solver": {"method": "rk4", "dt": 1e-3}, "rigid_body": {"rotation": ")") + rotation + R"("},
      "effects": [{"type": "gravity", "g": [0, 0, -9.81]}, {"type": "linear_drag", "k": 0.1, "k_angular": 0.01}],
      "bodies": [{"name": "b", "shape": {"box": [0.1, 0.4, 0.9]}, "mass": 2.0, "position": [1, 2, 3],
                  "orientation": [0.9238795325112867, 0.3826834323650898, 0, 0], "velocity": [1, 0, 5],
                  "angular_velocity": [3, -2, 5]}]})",
                           "bench");
}

// The rigid-body derivative alone (RigidBodies::derivative): no stage timer, whose
// two clock reads would cost as much as the mathematics.
template <class Bodies>
void derivative(benchmark::State& state, const char* rotation) {
  const auto scene = body_scene(rotation);
  const auto model = Bodies::build(scene, core::compile(scene));
  std::vector<double> y(Bodies::state_size(model)), dy(y.size());
  Bodies::initial_state(model, y);
  for (auto _ : state) {
    Bodies::derivative(model, 0.0, y, dy);
    benchmark::DoNotOptimize(dy.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations());
}

template <class B>
void step(benchmark::State& state, const char* rotation) {
  const auto scene = body_scene(rotation);
  const auto model = B::build(scene);
  std::vector<double> y(B::state_size(model));
  B::initial_state(model, y);
  core::OdeSolver solver(scene.solver, y.size());
  core::Profile profile;
  double t = 0;
  auto f = [&](double tt, std::span<const double> yy, std::span<double> dy) { B::derivative(model, tt, yy, dy, profile); };
  for (auto _ : state) {
    solver.advance(f, t, t + 1e-3, y, profile);
    benchmark::DoNotOptimize(y.data());
  }
  state.SetItemsProcessed(state.iterations());
}

constexpr int kVertices = 1000;
const std::vector<Eigen::Vector3d>& mesh() {
  static const std::vector<Eigen::Vector3d> v = [] {
    std::mt19937_64 g(5);
    std::uniform_real_distribution<double> u(-1, 1);
    std::vector<Eigen::Vector3d> out;
    for (int i = 0; i < kVertices; ++i) out.emplace_back(u(g), u(g), u(g));
    return out;
  }();
  return v;
}
const Eigen::Quaterniond kQ = Eigen::Quaterniond(0.9, 0.3, -0.2, 0.25).normalized();
const Eigen::Vector3d kX(1, 2, 3);

template <class V, class F>
void vertices(benchmark::State& state, F move) {
  std::vector<V> in, out(kVertices);
  for (const auto& p : mesh()) {
    if constexpr (std::is_same_v<V, Eigen::Vector3d>) in.push_back(p); else in.push_back(cga::vector3(p));
  }
  for (auto _ : state) {
    move(in, out);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kVertices);
}

void BM_vertices_matrix(benchmark::State& s) {
  const Eigen::Matrix3d r = kQ.toRotationMatrix();
  vertices<Eigen::Vector3d>(s, [&](const auto& in, auto& out) {
    for (int i = 0; i < kVertices; ++i) out[i] = r * in[i] + kX;
  });
}
void BM_vertices_quaternion(benchmark::State& s) {
  vertices<Eigen::Vector3d>(s, [&](const auto& in, auto& out) {
    for (int i = 0; i < kVertices; ++i) out[i] = kQ * in[i] + kX;
  });
}
void BM_vertices_rotor(benchmark::State& s) {
  const cga::Rotor3 r = cga::rotor_from_quaternion(kQ);
  const cga::Vector3 x = cga::vector3(kX);
  vertices<cga::Vector3>(s, [&](const auto& in, auto& out) {
    for (int i = 0; i < kVertices; ++i) out[i] = cga::sandwich(r, in[i]) + x;
  });
}
void BM_vertices_rotor_matrix(benchmark::State& s) {
  const cga::Rotor3 r = cga::rotor_from_quaternion(kQ);
  vertices<Eigen::Vector3d>(s, [&](const auto& in, auto& out) {
    const Eigen::Matrix3d m = cga::rotation_matrix(r);  // once per body per step
    for (int i = 0; i < kVertices; ++i) out[i] = m * in[i] + kX;
  });
}

void BM_vertices_motor(benchmark::State& s) {
  const pga::Motor m = pga::motor(kQ, kX);
  vertices<Eigen::Vector3d>(s, [&](const auto& in, auto& out) {
    for (int i = 0; i < kVertices; ++i) out[i] = pga::apply(m, in[i]);
  });
}

void BM_derivative_matrix(benchmark::State& s) { derivative<traditional::RigidBodies>(s, "matrix"); }
void BM_derivative_quaternion(benchmark::State& s) { derivative<traditional::RigidBodies>(s, "quaternion"); }
void BM_derivative_rotor(benchmark::State& s) { derivative<cga::RigidBodies>(s, "matrix"); }
void BM_step_matrix(benchmark::State& s) { step<traditional::Backend>(s, "matrix"); }
void BM_step_quaternion(benchmark::State& s) { step<traditional::Backend>(s, "quaternion"); }
void BM_step_rotor(benchmark::State& s) { step<cga::Backend>(s, "matrix"); }
void BM_derivative_motor(benchmark::State& s) { derivative<pga::RigidBodies>(s, "matrix"); }
void BM_step_motor(benchmark::State& s) { step<pga::Backend>(s, "matrix"); }
BENCHMARK(BM_derivative_matrix)->Name("BM_derivative/matrix");
BENCHMARK(BM_derivative_quaternion)->Name("BM_derivative/quaternion");
BENCHMARK(BM_derivative_rotor)->Name("BM_derivative/rotor");
BENCHMARK(BM_derivative_motor)->Name("BM_derivative/motor");
BENCHMARK(BM_step_matrix)->Name("BM_step/matrix");
BENCHMARK(BM_step_quaternion)->Name("BM_step/quaternion");
BENCHMARK(BM_step_rotor)->Name("BM_step/rotor");
BENCHMARK(BM_step_motor)->Name("BM_step/motor");
BENCHMARK(BM_vertices_matrix)->Name("BM_vertices/matrix");
BENCHMARK(BM_vertices_quaternion)->Name("BM_vertices/quaternion");
BENCHMARK(BM_vertices_rotor)->Name("BM_vertices/rotor");
BENCHMARK(BM_vertices_rotor_matrix)->Name("BM_vertices/rotor_matrix");
BENCHMARK(BM_vertices_motor)->Name("BM_vertices/motor");

}  // namespace

BENCHMARK_MAIN();
