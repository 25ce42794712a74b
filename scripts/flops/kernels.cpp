// One operation per function, for scripts/count-flops.py to count the
// multiplies and adds the compiler emits for it. Each wrapper is extern "C"
// (a plain symbol to find in the disassembly) and noinline, and takes and
// returns its operands by pointer, so what is counted is the operation alone:
// loads and stores are not arithmetic, and no operand is built inside.
// Inputs are taken as each backend stores them (a motor, a quaternion, a
// conformal point already lifted by up()); where a backend's form needs a
// conversion first, that conversion is not in the count (the table says so).
#include "cga/algebra/cl3.hpp"
#include "cga/algebra/cl41.hpp"
#include "cga/narrowphase.hpp"
#include "pga/algebra/cl301.hpp"

#include <Eigen/Core>
#include <Eigen/Geometry>

namespace cga = gacompare::cga;
namespace pga = gacompare::pga;
using Eigen::Vector3d;

// The conformal motor T R: a translator of cl41.hpp times a rotation rotor,
// the type their product has (scalar, e12 e13 e23, the e_i n terms and e123 n).
using CgaMotor = decltype(cga::translator(Vector3d::Zero()) * cga::Rotor5{});

#define KERNEL extern "C" [[gnu::noinline]]

// --- point transform -------------------------------------------------------------------

KERNEL void point_quaternion(const Eigen::Quaterniond* q, const Vector3d* t, const Vector3d* x, Vector3d* out) {
  *out = *q * *x + *t;
}
KERNEL void point_matrix(const Eigen::Matrix3d* r, const Vector3d* t, const Vector3d* x, Vector3d* out) {
  *out = *r * *x + *t;
}
KERNEL void point_cga_motor(const CgaMotor* m, const cga::Vector5* x, cga::Vector5* out) {
  *out = cga::sandwich(*m, *x);
}
KERNEL void point_cga_rotor(const cga::Rotor5* r, const cga::Vector5* x, cga::Vector5* out) {
  *out = cga::sandwich(*r, *x);
}
KERNEL void point_cga_outermorphism(const Eigen::Matrix<double, 5, 5>* m, const cga::Vector5* x, cga::Vector5* out) {
  Eigen::Map<Eigen::Matrix<double, 5, 1>>(out->c.data()) = *m * Eigen::Map<const Eigen::Matrix<double, 5, 1>>(x->c.data());
}
KERNEL void point_pga_apply(const pga::Motor* m, const Vector3d* x, Vector3d* out) { *out = pga::apply(*m, *x); }
KERNEL void point_pga_sandwich(const pga::Motor* m, const pga::Point* x, pga::Point* out) {
  *out = cga::sandwich(*m, *x);
}

// --- composition -----------------------------------------------------------------------

KERNEL void compose_quaternion(const Eigen::Quaterniond* a, const Eigen::Quaterniond* b, Eigen::Quaterniond* out) {
  *out = *a * *b;
}
// A rigid motion as the pair (q, t): (qa, ta)(qb, tb) = (qa qb, qa tb + ta).
KERNEL void compose_quaternion_translation(const Eigen::Quaterniond* qa, const Vector3d* ta,
                                           const Eigen::Quaterniond* qb, const Vector3d* tb,
                                           Eigen::Quaterniond* q, Vector3d* t) {
  *q = *qa * *qb;
  *t = *qa * *tb + *ta;
}
KERNEL void compose_matrix4(const Eigen::Matrix4d* a, const Eigen::Matrix4d* b, Eigen::Matrix4d* out) {
  *out = *a * *b;
}
KERNEL void compose_isometry(const Eigen::Isometry3d* a, const Eigen::Isometry3d* b, Eigen::Isometry3d* out) {
  *out = *a * *b;
}
KERNEL void compose_cga_rotor3(const cga::Rotor3* a, const cga::Rotor3* b, cga::Rotor3* out) { *out = *a * *b; }
KERNEL void compose_cga_motor(const CgaMotor* a, const CgaMotor* b, cga::Even5* out) {
  *out = cga::widen<cga::Even5::blades>(*a * *b);
}
KERNEL void compose_cga_even5(const cga::Even5* a, const cga::Even5* b, cga::Even5* out) { *out = *a * *b; }
KERNEL void compose_pga(const pga::Motor* a, const pga::Motor* b, pga::Motor* out) { *out = pga::compose(*a, *b); }

// --- face test: a point's signed distance from a plane ---------------------------------

KERNEL double face_traditional(const Vector3d* n, const double* d, const Vector3d* x) { return n->dot(*x) - *d; }
KERNEL double face_cga(const cga::DualPlane* f, const cga::ConformalPoint* x) {
  return cga::NarrowAlgebra::distance(*f, *x);
}
KERNEL double face_pga(const pga::Plane* f, const pga::Point* x) { return pga::distance(*f, *x); }

int main() { return 0; }
