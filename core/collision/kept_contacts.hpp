#pragma once
// Contacts kept between detections: a pair's face manifold, found by the whole
// narrowphase (core/collision/narrowphase.hpp), carried with the two bodies
// while their relative pose stays within a bound, its depths measured again
// at every detection. A resting pair then costs a few dot products instead of
// the separating-axis test and the clipping (about 0.9 µs for two boxes, most
// of a resting stack's narrowphase). Bullet's persistent manifolds and Jolt's
// body-pair cache do the same; the bound and the guards below are our own.
//
// What is kept, in the bodies' own frames: the reference face (its normal and
// offset), each contact's incident point (the point of the other body that the
// clipping gave, before it was moved midway to the face), the face of the
// separating-axis answer, and the relative pose at the full test. At a later
// pose each incident point is carried with its body and measured against the
// reference face where that is now, which is exact for every point that is a
// vertex of the incident body; the separating-axis depth is its face's support
// distance, exact too. What is not measured again is the choice of points and
// faces, so the pair is tested from scratch when that choice could have
// changed:
//   - slide: a point clipped at the reference face's rim moved sideways, or a
//     point the reduction to four left out overtook one it kept. The points
//     of either body move relative to the other by at most |Δt| + θ·size
//     (Δt the change of the relative translation, θ of the relative rotation,
//     size the larger body's bounding diagonal), so the part of that across
//     the normal is bounded by kKeepSlide × the pair's scale;
//   - approach: a clipped point left out for being above the touching band
//     could come down into it: the pair is tested again before it can, when
//     the approach along the normal (plus θ·size) reaches its height;
//   - a point kept that rose above the band, which the full test would drop;
//   - the choices between a's face and b's and between a face and an edge
//     pair (core/collision/manifold.hpp, kFacePreference): each compares two
//     gaps. A translation Δt changes a gap by its component along the gap's
//     normal, so the difference of two by at most |Δt| times the distance
//     between their normals (nothing for two parallel faces moving along
//     their normal, which is how a resting pair moves); a turn changes each
//     by at most θ·size; the slack shrinks as the pair parts. The pair is
//     tested again once these could have changed a choice's sign. (An edge
//     pair's axis also turns with the bodies, faster than θ when its edges
//     are nearly parallel: for the faces of a pair at rest that axis lies
//     near the faces' normal and its gap with theirs, and the slide bound
//     keeps the turn to 1e-7 rad of a body's size.)
// What the bound costs: a kept point may sit up to kKeepSlide × scale
// sideways of where the full test would put it now; depths are exact. The
// collisions effect's `reuse_contacts: false` tests every pair every time.
//
// The refresh is plain vector algebra in every backend: carrying points with
// their bodies is bookkeeping, not the report's geometry (the full test, in
// each backend's own algebra, still finds every kept manifold).
#include "core/collision/collision.hpp"
#include "core/collision/manifold.hpp"
#include "core/collision/separating_axis.hpp"

#include <algorithm>
#include <array>
#include <cstdint>
#include <cmath>
#include <limits>
#include <span>
#include <vector>

namespace gacompare::collision {

// How far a kept point may slide across the normal, relative to the pair's
// length scale: 1e-7 of a 0.2 m cube is 20 nm, far below any penetration
// tolerance a scene uses (≥ 1e-6 · size, collision.hpp) and below the drift a
// resting stack is held to.
inline constexpr double kKeepSlide = 1e-7;

// A pair in motion fails its bound at every detection, and keeping its
// contacts after each full test only to refuse them at the next cost the
// 10,000-body box, whose falling pile keeps almost nothing, 0.9 s of its
// 22 s (`reuse_contacts: false` against true, two interleaved runs). So a
// pair refused more than kKeepPatience times in a row waits before its
// contacts are kept again: 2^(r − kKeepPatience) − 1 detections after its
// r-th refusal (at most 31), tested whole meanwhile, as `reuse_contacts:
// false` tests every pair. One refresh that holds sets r back to 0. The
// patience is for stacks settling: with none (a wait from the first
// refusal), the friction pyramid of three layers in the stacking family,
// tested whole while its layers landed, ran its velocity sweeps to their
// cap once. With 16, a 10-layer pyramid gives the same run bit for bit.
inline constexpr int kKeepBackOff = 5;
inline constexpr int kKeepPatience = 16;
static_assert(kKeepPatience + kKeepBackOff <= 127 && kKeepBackOff < 7, "KeptState's counts are bytes");

// A pair's kept-contacts state, read at every detection of the pair: whether
// its kept contacts are current and its refusals in a row. It lies beside the
// pair's remembered axis (core/collision/collisions.hpp PairRecord), so that
// the kept manifold itself (KeptContacts, a third of a kilobyte) is read only
// where it is current and not waiting. Read for every pair, the manifolds'
// table was a sixth of a 10,000-body pile's narrowphase in cache misses, for
// one pair in a thousand kept.
struct KeptState {
  bool valid = false;        // the pair's KeptContacts are those of its last test
  std::int8_t refused = 0;   // refreshes refused in a row, at most kKeepPatience + kKeepBackOff
  std::int8_t wait = 0;      // detections left before the contacts are kept again
  bool operator==(const KeptState&) const = default;
};

// A pair's kept manifold, current where its KeptState says so.
struct KeptContacts {
  bool ref_is_a = true;  // the manifold's reference face is a's (else b's)
  bool sat_on_a = true;  // the separating-axis answer's face is a's (else b's)
  int count = 0;
  Mat3 rotation = Mat3::Identity();  // b's orientation in a's frame at the full test
  Vec3 offset = Vec3::Zero();        // b's position in a's frame at the full test
  Vec3 normal = Vec3::Zero();        // the reference face's outward normal, in its body's frame
  double plane = 0;                  // and its offset (n·x = plane on the face)
  Vec3 sat_normal = Vec3::Zero();    // the separating-axis answer's face, in its body's frame
  double sat_plane = 0;
  std::array<Vec3, kMaxManifoldPoints> points{Vec3::Zero(), Vec3::Zero(), Vec3::Zero(), Vec3::Zero()};  // incident points, in the incident body's frame
  double faces = 0, faces_spread = 0, edge = 0, edge_spread = 0;  // the full test's FaceChoice
  double left_out = 0;
};

// b's pose in a's frame: what the bound is measured on. Its two parts also
// apart, so that refresh can test the translation before it multiplies the
// rotations.
inline Vec3 relative_position(const Pose& a, const Pose& b) { return a.rotation.transpose() * (b.position - a.position); }
inline Mat3 relative_rotation(const Pose& a, const Pose& b) { return a.rotation.transpose() * b.rotation; }
inline Pose relative_pose(const Pose& a, const Pose& b) { return {relative_rotation(a, b), relative_position(a, b)}; }

// Keeps a pair's contacts found by the whole narrowphase at poses pa, pb (the
// answer `sat`, its axis `hint`, the manifold's `choice` and `features`, world
// coordinates). False, and nothing kept (k is then not current), for anything
// but a face manifold of at most kMaxManifoldPoints points whose
// separating-axis answer is a face.
inline bool keep(KeptContacts& k, const Mesh& ma, const Mesh& mb, const Pose& pa, const Pose& pb,
                 const PairContact& sat, const SatHint& hint, const FaceChoice& choice,
                 std::span<const FeatureContact> features) {
  if (!choice.made || features.empty() || features.size() > kMaxManifoldPoints) return false;
  const bool on_a = sat.feature == Feature::face_a;
  if (!(on_a || sat.feature == Feature::face_b) || hint.feature != sat.feature) return false;
  const int sat_face = on_a ? hint.i : hint.j;
  const Mesh& sat_mesh = on_a ? ma : mb;
  const Mesh& ref_mesh = choice.ref_is_a ? ma : mb;
  if (sat_face < 0 || sat_face >= static_cast<int>(sat_mesh.planes().size()) || choice.face < 0 ||
      choice.face >= static_cast<int>(ref_mesh.planes().size()))
    return false;
  const Feature ref = choice.ref_is_a ? Feature::face_a : Feature::face_b;
  const Pose& incident = choice.ref_is_a ? pb : pa;
  const Mesh& incident_mesh = choice.ref_is_a ? mb : ma;
  for (std::size_t c = 0; c < features.size(); ++c) {
    const FeatureContact& f = features[c];
    if (f.feature != ref) return false;
    const Vec3 n = choice.ref_is_a ? f.normal : Vec3(-f.normal);  // outward from the reference
    // The incident point about its body's position, from the pair's frame.
    const Vec3 q = choice.local[c] - 0.5 * f.depth * n - (incident.position - choice.origin);
    k.points[c] = incident.rotation.transpose() * q;
    // A point that is a vertex of the incident body (the clipping kept it)
    // is kept as that vertex: carried back from world coordinates it has
    // lost the last digits, and a symmetric stack's points would no longer
    // be symmetric (its torques no longer cancel exactly). Within 1e-13 of
    // the body's size: a few hundred times that rounding, and a thousandth
    // of the touching band, so that no point the clipping cut is moved to a
    // vertex that it is not.
    for (const Vec3& v : incident_mesh.vertices())
      if ((v - k.points[c]).norm() <= 1e-13 * incident_mesh.size()) k.points[c] = v;
  }
  k.count = static_cast<int>(features.size());
  k.ref_is_a = choice.ref_is_a;
  k.sat_on_a = on_a;
  const Pose rel = relative_pose(pa, pb);
  k.rotation = rel.rotation;
  k.offset = rel.position;
  k.normal = ref_mesh.planes()[static_cast<std::size_t>(choice.face)].normal;
  k.plane = ref_mesh.planes()[static_cast<std::size_t>(choice.face)].offset;
  k.sat_normal = sat_mesh.planes()[static_cast<std::size_t>(sat_face)].normal;
  k.sat_plane = sat_mesh.planes()[static_cast<std::size_t>(sat_face)].offset;
  k.faces = choice.faces, k.faces_spread = choice.faces_spread;
  k.edge = choice.edge, k.edge_spread = choice.edge_spread;
  k.left_out = choice.left_out;
  return true;
}

// A refresh refused (current contacts whose bound or guards failed): counts it,
// and sets the detections to wait before the pair's contacts are kept again
// (none within kKeepPatience refusals in a row). Returns whether this
// detection's full test is to keep them: only when there is no wait.
inline bool refuse(KeptState& k) {
  k.refused = static_cast<std::int8_t>(std::min(k.refused + 1, kKeepPatience + kKeepBackOff));
  k.wait = static_cast<std::int8_t>(k.refused > kKeepPatience ? (1 << (k.refused - kKeepPatience)) - 1 : 0);
  return k.wait == 0;
}

// The kept contacts (current: their KeptState is valid) at poses pa, pb: true
// with `sat` and the contacts appended to `out` (as the whole narrowphase
// gives them), false (nothing written) when the pair must be tested from
// scratch (the guards above). `band` is the pair's touching band in metres.
inline bool refresh(const KeptContacts& k, const Mesh& ma, const Mesh& mb, const Pose& pa, const Pose& pb,
                    double band, PairContact& sat, std::vector<FeatureContact>& out) {
  const double size = std::max(ma.size(), mb.size());
  const Vec3 dt = relative_position(pa, pb) - k.offset;
  const Vec3 n_ab = k.ref_is_a ? k.normal : Vec3(-(k.rotation * k.normal));  // a towards b, a's frame
  const double along = dt.dot(n_ab);  // > 0: apart
  // The slide across the normal without the turn first: a pair in motion
  // fails here, before the rotations are multiplied (the turn only adds).
  const double across = (dt - along * n_ab).norm();
  if (!(across <= kKeepSlide * size)) return false;
  const Mat3 rotation = relative_rotation(pa, pb);
  // The largest distance a unit vector of b's frame turned relative to a's
  // (the spectral norm of the change, 2 sin(θ/2): rotation_change_bound).
  const double turn = rotation_change_bound(k.rotation, rotation) * size;
  const double slide = across + turn;
  if (!(slide <= kKeepSlide * size) || !(turn - along < k.left_out)) return false;
  // The choices (FaceChoice): each compares two gaps, which a translation
  // changes by its component along each one's normal (so their difference by
  // at most |Δt| times the normals' spread) and a turn by at most `turn`
  // each; and the slack, kFacePreference of a gap, which shrinks as the pair
  // parts and grows as it closes.
  const double shift = dt.norm(), shrink = std::max(0.0, along + turn), grow = std::max(0.0, turn - along);
  const double faces = shift * k.faces_spread + 2 * turn;
  if (k.faces < 0 ? !(k.faces + faces + kFacePreference * shrink < 0) : !(k.faces - faces - kFacePreference * grow > 0))
    return false;
  if (!(k.edge - shift * k.edge_spread - 2 * turn - kFacePreference * shrink > 0)) return false;
  // The reference face and the incident body where they are now.
  const Pose& r = k.ref_is_a ? pa : pb;
  const Pose& i = k.ref_is_a ? pb : pa;
  const Vec3 n = r.rotation * k.normal;
  const Vec3 between = i.position - r.position;
  const std::size_t first = out.size();
  for (int c = 0; c < k.count; ++c) {
    const Vec3 q = i.rotation * k.points[static_cast<std::size_t>(c)] + between;  // about r's position
    const double s = n.dot(q) - k.plane;
    if (s > band) {
      out.resize(first);
      return false;
    }
    out.push_back({Vec3(q - 0.5 * s * n + r.position), k.ref_is_a ? n : Vec3(-n), -s,
                   k.ref_is_a ? Feature::face_a : Feature::face_b});
  }
  // The separating-axis answer: its face's support distance.
  const Pose& f = k.sat_on_a ? pa : pb;
  const Pose& o = k.sat_on_a ? pb : pa;
  const Mesh& other = k.sat_on_a ? mb : ma;
  const Vec3 m = f.rotation * k.sat_normal;
  const Vec3 m_o = o.rotation.transpose() * m;
  double low = std::numeric_limits<double>::infinity();
  std::size_t arg = 0;
  const auto& v = other.vertices();
  for (std::size_t j = 0; j < v.size(); ++j)
    if (const double h = m_o.dot(v[j]); h < low) low = h, arg = j;
  const double gap = low + m.dot(o.position - f.position) - k.sat_plane;
  sat.depth = -gap;
  sat.intersect = gap < 0;
  sat.normal = k.sat_on_a ? m : Vec3(-m);
  sat.contact = o.rotation * v[arg] + o.position - 0.5 * gap * m;
  sat.feature = k.sat_on_a ? Feature::face_a : Feature::face_b;
  return true;
}

}  // namespace gacompare::collision
