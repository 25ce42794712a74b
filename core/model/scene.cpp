// Scene loading and validation. Every rejection is one line
//   FILE: /json/pointer: expected WHAT, got WHAT-WAS-THERE
// (JSON syntax errors name the line and column instead of a pointer).
#include "core/model/scene.hpp"

#include <Eigen/Geometry>
#include <algorithm>
#include <array>
#include <cerrno>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <cstring>
#include <map>
#include <nlohmann/json.hpp>
#include <set>
#include <span>
#include <stdexcept>
#include <system_error>

#include "core/model/budget.hpp"
#include "core/error.hpp"
#include "core/model/mesh.hpp"
#include "core/model/sha256.hpp"
#include "core/read_file.hpp"

namespace gacompare::core {

Eigen::Matrix3d rotation_matrix(const Eigen::Vector4d& q) {
  return Eigen::Quaterniond(q[0], q[1], q[2], q[3]).normalized().toRotationMatrix();
}

std::string_view to_string(SolverMethod m) {
  switch (m) {
    case SolverMethod::euler:
      return "euler";
    case SolverMethod::rk4:
      return "rk4";
    case SolverMethod::rk4_doubling:
      return "rk4_doubling";
    case SolverMethod::cash_karp45:
      return "cash_karp45";
    case SolverMethod::bs3:
      return "bs3";
    case SolverMethod::dopri5:
      return "dopri5";
    case SolverMethod::tsit5:
      return "tsit5";
    case SolverMethod::vern6:
      return "vern6";
    case SolverMethod::vern7:
      return "vern7";
    case SolverMethod::vern8:
      return "vern8";
    case SolverMethod::vern9:
      return "vern9";
    case SolverMethod::symplectic_euler:
      return "symplectic_euler";
    case SolverMethod::velocity_verlet:
      return "velocity_verlet";
    case SolverMethod::rkmk4:
      return "rkmk4";
    case SolverMethod::rkmk45:
      return "rkmk45";
    case SolverMethod::crouch_grossman4:
      return "crouch_grossman4";
  }
  return "unknown";
}

bool is_lie_group(SolverMethod m) {
  return m == SolverMethod::rkmk4 || m == SolverMethod::rkmk45 || m == SolverMethod::crouch_grossman4;
}

std::string lie_group_refusal(const Scene& s) {
  if (!is_lie_group(s.solver.method)) return "";
  const std::string method = "solver.method '" + std::string(to_string(s.solver.method)) + "'";
  if (!s.particles.empty() || !s.generators.empty())
    return method + " steps rigid bodies' rotations on their group and cannot integrate particles; the scene has "
                    "particles (use a method of the flat state, such as rk4 or dopri5)";
  if (s.bodies.empty()) return method + " steps rigid bodies' rotations on their group; the scene has no bodies";
  return "";
}

std::string_view constraint_name(const Constraint& c) {
  static constexpr std::array<std::string_view, 6> names = {"distance_to_point", "distance", "on_plane",
                                                            "on_line",           "on_circle", "on_helix"};
  return names[c.index()];
}

std::optional<SolverMethod> solver_method_from_string(std::string_view s) {
  for (auto m : {SolverMethod::euler, SolverMethod::rk4, SolverMethod::rk4_doubling, SolverMethod::cash_karp45,
                 SolverMethod::bs3, SolverMethod::dopri5, SolverMethod::tsit5, SolverMethod::vern6, SolverMethod::vern7,
                 SolverMethod::vern8, SolverMethod::vern9, SolverMethod::symplectic_euler,
                 SolverMethod::velocity_verlet, SolverMethod::rkmk4, SolverMethod::rkmk45,
                 SolverMethod::crouch_grossman4})
    if (to_string(m) == s) return m;
  return std::nullopt;
}

std::string_view effect_name(const Effect& e) {
  static constexpr std::array<std::string_view, std::variant_size_v<Effect>> names = {
      "gravity",   "linear_drag", "quadratic_drag", "attraction_between_particles", "attraction_to_point",
      "collisions", "applied_forces"};
  return names[e.index()];
}

namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;
using Names = std::span<const std::string_view>;

constexpr int kMaxGenerated = 1'000'000;  // particles per generator: a guard against typos
constexpr double kUnitTolerance = 1e-6;   // |norm - 1| allowed for an orientation

// ---- message helpers ----------------------------------------------------------------
std::string shorten(std::string s, std::size_t max) {
  if (s.size() > max) s = s.substr(0, max) + "...";
  return s;
}

std::string quote(const std::string& s) {
  return shorten(json(s).dump(-1, ' ', false, json::error_handler_t::replace), 80);
}

std::string fmt(double x) {  // shortest round-trip form: 1, 0.1, 1e+300
  char buffer[32];
  const auto [end, ec] = std::to_chars(buffer, buffer + sizeof buffer, x);
  return ec == std::errc() ? std::string(buffer, end) : json(x).dump();
}

std::string join(Names names, std::string_view sep = ", ") {
  std::string out;
  for (auto n : names) {
    if (!out.empty()) out += sep;
    out += n;
  }
  return out;
}

// A JSON-pointer reference token ("~" -> "~0", "/" -> "~1"), shortened and kept on one line.
std::string token(std::string_view key) {
  std::string out;
  for (char c : key) {
    if (c == '~')
      out += "~0";
    else if (c == '/')
      out += "~1";
    else if (static_cast<unsigned char>(c) >= 0x20)
      out += c;
    else {  // a control character: written as JSON would, "\n" or "\u001f"
      const std::string escaped = json(std::string(1, c)).dump();
      out += escaped.substr(1, escaped.size() - 2);
    }
  }
  return shorten(out, 80);
}

// What was found, briefly: never a whole (possibly huge or deeply nested) document.
std::string describe(const json* j) {
  if (!j) return "nothing (the key is missing)";
  switch (j->type()) {
    case json::value_t::null:
      return "null";
    case json::value_t::boolean:
      return j->get<bool>() ? "true" : "false";
    case json::value_t::string:
      return quote(j->get<std::string>());
    case json::value_t::number_integer:
    case json::value_t::number_unsigned:
    case json::value_t::number_float:
      return j->dump();
    case json::value_t::array:
      if (j->size() <= 6 &&
          std::none_of(j->begin(), j->end(), [](const json& e) { return e.is_structured(); }))
        return shorten(j->dump(-1, ' ', false, json::error_handler_t::replace), 100);
      return "an array of " + std::to_string(j->size()) + (j->size() == 1 ? " element" : " elements");
    case json::value_t::object: {
      if (j->empty()) return "{}";
      std::string keys;
      int n = 0;
      for (const auto& [k, _] : j->items()) {
        if (n++ == 5) {
          keys += ", ...";
          break;
        }
        keys += (keys.empty() ? "" : ", ") + quote(k);
      }
      return "an object with keys " + keys;
    }
    default:
      return "an unsupported value";
  }
}

struct Ctx {
  std::string file;  // as given, for messages
  fs::path dir;      // the scene file's folder: meshes are resolved against it
};

[[noreturn]] void fail_at(const Ctx& ctx, const std::string& path, const std::string& what) {
  throw input_error(one_line(ctx.file + ": " + (path.empty() ? "/" : path) + ": " + what));
}

// A value at a JSON path; j == nullptr when a required key is missing.
struct Val {
  const Ctx& ctx;
  const json* j;
  std::string path;

  [[noreturn]] void fail(const std::string& what) const { fail_at(ctx, path, what); }
  [[noreturn]] void expected(const std::string& what) const {
    fail("expected " + what + ", got " + describe(j));
  }
  Val at(std::size_t i) const { return {ctx, &(*j)[i], path + "/" + std::to_string(i)}; }
  Val key(std::string_view k) const {
    auto it = j->find(std::string(k));
    return {ctx, it == j->end() ? nullptr : &*it, path + "/" + token(k)};
  }
};

// An object whose keys must all be in `allowed`; unknown keys are rejected up front,
// so a misspelt key is reported as such rather than as a missing one.
class Obj {
 public:
  Obj(const Val& v, Names allowed, const std::string& what = "an object") : v_(v), allowed_(allowed) {
    if (!v.j || !v.j->is_object()) v.expected(what);
    for (const auto& [k, _] : v.j->items())
      if (std::find(allowed.begin(), allowed.end(), k) == allowed.end())
        fail_at(v.ctx, v.path + "/" + token(k),
                "expected one of the keys " + join(allowed) + ", got the unknown key " + quote(k));
  }
  Val req(std::string_view k) const { return v_.key(check(k)); }  // missing -> j == nullptr
  std::optional<Val> opt(std::string_view k) const {
    Val v = v_.key(check(k));
    return v.j ? std::optional<Val>(v) : std::nullopt;
  }

 private:
  std::string_view check(std::string_view k) const {
    if (std::find(allowed_.begin(), allowed_.end(), k) == allowed_.end())
      throw std::logic_error("scene loader: key not declared: " + std::string(k));
    return k;
  }
  Val v_;
  Names allowed_;
};

// ---- typed getters --------------------------------------------------------------------
enum class Range { any, positive, non_negative, unit };

const char* range_text(Range r) {
  switch (r) {
    case Range::positive:
      return "a number > 0";
    case Range::non_negative:
      return "a number >= 0";
    case Range::unit:
      return "a number in [0, 1]";
    case Range::any:
      break;
  }
  return "a finite number";
}

double number(const Val& v, Range r = Range::any) {
  if (!v.j || !v.j->is_number()) v.expected(range_text(r));
  const double x = v.j->get<double>();
  const bool ok = std::isfinite(x) && (r != Range::positive || x > 0) &&
                  (r != Range::non_negative || x >= 0) && (r != Range::unit || (x >= 0 && x <= 1));
  if (!ok) v.expected(range_text(r));
  return x;
}

int integer(const Val& v, int lo, int hi) {
  const std::string what = "an integer in [" + std::to_string(lo) + ", " + std::to_string(hi) + "]";
  if (!v.j || !v.j->is_number()) v.expected(what);
  const double x = v.j->get<double>();  // exact for every integer that can pass the range check
  if (!std::isfinite(x) || x != std::floor(x) || x < lo || x > hi) v.expected(what);
  return static_cast<int>(x);
}

bool boolean(const Val& v) {
  if (!v.j || !v.j->is_boolean()) v.expected("true or false");
  return v.j->get<bool>();
}

std::string str(const Val& v, bool non_empty = true) {
  const char* what = non_empty ? "a non-empty string" : "a string";
  if (!v.j || !v.j->is_string() || (non_empty && v.j->get_ref<const std::string&>().empty()))
    v.expected(what);
  return v.j->get<std::string>();
}

// Names of particles, bodies and generators: '[' and ']' are reserved for the names
// generators make (net[0][1], chain[3]), so a given name can never collide with one.
std::string name(const Val& v) {
  static const std::string what = "a non-empty name without '[', ']' or control characters";
  if (!v.j || !v.j->is_string()) v.expected(what);
  std::string s = v.j->get<std::string>();
  if (s.empty() || std::any_of(s.begin(), s.end(), [](char c) {
        return c == '[' || c == ']' || static_cast<unsigned char>(c) < 0x20 || c == 0x7f;
      }))
    v.expected(what);
  return s;
}

std::string one_of(const Val& v, Names names) {
  const std::string what = "one of " + join(names);
  if (!v.j || !v.j->is_string()) v.expected(what);
  std::string s = v.j->get<std::string>();
  if (std::find(names.begin(), names.end(), s) == names.end()) v.expected(what);
  return s;
}

void array_of(const Val& v, std::size_t n, const std::string& what) {
  if (!v.j || !v.j->is_array() || v.j->size() != n) v.expected(what);
}

Vec3 vec3(const Val& v, Range r = Range::any) {
  array_of(v, 3, std::string("an array of 3 numbers") + (r == Range::positive ? " > 0" : ""));
  return {number(v.at(0), r), number(v.at(1), r), number(v.at(2), r)};
}

// A size: between a proton and the observable universe (core/model/budget.hpp).
double length(const Val& v) {
  const double x = number(v, Range::positive);
  if (x < kMinLength || x > kMaxLength)
    v.expected("a length in [1e-15, 1e26] m (a proton's radius to the observable universe's)");
  return x;
}

Vec3 lengths(const Val& v) {
  array_of(v, 3, "an array of 3 numbers > 0");
  return {length(v.at(0)), length(v.at(1)), length(v.at(2))};
}

// A point of a shape: no farther out than the observable universe, so that its
// products (Qhull's, the mass properties') stay finite.
Vec3 shape_point(const Val& v) {
  const Vec3 p = vec3(v);
  if (!(p.cwiseAbs().maxCoeff() <= kMaxLength))
    v.expected("a point within 1e26 m of the shape's origin (the observable universe's radius)");
  return p;
}

Eigen::Vector4d quaternion(const Val& v) {
  array_of(v, 4, "a unit quaternion [w, x, y, z]");
  Eigen::Vector4d q(number(v.at(0)), number(v.at(1)), number(v.at(2)), number(v.at(3)));
  if (!(std::abs(q.norm() - 1) <= kUnitTolerance))
    v.fail("expected a unit quaternion [w, x, y, z] (norm within 1e-6 of 1), got " + describe(v.j) +
           " with norm " + fmt(q.norm()));
  return q;
}

// Calls f(element) for each element of an optional array.
template <class F>
void each(const std::optional<Val>& v, F&& f) {
  if (!v) return;
  if (!v->j->is_array()) v->expected("an array");
  for (std::size_t i = 0; i < v->j->size(); ++i) f(v->at(i));
}

// The "type" of a tagged object (effects, constraints, generators).
std::string type_of(const Val& v, Names types) {
  if (!v.j || !v.j->is_object()) v.expected("an object with a \"type\" (one of " + join(types) + ")");
  return one_of(v.key("type"), types);
}

// True when the points span a solid (not all on one plane, line or point).
bool spans_volume(const std::vector<Vec3>& p) {
  std::size_t a = 0, b = 0, c = 0;
  for (std::size_t i = 0; i < p.size(); ++i)
    if ((p[i] - p[0]).squaredNorm() > (p[a] - p[0]).squaredNorm()) a = i;
  const Vec3 u = p[a] - p[0];
  for (std::size_t i = 0; i < p.size(); ++i)
    if (u.cross(p[i] - p[0]).squaredNorm() > u.cross(p[b] - p[0]).squaredNorm()) b = i;
  const Vec3 n = u.cross(p[b] - p[0]);
  for (std::size_t i = 0; i < p.size(); ++i)
    if (std::abs(n.dot(p[i] - p[0])) > std::abs(n.dot(p[c] - p[0]))) c = i;
  const double scale = u.norm();
  return scale > 0 && std::abs(n.dot(p[c] - p[0])) > 1e-12 * scale * scale * scale;
}

constexpr std::array<std::string_view, 7> kEffectTypes = {
    "gravity",   "linear_drag", "quadratic_drag", "attraction_between_particles", "attraction_to_point",
    "collisions", "applied_forces"};
constexpr std::array<std::string_view, 6> kConstraintTypes = {"distance_to_point", "distance", "on_plane",
                                                               "on_line",           "on_circle", "on_helix"};
constexpr std::array<std::string_view, 3> kDrift = {"off", "baumgarte", "projection"};
constexpr std::array<std::string_view, 2> kGeneratorTypes = {"particle_net", "particle_chain"};
constexpr std::array<std::string_view, 16> kMethods = {
    "euler", "rk4",   "rk4_doubling", "cash_karp45", "bs3",   "dopri5",           "tsit5",
    "vern6", "vern7", "vern8",        "vern9",       "symplectic_euler", "velocity_verlet",
    "rkmk4", "rkmk45", "crouch_grossman4"};
constexpr std::array<std::string_view, 9> kShapes = {"box",  "tetrahedron", "pyramid", "octahedron", "icosahedron",
                                                     "hull", "mesh",        "sphere",  "capsule"};

template <std::size_t N>
using Keys = std::array<std::string_view, N>;

// ---- the loader ------------------------------------------------------------------------
class Loader {
 public:
  explicit Loader(const Ctx& ctx, const Limits& limits = {}) : ctx_(ctx), limits_(limits) {}

  Scene scene(const json& root) {
    static constexpr Keys<13> keys = {"name",      "description", "duration",          "output",
                                      "solver",    "effects",     "particles",         "constraints",
                                      "bodies",    "generators",  "constraint_solver", "rigid_body",
                                      "check"};
    Obj o({ctx_, &root, ""}, keys);
    Scene s;
    {
      // The scene's name names its report folder and its baseline file: it is
      // data, never a path. No separators, no control characters, not . or ..
      const Val v = o.req("name");
      s.name = str(v);
      const bool path_like = s.name == "." || s.name == ".." ||
                             std::any_of(s.name.begin(), s.name.end(), [](char c) {
                               const auto u = static_cast<unsigned char>(c);
                               return c == '/' || c == '\\' || u < 0x20 || u == 0x7f;
                             });
      if (path_like) v.expected("a name without '/', '\\' or control characters, and not '.' or '..' (it names files)");
    }
    if (auto d = o.opt("description")) s.description = str(*d, false);
    s.duration = number(o.req("duration"), Range::positive);
    static constexpr Keys<1> output_keys = {"every"};
    const Obj out(o.req("output"), output_keys, "an object {\"every\": seconds}");
    const Val every = out.req("every");
    s.output_every = number(every, Range::positive);
    if (s.output_every > s.duration) every.expected("a number > 0 and <= duration (" + fmt(s.duration) + ")");
    // How many samples that is, and what they cost, is checked with the other
    // budgets once the whole scene is read (core/model/budget.hpp).
    s.solver = solver(o.req("solver"));
    if (auto c = o.opt("constraint_solver")) s.constraint_solver = constraint_solver(*c);
    if (auto c = o.opt("rigid_body")) s.rigid_body = rigid_body(*c);
    each(o.opt("particles"), [&](const Val& v) { s.particles.push_back(particle(v)); });
    each(o.opt("bodies"), [&](const Val& v) { s.bodies.push_back(body(v)); });
    if (auto c = o.opt("check")) s.check = check(*c);  // after the bodies its rest positions name
    each(o.opt("generators"), [&](const Val& v) { s.generators.push_back(generator(v)); });
    each(o.opt("effects"), [&](const Val& v) { s.effects.push_back(effect(v)); });  // after the bodies they name
    each(o.opt("constraints"), [&](const Val& v) { s.constraints.push_back(constraint(v, s)); });
    if (const std::string why = lie_group_refusal(s); !why.empty()) fail_at(ctx_, "/solver/method", why);
    // Before any work: the samples the run would record. What needs the
    // bodies' meshes (convexity, sizes, steps) is refused once the model is
    // compiled (core/model/model.hpp load_compiled).
    s.limits = limits_;
    if (const auto r = over_sample_budget(s)) fail_at(ctx_, r->path, r->what);
    return s;
  }

 private:
  SolverSpec solver(const Val& v) {
    static constexpr Keys<5> keys = {"method", "dt", "abs_tol", "rel_tol", "error_norm"};
    Obj o(v, keys);
    SolverSpec spec;
    if (auto x = o.opt("error_norm")) {
      const std::string m = str(*x);
      if (m == "physical") spec.error_norm = ErrorNorm::physical;
      else if (m == "component") spec.error_norm = ErrorNorm::component;
      else x->expected("\"physical\" or \"component\"");
    }
    spec.method = *solver_method_from_string(one_of(o.req("method"), kMethods));
    if (auto x = o.opt("dt")) spec.dt = number(*x, Range::positive);
    if (auto x = o.opt("abs_tol")) spec.abs_tol = number(*x, Range::positive);
    if (auto x = o.opt("rel_tol")) spec.rel_tol = number(*x, Range::non_negative);
    return spec;
  }

  ConstraintSolverSpec constraint_solver(const Val& v) {
    static constexpr Keys<6> keys = {"drift",          "baumgarte_alpha", "baumgarte_beta", "projection_tolerance",
                                     "cg_tolerance",   "cg_max_iterations"};
    Obj o(v, keys);
    ConstraintSolverSpec c;
    if (auto x = o.opt("drift")) {
      const std::string d = one_of(*x, kDrift);
      c.drift = d == "off" ? Drift::off : d == "baumgarte" ? Drift::baumgarte : Drift::projection;
    }
    if (auto x = o.opt("baumgarte_alpha")) c.baumgarte_alpha = number(*x, Range::non_negative);
    if (auto x = o.opt("baumgarte_beta")) c.baumgarte_beta = number(*x, Range::non_negative);
    if (auto x = o.opt("projection_tolerance")) c.projection_tolerance = number(*x, Range::positive);
    if (auto x = o.opt("cg_tolerance")) c.cg_tolerance = number(*x, Range::positive);
    if (auto x = o.opt("cg_max_iterations")) c.cg_max_iterations = integer(*x, 1, 1000000);
    return c;
  }

  CheckSpec check(const Val& v) {
    static constexpr Keys<6> keys = {"max_divergence",           "baseline_tolerance", "max_energy_drift",
                                     "max_constraint_violation", "max_rotation_drift", "rest"};
    Obj o(v, keys);
    CheckSpec c;
    if (auto x = o.opt("max_divergence")) c.max_divergence = number(*x, Range::non_negative);
    if (auto x = o.opt("baseline_tolerance")) c.baseline_tolerance = number(*x, Range::non_negative);
    if (auto x = o.opt("max_energy_drift")) c.max_energy_drift = number(*x, Range::non_negative);
    if (auto x = o.opt("max_constraint_violation")) c.max_constraint_violation = number(*x, Range::non_negative);
    if (auto x = o.opt("max_rotation_drift")) c.max_rotation_drift = number(*x, Range::non_negative);
    if (auto r = o.opt("rest")) {
      static constexpr Keys<3> rest_keys = {"after", "tolerance", "at"};
      const Obj ro(*r, rest_keys, "an object {\"after\": s, \"tolerance\": m, \"at\": {body: [x, y, z]}}");
      if (auto x = ro.opt("after")) c.rest_after = number(*x, Range::non_negative);
      if (auto x = ro.opt("tolerance")) c.rest_tolerance = number(*x, Range::positive);
      const Val at = ro.req("at");
      if (!at.j || !at.j->is_object() || at.j->empty()) at.expected("an object naming at least one body's rest position");
      for (const auto& [name, _] : at.j->items()) {
        const Val where = at.key(name);
        const json as_name = name;
        body_ref(Val{where.ctx, &as_name, where.path});  // the key must name a body
        c.rest.push_back({name, vec3(where)});
      }
    }
    return c;
  }

  RigidBodySpec rigid_body(const Val& v) {
    static constexpr Keys<2> keys = {"rotation", "renormalise"};
    static constexpr Keys<2> rotations = {"matrix", "quaternion"};
    static constexpr Keys<2> renormalise = {"none", "every_step"};
    Obj o(v, keys);
    RigidBodySpec r;
    if (auto x = o.opt("rotation")) r.rotation = one_of(*x, rotations) == "matrix" ? Rotation::matrix : Rotation::quaternion;
    if (auto x = o.opt("renormalise"))
      r.renormalise = one_of(*x, renormalise) == "none" ? Renormalise::none : Renormalise::every_step;
    return r;
  }

  Effect effect(const Val& v) {
    const std::string type = type_of(v, kEffectTypes);
    if (auto [it, fresh] = effect_paths_.emplace(type, v.path); !fresh)
      v.key("type").fail("expected each effect type at most once, got a second " + quote(type) +
                         " (the first is " + it->second + ")");
    if (type == "gravity") {
      static constexpr Keys<2> keys = {"type", "g"};
      Obj o(v, keys);
      Gravity g;
      if (auto x = o.opt("g")) g.g = vec3(*x);
      return g;
    }
    if (type == "linear_drag" || type == "quadratic_drag") {
      static constexpr Keys<3> keys = {"type", "k", "k_angular"};
      Obj o(v, keys);
      const double k = number(o.req("k"), Range::non_negative);
      double ka = 0;
      if (auto x = o.opt("k_angular")) ka = number(*x, Range::non_negative);
      return type == "linear_drag" ? Effect(LinearDrag{k, ka}) : Effect(QuadraticDrag{k, ka});
    }
    if (type == "attraction_between_particles") {
      static constexpr Keys<3> keys = {"type", "C", "softening"};
      Obj o(v, keys);
      AttractionBetweenParticles a{number(o.req("C")), 0};
      if (auto x = o.opt("softening")) a.softening = number(*x, Range::non_negative);
      return a;
    }
    if (type == "attraction_to_point") {
      static constexpr Keys<4> keys = {"type", "point", "D", "softening"};
      Obj o(v, keys);
      AttractionToPoint a{vec3(o.req("point")), number(o.req("D")), 0};
      if (auto x = o.opt("softening")) a.softening = number(*x, Range::non_negative);
      return a;
    }
    if (type == "applied_forces") {
      static constexpr Keys<2> keys = {"type", "forces"};
      static constexpr Keys<5> force_keys = {"body", "point", "force", "from", "until"};
      Obj o(v, keys);
      AppliedForces a;
      each(o.req("forces"), [&](const Val& f) {
        Obj fo(f, force_keys);
        AppliedForce af;
        af.body = body_ref(fo.req("body"));
        af.point = vec3(fo.req("point"));
        af.force = vec3(fo.req("force"));
        if (auto x = fo.opt("from")) af.from = number(*x, Range::non_negative);
        if (auto x = fo.opt("until")) {
          af.until = number(*x, Range::positive);
          if (!(af.until > af.from)) x->expected("a time > from (" + fmt(af.from) + ")");
        }
        a.forces.push_back(af);
      });
      return a;
    }
    static constexpr Keys<12> keys = {"type",           "restitution",   "penetration_tolerance", "step",
                                      "time_of_impact", "impact_motion", "method",                "broadphase",
                                      "reuse",          "reuse_contacts", "contact_solver",       "sleep"};
    static constexpr Keys<2> sleep_keys = {"speed", "time"};
    Obj o(v, keys);
    Collisions c;
    if (auto x = o.opt("method")) {
      const std::string m = str(*x);
      if (m == "manifold") c.method = ContactMethod::manifold;
      else if (m == "report") c.method = ContactMethod::report;
      else x->expected("\"manifold\" or \"report\"");
    }
    if (auto x = o.opt("step")) c.step = number(*x, Range::positive);
    if (auto x = o.opt("time_of_impact")) {
      const std::string m = str(*x);
      if (m == "bisection") c.time_of_impact = TimeOfImpact::bisection;
      else if (m == "illinois") c.time_of_impact = TimeOfImpact::illinois;
      else if (m == "golden_section") c.time_of_impact = TimeOfImpact::golden_section;
      else if (m == "conservative_advancement") c.time_of_impact = TimeOfImpact::conservative_advancement;
      else if (m == "none") c.time_of_impact = TimeOfImpact::none;
      else x->expected("\"bisection\", \"illinois\", \"golden_section\", \"conservative_advancement\" or \"none\"");
    }
    if (auto x = o.opt("impact_motion")) {
      const std::string m = str(*x);
      if (m == "integrate") c.impact_motion = ImpactMotion::integrate;
      else if (m == "interpolate") c.impact_motion = ImpactMotion::interpolate;
      else x->expected("\"integrate\" or \"interpolate\"");
    }
    if (auto x = o.opt("broadphase")) {
      const std::string m = str(*x);
      if (m == "sweep") c.broadphase = BroadphaseMethod::sweep;
      else if (m == "aabb_tree") c.broadphase = BroadphaseMethod::aabb_tree;
      else if (m == "sphere_tree") c.broadphase = BroadphaseMethod::sphere_tree;
      else x->expected("\"sweep\", \"aabb_tree\" or \"sphere_tree\"");
    }
    if (auto x = o.opt("contact_solver")) {
      const std::string m = str(*x);
      if (m == "pgs") c.contact_solver = ContactSolverMethod::pgs;
      else if (m == "direct") c.contact_solver = ContactSolverMethod::direct;
      else x->expected("\"pgs\" or \"direct\"");
    }
    if (auto x = o.opt("restitution")) c.restitution = number(*x, Range::unit);
    if (auto x = o.opt("penetration_tolerance")) c.penetration_tolerance = number(*x, Range::positive);
    if (auto x = o.opt("reuse")) c.reuse = boolean(*x);
    if (auto x = o.opt("reuse_contacts")) c.reuse_contacts = boolean(*x);
    if (auto x = o.opt("sleep")) {
      const Obj so(*x, sleep_keys, "an object {\"speed\": m/s, \"time\": s}");
      c.sleep.on = true;
      if (auto y = so.opt("speed")) c.sleep.speed = number(*y, Range::positive);
      if (auto y = so.opt("time")) c.sleep.time = number(*y, Range::positive);
    }
    return c;
  }

  Particle particle(const Val& v) {
    static constexpr Keys<5> keys = {"name", "mass", "position", "velocity", "pinned"};
    Obj o(v, keys);
    Particle p;
    p.name = claim(o.req("name"), "particle");
    p.mass = number(o.req("mass"), Range::positive);
    p.position = vec3(o.req("position"));
    if (auto x = o.opt("velocity")) p.velocity = vec3(*x);
    if (auto x = o.opt("pinned")) p.pinned = boolean(*x);
    return p;
  }

  Body body(const Val& v) {
    static constexpr Keys<11> keys = {"name",     "shape",       "mass",     "density",
                                      "position", "orientation", "velocity", "angular_velocity",
                                      "static",   "restitution", "friction"};
    Obj o(v, keys);
    Body b;
    b.name = claim(o.req("name"), "body");
    b.shape = shape(o.req("shape"));
    const auto mass = o.opt("mass"), density = o.opt("density");
    if (mass.has_value() == density.has_value())
      v.fail(std::string("expected exactly one of \"mass\" and \"density\", got ") +
             (mass ? "both" : "neither"));
    if (mass) b.mass = number(*mass, Range::positive);
    if (density) b.density = number(*density, Range::positive);
    b.position = vec3(o.req("position"));
    if (auto x = o.opt("orientation")) b.orientation = quaternion(*x);
    if (auto x = o.opt("velocity")) b.velocity = vec3(*x);
    if (auto x = o.opt("angular_velocity")) b.angular_velocity = vec3(*x);
    if (auto x = o.opt("static")) b.is_static = boolean(*x);
    if (auto x = o.opt("restitution")) b.restitution = number(*x, Range::unit);
    if (auto x = o.opt("friction")) b.friction = number(*x, Range::non_negative);
    return b;
  }

 public:
  std::vector<CollisionCaseSpec> collision_cases(const json& root) {
    const Val top{ctx_, &root, ""};
    if (!root.is_array() || root.empty()) top.expected("a non-empty array of pairs {\"a\": body, \"b\": body}");
    std::vector<CollisionCaseSpec> out;
    for (std::size_t i = 0; i < root.size(); ++i) {
      static constexpr Keys<3> keys = {"name", "a", "b"};
      const Val v = top.at(i);
      Obj o(v, keys, "an object {\"name\": ..., \"a\": body, \"b\": body}");
      CollisionCaseSpec c;
      c.name = "case " + std::to_string(i);
      if (auto n = o.opt("name")) c.name = str(*n);
      c.a = placed_shape(o.req("a"));
      c.b = placed_shape(o.req("b"));
      out.push_back(std::move(c));
    }
    return out;
  }

 private:
  // A shape key of the scene format beside "position" and "orientation".
  PlacedShape placed_shape(const Val& v) {
    static constexpr Keys<11> keys = {"box",    "tetrahedron", "pyramid",  "octahedron", "icosahedron", "hull",
                                      "mesh",   "sphere",      "capsule",  "position",   "orientation"};
    const std::string what = "an object with one shape key (" + join(kShapes) + "), \"position\" and optionally \"orientation\"";
    Obj o(v, keys, what);
    json only_shape = json::object();
    for (const auto& [k, x] : v.j->items())
      if (k != "position" && k != "orientation") only_shape[k] = x;
    if (only_shape.size() != 1) v.fail("expected " + what + ", got " + std::to_string(only_shape.size()) + " shape keys");
    PlacedShape p;
    const std::string key = only_shape.begin().key();
    // Parse the shape from the original value, so paths in messages point into the file.
    p.shape = shape_value(key, v.key(key));
    p.position = vec3(o.req("position"));
    if (auto q = o.opt("orientation")) p.orientation = quaternion(*q);
    return p;
  }

  Shape shape(const Val& v) {
    const std::string what = "an object with exactly one key: " + join(kShapes);
    if (!v.j || !v.j->is_object() || v.j->size() != 1) v.expected(what);
    Obj o(v, kShapes, what);
    const std::string key = v.j->begin().key();
    return shape_value(key, o.req(key));
  }

  // The value of one shape key.
  Shape shape_value(const std::string& key, const Val& x) {
    if (key == "box") return BoxShape{lengths(x)};
    if (key == "tetrahedron") return TetrahedronShape{length(x)};
    if (key == "octahedron") return OctahedronShape{length(x)};
    if (key == "icosahedron") return IcosahedronShape{length(x)};
    if (key == "sphere") return SphereShape{length(x)};
    if (key == "capsule") {
      // [r, L]: L = 0 is accepted, and is the sphere of radius r (make_capsule).
      array_of(x, 2, "an array [radius, length]: radius > 0, length >= 0");
      const double r = length(x.at(0));
      const double l = number(x.at(1), Range::non_negative);
      if (l > kMaxLength) x.at(1).expected("a length in [0, 1e26] m (0: a sphere)");
      return CapsuleShape{r, l};
    }
    if (key == "pyramid") {
      static constexpr Keys<2> keys = {"base", "height"};
      Obj p(x, keys, "an object {\"base\": b, \"height\": h}");
      return PyramidShape{length(p.req("base")), length(p.req("height"))};
    }
    if (key == "hull") {
      const std::string hull_what = "an array of at least 4 points [x, y, z], not all in one plane";
      if (!x.j->is_array() || x.j->size() < 4) x.expected(hull_what);
      HullShape h;
      for (std::size_t i = 0; i < x.j->size(); ++i) h.points.push_back(shape_point(x.at(i)));
      if (!spans_volume(h.points)) x.fail("expected " + hull_what + ", got points that span no volume");
      h.mesh = built(x, [&] { return convex_hull(h.points); });
      return h;
    }
    const Val& m = x;
    const std::string rel = str(m);
    const fs::path resolved = (ctx_.dir / fs::path(rel)).lexically_normal();
    std::error_code ec;
    if (!fs::is_regular_file(resolved, ec))
      m.fail("expected the path of an existing mesh file, relative to the scene's folder, got " + quote(rel) +
             " (resolved to " + quote(resolved.string()) + ", where there is no such file)");
    return MeshShape{resolved, built(m, [&] { return load_obj(resolved); })};
  }

  // A hull or mesh built once, here, so that what is wrong with it is named at
  // its JSON path (the mesh's own message follows).
  template <class Build>
  std::shared_ptr<const Mesh> built(const Val& v, Build&& build) {
    try {
      return std::make_shared<const Mesh>(build());
    } catch (const Error& e) {
      v.fail(e.what());
    }
  }

  Generator generator(const Val& v) {
    if (type_of(v, kGeneratorTypes) == "particle_net") {
      static constexpr Keys<8> keys = {"type", "name", "rows", "cols", "spacing", "mass", "origin", "pinned"};
      Obj o(v, keys);
      ParticleNet n;
      n.name = claim(o.req("name"), "generator");
      n.rows = integer(o.req("rows"), 1, kMaxGenerated);
      n.cols = integer(o.req("cols"), 1, kMaxGenerated);
      if (static_cast<long long>(n.rows) * n.cols > kMaxGenerated)
        o.req("cols").fail("expected rows x cols <= " + std::to_string(kMaxGenerated) + ", got " +
                           std::to_string(n.rows) + " x " + std::to_string(n.cols));
      n.spacing = number(o.req("spacing"), Range::positive);
      n.mass = number(o.req("mass"), Range::positive);
      if (auto x = o.opt("origin")) n.origin = vec3(*x);
      each(o.opt("pinned"), [&](const Val& pin) {
        array_of(pin, 2, "[row, col]");
        std::pair<int, int> rc{integer(pin.at(0), 0, n.rows - 1), integer(pin.at(1), 0, n.cols - 1)};
        if (std::find(n.pinned.begin(), n.pinned.end(), rc) != n.pinned.end())
          pin.fail("expected each pinned particle once, got " + describe(pin.j) + " again");
        n.pinned.push_back(rc);
      });
      return n;
    }
    static constexpr Keys<8> keys = {"type", "name",   "count",     "spacing",
                                     "mass", "origin", "direction", "pinned"};
    Obj o(v, keys);
    ParticleChain c;
    c.name = claim(o.req("name"), "generator");
    c.count = integer(o.req("count"), 2, kMaxGenerated);
    c.spacing = number(o.req("spacing"), Range::positive);
    c.mass = number(o.req("mass"), Range::positive);
    if (auto x = o.opt("origin")) c.origin = vec3(*x);
    if (auto x = o.opt("direction")) {
      c.direction = vec3(*x);
      if (!(c.direction.norm() > 0 && std::isfinite(c.direction.norm())))
        x->expected("a direction [x, y, z] with a length > 0 (and finite)");
    }
    each(o.opt("pinned"), [&](const Val& pin) {
      const int i = integer(pin, 0, c.count - 1);
      if (std::find(c.pinned.begin(), c.pinned.end(), i) != c.pinned.end())
        pin.fail("expected each pinned particle once, got " + std::to_string(i) + " again");
      c.pinned.push_back(i);
    });
    return c;
  }

  // A direction given in a scene: non-zero and finite, returned as a unit vector.
  static Vec3 unit(const Val& v) {
    const Vec3 d = vec3(v);
    const double n = d.norm();
    if (!(n > 0 && std::isfinite(n))) v.expected("a direction [x, y, z] with a length > 0 (and finite)");
    return d / n;
  }

  Constraint constraint(const Val& v, const Scene& s) {
    const std::string type = type_of(v, kConstraintTypes);
    if (type == "on_plane") {
      static constexpr Keys<4> keys = {"type", "particle", "point", "normal"};
      Obj o(v, keys);
      return OnPlane{particle_ref(o.req("particle"), s), vec3(o.req("point")), unit(o.req("normal"))};
    }
    if (type == "on_line") {
      static constexpr Keys<4> keys = {"type", "particle", "point", "direction"};
      Obj o(v, keys);
      return OnLine{particle_ref(o.req("particle"), s), vec3(o.req("point")), unit(o.req("direction"))};
    }
    if (type == "on_circle") {
      static constexpr Keys<5> keys = {"type", "particle", "center", "normal", "radius"};
      Obj o(v, keys);
      return OnCircle{particle_ref(o.req("particle"), s), vec3(o.req("center")), unit(o.req("normal")),
                      number(o.req("radius"), Range::positive)};
    }
    if (type == "on_helix") {
      static constexpr Keys<6> keys = {"type", "particle", "center", "axis", "radius", "pitch"};
      Obj o(v, keys);
      return OnHelix{particle_ref(o.req("particle"), s), vec3(o.req("center")), unit(o.req("axis")),
                     number(o.req("radius"), Range::positive), number(o.req("pitch"), Range::positive)};
    }
    if (type == "distance_to_point") {
      static constexpr Keys<4> keys = {"type", "particle", "point", "length"};
      Obj o(v, keys);
      DistanceToPoint d;
      d.particle = particle_ref(o.req("particle"), s);
      d.point = vec3(o.req("point"));
      d.length = number(o.req("length"), Range::positive);
      return d;
    }
    static constexpr Keys<3> keys = {"type", "particles", "length"};
    Obj o(v, keys);
    const Val pair = o.req("particles");
    array_of(pair, 2, "two particle names [a, b]");
    DistanceBetween d{particle_ref(pair.at(0), s), particle_ref(pair.at(1), s), 0};
    if (d.a == d.b) pair.expected("two different particle names");
    d.length = number(o.req("length"), Range::positive);
    return d;
  }

  // Registers a particle, body or generator name; all three share one namespace.
  std::string claim(const Val& v, const char* kind) {
    std::string n = name(v);
    if (auto [it, fresh] = names_.emplace(n, Named{kind, v.path}); !fresh)
      v.fail("expected a name not used by another particle, body or generator, got " + quote(n) +
             " (already the " + it->second.kind + " at " + it->second.path + ")");
    return n;
  }

  // A body given in "bodies".
  std::string body_ref(const Val& v) const {
    const std::string what = "the name of a body";
    if (!v.j || !v.j->is_string()) v.expected(what);
    std::string n = v.j->get<std::string>();
    if (auto it = names_.find(n); it != names_.end() && std::string_view(it->second.kind) == "body") return n;
    v.expected(what);
    return n;
  }

  // A particle given in "particles" or made by a generator (net[r][c], chain[i]).
  std::string particle_ref(const Val& v, const Scene& s) const {
    const std::string what = "the name of a particle (given, or generated such as net[0][1] or chain[2])";
    if (!v.j || !v.j->is_string()) v.expected(what);
    std::string n = v.j->get<std::string>();
    if (auto it = names_.find(n); it != names_.end()) {
      if (std::string_view(it->second.kind) == "particle") return n;
      v.fail("expected " + what + ", got " + quote(n) + ", which names a " + it->second.kind);
    }
    if (!generated(n, s)) v.expected(what);
    return n;
  }

  static bool generated(const std::string& n, const Scene& s) {
    const auto open = n.find('[');
    if (open == std::string::npos) return false;
    const std::string base = n.substr(0, open);
    std::vector<long> index;  // the bracketed indices: canonical decimal, at most 9 digits
    for (std::size_t i = open; i < n.size();) {
      const auto close = n.find(']', i);
      if (n[i] != '[' || close == std::string::npos) return false;
      const std::string digits = n.substr(i + 1, close - i - 1);
      if (digits.empty() || digits.size() > 9 || (digits.size() > 1 && digits[0] == '0') ||
          !std::all_of(digits.begin(), digits.end(), [](char c) { return c >= '0' && c <= '9'; }))
        return false;
      index.push_back(std::stol(digits));
      i = close + 1;
    }
    for (const auto& g : s.generators) {
      if (auto* net = std::get_if<ParticleNet>(&g); net && net->name == base)
        return index.size() == 2 && index[0] < net->rows && index[1] < net->cols;
      if (auto* chain = std::get_if<ParticleChain>(&g); chain && chain->name == base)
        return index.size() == 1 && index[0] < chain->count;
    }
    return false;
  }

  struct Named {
    const char* kind;
    std::string path;
  };
  const Ctx& ctx_;
  Limits limits_;
  std::map<std::string, Named> names_;
  std::map<std::string, std::string> effect_paths_;  // effect type -> where it was first given
};

// "line L, column C" of a byte offset (0-based) in text.
std::string location(const std::string& text, std::size_t offset) {
  offset = std::min(offset, text.size());
  const auto line = 1 + std::count(text.begin(), text.begin() + static_cast<std::ptrdiff_t>(offset), '\n');
  const auto last_newline = offset == 0 ? std::string::npos : text.rfind('\n', offset - 1);
  const auto column = last_newline == std::string::npos ? offset + 1 : offset - last_newline;
  return "line " + std::to_string(line) + ", column " + std::to_string(column);
}

// Parses strictly: no comments, and a key given twice in one object is an error
// (nlohmann would silently keep the last one).
json parse_json(const std::string& text, const Ctx& ctx) {
  struct Frame {
    bool array;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  std::vector<Frame> stack;
  auto callback = [&](int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start:
        stack.push_back(Frame{false, 0, {}, {}});
        break;
      case json::parse_event_t::array_start:
        stack.push_back(Frame{true, 0, {}, {}});
        break;
      case json::parse_event_t::key: {
        Frame& f = stack.back();
        f.key = parsed.get<std::string>();
        if (f.keys.insert(f.key).second) break;
        // The path is built only for the message: building it at every key
        // made deeply nested input quadratic.
        std::string path;
        for (const Frame& outer : stack) {
          path += '/';
          path += outer.array ? std::to_string(outer.index) : token(outer.key);
        }
        fail_at(ctx, path, "expected each key at most once per object, got it twice");
      }
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        stack.pop_back();
        [[fallthrough]];
      case json::parse_event_t::value:
        if (!stack.empty() && stack.back().array) ++stack.back().index;
        break;
    }
    return true;
  };
  try {
    return json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const json::parse_error& e) {
    // what(): "[json.exception.parse_error.101] parse error at line 2, column 3: DETAIL"
    std::string detail = e.what();
    if (auto p = detail.find("parse error"); p != std::string::npos)
      if (auto colon = detail.find(": ", p); colon != std::string::npos) detail = detail.substr(colon + 2);
    const std::size_t offset = e.byte > 0 ? e.byte - 1 : 0;
    throw input_error(
        one_line(ctx.file + ": " + location(text, offset) + ": malformed JSON: " + shorten(detail, 300)));
  } catch (const json::exception& e) {
    // e.g. "[json.exception.out_of_range.406] number overflow parsing '1e400'" (no position given)
    std::string detail = e.what();
    if (auto p = detail.find("] "); p != std::string::npos) detail = detail.substr(p + 2);
    std::string where;
    if (auto q = detail.find('\''); q != std::string::npos)
      if (auto end = detail.find('\'', q + 1); end != std::string::npos)
        if (auto at = text.find(detail.substr(q + 1, end - q - 1)); at != std::string::npos)
          where = location(text, at) + ": ";
    throw input_error(one_line(ctx.file + ": " + where + "malformed JSON: " + shorten(detail, 300)));
  }
}

}  // namespace

Scene parse_scene(const std::string& text, const std::filesystem::path& file, const Limits& limits) {
  const Ctx ctx{file.string(), file.parent_path()};
  const json root = parse_json(text, ctx);
  Scene s = Loader(ctx, limits).scene(root);
  s.file = file;
  s.sha256 = sha256_hex(text);
  return s;
}

std::vector<CollisionCaseSpec> parse_collision_cases(const std::string& text, const std::filesystem::path& file) {
  const Ctx ctx{file.string(), file.parent_path()};
  const json root = parse_json(text, ctx);
  return Loader(ctx).collision_cases(root);
}

void refuse_at(const std::filesystem::path& file, const std::string& path, const std::string& what) {
  fail_at(Ctx{file.string(), file.parent_path()}, path, what);
}

Scene load_scene(const std::filesystem::path& file, const Limits& limits) {
  return parse_scene(read_file(file, "scene file", Links::follow), file, limits);
}

std::vector<CollisionCaseSpec> load_collision_cases(const std::filesystem::path& file) {
  return parse_collision_cases(read_file(file, "collision case file", Links::follow), file);
}

std::span<const std::string_view> solver_method_names() { return kMethods; }

}  // namespace gacompare::core
