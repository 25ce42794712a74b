// Scene loader: a full scene loads with the right values, and every class of bad
// input is rejected with one line "FILE: /json/pointer: expected ..., got ...".
#include "core/model/model.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

#include <cstdlib>
#include <fstream>
#include <functional>
#include <iostream>
#include <iterator>
#include <nlohmann/json.hpp>
#include <sstream>

#include "core/error.hpp"
#include "core/model/sha256.hpp"

namespace gacompare::core {
namespace {

namespace fs = std::filesystem;
using json = nlohmann::json;

const fs::path kTestData = GACOMPARE_TEST_DATA_DIR;
const fs::path kData = GACOMPARE_DATA_DIR;

std::string read_bytes(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  return {std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>()};
}

// Runs f, which must throw an input error; returns its message.
std::string input_error_of(const std::function<void()>& f) {
  try {
    f();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    return e.what();
  }
  ADD_FAILURE() << "no error was thrown";
  return {};
}

// ---- sha256 --------------------------------------------------------------------------
TEST(Sha256, KnownDigests) {
  EXPECT_EQ(sha256_hex(""), "e3b0c44298fc1c149afbf4c8996fb92427ae41e4649b934ca495991b7852b855");
  EXPECT_EQ(sha256_hex("abc"), "ba7816bf8f01cfea414140de5dae2223b00361a396177a9cb410ff61f20015ad");
  EXPECT_EQ(sha256_hex("abcdbcdecdefdefgefghfghighijhijkijkljklmklmnlmnomnopnopq"),
            "248d6a61d20638b8e5c026930c3e6039a33ce45964ff2167f6ecedd419db06c1");
  EXPECT_EQ(sha256_hex(std::string(1'000'000, 'a')),
            "cdc76e5c9914fb9281a1c7e284d73e67f1809a48a497200e046d39ccc7112cd0");
}

// ---- names -----------------------------------------------------------------------------
TEST(SceneNames, SolverMethodsRoundTrip) {
  for (auto m : {SolverMethod::euler, SolverMethod::rk4, SolverMethod::rk4_doubling, SolverMethod::cash_karp45,
                 SolverMethod::bs3, SolverMethod::dopri5, SolverMethod::tsit5, SolverMethod::vern6, SolverMethod::vern7,
                 SolverMethod::vern8, SolverMethod::vern9, SolverMethod::symplectic_euler, SolverMethod::velocity_verlet,
                 SolverMethod::rkmk4, SolverMethod::rkmk45, SolverMethod::crouch_grossman4})
    EXPECT_EQ(solver_method_from_string(to_string(m)), m) << to_string(m);
  // The names the loader and the command line offer, one per method, in order.
  const auto names = solver_method_names();
  ASSERT_EQ(names.size(), 16u);
  for (auto name : names) EXPECT_EQ(to_string(*solver_method_from_string(name)), name);
  EXPECT_EQ(to_string(SolverMethod::cash_karp45), "cash_karp45");
  EXPECT_FALSE(solver_method_from_string("RK4").has_value());
  EXPECT_FALSE(solver_method_from_string("").has_value());
}

TEST(SceneNames, EffectNames) {
  EXPECT_EQ(effect_name(Gravity{}), "gravity");
  EXPECT_EQ(effect_name(LinearDrag{}), "linear_drag");
  EXPECT_EQ(effect_name(QuadraticDrag{}), "quadratic_drag");
  EXPECT_EQ(effect_name(AttractionBetweenParticles{}), "attraction_between_particles");
  EXPECT_EQ(effect_name(AttractionToPoint{}), "attraction_to_point");
  EXPECT_EQ(effect_name(Collisions{}), "collisions");
}

// ---- a full scene --------------------------------------------------------------------------
TEST(SceneLoad, FullSceneHasEveryValue) {
  const fs::path file = kTestData / "scenes" / "full.json";
  const Scene s = load_scene(file);
  EXPECT_EQ(s.name, "full");
  EXPECT_EQ(s.description, "Every key the scene loader knows, each with a non-default value.");
  EXPECT_EQ(s.file, file);
  EXPECT_EQ(s.sha256, sha256_hex(read_bytes(file)));
  EXPECT_EQ(s.sha256.size(), 64u);
  EXPECT_DOUBLE_EQ(s.duration, 2.5);
  EXPECT_DOUBLE_EQ(s.output_every, 0.05);
  EXPECT_EQ(s.solver.method, SolverMethod::cash_karp45);
  EXPECT_DOUBLE_EQ(s.solver.dt, 0.002);
  EXPECT_DOUBLE_EQ(s.solver.abs_tol, 1e-8);
  EXPECT_DOUBLE_EQ(s.solver.rel_tol, 1e-7);

  ASSERT_EQ(s.effects.size(), 6u);
  ASSERT_NE(s.find_effect<Gravity>(), nullptr);
  EXPECT_EQ(s.find_effect<Gravity>()->g, Vec3(0, 0, -9.8));
  EXPECT_DOUBLE_EQ(s.find_effect<LinearDrag>()->k, 0.1);
  EXPECT_DOUBLE_EQ(s.find_effect<QuadraticDrag>()->k, 0.05);
  EXPECT_DOUBLE_EQ(s.find_effect<AttractionBetweenParticles>()->C, 2.0);
  EXPECT_EQ(s.find_effect<AttractionToPoint>()->point, Vec3(1, 2, 3));
  EXPECT_DOUBLE_EQ(s.find_effect<AttractionToPoint>()->D, 0.5);
  EXPECT_DOUBLE_EQ(s.find_effect<Collisions>()->restitution, 0.25);
  EXPECT_DOUBLE_EQ(s.find_effect<Collisions>()->penetration_tolerance, 0.001);
  EXPECT_EQ(s.find_effect<Collisions>()->broadphase, BroadphaseMethod::sphere_tree);
  for (std::size_t i = 0; i < s.effects.size(); ++i)  // kept in file order
    EXPECT_EQ(s.effects[i].index(), i);

  ASSERT_EQ(s.particles.size(), 2u);
  EXPECT_EQ(s.particles[0].name, "bob");
  EXPECT_DOUBLE_EQ(s.particles[0].mass, 1.5);
  EXPECT_EQ(s.particles[0].position, Vec3(1, 0, 0));
  EXPECT_EQ(s.particles[0].velocity, Vec3(0, 1, 0));
  EXPECT_FALSE(s.particles[0].pinned);
  EXPECT_EQ(s.particles[1].name, "anchor");
  EXPECT_EQ(s.particles[1].velocity, Vec3::Zero());
  EXPECT_TRUE(s.particles[1].pinned);

  ASSERT_EQ(s.constraints.size(), 4u);
  const auto& c0 = std::get<DistanceToPoint>(s.constraints[0]);
  EXPECT_EQ(c0.particle, "bob");
  EXPECT_EQ(c0.point, Vec3::Zero());
  EXPECT_DOUBLE_EQ(c0.length, 1.0);
  const auto& c1 = std::get<DistanceBetween>(s.constraints[1]);
  EXPECT_EQ(c1.a, "bob");
  EXPECT_EQ(c1.b, "anchor");
  EXPECT_DOUBLE_EQ(c1.length, 1.4142);
  const auto& c2 = std::get<DistanceBetween>(s.constraints[2]);
  EXPECT_EQ(c2.a, "net[0][1]");
  EXPECT_EQ(c2.b, "net[1][2]");
  EXPECT_EQ(std::get<DistanceToPoint>(s.constraints[3]).particle, "chain[3]");

  ASSERT_EQ(s.bodies.size(), 7u);
  const Body& box = s.bodies[0];
  EXPECT_EQ(box.name, "box");
  EXPECT_EQ(std::get<BoxShape>(box.shape).size, Vec3(0.1, 0.4, 0.9));
  EXPECT_EQ(box.mass, 10.0);
  EXPECT_FALSE(box.density.has_value());
  EXPECT_EQ(box.orientation, Eigen::Vector4d(0.7071067811865476, 0, 0.7071067811865476, 0));
  EXPECT_EQ(box.velocity, Vec3(1, 2, 3));
  EXPECT_EQ(box.angular_velocity, Vec3(0, 5, 0));
  EXPECT_FALSE(box.is_static);
  EXPECT_DOUBLE_EQ(std::get<TetrahedronShape>(s.bodies[1].shape).edge, 0.3);
  EXPECT_FALSE(s.bodies[1].mass.has_value());
  EXPECT_EQ(s.bodies[1].density, 1000.0);
  EXPECT_EQ(s.bodies[1].orientation, Eigen::Vector4d(1, 0, 0, 0));
  EXPECT_DOUBLE_EQ(std::get<PyramidShape>(s.bodies[2].shape).base, 0.5);
  EXPECT_DOUBLE_EQ(std::get<PyramidShape>(s.bodies[2].shape).height, 0.7);
  EXPECT_DOUBLE_EQ(std::get<OctahedronShape>(s.bodies[3].shape).radius, 0.2);
  EXPECT_DOUBLE_EQ(std::get<IcosahedronShape>(s.bodies[4].shape).radius, 0.25);
  const auto& hull = std::get<HullShape>(s.bodies[5].shape);
  ASSERT_EQ(hull.points.size(), 5u);
  EXPECT_EQ(hull.points[3], Vec3(0, 0, 1));
  EXPECT_EQ(s.bodies[5].density, 500.0);
  const auto& mesh = std::get<MeshShape>(s.bodies[6].shape);
  EXPECT_EQ(mesh.file, (kTestData / "scenes" / "meshes" / "tetra.obj").lexically_normal());
  EXPECT_TRUE(fs::is_regular_file(mesh.file));
  EXPECT_TRUE(s.bodies[6].is_static);

  ASSERT_EQ(s.generators.size(), 2u);
  const auto& net = std::get<ParticleNet>(s.generators[0]);
  EXPECT_EQ(net.name, "net");
  EXPECT_EQ(net.rows, 2);
  EXPECT_EQ(net.cols, 3);
  EXPECT_DOUBLE_EQ(net.spacing, 0.1);
  EXPECT_DOUBLE_EQ(net.mass, 0.01);
  EXPECT_EQ(net.origin, Vec3(0, 0, 2));
  EXPECT_EQ(net.pinned, (std::vector<std::pair<int, int>>{{0, 0}, {0, 2}}));
  const auto& chain = std::get<ParticleChain>(s.generators[1]);
  EXPECT_EQ(chain.name, "chain");
  EXPECT_EQ(chain.count, 4);
  EXPECT_DOUBLE_EQ(chain.spacing, 0.2);
  EXPECT_DOUBLE_EQ(chain.mass, 0.5);
  EXPECT_EQ(chain.origin, Vec3(0, 1, 0));
  EXPECT_EQ(chain.direction, Vec3(0, 0, -1));
  EXPECT_EQ(chain.pinned, std::vector<int>{0});
}

TEST(SceneLoad, OptionalKeysTakeTheirDefaults) {
  const Scene s = parse_scene(
      R"({"name": "min", "duration": 1, "output": {"every": 1}, "solver": {"method": "euler"},
          "bodies": [{"name": "b", "shape": {"box": [1, 1, 1]}, "mass": 1, "position": [0, 0, 0]}],
          "effects": [{"type": "gravity"}, {"type": "collisions"}],
          "generators": [{"type": "particle_chain", "name": "c", "count": 2, "spacing": 1, "mass": 1}]})",
      "min.json");
  const SolverSpec defaults;
  EXPECT_EQ(s.solver.method, SolverMethod::euler);
  EXPECT_EQ(s.solver.dt, defaults.dt);
  EXPECT_EQ(s.solver.abs_tol, defaults.abs_tol);
  EXPECT_EQ(s.solver.rel_tol, defaults.rel_tol);
  EXPECT_EQ(s.description, "");
  EXPECT_EQ(s.find_effect<Gravity>()->g, Vec3(0, 0, -9.81));
  EXPECT_EQ(s.find_effect<Collisions>()->restitution, Collisions{}.restitution);
  EXPECT_EQ(s.find_effect<Collisions>()->broadphase, Collisions{}.broadphase);
  EXPECT_TRUE(s.find_effect<Collisions>()->reuse);
  EXPECT_TRUE(s.find_effect<Collisions>()->reuse_contacts);
  EXPECT_FALSE(s.find_effect<Collisions>()->sleep.on);
  EXPECT_TRUE(s.particles.empty());
  EXPECT_TRUE(s.constraints.empty());
  EXPECT_EQ(s.bodies[0].velocity, Vec3::Zero());
  EXPECT_EQ(s.bodies[0].angular_velocity, Vec3::Zero());
  EXPECT_EQ(s.bodies[0].orientation, Eigen::Vector4d(1, 0, 0, 0));
  EXPECT_FALSE(s.bodies[0].is_static);
  EXPECT_EQ(std::get<ParticleChain>(s.generators[0]).direction, Vec3(1, 0, 0));
  EXPECT_EQ(s.file, fs::path("min.json"));
  EXPECT_EQ(s.sha256.size(), 64u);
}

TEST(SceneLoad, MeshesResolveAgainstTheSceneFilesFolder) {
  const std::string text =
      R"({"name": "m", "duration": 1, "output": {"every": 0.5}, "solver": {"method": "rk4"},
          "bodies": [{"name": "m", "shape": {"mesh": "meshes/tetra.obj"}, "mass": 1, "position": [0, 0, 0]}]})";
  const Scene s = parse_scene(text, kTestData / "scenes" / "virtual.json");
  EXPECT_EQ(std::get<MeshShape>(s.bodies[0].shape).file,
            (kTestData / "scenes" / "meshes" / "tetra.obj").lexically_normal());

  // The same text placed one folder up finds no mesh, and says where it looked.
  const std::string msg = input_error_of([&] { parse_scene(text, kTestData / "virtual.json"); });
  EXPECT_NE(msg.find("/bodies/0/shape/mesh: expected the path of an existing mesh file"), std::string::npos)
      << msg;
  EXPECT_NE(msg.find((kTestData / "meshes" / "tetra.obj").lexically_normal().string()), std::string::npos)
      << msg;

  // "../" is resolved from the scene's folder too.
  const std::string up =
      R"({"name": "m", "duration": 1, "output": {"every": 0.5}, "solver": {"method": "rk4"},
      "bodies": [{"name": "m", "shape": {"mesh": "../scenes/meshes/tetra.obj"}, "mass": 1, "position": [0, 0, 0]}]})";
  const Scene s2 = parse_scene(up, kTestData / "scenes" / "virtual.json");
  EXPECT_EQ(std::get<MeshShape>(s2.bodies[0].shape).file,
            (kTestData / "scenes" / "meshes" / "tetra.obj").lexically_normal());
}

TEST(SceneLoad, MissingFileOrDirectoryIsAnInputError) {
  const fs::path missing = kTestData / "no-such-scene.json";
  std::string msg = input_error_of([&] { load_scene(missing); });
  EXPECT_EQ(msg.rfind(missing.string() + ": ", 0), 0u) << msg;
  EXPECT_NE(msg.find("cannot open"), std::string::npos) << msg;
  msg = input_error_of([&] { load_scene(kTestData); });
  EXPECT_NE(msg.find("got a directory"), std::string::npos) << msg;
}

TEST(SceneLoad, EveryBundledSceneLoads) {
  std::size_t count = 0;
  const fs::path dir = kData / "scenes";
  if (fs::is_directory(dir))
    for (const auto& entry : fs::directory_iterator(dir)) {
      if (entry.path().extension() != ".json") continue;
      ++count;
      SCOPED_TRACE(entry.path().string());
      EXPECT_NO_THROW({
        try {
          load_compiled(entry.path());
        } catch (const Error& e) {
          ADD_FAILURE() << e.what();
          throw;
        }
      });
    }
  std::cout << "[          ] loaded " << count << " bundled scene(s) from " << dir.string() << "\n";
  RecordProperty("bundled_scenes", static_cast<int>(count));
}

// ---- bad input: one line naming file, JSON path, expectation and what was found ---------------
const char* const kBase = R"({
  "name": "base", "duration": 1, "output": {"every": 0.1}, "solver": {"method": "rk4"},
  "effects": [{"type": "gravity", "g": [0, 0, -9.81]},
              {"type": "collisions", "restitution": 0.5, "penetration_tolerance": 1e-4}],
  "particles": [{"name": "a", "mass": 1, "position": [0, 0, 0]},
                {"name": "b", "mass": 1, "position": [1, 0, 0]}],
  "constraints": [{"type": "distance", "particles": ["a", "b"], "length": 1},
                  {"type": "distance_to_point", "particle": "a", "point": [0, 0, 1], "length": 1}],
  "bodies": [{"name": "box", "shape": {"box": [1, 1, 1]}, "mass": 1, "position": [0, 0, 0]}],
  "generators": [{"type": "particle_net", "name": "net", "rows": 2, "cols": 3, "spacing": 0.1,
                  "mass": 0.1, "pinned": [[0, 0]]},
                 {"type": "particle_chain", "name": "chain", "count": 3, "spacing": 0.1,
                  "mass": 0.1, "pinned": [0]}]
})";

struct BadCase {
  std::string name;
  std::function<std::string()> text;  // the scene text to parse
  std::vector<std::string> needles;   // substrings the message must contain
};

void PrintTo(const BadCase& c, std::ostream* os) { *os << c.name; }

std::function<std::string()> raw(std::string text) {
  return [text] { return text; };
}
std::function<std::string()> set(std::string pointer, json value) {
  return [=] {
    json j = json::parse(kBase);
    j[json::json_pointer(pointer)] = value;
    return j.dump(2);
  };
}
std::function<std::string()> erase(std::string pointer) {
  return [=] {
    json j = json::parse(kBase);
    const json::json_pointer p(pointer);
    j[p.parent_pointer()].erase(p.back());
    return j.dump(2);
  };
}

const fs::path kCaseFile = "scenes/case.json";

std::vector<BadCase> bad_cases() {
  return {
      // JSON itself
      {"SyntaxError",
       raw("{\n  \"name\": \"x\",\n  \"duration\": ,\n}"),
       {": line 3, column 15: malformed JSON"}},
      {"EmptyText", raw(""), {": line 1, column 1: malformed JSON"}},
      {"NumberOverflow",
       raw(R"({"name": "x", "duration": 1e400})"),
       {"line 1, column 27: malformed JSON", "1e400"}},
      {"DuplicateKey",
       raw(R"({"name": "x", "solver": {"method": "rk4", "method": "euler"}})"),
       {": /solver/method: expected each key at most once"}},
      {"DuplicateKeyInArray",
       raw(R"({"particles": [{}, {"name": "p", "name": "q"}]})"),
       {": /particles/1/name: expected each key at most once"}},
      {"CommentsAreNotJson", raw("{\"name\": \"x\" // no\n}"), {"malformed JSON"}},
      {"RootNotObject", raw("[1, 2]"), {": /: expected an object, got [1,2]"}},
      // unknown keys anywhere
      {"UnknownTopKey",
       set("/colour", "red"),
       {": /colour: expected one of the keys name, description, duration, output, solver, effects, "
        "particles, "
        "constraints, bodies, generators, constraint_solver, rigid_body, check, got the unknown key \"colour\""}},
      {"UnknownParticleKey",
       set("/particles/0/mas", 1),
       {": /particles/0/mas: expected one of the keys name, mass, position, velocity, pinned, got the "
        "unknown key \"mas\""}},
      {"UnknownKeyIsEscaped",
       set("/a~1b", 1),
       {": /a~1b: expected one of the keys", "got the unknown key \"a/b\""}},
      {"UnknownEffectKey",
       set("/effects/0/k", 1),
       {": /effects/0/k: expected one of the keys type, g, got the unknown key \"k\""}},
      {"UnknownShape",
       set("/bodies/0/shape", json{{"cylinder", 1}}),
       {": /bodies/0/shape/cylinder: expected one of the keys box, tetrahedron",
        "mesh, sphere, capsule, got the unknown key \"cylinder\""}},
      // capsules: [radius > 0, length >= 0]
      {"CapsuleNotPair",
       set("/bodies/0/shape", json{{"capsule", 1}}),
       {": /bodies/0/shape/capsule: expected an array [radius, length]: radius > 0, length >= 0, got 1"}},
      {"CapsuleZeroRadius",
       set("/bodies/0/shape", json{{"capsule", {0, 1}}}),
       {": /bodies/0/shape/capsule/0: expected a number > 0, got 0"}},
      {"CapsuleNegativeLength",
       set("/bodies/0/shape", json{{"capsule", {0.1, -1}}}),
       {": /bodies/0/shape/capsule/1: expected a number >= 0, got -1"}},
      {"CapsuleLengthNotNumber",
       set("/bodies/0/shape", json{{"capsule", {0.1, "1"}}}),
       {": /bodies/0/shape/capsule/1: expected a number >= 0, got \"1\""}},
      // missing and mistyped top-level values
      {"MissingName",
       erase("/name"),
       {": /name: expected a non-empty string, got nothing (the key is missing)"}},
      {"EmptyName", set("/name", ""), {": /name: expected a non-empty string, got \"\""}},
      {"DescriptionNotString", set("/description", 5), {": /description: expected a string, got 5"}},
      {"DurationZero", set("/duration", 0), {": /duration: expected a number > 0, got 0"}},
      {"DurationString", set("/duration", "10"), {": /duration: expected a number > 0, got \"10\""}},
      {"DurationBool", set("/duration", true), {": /duration: expected a number > 0, got true"}},
      {"MissingOutput",
       erase("/output"),
       {": /output: expected an object {\"every\": seconds}, got nothing"}},
      {"OutputEveryAboveDuration",
       set("/output/every", 2),
       {": /output/every: expected a number > 0 and <= duration (1), got 2"}},
      {"MissingSolver", erase("/solver"), {": /solver: expected an object, got nothing"}},
      {"MissingMethod",
       erase("/solver/method"),
       {": /solver/method: expected one of euler, rk4", "got nothing"}},
      // The Lie-group methods step bodies only (SceneLoad.LieGroupMethodsTakeCollisions: with collisions too).
      {"LieGroupMethodWithParticles",
       set("/solver/method", "rkmk4"),
       {": /solver/method: solver.method 'rkmk4' steps rigid bodies' rotations on their group and cannot "
        "integrate particles; the scene has particles"}},
      {"LieGroupMethodWithoutBodies",
       [] {
         json j = json::parse(kBase);
         j["solver"]["method"] = "rkmk45";
         for (const char* key : {"particles", "constraints", "generators", "bodies"}) j.erase(key);
         j["effects"].erase(1);
         return j.dump();
       },
       {": /solver/method: solver.method 'rkmk45' steps rigid bodies' rotations on their group; the scene has no "
        "bodies"}},
      {"UnknownMethod",
       set("/solver/method", "rk5"),
       {": /solver/method: expected one of euler, rk4, rk4_doubling, cash_karp45, bs3, dopri5, tsit5, vern6, "
        "vern7, vern8, vern9, symplectic_euler, velocity_verlet, rkmk4, rkmk45, crouch_grossman4, got \"rk5\""}},
      {"NegativeDt", set("/solver/dt", -1), {": /solver/dt: expected a number > 0, got -1"}},
      {"NegativeRelTol",
       set("/solver/rel_tol", -1e-9),
       {": /solver/rel_tol: expected a number >= 0, got -1e-09"}},
      {"ZeroAbsTol", set("/solver/abs_tol", 0), {": /solver/abs_tol: expected a number > 0, got 0"}},
      {"EffectsNotArray", set("/effects", json::object()), {": /effects: expected an array, got {}"}},
      // effects
      {"UnknownEffectType",
       set("/effects/0/type", "gravty"),
       {": /effects/0/type: expected one of gravity, linear_drag", "got \"gravty\""}},
      {"EffectWithoutType",
       set("/effects/0", json{{"g", {0, 0, -1}}}),
       {": /effects/0/type: expected one of", "got nothing"}},
      {"EffectNotObject",
       set("/effects/0", "gravity"),
       {": /effects/0: expected an object with a \"type\"", "got \"gravity\""}},
      {"DuplicateEffect",
       set("/effects/2", json{{"type", "gravity"}}),
       {": /effects/2/type: expected each effect type at most once", "(the first is /effects/0)"}},
      {"GravityTwoNumbers",
       set("/effects/0/g", {0, -9.81}),
       {": /effects/0/g: expected an array of 3 numbers, got [0,-9.81]"}},
      {"GravityComponentString",
       set("/effects/0/g/2", "down"),
       {": /effects/0/g/2: expected a finite number, got \"down\""}},
      {"RestitutionAboveOne",
       set("/effects/1/restitution", 1.5),
       {": /effects/1/restitution: expected a number in [0, 1], got 1.5"}},
      {"UnknownBroadphase",
       set("/effects/1/broadphase", "octree"),
       {": /effects/1/broadphase: expected \"sweep\", \"aabb_tree\" or \"sphere_tree\", got \"octree\""}},
      {"ZeroPenetrationTolerance",
       set("/effects/1/penetration_tolerance", 0),
       {": /effects/1/penetration_tolerance: expected a number > 0, got 0"}},
      {"ReuseNotBool", set("/effects/1/reuse", "no"), {": /effects/1/reuse: expected true or false, got \"no\""}},
      {"ReuseContactsNotBool",
       set("/effects/1/reuse_contacts", 1),
       {": /effects/1/reuse_contacts: expected true or false, got 1"}},
      {"SleepNotObject",
       set("/effects/1/sleep", true),
       {": /effects/1/sleep: expected an object {\"speed\": m/s, \"time\": s}, got true"}},
      {"SleepZeroSpeed",
       set("/effects/1/sleep", json{{"speed", 0}}),
       {": /effects/1/sleep/speed: expected a number > 0, got 0"}},
      {"SleepUnknownKey",
       set("/effects/1/sleep", json{{"after", 1}}),
       {": /effects/1/sleep/after: expected one of the keys", "got the unknown key \"after\""}},
      {"DragWithoutK",
       set("/effects/2", json{{"type", "linear_drag"}}),
       {": /effects/2/k: expected a number >= 0, got nothing"}},
      {"NegativeDrag",
       set("/effects/2", json{{"type", "quadratic_drag"}, {"k", -1}}),
       {": /effects/2/k: expected a number >= 0, got -1"}},
      {"AttractionWithoutPoint",
       set("/effects/2", json{{"type", "attraction_to_point"}, {"D", 1}}),
       {": /effects/2/point: expected an array of 3 numbers, got nothing"}},
      // particles
      {"NegativeMass", set("/particles/1/mass", -1), {": /particles/1/mass: expected a number > 0, got -1"}},
      {"MissingPosition",
       erase("/particles/0/position"),
       {": /particles/0/position: expected an array of 3 numbers, got nothing"}},
      {"PinnedNotBool",
       set("/particles/0/pinned", "yes"),
       {": /particles/0/pinned: expected true or false, got \"yes\""}},
      {"PinnedNumber",
       set("/particles/0/pinned", 1),
       {": /particles/0/pinned: expected true or false, got 1"}},
      {"DuplicateParticleName",
       set("/particles/1/name", "a"),
       {": /particles/1/name: expected a name not used by another particle, body or generator, got \"a\"",
        "/particles/0/name"}},
      {"BodyNamedLikeParticle",
       set("/bodies/0/name", "b"),
       {": /bodies/0/name: expected a name not used", "particle at /particles/1/name"}},
      {"GeneratorNamedLikeBody",
       set("/generators/1/name", "box"),
       {": /generators/1/name: expected a name not used", "body at /bodies/0/name"}},
      {"NameWithBracket",
       set("/particles/0/name", "a[0]"),
       {": /particles/0/name: expected a non-empty name without '['"}},
      {"NameNotString",
       set("/particles/0/name", 7),
       {": /particles/0/name: expected a non-empty name", "got 7"}},
      // constraints
      {"UnknownParticle",
       set("/constraints/0/particles/1", "zed"),
       {": /constraints/0/particles/1: expected the name of a particle", "got \"zed\""}},
      {"SameParticleTwice",
       set("/constraints/0/particles", {"a", "a"}),
       {": /constraints/0/particles: expected two different particle names, got [\"a\",\"a\"]"}},
      {"ConstraintOnBody",
       set("/constraints/1/particle", "box"),
       {": /constraints/1/particle: expected the name of a particle", "names a body"}},
      {"ConstraintOnGenerator",
       set("/constraints/1/particle", "net"),
       {": /constraints/1/particle:", "names a generator"}},
      {"GeneratedRowOutOfRange",
       set("/constraints/1/particle", "net[2][0]"),
       {": /constraints/1/particle: expected the name of a particle", "got \"net[2][0]\""}},
      {"GeneratedNotCanonical",
       set("/constraints/1/particle", "chain[01]"),
       {": /constraints/1/particle: expected the name of a particle"}},
      {"GeneratedWrongArity",
       set("/constraints/1/particle", "chain[0][0]"),
       {": /constraints/1/particle: expected the name of a particle"}},
      {"ThreeParticles",
       set("/constraints/0/particles", {"a", "b", "a"}),
       {": /constraints/0/particles: expected two particle names [a, b]"}},
      {"ZeroLength",
       set("/constraints/1/length", 0),
       {": /constraints/1/length: expected a number > 0, got 0"}},
      {"UnknownConstraintType",
       set("/constraints/0/type", "spring"),
       {": /constraints/0/type: expected one of distance_to_point, distance, on_plane, on_line, on_circle, "
        "on_helix, got \"spring\""}},
      // bodies and shapes
      {"MassAndDensity",
       set("/bodies/0/density", 1),
       {": /bodies/0: expected exactly one of \"mass\" and \"density\", got both"}},
      {"NoMassNoDensity",
       erase("/bodies/0/mass"),
       {": /bodies/0: expected exactly one of \"mass\" and \"density\", got neither"}},
      {"ZeroDensity",
       [] {
         json j = json::parse(kBase);
         j["bodies"][0].erase("mass");
         j["bodies"][0]["density"] = 0;
         return j.dump();
       },
       {": /bodies/0/density: expected a number > 0, got 0"}},
      {"OrientationNotUnit",
       set("/bodies/0/orientation", {2, 0, 0, 0}),
       {": /bodies/0/orientation: expected a unit quaternion [w, x, y, z] (norm within 1e-6 of 1), got "
        "[2,0,0,0] with norm 2"}},
      {"OrientationThreeNumbers",
       set("/bodies/0/orientation", {1, 0, 0}),
       {": /bodies/0/orientation: expected a unit quaternion [w, x, y, z], got [1,0,0]"}},
      {"StaticNotBool", set("/bodies/0/static", "no"), {": /bodies/0/static: expected true or false"}},
      {"MissingShape",
       erase("/bodies/0/shape"),
       {": /bodies/0/shape: expected an object with exactly one key: box, tetrahedron", "got nothing"}},
      {"TwoShapes",
       set("/bodies/0/shape/tetrahedron", 1),
       {": /bodies/0/shape: expected an object with exactly one key",
        "got an object with keys \"box\", \"tetrahedron\""}},
      {"BoxZeroSide",
       set("/bodies/0/shape/box/1", 0),
       {": /bodies/0/shape/box/1: expected a number > 0, got 0"}},
      {"BoxScalar",
       set("/bodies/0/shape/box", 1),
       {": /bodies/0/shape/box: expected an array of 3 numbers > 0, got 1"}},
      {"TetrahedronNegative",
       set("/bodies/0/shape", json{{"tetrahedron", -0.5}}),
       {": /bodies/0/shape/tetrahedron: expected a number > 0, got -0.5"}},
      {"PyramidMissingHeight",
       set("/bodies/0/shape", json{{"pyramid", {{"base", 1}}}}),
       {": /bodies/0/shape/pyramid/height: expected a number > 0, got nothing"}},
      {"HullThreePoints",
       set("/bodies/0/shape", json{{"hull", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}}}}),
       {": /bodies/0/shape/hull: expected an array of at least 4 points"}},
      {"HullFlat",
       set("/bodies/0/shape", json{{"hull", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {1, 1, 0}}}}),
       {": /bodies/0/shape/hull: expected an array of at least 4 points [x, y, z], not all in one plane, got "
        "points that span no volume"}},
      {"HullBadPoint",
       set("/bodies/0/shape", json{{"hull", {{0, 0, 0}, {1, 0, 0}, {0, 1, 0}, {0, 0}}}}),
       {": /bodies/0/shape/hull/3: expected an array of 3 numbers, got [0,0]"}},
      {"MeshMissing",
       set("/bodies/0/shape", json{{"mesh", "meshes/nothing.obj"}}),
       {": /bodies/0/shape/mesh: expected the path of an existing mesh file",
        "\"scenes/meshes/nothing.obj\""}},
      {"MeshEmpty",
       set("/bodies/0/shape", json{{"mesh", ""}}),
       {": /bodies/0/shape/mesh: expected a non-empty string, got \"\""}},
      // generators
      {"RowsNotInteger",
       set("/generators/0/rows", 2.5),
       {": /generators/0/rows: expected an integer in [1, 1000000], got 2.5"}},
      {"RowsZero",
       set("/generators/0/rows", 0),
       {": /generators/0/rows: expected an integer in [1, 1000000], got 0"}},
      {"RowsHuge",
       set("/generators/0/rows", 1e300),
       {": /generators/0/rows: expected an integer in [1, 1000000], got 1e+300"}},
      {"NetTooLarge",
       [] {
         json j = json::parse(kBase);
         j["generators"][0]["rows"] = 2000;
         j["generators"][0]["cols"] = 2000;
         return j.dump();
       },
       {": /generators/0/cols: expected rows x cols <= 1000000, got 2000 x 2000"}},
      {"NetPinOutOfRange",
       set("/generators/0/pinned/0", {2, 0}),
       {": /generators/0/pinned/0/0: expected an integer in [0, 1], got 2"}},
      {"NetPinShape",
       set("/generators/0/pinned/0", 0),
       {": /generators/0/pinned/0: expected [row, col], got 0"}},
      {"NetPinTwice",
       set("/generators/0/pinned/1", {0, 0}),
       {": /generators/0/pinned/1: expected each pinned particle once"}},
      {"NetMissingSpacing",
       erase("/generators/0/spacing"),
       {": /generators/0/spacing: expected a number > 0, got nothing"}},
      {"ChainCountOne",
       set("/generators/1/count", 1),
       {": /generators/1/count: expected an integer in [2, 1000000], got 1"}},
      {"ChainZeroDirection",
       set("/generators/1/direction", {0, 0, 0}),
       {": /generators/1/direction: expected a direction [x, y, z] with a length > 0", "got [0,0,0]"}},
      {"ChainPinOutOfRange",
       set("/generators/1/pinned/0", 3),
       {": /generators/1/pinned/0: expected an integer in [0, 2], got 3"}},
      {"ChainUnknownKey",
       set("/generators/1/rows", 2),
       {": /generators/1/rows: expected one of the keys type, name, count, spacing", "unknown key \"rows\""}},
      {"GeneratorUnknownType",
       set("/generators/0/type", "particle_cloth"),
       {": /generators/0/type: expected one of particle_net, particle_chain, got \"particle_cloth\""}},
  };
}

class BadScene : public testing::TestWithParam<BadCase> {};

TEST_P(BadScene, IsRejectedWithOneLineNamingPathAndExpectation) {
  const BadCase& c = GetParam();
  const std::string text = c.text();
  const std::string msg = input_error_of([&] { parse_compiled(text, kCaseFile); });
  EXPECT_EQ(msg.rfind(kCaseFile.string() + ":", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  if (std::getenv("GACOMPARE_PRINT_MESSAGES")) std::cout << msg << "\n";
  for (const auto& needle : c.needles)
    EXPECT_NE(msg.find(needle), std::string::npos) << "missing: " << needle << "\nin: " << msg;
}

INSTANTIATE_TEST_SUITE_P(Scene, BadScene, testing::ValuesIn(bad_cases()),
                         [](const testing::TestParamInfo<BadCase>& info) { return info.param.name; });

// check.rest: where bodies must come to rest, each key a body's name.
TEST(SceneLoad, RestPositionsNameBodies) {
  const auto scene = [](const std::string& at) {
    return R"({"name": "r", "duration": 2, "output": {"every": 0.5}, "solver": {"method": "rk4"},
      "particles": [{"name": "p", "mass": 1, "position": [0, 0, 0]}],
      "bodies": [{"name": "box", "shape": {"box": [1, 1, 1]}, "mass": 1, "position": [0, 0, 1]}],
      "check": {"rest": {"after": 1, "tolerance": 0.002, "at": )" + at + "}}}";
  };
  const Scene s = parse_scene(scene(R"({"box": [0, 0, 0.5]})"), kCaseFile);
  ASSERT_EQ(s.check.rest.size(), 1u);
  EXPECT_EQ(s.check.rest[0].body, "box");
  EXPECT_EQ(s.check.rest[0].position, Vec3(0, 0, 0.5));
  EXPECT_EQ(s.check.rest_after, 1);
  EXPECT_EQ(s.check.rest_tolerance, 0.002);
  const std::string nobody = input_error_of([&] { parse_scene(scene(R"({"nobody": [0, 0, 0]})"), kCaseFile); });
  EXPECT_NE(nobody.find(": /check/rest/at/nobody: expected the name of a body"), std::string::npos) << nobody;
  const std::string particle = input_error_of([&] { parse_scene(scene(R"({"p": [0, 0, 0]})"), kCaseFile); });
  EXPECT_NE(particle.find(": /check/rest/at/p: expected the name of a body"), std::string::npos) << particle;
  const std::string empty = input_error_of([&] { parse_scene(scene("{}"), kCaseFile); });
  EXPECT_NE(empty.find(": /check/rest/at: expected an object naming at least one body"), std::string::npos) << empty;
}

TEST(SceneLoad, TheBaseOfTheBadCasesIsValid) {
  const Scene s = parse_scene(kBase, kCaseFile);
  EXPECT_EQ(s.particles.size(), 2u);
  EXPECT_EQ(s.generators.size(), 2u);
}

// The Lie-group methods take the collisions effect: the collision stages'
// islands and time-of-impact trials step on the group as the world does
// (core/collision/subsystem.hpp). The base's bodies without its particles.
TEST(SceneLoad, LieGroupMethodsTakeCollisions) {
  for (const char* method : {"rkmk4", "rkmk45", "crouch_grossman4"}) {
    json j = json::parse(kBase);
    j["solver"]["method"] = method;
    for (const char* key : {"particles", "constraints", "generators"}) j.erase(key);
    const Scene s = parse_scene(j.dump(), kCaseFile);
    EXPECT_NE(s.find_effect<Collisions>(), nullptr) << method;
    EXPECT_EQ(lie_group_refusal(s), "") << method;
  }
}

TEST(SceneLoad, OrientationIsCheckedButNotNormalised) {
  json j = json::parse(kBase);
  j["bodies"][0]["orientation"] = {1.0000009, 0, 0, 0};  // within 1e-6 of unit norm
  EXPECT_EQ(parse_scene(j.dump(), kCaseFile).bodies[0].orientation, Eigen::Vector4d(1.0000009, 0, 0, 0));
  j["bodies"][0]["orientation"] = {1.0000011, 0, 0, 0};
  const std::string msg = input_error_of([&] { parse_scene(j.dump(), kCaseFile); });
  EXPECT_NE(msg.find("with norm 1.0000011"), std::string::npos) << msg;
}

TEST(SceneLoad, ErrorMessagesStayOnOneLine) {
  // Control characters in keys, values and the file name never break the line.
  const std::string text = "{\"na\\nme\": \"x\"}";
  std::string msg = input_error_of([&] { parse_scene(text, "dir\nname.json"); });
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(msg.find("dir name.json: /na\\nme: expected one of the keys"), std::string::npos) << msg;
  msg = input_error_of([&] { parse_scene("{\"name\": \"a\nb\"}", "x.json"); });  // raw newline in a string
  EXPECT_EQ(msg.find('\n'), std::string::npos) << msg;
  EXPECT_NE(msg.find("x.json: line 1, column 12: malformed JSON"), std::string::npos) << msg;
  msg = input_error_of([&] { parse_scene("{\"name\": \"x\xff\"}", "bad\xfe.json"); });  // not UTF-8
  EXPECT_EQ(msg.rfind("bad?.json: line 1, column 12: malformed JSON", 0), 0u) << msg;
  EXPECT_EQ(msg.find('\xff'), std::string::npos) << msg;
}

TEST(SceneLoad, DeeplyNestedInputDoesNotCrash) {
  const std::string deep =
      R"({"name": "d", "duration": 1, "output": {"every": 1}, "solver": {"method": "rk4"},
      "particles": )" +
      std::string(100000, '[') + std::string(100000, ']') + "}";
  const std::string msg = input_error_of([&] { parse_scene(deep, "deep.json"); });
  EXPECT_EQ(msg, "deep.json: /particles/0: expected an object, got an array of 1 element");
}

// A scene's name names its report folder and baseline file, so a name that is
// a path ("../x" would make compare write outside --out) or carries a
// control character is refused with one line naming the key; ordinary names
// with spaces, dots and brackets load.
TEST(SceneLoad, NamesThatArePathsAreRefused) {
  const auto with_name = [](const std::string& name) {
    json j = {{"name", name}, {"duration", 1.0}, {"output", {{"every", 0.5}}}, {"solver", {{"method", "rk4"}}},
              {"particles", json::array({{{"name", "p"}, {"mass", 1.0}, {"position", {0, 0, 0}}}})}};
    return j.dump();
  };
  const std::vector<std::string> bad_names = {"../escape", "a/b", "a\\b", ".", "..", "line\nbreak", "bell\x07"};
  for (const std::string& bad : bad_names) {
    const std::string what = input_error_of([&] { parse_scene(with_name(bad), "s.json"); });
    EXPECT_NE(what.find("s.json: /name:"), std::string::npos) << what;
    EXPECT_NE(what.find("it names files"), std::string::npos) << what;
  }
  for (const std::string good : {"drop test 2", "v1.2", "net[3][4]", "x`y`"})
    EXPECT_EQ(parse_scene(with_name(good), "s.json").name, good);
}

// Every output sample is kept: a scene asking for more than kMaxSamples of
// them (every 1e-300, or duration 1e308, would overflow the count, and every
// 1e-9 over 10 s run out of memory) is refused naming output.every.
TEST(SceneLoad, TooManySamplesAreRefused) {
  const auto scene = [](const std::string& duration, const std::string& every) {
    return R"({"name": "s", "duration": )" + duration + R"(, "output": {"every": )" + every +
           R"(}, "solver": {"method": "rk4"}, "particles": [{"name": "p", "mass": 1, "position": [0, 0, 0]}]})";
  };
  for (const auto& [d, e] : std::vector<std::pair<std::string, std::string>>{
           {"1", "1e-300"}, {"1e308", "1"}, {"10", "1e-9"}}) {
    const std::string what = input_error_of([&] { parse_scene(scene(d, e), "s.json"); });
    EXPECT_NE(what.find("s.json: /output/every:"), std::string::npos) << what;
    EXPECT_NE(what.find("samples"), std::string::npos) << what;
  }
  EXPECT_NO_THROW(parse_scene(scene("10", "1e-5"), "s.json"));  // exactly 1e6 samples
}

}  // namespace
}  // namespace gacompare::core
