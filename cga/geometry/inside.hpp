#pragma once
// Inside or outside a sphere by a sign (§2.4.1, last paragraph), with the
// orientation fix of Appendix A fig. 14. Twin: traditional/geometry.hpp.
//
// The convention, once, here: side(S, x) = ½(|x − c|² − ρ²): negative inside,
// zero on the sphere, positive outside, as the report asks ("points inside have a
// dot product with the sphere of less than 0"), and like a plane's signed
// distance with an outward normal (X·π > 0 on the normal's side).
//
// What the report got wrong. (1) Its dual sphere M* = C − ½ρ²n (§2.4.1, after
// [7]) gives X·M* = ½(ρ² − |x − c|²), positive inside: the opposite of its own
// rule, so a sign flip has to live somewhere. (2) Fig. 14 tests the orientation
// with `check = n · sphere` on the 4-blade and reads the scalar component of the
// result; but n·(4-blade) is a 3-vector, whose scalar component is always zero,
// so the flip never fires and the orientation stays whatever the order of the
// four points made it. The orientation is in the dual: S·n (or n∧M, a multiple
// of I), the signed volume of the four points.
//
// The fix here: every constructor normalises a dual sphere to S·n = −1 (the form
// C − ½ρ²n, whatever the point order), and side() divides by S·n, so it gives the
// convention even for a sphere built elsewhere with either orientation or scale.
#include "cga/geometry/entities.hpp"

namespace gacompare::cga {

// Fig. 14's make4pointsphere, fixed: the dual of A∧B∧C∧D oriented and scaled to
// S·n = −1; nullopt for coplanar points (no sphere).
inline std::optional<DualSphere> four_point_sphere(const ConformalPoint& a, const ConformalPoint& b,
                                                   const ConformalPoint& c, const ConformalPoint& d) {
  return dual_sphere_through(a, b, c, d);
}

// Any nonzero multiple of a dual sphere, brought to the normalised orientation.
inline DualSphere oriented(const DualSphere& s) { return s / detail::weight(s); }

// ½(|x − c|² − ρ²) = (X·S)/(S·n): independent of the orientation and scale of S.
inline double side(const DualSphere& s, const ConformalPoint& x) {
  return scalar_product(x, s) / scalar_product(s, n_inf());
}
inline double side(const DualSphere& s, const Vec3& x) { return side(s, up(x)); }
inline bool inside(const DualSphere& s, const Vec3& x) { return side(s, x) < 0; }
inline bool outside(const DualSphere& s, const Vec3& x) { return side(s, x) > 0; }

}  // namespace gacompare::cga
