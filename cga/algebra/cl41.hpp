#pragma once
// Cl(4,1): the conformal model of 3D space (§1.3), the algebra of the geometry.
// Basis e1 e2 e3 e ē with e² = +1, ē² = −1 (eq. 9), bits 0..4. Null vectors
// n = e + ē (the point at infinity) and n̄ = e − ē (the origin), n·n̄ = 2.
// Up-projection X = ½(x² n + 2x − n̄) (eq. 10), so X·Y = −½|x − y|² and X·n = −1.
#include "cga/algebra/cl3.hpp"

#include <optional>

namespace gacompare::cga {

namespace e5 {  // basis vectors of Cl(4,1) as bitmasks; blades are their ORs
inline constexpr unsigned scalar = 0, e1 = 1, e2 = 2, e3 = 4, e = 8, ebar = 16;
}

using Scalar5 = Multivector<Cl41, grades<Cl41>({0})>;
using Vector5 = Multivector<Cl41, grades<Cl41>({1})>;
using Bivector5 = Multivector<Cl41, grades<Cl41>({2})>;
using Trivector5 = Multivector<Cl41, grades<Cl41>({3})>;
using Quadvector5 = Multivector<Cl41, grades<Cl41>({4})>;
using Pseudoscalar5 = Multivector<Cl41, grades<Cl41>({5})>;
using Even5 = Multivector<Cl41, grades<Cl41>({0, 2, 4})>;
using Full5 = Multivector<Cl41, Cl41::all>;

// Named entities (Table 1). The grade is the type; the name says the intent.
using ConformalPoint = Vector5;  // up(x), null
using DualSphere = Vector5;      // C − ½ρ² n
using DualPlane = Vector5;       // normal + d n
using PointPair = Bivector5;     // P1 ∧ P2
using Circle = Trivector5;       // P1 ∧ P2 ∧ P3
using Line = Trivector5;         // P1 ∧ P2 ∧ n
using Sphere = Quadvector5;      // P1 ∧ P2 ∧ P3 ∧ P4
using Plane = Quadvector5;       // P1 ∧ P2 ∧ P3 ∧ n

constexpr Vector5 vector5(double x, double y, double z, double e, double ebar) { return {{x, y, z, e, ebar}}; }
// n and n̄ hold only e and ē, so products with them skip the zero e1 e2 e3 terms.
using NullVector = Multivector<Cl41, (BladeSet{1} << e5::e) | (BladeSet{1} << e5::ebar)>;
constexpr NullVector n_inf() { return {{1, 1}}; }      // n = e + ē
constexpr NullVector n_origin() { return {{1, -1}}; }  // n̄ = e − ē

// A Cl(3,0) element as the same element of Cl(4,1): its blades have the same bits.
template <BladeSet S>
constexpr Multivector<Cl41, S> embed(const Multivector<Cl3, S>& m) { return {m.c}; }

// Up-projection (eq. 10): X = x + ½(x² − 1) e + ½(x² + 1) ē.
constexpr ConformalPoint up(double x, double y, double z) {
  const double x2 = x * x + y * y + z * z;
  return vector5(x, y, z, 0.5 * (x2 - 1.0), 0.5 * (x2 + 1.0));
}
inline ConformalPoint up(const Eigen::Vector3d& x) { return up(x.x(), x.y(), x.z()); }

// Down-projection: normalise by −X·n = X_ē − X_e, then read x off e1 e2 e3.
// nullopt when X·n vanishes relative to X (a point at infinity, or not a point).
template <BladeSet S>
std::optional<Eigen::Vector3d> down(const Multivector<Cl41, S>& X) {
  static_assert((S & ~Vector5::blades) == 0, "down() takes a vector");
  const double w = X[e5::ebar] - X[e5::e];
  double size = 0;
  for (double x : X.c) size += std::abs(x);
  if (!(std::abs(w) > 1e-300) || !(std::abs(w) > 1e-15 * size)) return std::nullopt;
  return Eigen::Vector3d(X[e5::e1] / w, X[e5::e2] / w, X[e5::e3] / w);
}

// Translator T = 1 + n a / 2 (eq. 15): T up(x) T̃ = up(x + a) (eq. 16).
inline auto translator(const Eigen::Vector3d& a) {
  return scalar<Cl41>(1.0) + (n_inf() * embed(vector3(a))) * 0.5;
}
using Translator = decltype(translator(Eigen::Vector3d::Zero()));

// Dilator D = exp(α/2 e ē) (§1.4.2): D up(x) D̃ = e^α up(e^−α x), i.e. scales
// space by e^−α about the origin. (eē)² = +1, hence cosh and sinh.
inline auto dilator(double alpha) {
  using D = Multivector<Cl41, 1 | (BladeSet{1} << (e5::e | e5::ebar))>;
  return D{{std::cosh(0.5 * alpha), std::sinh(0.5 * alpha)}};
}
using Dilator = decltype(dilator(0.0));

// A rotation rotor of Cl(3,0) acting in Cl(4,1): it leaves n and n̄ fixed (eq. 13).
using Rotor5 = Multivector<Cl41, Rotor3::blades>;

// The 5×5 matrix of X ↦ V X Ṽ on vectors (the versor's outermorphism), column i
// the image of basis vector i. Built once per body, it moves each conformal point
// for 25 multiply-adds instead of a full sandwich: the form the Gaigen ray tracer
// used (docs/architecture.md "Fair comparison").
template <BladeSet S>
Eigen::Matrix<double, 5, 5> outermorphism(const Multivector<Cl41, S>& v) {
  Eigen::Matrix<double, 5, 5> m;
  const auto vr = reverse(v);
  for (int i = 0; i < 5; ++i) {
    Vector5 e{};
    e.c[i] = 1;
    const auto img = widen<Vector5::blades>(product<Product::geometric, Vector5::blades>(v * e, vr));
    for (int k = 0; k < 5; ++k) m(k, i) = img.c[k];
  }
  return m;
}

// exp of a 2-blade B of Cl(4,1) (B² a scalar), the closed forms of §1.4:
//   B² < 0 rotation: cos|B| + B sin|B|/|B|
//   B² = 0 translation: 1 + B (n a is null, eq. 15)
//   B² > 0 dilation/boost: cosh|B| + B sinh|B|/|B|
// nullopt for a bivector that is not a blade (B² has a grade-4 part): its exp needs
// a split into commuting blades, which no code here needs.
template <BladeSet S>
std::optional<Even5> exp_blade(const Multivector<Cl41, S>& b) {
  static_assert((S & ~Bivector5::blades) == 0, "exp_blade() takes a bivector");
  const auto bb = b * b;
  const double s = bb.template get<0>();
  double size = 0, g4 = 0;
  for (double x : b.c) size += x * x;
  for (double x : grade<4>(bb).c) g4 += x * x;
  if (std::sqrt(g4) > 1e-12 * size) return std::nullopt;
  const double t = std::sqrt(std::abs(s));
  double c, k;  // exp(B) = c + k B
  if (t < 1e-8 * std::sqrt(size) || t == 0.0) {
    c = 1.0 + 0.5 * s;
    k = 1.0 + s / 6.0;
  } else if (s < 0) {
    c = std::cos(t);
    k = std::sin(t) / t;
  } else {
    c = std::cosh(t);
    k = std::sinh(t) / t;
  }
  return widen<Even5::blades>(scalar<Cl41>(c) + b * k);
}

}  // namespace gacompare::cga
