#pragma once
// Lie-group integrators for the rotational motion of a rigid body, written once
// over a rotation representation (the RotationGroup concept below); the
// representations are traditional/rotation_group.hpp (matrix by Rodrigues'
// formula, unit quaternion), cga/rotation_group.hpp (rotor, the exponential of a
// bivector) and pga/rotation_group.hpp (motor, the exponential of a line).
//
// State: the rotation R (body to world) and the body angular momentum Π, with
// the principal moments I = diag(I1, I2, I3):
//   Ṙ = R ω̂,  ω = I⁻¹ Π,  Π̇ = Π × ω + Rᵀ τ(t, R, L),  L = R Π (world).
// The rotation advances by R ← R exp(θ), θ a body-frame rotation vector; the
// Lie algebra so(3) is written as R³ (the bracket [a, b] is a × b) in every
// representation, and each turns θ into its own element only inside exp. Π is
// a vector in R³ and advances additively (a plain RK on Π) in every method but
// the splitting, which rotates it.
//
// Methods (step() below):
//   rk4_flat          classical RK4 on the representation's stored numbers
//                     (Ṙ = R ω̂, q̇ = ½ q ω, Ṙ = −½ R Ω): leaves the group
//   rkmk4, rkmk5      Runge–Kutta–Munthe-Kaas (Munthe-Kaas 1999, Appl. Numer.
//                     Math. 29; Iserles, Munthe-Kaas, Nørsett & Zanna 2000,
//                     "Lie-group methods", Acta Numerica 9) on
//                     the classical RK4 and on Dormand–Prince 5(4); rkmk45
//                     integrates adaptively with the pair's error estimate
//   crouch_grossman3  Crouch & Grossman 1993 (J. Nonlinear Sci. 3), order 3,
//                     the coefficients as Owren & Marthinsen 1999 (BIT 39) list them
//   crouch_grossman4  Jackiewicz, Marthinsen & Owren 2000, order 4 in 5 stages
//   splitting         Dullweber, Leimkuhler & McLachlan 1997 (J. Chem. Phys.
//                     107): the free-body Hamiltonian split into the three
//                     axis terms Π_i²/(2 I_i), each flow an exact rotation about
//                     a principal axis, in a symmetric (Strang) composition:
//                     order 2, symplectic, |Π| kept to rounding. Torque-free only.
//
// The body-frame (right) action R exp(θ) turns the RKMK equation for θ into
//   θ' = dexp⁻¹₋θ(ω) = ω + ½ θ × ω + (1/12) θ × (θ × ω) − (1/720) ad⁴ ...
// (the Bernoulli series with the odd term's sign flipped, because the action is
// on the right). An RKMK method of order p needs the series only through
// ad^(p−2) (Munthe-Kaas 1999; Iserles et al. 2000): θ and ω commute to
// leading order, so adᵏ_θ ω = O(h^(k+1)); B3 = 0, so the double commutator
// serves p = 4 and 5.
//
// Torque-free, ω does not depend on R: the stage rotations are then never
// formed, and a step costs its final exp and compositions only.
//
// A scene's solver (solver.method rkmk4, rkmk45, crouch_grossman4) steps each
// body through body_step() below: the rotation and Π as above, the centre x
// and the linear momentum P additively with the same tableau (each backend's
// rigid_body.cpp group_step, on its own R and L = R Π).
#include <Eigen/Core>

#include <algorithm>
#include <array>
#include <cmath>
#include <concepts>
#include <cstdint>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string_view>
#include <utility>

namespace gacompare::core::lie {

// What a rotation representation supplies: the group operations, its own
// exponential of a body-frame rotation vector, its action on vectors, and for
// the flat (non-group) RK4 its stored numbers and their rate.
template <class G>
concept RotationGroup = requires(const typename G::Element& r, const Eigen::Vector3d& v,
                                 const typename G::Coordinates& c) {
  { G::name } -> std::convertible_to<std::string_view>;
  { G::identity() } -> std::same_as<typename G::Element>;
  // a then b in the body frame: the rotation x ↦ a (b x).
  { G::compose(r, r) } -> std::same_as<typename G::Element>;
  // The rotation by |v| about v / |v| (right-handed), the representation's exp.
  { G::exp(v) } -> std::same_as<typename G::Element>;
  { G::rotate(r, v) } -> std::same_as<Eigen::Vector3d>;          // R v
  { G::inverse_rotate(r, v) } -> std::same_as<Eigen::Vector3d>;  // R⁻¹ v
  { G::matrix(r) } -> std::same_as<Eigen::Matrix3d>;             // for error measurement and torques
  // How far the stored numbers are from a rotation: ‖RᵀR − I‖_F, |q q* − 1|, |R R̃ − 1|.
  { G::drift(r) } -> std::same_as<double>;
  { G::coordinates(r) } -> std::same_as<typename G::Coordinates>;
  { G::from_coordinates(c) } -> std::same_as<typename G::Element>;
  // The rate of the stored numbers when the body turns at ω (body frame).
  { G::rate(r, v) } -> std::same_as<typename G::Coordinates>;
};

struct FreeBody {
  Eigen::Vector3d inertia;  // principal moments I1, I2, I3
  // World torque τ(t, R, L), R the rotation matrix and L = R Π the world
  // angular momentum; empty: torque-free.
  std::function<Eigen::Vector3d(double, const Eigen::Matrix3d&, const Eigen::Vector3d&)> torque;
  // A scene's body, whose body axes need not be principal: ω = I⁻¹ Π with
  // this body-frame inverse (then `inertia` is not read); empty: principal axes.
  std::optional<Eigen::Matrix3d> inverse_inertia = std::nullopt;
};

template <RotationGroup G>
struct State {
  typename G::Element rotation;
  Eigen::Vector3d momentum;  // Π, body frame
};

// The invariants of the torque-free body: E = ½ Π·I⁻¹Π and L = R Π.
inline double energy(const FreeBody& body, const Eigen::Vector3d& pi) {
  return 0.5 * pi.dot(pi.cwiseQuotient(body.inertia));
}
template <RotationGroup G>
Eigen::Vector3d world_momentum(const State<G>& y) { return G::rotate(y.rotation, y.momentum); }

// The period of Euler's free equations for a body with distinct moments
// (Landau & Lifshitz §37): with I_a > I_b > I_c, 2E = Π·ω and L² = |Π|²,
//   T = 4 K(k) √(I_a I_b I_c / ((I_a − I_b)(L² − 2E I_c))),
//   k² = (I_b − I_c)(2E I_a − L²) / ((I_a − I_b)(L² − 2E I_c))   when L² > 2E I_b,
// the roles of I_a and I_c exchanged when L² < 2E I_b. The time between flips
// of the Dzhanibekov body.
inline double free_period(const Eigen::Vector3d& inertia, const Eigen::Vector3d& pi) {
  Eigen::Vector3d sorted = inertia;
  std::sort(sorted.data(), sorted.data() + 3, std::greater<>());
  const double ia = sorted[0], ib = sorted[1], ic = sorted[2];
  const double l2 = pi.squaredNorm(), e2 = pi.dot(pi.cwiseQuotient(inertia));
  const bool near_a = l2 > e2 * ib;
  const double big = near_a ? ia : ic, small = near_a ? ic : ia;
  const double k2 = (ib - small) * (e2 * big - l2) / ((big - ib) * (l2 - e2 * small));
  return 4 * std::comp_ellint_1(std::sqrt(k2)) * std::sqrt(ia * ib * ic / ((big - ib) * (l2 - e2 * small)));
}

namespace detail {

struct Rates {
  Eigen::Vector3d omega, momentum;  // ω (body) and Π̇
};
// The right-hand side; rotation_at() yields the stage rotation, called only
// when a torque reads it.
template <RotationGroup G, class RotationAt>
Rates rates(const FreeBody& body, double t, const Eigen::Vector3d& pi, RotationAt&& rotation_at) {
  Rates r{body.inverse_inertia ? Eigen::Vector3d(*body.inverse_inertia * pi) : pi.cwiseQuotient(body.inertia), {}};
  r.momentum = pi.cross(r.omega);
  if (body.torque) {
    const Eigen::Matrix3d m = G::matrix(rotation_at());
    r.momentum += m.transpose() * body.torque(t, m, m * pi);
  }
  return r;
}

// dexp⁻¹₋θ(ω) through the double commutator (the header's note on the order).
inline Eigen::Vector3d dexpinv(const Eigen::Vector3d& theta, const Eigen::Vector3d& w) {
  const Eigen::Vector3d c = theta.cross(w);
  return w + 0.5 * c + theta.cross(c) / 12.0;
}

template <int S>
struct Tableau {
  std::array<std::array<double, S>, S> a;
  std::array<double, S> b, c;
  std::array<double, S> e;  // b − b̂ of an embedded pair, zero otherwise
};

inline constexpr Tableau<4> kRk4{{{{0, 0, 0, 0}, {0.5, 0, 0, 0}, {0, 0.5, 0, 0}, {0, 0, 1, 0}}},
                                 {1.0 / 6, 1.0 / 3, 1.0 / 3, 1.0 / 6}, {0, 0.5, 0.5, 1}, {}};

// Dormand & Prince 1980, the 5th-order solution kept, the 4th-order one for the error.
inline constexpr Tableau<7> kDormandPrince{
    {{{0, 0, 0, 0, 0, 0, 0},
      {1.0 / 5, 0, 0, 0, 0, 0, 0},
      {3.0 / 40, 9.0 / 40, 0, 0, 0, 0, 0},
      {44.0 / 45, -56.0 / 15, 32.0 / 9, 0, 0, 0, 0},
      {19372.0 / 6561, -25360.0 / 2187, 64448.0 / 6561, -212.0 / 729, 0, 0, 0},
      {9017.0 / 3168, -355.0 / 33, 46732.0 / 5247, 49.0 / 176, -5103.0 / 18656, 0, 0},
      {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0}}},
    {35.0 / 384, 0, 500.0 / 1113, 125.0 / 192, -2187.0 / 6784, 11.0 / 84, 0},
    {0, 1.0 / 5, 3.0 / 10, 4.0 / 5, 8.0 / 9, 1, 1},
    {35.0 / 384 - 5179.0 / 57600, 0, 500.0 / 1113 - 7571.0 / 16695, 125.0 / 192 - 393.0 / 640,
     -2187.0 / 6784 + 92097.0 / 339200, 11.0 / 84 - 187.0 / 2100, -1.0 / 40}};

// Crouch & Grossman 1993, 3 stages, order 3.
inline constexpr Tableau<3> kCrouchGrossman3{{{{0, 0, 0}, {3.0 / 4, 0, 0}, {119.0 / 216, 17.0 / 108, 0}}},
                                             {13.0 / 51, -2.0 / 3, 24.0 / 17}, {0, 3.0 / 4, 17.0 / 24}, {}};

// Jackiewicz, Marthinsen & Owren 2000 (Adv. Comput. Math. 13), Example 1: 5
// stages, order 4 on a Lie group (the classical conditions and those of the
// non-commuting exps). a54 is the row sum c5 − a51 − a52 − a53; some copies
// print −1.1092979392113565, which breaks it by 1e-14.
inline constexpr Tableau<5> kCrouchGrossman4{
    {{{0, 0, 0, 0, 0},
      {0.8177227988124852, 0, 0, 0, 0},
      {0.3199876375476427, 0.0659864263556022, 0, 0, 0},
      {0.9214417194464946, 0.4997857776773573, -1.0969984448371582, 0, 0},
      {0.3552358559023322, 0.2390958372307326, 1.3918565724203246, -1.1092979392113465, 0}}},
    {0.1370831520630755, -0.0183698531564020, 0.7397813985370780, -0.1907142565505889, 0.3322195591068374},
    {0, 0.8177227988124852, 0.3859740639032449, 0.3242290522866937, 0.8768903263420429},
    {}};

// A step in the algebra: R ← R exp(θ), Π ← Π + ΔΠ.
struct Increment {
  Eigen::Vector3d theta = Eigen::Vector3d::Zero(), momentum = Eigen::Vector3d::Zero();
};

// One RKMK step of tableau `tab`; with an embedded pair, *error gets h Σ eᵢ Kᵢ.
template <RotationGroup G, int S>
Increment rkmk(const Tableau<S>& tab, const FreeBody& body, double t, const State<G>& y, double h,
               Increment* error = nullptr) {
  std::array<Eigen::Vector3d, S> k, q;
  for (int i = 0; i < S; ++i) {
    Increment stage;
    for (int j = 0; j < i; ++j) {
      stage.theta += (h * tab.a[i][j]) * k[j];
      stage.momentum += (h * tab.a[i][j]) * q[j];
    }
    const Rates r = rates<G>(body, t + tab.c[i] * h, y.momentum + stage.momentum,
                             [&] { return G::compose(y.rotation, G::exp(stage.theta)); });
    k[i] = dexpinv(stage.theta, r.omega);
    q[i] = r.momentum;
  }
  Increment out;
  for (int i = 0; i < S; ++i) {
    out.theta += (h * tab.b[i]) * k[i];
    out.momentum += (h * tab.b[i]) * q[i];
    if (error) {
      error->theta += (h * tab.e[i]) * k[i];
      error->momentum += (h * tab.e[i]) * q[i];
    }
  }
  return out;
}

template <RotationGroup G>
State<G> advanced(const State<G>& y, const Increment& d) {
  return {G::compose(y.rotation, G::exp(d.theta)), y.momentum + d.momentum};
}

// Crouch–Grossman: each stage the product of exps of the earlier stages' ω,
// Yᵢ = R exp(h aᵢ₁ ω₁) ⋯ exp(h aᵢ,ᵢ₋₁ ωᵢ₋₁) (the left-action form mirrored), so
// no dexp⁻¹; the step is R exp(h b₁ ω₁) ⋯ exp(h b_s ω_s).
template <RotationGroup G, int S>
State<G> crouch_grossman(const Tableau<S>& tab, const FreeBody& body, double t, const State<G>& y, double h) {
  std::array<Eigen::Vector3d, S> w, q;
  for (int i = 0; i < S; ++i) {
    Eigen::Vector3d pi = y.momentum;
    for (int j = 0; j < i; ++j) pi += (h * tab.a[i][j]) * q[j];
    const Rates r = rates<G>(body, t + tab.c[i] * h, pi, [&] {
      typename G::Element stage = y.rotation;
      for (int j = 0; j < i; ++j) stage = G::compose(stage, G::exp((h * tab.a[i][j]) * w[j]));
      return stage;
    });
    w[i] = r.omega;
    q[i] = r.momentum;
  }
  State<G> out = y;
  for (int i = 0; i < S; ++i) {
    out.rotation = G::compose(out.rotation, G::exp((h * tab.b[i]) * w[i]));
    out.momentum += (h * tab.b[i]) * q[i];
  }
  return out;
}

// Classical RK4 on the stored numbers: what the backends' rk4 does to a rotation.
template <RotationGroup G>
State<G> rk4_flat(const FreeBody& body, double t, const State<G>& y, double h) {
  using C = typename G::Coordinates;
  const C r0 = G::coordinates(y.rotation);
  std::array<C, 4> kr;
  std::array<Eigen::Vector3d, 4> kp;
  for (int i = 0; i < 4; ++i) {
    const double a = i == 0 ? 0.0 : i == 3 ? h : 0.5 * h;
    const C ri = i == 0 ? r0 : C(r0 + a * kr[static_cast<std::size_t>(i - 1)]);
    const Eigen::Vector3d pi = i == 0 ? y.momentum : Eigen::Vector3d(y.momentum + a * kp[static_cast<std::size_t>(i - 1)]);
    const typename G::Element element = G::from_coordinates(ri);
    const Rates r = rates<G>(body, t + a, pi, [&] { return element; });
    kr[static_cast<std::size_t>(i)] = G::rate(element, r.omega);
    kp[static_cast<std::size_t>(i)] = r.momentum;
  }
  return {G::from_coordinates(C(r0 + (h / 6) * (kr[0] + 2 * kr[1] + 2 * kr[2] + kr[3]))),
          y.momentum + (h / 6) * (kp[0] + 2 * kp[1] + 2 * kp[2] + kp[3])};
}

// The flow of Π_i²/(2 I_i) for time s: ω = (Π_i/I_i) eᵢ is constant, so
// R ← R exp(θ eᵢ) and Π ← exp(−θ êᵢ) Π with θ = s Π_i / I_i.
template <RotationGroup G>
void axis_flow(const FreeBody& body, int i, double s, State<G>& y) {
  const double theta = s * y.momentum[i] / body.inertia[i];
  y.rotation = G::compose(y.rotation, G::exp(theta * Eigen::Vector3d::Unit(i)));
  const int j = (i + 1) % 3, k = (i + 2) % 3;  // (j, k) turn by −θ in their plane
  const double c = std::cos(theta), sn = std::sin(theta);
  const double pj = y.momentum[j], pk = y.momentum[k];
  y.momentum[j] = c * pj + sn * pk;
  y.momentum[k] = -sn * pj + c * pk;
}

}  // namespace detail

enum class GroupMethod { rk4_flat, rkmk4, rkmk5, crouch_grossman3, crouch_grossman4, splitting };
inline constexpr std::array kGroupMethods{GroupMethod::rk4_flat,         GroupMethod::rkmk4,
                                          GroupMethod::rkmk5,            GroupMethod::crouch_grossman3,
                                          GroupMethod::crouch_grossman4, GroupMethod::splitting};
inline std::string_view to_string(GroupMethod m) {
  switch (m) {
    case GroupMethod::rk4_flat: return "rk4 (flat)";
    case GroupMethod::rkmk4: return "rkmk4";
    case GroupMethod::rkmk5: return "rkmk5 (Dormand-Prince)";
    case GroupMethod::crouch_grossman3: return "crouch-grossman3";
    case GroupMethod::crouch_grossman4: return "crouch-grossman4";
    case GroupMethod::splitting: return "splitting (DLM)";
  }
  return "?";
}
inline int order(GroupMethod m) {
  switch (m) {
    case GroupMethod::rk4_flat: case GroupMethod::rkmk4: case GroupMethod::crouch_grossman4: return 4;
    case GroupMethod::rkmk5: return 5;
    case GroupMethod::crouch_grossman3: return 3;
    case GroupMethod::splitting: return 2;
  }
  return 0;
}

// exp-and-compose pairs a torque-free step makes on the rotation (none for the
// flat RK4): what its cost and its rounding scale with.
inline int compositions_per_step(GroupMethod m) {
  switch (m) {
    case GroupMethod::rk4_flat: return 0;
    case GroupMethod::rkmk4: case GroupMethod::rkmk5: return 1;
    case GroupMethod::crouch_grossman3: return 3;
    case GroupMethod::crouch_grossman4: return 5;
    case GroupMethod::splitting: return 5;
  }
  return 0;
}

// One step of h from (t, y). The splitting takes no torque (it throws).
template <RotationGroup G>
State<G> step(GroupMethod m, const FreeBody& body, double t, const State<G>& y, double h) {
  switch (m) {
    case GroupMethod::rk4_flat: return detail::rk4_flat(body, t, y, h);
    case GroupMethod::rkmk4: return detail::advanced(y, detail::rkmk(detail::kRk4, body, t, y, h));
    case GroupMethod::rkmk5: return detail::advanced(y, detail::rkmk(detail::kDormandPrince, body, t, y, h));
    case GroupMethod::crouch_grossman3: return detail::crouch_grossman(detail::kCrouchGrossman3, body, t, y, h);
    case GroupMethod::crouch_grossman4: return detail::crouch_grossman(detail::kCrouchGrossman4, body, t, y, h);
    case GroupMethod::splitting: {
      if (body.torque) throw std::invalid_argument("the splitting integrates the torque-free body only");
      State<G> out = y;
      for (const auto& [axis, s] : {std::pair{0, 0.5}, {1, 0.5}, {2, 1.0}, {1, 0.5}, {0, 0.5}})
        detail::axis_flow(body, axis, s * h, out);
      return out;
    }
  }
  return y;
}

// n equal steps from t0 to t1; observe(t, y) after each when given.
template <RotationGroup G, class Observe>
State<G> integrate(GroupMethod m, const FreeBody& body, double t0, double t1, long n, State<G> y, Observe&& observe) {
  const double h = (t1 - t0) / static_cast<double>(n);
  for (long k = 0; k < n; ++k) {
    y = step(m, body, t0 + static_cast<double>(k) * h, y, h);
    observe(t0 + static_cast<double>(k + 1) * h, y);
  }
  return y;
}
template <RotationGroup G>
State<G> integrate(GroupMethod m, const FreeBody& body, double t0, double t1, long n, const State<G>& y) {
  return integrate(m, body, t0, t1, n, y, [](double, const State<G>&) {});
}

// RKMK 5(4) with step control on the physical error: per step the rotation
// angle between the 5th- and 4th-order rotations, |θ₅ − θ₄| (the angle of
// R₄⁻¹ R₅ to first order, the estimate's own accuracy), against abs + rel (a
// rotation has no size of its own), and |δΠ| against abs + rel·|Π|. The
// controller is ode.hpp's: h ← h·clamp(0.9 E^(−1/5), 0.2, 5).
struct StepStats {
  std::uint64_t accepted = 0, rejected = 0;
};
template <RotationGroup G>
State<G> rkmk45(const FreeBody& body, double t0, double t1, State<G> y, double h, double abs_tol, double rel_tol,
                StepStats& stats) {
  double t = t0;
  while (t < t1) {
    const bool last = t + h >= t1;
    const double hs = last ? t1 - t : h;
    detail::Increment err;
    const detail::Increment d = detail::rkmk(detail::kDormandPrince, body, t, y, hs, &err);
    const double e = std::max(err.theta.norm() / (abs_tol + rel_tol),
                              err.momentum.norm() / (abs_tol + rel_tol * (y.momentum + d.momentum).norm()));
    if (!std::isfinite(e)) throw std::runtime_error("rkmk45: the step's error is not finite");
    const double grow = std::clamp(0.9 * std::pow(std::max(e, 1e-300), -0.2), 0.2, 5.0);
    if (e <= 1) {
      y = detail::advanced(y, d);
      t = last ? t1 : t + hs;
      ++stats.accepted;
      if (!last || grow < 1) h = hs * grow;
    } else {
      ++stats.rejected;
      h = hs * grow;
      if (!(h > 1e-14 * std::max(1.0, std::abs(t)))) throw std::runtime_error("rkmk45: the step underflowed");
    }
  }
  return y;
}

// ---- a scene's body: the rotation group times the translations ----------------------

// The centre x and the linear momentum P: ẋ = P/m, Ṗ = F(t, P). The scene's
// forces read neither the rotation nor L, and its torques neither x nor P
// (core/model/model.hpp BodyEffects), so a step of the body on SO(3) × R⁹ is
// the rotation's step above and, on (x, P), the classical RK of the same
// coefficients (RKMK and Crouch–Grossman are that RK on a vector space):
// the same stages, taken apart.
struct Translation {
  Eigen::Vector3d x = Eigen::Vector3d::Zero(), momentum = Eigen::Vector3d::Zero();
};
template <RotationGroup G>
struct BodyState {
  State<G> rotation;
  Translation translation;
};

namespace detail {
// One RK step of `tab` on (x, P); with `embedded`, the embedded solution too.
template <int S, class Force>
Translation translate(const Tableau<S>& tab, double inv_mass, Force& force, double t, const Translation& y, double h,
                      Translation* embedded) {
  std::array<Eigen::Vector3d, S> kx, kp;
  for (int i = 0; i < S; ++i) {
    Eigen::Vector3d p = y.momentum;
    for (int j = 0; j < i; ++j) p += (h * tab.a[i][j]) * kp[j];
    kx[i] = inv_mass * p;
    kp[i] = force(t + tab.c[i] * h, p);
  }
  Translation out = y, err;
  for (int i = 0; i < S; ++i) {
    out.x += (h * tab.b[i]) * kx[i];
    out.momentum += (h * tab.b[i]) * kp[i];
    err.x += (h * tab.e[i]) * kx[i];
    err.momentum += (h * tab.e[i]) * kp[i];
  }
  if (embedded) *embedded = {out.x - err.x, out.momentum - err.momentum};
  return out;
}
}  // namespace detail

// The stages a scene's body step evaluates its forces at: 4 (RKMK on the
// classical RK4), 7 (RKMK on Dormand–Prince 5(4), not first-same-as-last: the
// stages are re-evaluated at the new rotation) and 5 (Crouch–Grossman 4).
inline int body_step_stages(GroupMethod m) {
  switch (m) {
    case GroupMethod::rkmk4: return 4;
    case GroupMethod::rkmk5: return 7;
    case GroupMethod::crouch_grossman4: return 5;
    default: return 0;
  }
}

// One step of h of a scene's body by rkmk4, rkmk5 or crouch_grossman4;
// force(t, P) is the world force. With `embedded` (rkmk5 only), the pair's
// 4th-order solution as well: the difference of the two is the step's error
// estimate, which the caller measures in its own stored numbers.
template <RotationGroup G, class Force>
BodyState<G> body_step(GroupMethod m, const FreeBody& body, double inv_mass, Force&& force, double t,
                       const BodyState<G>& y, double h, BodyState<G>* embedded = nullptr) {
  BodyState<G> out;
  switch (m) {
    case GroupMethod::rkmk4:
      out.rotation = detail::advanced(y.rotation, detail::rkmk(detail::kRk4, body, t, y.rotation, h));
      out.translation = detail::translate(detail::kRk4, inv_mass, force, t, y.translation, h, nullptr);
      break;
    case GroupMethod::rkmk5: {
      detail::Increment err;
      const detail::Increment d = detail::rkmk(detail::kDormandPrince, body, t, y.rotation, h, embedded ? &err : nullptr);
      out.rotation = detail::advanced(y.rotation, d);
      out.translation = detail::translate(detail::kDormandPrince, inv_mass, force, t, y.translation, h,
                                          embedded ? &embedded->translation : nullptr);
      if (embedded) embedded->rotation = detail::advanced(y.rotation, {d.theta - err.theta, d.momentum - err.momentum});
      break;
    }
    case GroupMethod::crouch_grossman4:
      out.rotation = detail::crouch_grossman(detail::kCrouchGrossman4, body, t, y.rotation, h);
      out.translation = detail::translate(detail::kCrouchGrossman4, inv_mass, force, t, y.translation, h, nullptr);
      break;
    default:
      throw std::invalid_argument("body_step takes rkmk4, rkmk5 and crouch_grossman4");
  }
  return out;
}

}  // namespace gacompare::core::lie
