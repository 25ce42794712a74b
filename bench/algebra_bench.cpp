// The algebra's cost against hand-written traditional code: the same
// operation on the same 256 seeded random inputs through
//   sparse  the compile-time sparse multivectors (cga/algebra/multivector.hpp)
//   dense   the 2003-style run-time multivector, all 2^n components (dense.hpp)
//   eigen   what a traditional programmer writes with Eigen
// Names are BM_<operation>/<implementation>; scripts/bench-ratios.py turns a run
// into a ratio table (docs/results/algebra.md). Every loop writes its results to an array that
// is kept alive, so nothing is optimised away.
#include "cga/algebra/cl41.hpp"
#include "cga/algebra/dense.hpp"

#include <Eigen/Dense>
#include <benchmark/benchmark.h>

#include <random>
#include <vector>

namespace {
using namespace gacompare::cga;

constexpr int kN = 256;

struct Inputs {
  std::vector<Eigen::Vector3d> a, b, c, d;
  std::vector<Eigen::Quaterniond> q, r;
  Inputs() {
    std::mt19937_64 g(2003);
    std::uniform_real_distribution<double> u(-1, 1);
    for (int i = 0; i < kN; ++i) {
      a.emplace_back(u(g), u(g), u(g));
      b.emplace_back(u(g), u(g), u(g));
      c.emplace_back(u(g), u(g), u(g));
      d.emplace_back(u(g), u(g), u(g));
      q.push_back(Eigen::Quaterniond(u(g), u(g), u(g), u(g)).normalized());
      r.push_back(Eigen::Quaterniond(u(g), u(g), u(g), u(g)).normalized());
    }
  }
};
const Inputs& in() {
  static const Inputs inputs;
  return inputs;
}

template <class T>
std::vector<T> convert(const std::vector<Eigen::Vector3d>& v, T (*f)(const Eigen::Vector3d&)) {
  std::vector<T> out;
  for (const auto& x : v) out.push_back(f(x));
  return out;
}
Vector3 as_vector3(const Eigen::Vector3d& v) { return vector3(v); }
Vector5 as_point(const Eigen::Vector3d& v) { return up(v); }
template <class A, class M>
std::vector<Dense<A>> densify(const std::vector<M>& v) {
  std::vector<Dense<A>> out;
  for (const auto& x : v) out.push_back(to_dense(x));
  return out;
}
std::vector<Rotor3> rotors(const std::vector<Eigen::Quaterniond>& q) {
  std::vector<Rotor3> out;
  for (const auto& x : q) out.push_back(rotor_from_quaternion(x));
  return out;
}

template <class Out, class F>
void run(benchmark::State& state, F f) {
  std::vector<Out> out(kN);
  for (auto _ : state) {
    for (int i = 0; i < kN; ++i) out[i] = f(i);
    benchmark::DoNotOptimize(out.data());
    benchmark::ClobberMemory();
  }
  state.SetItemsProcessed(state.iterations() * kN);
}

// --- vector × vector: ab = a·b + a∧b  vs  dot and cross ----------------------------
void BM_vector_product_sparse(benchmark::State& s) {
  const auto a = convert(in().a, as_vector3), b = convert(in().b, as_vector3);
  run<Rotor3>(s, [&](int i) { return a[i] * b[i]; });
}
void BM_vector_product_dense(benchmark::State& s) {
  const auto a = densify<Cl3>(convert(in().a, as_vector3)), b = densify<Cl3>(convert(in().b, as_vector3));
  run<Dense<Cl3>>(s, [&](int i) { return a[i] * b[i]; });
}
// The same formula written out by hand on the same layout: shows what the
// compile-time tables cost over hand-written scalar code (nothing: the assembly is
// the same), apart from what Eigen's own layout buys.
void BM_vector_product_hand(benchmark::State& s) {
  const auto a = convert(in().a, as_vector3), b = convert(in().b, as_vector3);
  run<Rotor3>(s, [&](int i) {
    const auto &x = a[i].c, &y = b[i].c;
    return Rotor3{{x[0] * y[0] + x[1] * y[1] + x[2] * y[2], x[0] * y[1] - x[1] * y[0], x[0] * y[2] - x[2] * y[0],
                   x[1] * y[2] - x[2] * y[1]}};
  });
}
void BM_vector_product_eigen(benchmark::State& s) {
  const auto& a = in().a;
  const auto& b = in().b;
  run<Eigen::Vector4d>(s, [&](int i) {
    Eigen::Vector4d r;
    r[0] = a[i].dot(b[i]);
    r.tail<3>() = a[i].cross(b[i]);
    return r;
  });
}

// --- rotor × rotor  vs  quaternion × quaternion --------------------------------------
void BM_rotor_product_sparse(benchmark::State& s) {
  const auto a = rotors(in().q), b = rotors(in().r);
  run<Rotor3>(s, [&](int i) { return a[i] * b[i]; });
}
void BM_rotor_product_dense(benchmark::State& s) {
  const auto a = densify<Cl3>(rotors(in().q)), b = densify<Cl3>(rotors(in().r));
  run<Dense<Cl3>>(s, [&](int i) { return a[i] * b[i]; });
}
void BM_rotor_product_eigen(benchmark::State& s) {
  const auto& a = in().q;
  const auto& b = in().r;
  run<Eigen::Quaterniond>(s, [&](int i) { return a[i] * b[i]; });
}

// --- rotate a vector: R x R̃  vs  q x q*  vs  the rotor's matrix ----------------------
void BM_rotate_vector_sparse(benchmark::State& s) {
  const auto r = rotors(in().q);
  const auto x = convert(in().a, as_vector3);
  run<Vector3>(s, [&](int i) { return sandwich(r[i], x[i]); });
}
void BM_rotate_vector_dense(benchmark::State& s) {
  const auto r = densify<Cl3>(rotors(in().q));
  const auto x = densify<Cl3>(convert(in().a, as_vector3));
  run<Dense<Cl3>>(s, [&](int i) { return r[i] * x[i] * ~r[i]; });
}
void BM_rotate_vector_eigen(benchmark::State& s) {
  const auto& q = in().q;
  const auto& x = in().a;
  run<Eigen::Vector3d>(s, [&](int i) { return q[i] * x[i]; });
}
// The outermorphism form: one 3×3 matrix per rotor (built outside the loop, as a
// body would once per step) applied to the vector. Traditional code does the same.
void BM_rotate_vector_matrix(benchmark::State& s) {
  std::vector<Eigen::Matrix3d> m;
  for (const auto& r : rotors(in().q)) m.push_back(rotation_matrix(r));
  const auto& x = in().a;
  run<Eigen::Vector3d>(s, [&](int i) { return m[i] * x[i]; });
}

// --- rotate a conformal point: R X R̃ (eq. 12)  vs  q x q* -----------------------------
void BM_rotate_point_sparse(benchmark::State& s) {
  std::vector<Rotor5> r;
  for (const auto& x : rotors(in().q)) r.push_back(embed(x));
  const auto x = convert(in().a, as_point);
  run<Vector5>(s, [&](int i) { return sandwich(r[i], x[i]); });
}
void BM_rotate_point_dense(benchmark::State& s) {
  std::vector<Dense<Cl41>> r;
  for (const auto& x : rotors(in().q)) r.push_back(to_dense(embed(x)));
  const auto x = densify<Cl41>(convert(in().a, as_point));
  run<Dense<Cl41>>(s, [&](int i) { return r[i] * x[i] * ~r[i]; });
}
void BM_rotate_point_eigen(benchmark::State& s) {
  const auto& q = in().q;
  const auto& x = in().a;
  run<Eigen::Vector3d>(s, [&](int i) { return q[i] * x[i]; });
}

// --- move a conformal point: M X M̃ with M = T R  vs  R x + t --------------------------
std::vector<decltype(Translator{} * Rotor5{})> motors() {
  std::vector<decltype(Translator{} * Rotor5{})> out;
  for (int i = 0; i < kN; ++i) out.push_back(translator(in().b[i]) * embed(rotor_from_quaternion(in().q[i])));
  return out;
}
void BM_move_point_sparse(benchmark::State& s) {
  const auto m = motors();
  const auto x = convert(in().a, as_point);
  run<Vector5>(s, [&](int i) { return sandwich(m[i], x[i]); });
}
void BM_move_point_dense(benchmark::State& s) {
  const auto m = densify<Cl41>(motors());
  const auto x = densify<Cl41>(convert(in().a, as_point));
  run<Dense<Cl41>>(s, [&](int i) { return m[i] * x[i] * ~m[i]; });
}
void BM_move_point_eigen(benchmark::State& s) {
  const auto& q = in().q;
  const auto& t = in().b;
  const auto& x = in().a;
  run<Eigen::Vector3d>(s, [&](int i) { return Eigen::Vector3d(q[i] * x[i] + t[i]); });
}

// The outermorphism: the motor's 5×5 matrix once per motor, then matrix × point.
void BM_move_point_matrix(benchmark::State& s) {
  std::vector<Eigen::Matrix<double, 5, 5>> m;
  for (const auto& mm : motors()) m.push_back(outermorphism(mm));
  std::vector<Eigen::Matrix<double, 5, 1>> x;
  for (const auto& p : convert(in().a, as_point)) x.emplace_back(p.c[0], p.c[1], p.c[2], p.c[3], p.c[4]);
  run<Eigen::Matrix<double, 5, 1>>(s, [&](int i) { return Eigen::Matrix<double, 5, 1>(m[i] * x[i]); });
}
// Traditional with the rotation as a matrix too (what a rigid body keeps).
void BM_move_point_eigen_matrix(benchmark::State& s) {
  std::vector<Eigen::Matrix3d> m;
  for (const auto& q : in().q) m.push_back(q.toRotationMatrix());
  const auto& t = in().b;
  const auto& x = in().a;
  run<Eigen::Vector3d>(s, [&](int i) { return Eigen::Vector3d(m[i] * x[i] + t[i]); });
}

// --- sphere through four points: P1∧P2∧P3∧P4  vs  solving for the centre ------------
void BM_sphere_4_points_sparse(benchmark::State& s) {
  const auto a = convert(in().a, as_point), b = convert(in().b, as_point), c = convert(in().c, as_point),
             d = convert(in().d, as_point);
  run<Quadvector5>(s, [&](int i) { return a[i] ^ b[i] ^ c[i] ^ d[i]; });
}
void BM_sphere_4_points_dense(benchmark::State& s) {
  const auto a = densify<Cl41>(convert(in().a, as_point)), b = densify<Cl41>(convert(in().b, as_point)),
             c = densify<Cl41>(convert(in().c, as_point)), d = densify<Cl41>(convert(in().d, as_point));
  run<Dense<Cl41>>(s, [&](int i) { return a[i] ^ b[i] ^ c[i] ^ d[i]; });
}
// Traditional: the centre from 2(p_k − p_0)·c = |p_k|² − |p_0|², k = 1..3 (Eigen's
// closed-form 3×3 inverse), and the radius. Both sides deliver the sphere.
void BM_sphere_4_points_eigen(benchmark::State& s) {
  const auto &a = in().a, &b = in().b, &c = in().c, &d = in().d;
  run<Eigen::Vector4d>(s, [&](int i) {
    Eigen::Matrix3d m;
    m.row(0) = 2 * (b[i] - a[i]);
    m.row(1) = 2 * (c[i] - a[i]);
    m.row(2) = 2 * (d[i] - a[i]);
    const double a2 = a[i].squaredNorm();
    const Eigen::Vector3d rhs(b[i].squaredNorm() - a2, c[i].squaredNorm() - a2, d[i].squaredNorm() - a2);
    const Eigen::Vector3d centre = m.inverse() * rhs;
    Eigen::Vector4d r;
    r.head<3>() = centre;
    r[3] = (centre - a[i]).norm();
    return r;
  });
}

#define GA_BENCH(op)                                 \
  BENCHMARK(BM_##op##_sparse)->Name("BM_" #op "/sparse"); \
  BENCHMARK(BM_##op##_dense)->Name("BM_" #op "/dense");   \
  BENCHMARK(BM_##op##_eigen)->Name("BM_" #op "/eigen");

GA_BENCH(vector_product)
BENCHMARK(BM_vector_product_hand)->Name("BM_vector_product/hand");
GA_BENCH(rotor_product)
GA_BENCH(rotate_vector)
BENCHMARK(BM_rotate_vector_matrix)->Name("BM_rotate_vector/matrix");
GA_BENCH(rotate_point)
GA_BENCH(move_point)
BENCHMARK(BM_move_point_matrix)->Name("BM_move_point/matrix");
BENCHMARK(BM_move_point_eigen_matrix)->Name("BM_move_point/eigen_matrix");
GA_BENCH(sphere_4_points)

}  // namespace

BENCHMARK_MAIN();
