// Hostile input and faults, end to end through the gacompare
// binary: every case of the issue with its exit code and its one line, inside
// a time limit (the TIMEOUT of the `reliability` label), with no command run
// (a marker a name would touch stays absent) and no file outside --out (each
// run works in a fresh folder with its own TMPDIR, which is checked after).
#include "reliability_work.hpp"

#include "core/model/sha256.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <fstream>
#include <set>
#include <string>
#include <sys/wait.h>
#include <thread>
#include <unistd.h>
#include <vector>

namespace {

// ---- names are data --------------------------------------------------------------------

// Scene and body names with backquotes, $(...), quotes, path separators and a
// 300-byte name: the comparison runs (reports with gnuplot figures that title
// them), nothing is executed, every file is under --out, each scene's folder is
// the name's sanitised form, and results.json keeps the real names.
TEST(Reliability, NamesWithShellSyntaxAreData) {
  const Work w("names");
  json a = bundled("cube_drop_flat");
  a["name"] = "x`touch PWNED`y $(touch PWNED) \"q\" it's";
  a["duration"] = 0.2;
  a["bodies"][0]["name"] = "../slab`touch PWNED`";
  a["bodies"][1]["name"] = "/cube $(touch PWNED) 'q' \"qq\"";
  json b = bundled("projectile_linear_drag");
  b["name"] = std::string(300, 'n');
  const Result r = w.run("compare " + sh(w.scene("a.json", a).string()) + " " + sh(w.scene("b.json", b).string()) +
                         " --repeat 1 --quiet --out out");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_clean(w);
  std::vector<std::string> folders;
  for (const auto& e : fs::directory_iterator(w.out()))
    if (e.is_directory()) folders.push_back(e.path().filename().string());
  ASSERT_EQ(folders.size(), 2u);
  for (const auto& f : folders) {
    EXPECT_LE(f.size(), 89u) << f;  // 80 bytes and "-" and 8 hex digits
    EXPECT_EQ(f.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-"), std::string::npos) << f;
    const json j = read_json(w.out() / f / "results.json");
    const std::string name = j["scene"]["name"];
    EXPECT_TRUE(name == a["name"] || name == b["name"]) << name;
    if (name == a["name"]) {
      EXPECT_TRUE(j["runs"][0]["samples"][0]["bodies"].contains(a["bodies"][1]["name"]));
    }
    EXPECT_NE(slurp(w.out() / f / "report.html").find("<svg"), std::string::npos);
  }
  // sweep names its diagram after the scene: the sanitised name too.
  json c = bundled("projectile_linear_drag");
  c["name"] = "..up`touch PWNED`";
  const Result swept = w.run("sweep " + sh(w.scene("c.json", c).string()) +
                             " --out out/sweep --solvers rk4 --steps 1e-2:1 --repeat 1 --no-peer --quiet");
  ASSERT_EQ(swept.code, 0) << swept.err;
  EXPECT_TRUE(fs::exists(w.out() / "sweep" / ("_.up_touch_PWNED_-" + gacompare::core::sha256_hex(c["name"].get<std::string>()).substr(0, 8) +
                                              "_work_precision.svg")));
  expect_clean(w);
}

// A newline or a terminal control character in any name is refused at load.
TEST(Reliability, NamesWithControlCharactersAreRefused) {
  for (const std::string& bad : {std::string("two\nlines"), std::string("red\x1b[31m"), std::string("bell\x07")}) {
    json scene = bundled("cube_drop_flat");
    scene["name"] = bad;
    expect_refused("control_scene", scene, {"/name: expected a name without"});
    scene = bundled("cube_drop_flat");
    scene["bodies"][1]["name"] = bad;
    expect_refused("control_body", scene, {"/bodies/1/name: expected a non-empty name without"});
  }
}

// A scene name is never a path: "../x", "a/b", "..".
TEST(Reliability, SceneNamesThatArePathsAreRefused) {
  for (const std::string bad : {"../escape", "a/b", "..", "/etc/x"}) {
    json scene = bundled("projectile_linear_drag");
    scene["name"] = bad;
    expect_refused("path_name", scene, {"/name: expected a name without '/'", "it names files"});
  }
}

// ---- budgets decided before work ------------------------------------------------------

TEST(Reliability, AbsurdSampleCountsAreRefused) {
  for (const auto& [duration, every] : std::vector<std::pair<double, double>>{{1e308, 1}, {1, 1e-300}, {100, 1e-12}, {10, 1e-9}}) {
    json scene = bundled("projectile_linear_drag");
    scene["duration"] = duration;
    scene["output"]["every"] = every;
    expect_refused("samples", scene, {"/output/every: expected an interval giving at most 1e+06 samples", "--max-samples"});
  }
}

// A million samples are allowed, but not of a hundred bodies: their memory.
TEST(Reliability, SampleMemoryIsBudgeted) {
  json scene = bundled("spinning_top");
  scene["duration"] = 1000;
  scene["output"]["every"] = 0.001;
  json body = scene["bodies"][0];
  scene["bodies"] = json::array();
  for (int i = 0; i < 100; ++i) {
    body["name"] = "top" + std::to_string(i);
    body["position"] = {i, 0, 0};
    scene["bodies"].push_back(body);
  }
  expect_refused("memory", scene, {"/output/every: expected an interval whose samples fit in 4096 MB", "--max-memory", "100 body"});
}

TEST(Reliability, TinyStepsAreRefusedWithTheirCount) {
  json scene = bundled("cube_drop_flat");
  scene["effects"][1]["step"] = 1e-300;
  expect_refused("collision_step", scene, {"/effects/1/step: expected a collision step giving at most 1e+08 steps", "2.5e+300 steps"});
  scene = bundled("cube_drop_flat");
  scene["solver"]["dt"] = 1e-300;  // used to run zero steps: the count overflowed and the cube never moved
  expect_refused("fixed_step", scene, {"/solver/dt: expected a step giving at most 1e+08 steps", "2.5e+300 steps"});
}

// --max-samples, --max-steps and --max-memory raise the budgets (list loads
// the scenes of a folder and runs nothing).
TEST(Reliability, FlagsRaiseTheBudgets) {
  const Work w("flags");
  json scene = bundled("projectile_linear_drag");
  scene["output"]["every"] = 1e-6;  // 2e6 samples of 3 particles, 9.6 GB
  scene["solver"] = {{"method", "rk4"}, {"dt", 1e-8}};  // 2e8 steps
  w.scene("s.json", scene);
  expect_one_line(w.run("list --scenes in"), 2, {"/output/every", "--max-samples"});
  expect_one_line(w.run("--max-samples 3e6 list --scenes in"), 2, {"/output/every", "4096 MB", "--max-memory"});
  expect_one_line(w.run("--max-samples 3e6 --max-memory 1e4 list --scenes in"), 2, {"/solver/dt", "2e+08 steps", "--max-steps"});
  const Result ok = w.run("--max-samples 3e6 --max-memory 1e4 --max-steps 3e8 list --scenes in");
  EXPECT_EQ(ok.code, 0) << ok.err;
  EXPECT_NE(ok.out.find("projectile_linear_drag"), std::string::npos) << ok.out;
  expect_clean(w);
}

// Speeds, accelerations, sizes and masses no physics means are refused at
// load with their path (they used to hang the run, or make every step NaN).
TEST(Reliability, AbsurdMagnitudesAreRefusedAtLoad) {
  const auto with = [](const std::string& pointer, const json& value) {
    json scene = bundled("cube_drop_flat");
    scene[json::json_pointer(pointer)] = value;
    return scene;
  };
  expect_refused("velocity", with("/bodies/1/velocity", {0, 0, 1e308}), {"/bodies/1/velocity:", "faster than light"});
  expect_refused("spin", with("/bodies/1/angular_velocity", {0, 1e308, 0}), {"/bodies/1/angular_velocity:", "rim"});
  expect_refused("gravity", with("/effects/0/g", {0, 0, -1e308}), {"/effects/0/g:", "faster than light"});
  expect_refused("size", with("/bodies/1/shape", {{"box", {1e300, 1, 1}}}), {"/bodies/1/shape/box/0:", "observable universe"});
  expect_refused("position", with("/bodies/1/position", {1e300, 0, 0}), {"/bodies/1/position:", "observable universe"});
  expect_refused("mass", with("/bodies/1/mass", 1e-300), {"/bodies/1/mass:", "electron"});
  json particle = bundled("projectile_linear_drag");
  particle["particles"][0]["velocity"] = {3e8, 0, 0};
  expect_refused("particle", particle, {"/particles/0/velocity:", "faster than light"});
}

// ---- hulls in bounded time ---------------------------------------------------------------

json hull_scene(const std::vector<std::array<double, 3>>& points, bool collisions) {
  json scene = bundled("cube_drop_flat");
  scene["duration"] = 0.05;
  scene["bodies"][1]["shape"] = {{"hull", points}};
  if (!collisions) {
    scene["effects"].erase(1);
    scene["bodies"].erase(0);
  }
  return scene;
}

// Points 1e-9 and 1e-12 from a plane used to be accepted and then never
// finish: with collisions such a body is refused (it is thinner than the
// penetration tolerance, so a contact could pass through it); without, it is
// built, thin, and runs.
TEST(Reliability, NearlyFlatHullsAreRefusedOrBuiltThin) {
  for (double thickness : {1e-9, 1e-12}) {
    std::vector<std::array<double, 3>> points;
    for (int i = 0; i < 50; ++i)  // a 0.2 m square, alternately above and below its plane
      points.push_back({0.2 * ((i * 37) % 50) / 50.0 - 0.1, 0.2 * ((i * 11) % 50) / 50.0 - 0.1, i % 2 ? thickness : -thickness});
    expect_refused("flat", hull_scene(points, true), {"/bodies/1/shape: expected a body thicker than the collisions' penetration tolerance"});
    const Work w("flat_free");
    const Result r = w.run("run " + sh(w.scene("s.json", hull_scene(points, false)).string()) + " --backend cga --quiet --out out");
    EXPECT_EQ(r.code, 0) << r.err;
    expect_clean(w);
  }
}

// A hull of 100,000 points on a sphere: loaded,
// built and run within the test's time limit; bench/hull_bench times it.
TEST(Reliability, LargeHullsLoadAndRun) {
  std::vector<std::array<double, 3>> points;
  const double turn = 3.141592653589793 * (3 - std::sqrt(5.0));
  for (int i = 0; i < 100000; ++i) {
    const double z = 1 - 2 * (i + 0.5) / 100000, r = std::sqrt(1 - z * z);
    points.push_back({0.1 * r * std::cos(turn * i), 0.1 * r * std::sin(turn * i), 0.1 * z});
  }
  const Work w("large_hull");
  const Result r = w.run("run " + sh(w.scene("s.json", hull_scene(points, true)).string()) + " --backend traditional --quiet --out out");
  EXPECT_EQ(r.code, 0) << r.err;
  expect_clean(w);
}

// ---- silent wrong answers ------------------------------------------------------------------

// The flat drop 1e7 m from the origin (the cga broadphase used to lose the
// pair and the cube fell through): the cube comes to rest on the slab in both
// backends, where it rests at the origin, to 1e-13 D (the rounding of
// coordinates of size D over a few thousand updates; see
// docs/algebra.md, "Precision far from the origin").
TEST(Reliability, FarFromTheOriginTheCubeStillLands) {
  const double d = 1e7;
  for (const std::string backend : {"traditional", "cga"}) {
    json near = bundled("cube_drop_flat"), far = near;
    for (auto& b : far["bodies"])
      for (int k = 0; k < 3; ++k) b["position"][k] = b["position"][k].get<double>() + d;
    const Work w("far_" + backend);
    ASSERT_EQ(w.run("run " + sh(w.scene("near.json", near).string()) + " --backend " + backend + " --quiet --out out/near").code, 0);
    const Result r = w.run("run " + sh(w.scene("far.json", far).string()) + " --backend " + backend + " --quiet --out out/far");
    ASSERT_EQ(r.code, 0) << r.err;
    const auto final_position = [&](const char* which) {
      const json j = read_json(w.out() / which / "results.json");
      const json& p = j["runs"][0]["samples"].back()["bodies"]["cube"]["position"];
      return std::array<double, 3>{p[0], p[1], p[2]};
    };
    const auto a = final_position("near"), b = final_position("far");
    for (int k = 0; k < 3; ++k) EXPECT_NEAR(b[k] - d, a[k], 1e-13 * d) << backend << " axis " << k;
    EXPECT_NEAR(a[2], 0.1, 2e-4) << backend;  // resting on the slab's top (z = 0), half its 0.2 m up, within tolerance
  }
}

// ---- every loop makes progress or stops -------------------------------------------------

// An adaptive run that would take more steps than --max-steps stops with exit
// 1 naming the stage, the time and the body, and keeps what it had.
TEST(Reliability, AnAdaptiveRunStopsWhenItsStepBudgetIsSpent) {
  const Work w("budget");
  const Result r = w.run("--max-steps 100 run " + sh((kScenes / "spinning_top.json").string()) +
                         " --backend cga --quiet --out out");
  expect_one_line(r, 1, {"integrate: the budget of 100 steps is spent (--max-steps raises it), at t=",
                         "body 'top' has the largest error estimate"});
  const json j = read_json(w.out() / "results.json");
  EXPECT_TRUE(j["runs"][0].contains("error"));
  EXPECT_GT(j["runs"][0]["samples"].size(), 1u);  // the samples before it are kept
  EXPECT_LT(j["runs"][0]["samples"].size(), 501u);
  expect_clean(w);
}

// ---- the smaller findings ---------------------------------------------------------------------

// 1e5 nested objects took 386 s (the duplicate-key check rebuilt the JSON path
// at every key); now the path is only built for a message.
TEST(Reliability, DeeplyNestedObjectsAreRefusedQuickly) {
  const Work w("nested");
  const fs::path file = w.root / "in" / "deep.json";
  {
    std::ofstream deep(file);
    for (int i = 0; i < 100000; ++i) deep << "{\"a\":";
    deep << "1" << std::string(100000, '}');
  }
  expect_one_line(w.run("run " + sh(file.string()) + " --backend traditional --quiet --out out"), 2, {file.string() + ": /a: expected one of the keys"});
  expect_clean(w);
}

// A vertex coordinate that is not a number used to become 0.
TEST(Reliability, ObjCoordinatesMustBeNumbers) {
  const Work w("obj");
  std::ofstream(w.root / "in" / "bad.obj") << slurp(kMeshes / "cube.obj").replace(slurp(kMeshes / "cube.obj").find("v 1 1 1"), 7, "v 1 one 1");
  json scene = bundled("spinning_top");
  scene["bodies"][0]["shape"] = {{"mesh", "bad.obj"}};
  const fs::path file = w.scene("s.json", scene);
  expect_one_line(w.run("run " + sh(file.string()) + " --backend traditional --quiet --out out"), 2,
                  {file.string() + ": /bodies/0/shape/mesh: ", "bad.obj: line 9: expected a finite number as a vertex coordinate, got 'one'"});
  expect_clean(w);
}

// Mesh, shape and overlap errors name the scene file and the JSON path.
TEST(Reliability, MeshShapeAndOverlapErrorsNameFileAndPath) {
  const Work w("mesh_errors");
  fs::copy_file(kMeshes / "open_cube.obj", w.root / "in" / "open.obj");
  fs::copy_file(kMeshes / "l_shape.obj", w.root / "in" / "l.obj");
  json open = bundled("spinning_top");
  open["bodies"][0]["shape"] = {{"mesh", "open.obj"}};
  fs::path file = w.scene("open.json", open);
  expect_one_line(w.run("run " + sh(file.string()) + " --backend traditional --quiet --out out"), 2, {file.string() + ": /bodies/0/shape/mesh: ", "open.obj: not closed"});
  json concave = bundled("cube_drop_flat");
  concave["bodies"][1]["shape"] = {{"mesh", "l.obj"}};
  file = w.scene("concave.json", concave);
  expect_one_line(w.run("run " + sh(file.string()) + " --backend traditional --quiet --out out"), 2, {file.string() + ": /bodies/1/shape: expected a convex body", "not convex"});
  json overlap = bundled("cube_drop_flat");
  overlap["bodies"][1]["position"] = {0, 0, 0.05};
  file = w.scene("overlap.json", overlap);
  expect_one_line(w.run("run " + sh(file.string()) + " --backend cga --quiet --out out"), 2,
                  {file.string() + ": /bodies/0: bodies 'slab' and 'cube' overlap at t = 0"});
  EXPECT_FALSE(fs::exists(w.out()));
  expect_clean(w);
}

// A bad --out is refused before anything runs (it was found after the whole
// simulation, exit 1): here the run would have failed, and exit 2 says the
// folder is what was wrong.
TEST(Reliability, ABadOutIsRefusedBeforeAnyWork) {
  const Work w("bad_out");
  std::ofstream(w.root / "in" / "file") << "x";
  const Result r = w.run("--max-steps 10 run " + sh((kScenes / "spinning_top.json").string()) + " --backend traditional --quiet --out in/file/out");
  expect_one_line(r, 2, {"in/file/out: cannot create the output folder"});
  expect_clean(w);
}

// A write that fails (here: the file-size limit, as a full disk would) says
// why in one line, exit 1, and leaves no temporary behind.
TEST(Reliability, AFailedWriteSaysWhyAndLeavesNoTemporary) {
  const Work w("full");
  const Result r = w.run("run " + sh((kScenes / "projectile_linear_drag.json").string()) + " --backend traditional --quiet --out out",
                         "trap '' XFSZ; ulimit -f 8; ");
  // Written into the folder's staging sibling (compare/files.hpp, StagedFolder), which goes with it.
  expect_one_line(r, 1, {"/.out.staging-", "/results.json: cannot write: File too large"});
  EXPECT_FALSE(fs::exists(w.out()));
  for (const auto& e : fs::recursive_directory_iterator(w.root)) EXPECT_NE(e.path().extension(), ".tmp") << e.path();
  expect_clean(w);
}

// ---- concurrent and interrupted runs -----------------------------------------------------------

pid_t start(const Work& w, const std::string& args) {
  const std::string cmd = w.command(args);
  const pid_t pid = ::fork();
  if (pid == 0) {
    ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
    ::_exit(127);
  }
  return pid;
}

int wait_for(pid_t pid) {
  int status = 0;
  ::waitpid(pid, &status, 0);
  return WIFEXITED(status) ? WEXITSTATUS(status) : -WTERMSIG(status);
}

// Two compares given the same --out: the second, started while the first
// holds the folder, is refused with one line; the first's files are all its
// own (its scene in results.json and in report.md).
TEST(Reliability, ASecondRunOnTheSameFolderIsRefused) {
  const Work first("same_first"), second("same_second");
  const fs::path out = first.root / "shared";
  const pid_t pid = start(first, "compare " + sh((kScenes / "cube_drop_flat.json").string()) + " --repeat 3 --quiet --out " + sh(out.string()));
  while (!fs::exists(out)) std::this_thread::sleep_for(std::chrono::milliseconds(5));
  std::this_thread::sleep_for(std::chrono::milliseconds(300));  // from mkdir to flock is microseconds
  const Result r = second.run("compare " + sh((kScenes / "projectile_linear_drag.json").string()) + " --repeat 1 --quiet --out " + sh(out.string()));
  ASSERT_EQ(::waitpid(pid, nullptr, WNOHANG), 0) << "the first run ended before the second started: the test proves nothing";
  expect_one_line(r, 2, {out.string() + ": another gacompare is writing this folder"});
  ASSERT_EQ(wait_for(pid), 0);
  EXPECT_EQ(read_json(out / "results.json")["scene"]["name"], "cube_drop_flat");
  EXPECT_EQ(slurp(out / "report.md").rfind("# cube_drop_flat", 0), 0u);
  expect_clean(second);
}

// Runs started in the same second without --out get folders of their own
// (reports/<scene>-<date> has one-second resolution: without a claim they would overwrite each other).
TEST(Reliability, DefaultFoldersAreUnique) {
  const Work w("default_folders");
  std::vector<pid_t> pids;
  for (int i = 0; i < 3; ++i)
    pids.push_back(start(w, "run " + sh((kScenes / "projectile_linear_drag.json").string()) + " --backend traditional --quiet"));
  for (pid_t p : pids) EXPECT_EQ(wait_for(p), 0);
  std::set<std::string> folders;
  for (const auto& e : fs::directory_iterator(w.root / "reports")) {
    folders.insert(e.path().filename().string());
    EXPECT_TRUE(fs::exists(e.path() / "results.json")) << e.path();
  }
  EXPECT_EQ(folders.size(), 3u);
}

// Every file a killed run left is whole: JSON parses, reports and figures end
// as they should, nothing is in TMPDIR, and the same command run again works.
void expect_whole(const fs::path& dir) {
  if (!fs::exists(dir)) return;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    if (!e.is_regular_file()) continue;
    const std::string text = slurp(e.path()), ext = e.path().extension().string();
    EXPECT_FALSE(text.empty()) << e.path();
    if (ext == ".json") {
      EXPECT_TRUE(json::accept(text)) << e.path();
    } else if (ext == ".html") {
      EXPECT_NE(text.rfind("</html>"), std::string::npos) << e.path();
    } else if (ext == ".svg") {
      EXPECT_NE(text.rfind("</svg>"), std::string::npos) << e.path();
    } else if (!text.empty()) {  // .md, .csv
      EXPECT_EQ(text.back(), '\n') << e.path();
    }
  }
}

TEST(Reliability, KilledRunsLeaveNoHalfFileAndRerunsWork) {
  const std::string drop = sh((kScenes / "cube_drop_flat.json").string()), shot = sh((kScenes / "projectile_linear_drag.json").string());
  const std::vector<std::pair<std::string, std::string>> commands = {
      {"run", "run " + drop + " --backend cga --quiet --out out"},
      {"compare", "compare " + drop + " " + shot + " --repeat 1 --quiet --out out"},
      {"check", "check " + shot + " --baseline out --update --quiet"},
      {"sweep", "sweep " + shot + " --out out --solvers rk4,cash_karp45 --tolerances 1e-3:1e-5 --steps 1e-2:2 --repeat 1 --no-peer --quiet"},
      {"corpus", "corpus --seed 1 --count 2000 --out out/corpus.json"},
      {"collide", "collide " + sh((fs::path(GACOMPARE_DATA_DIR) / "collision" / "hand.json").string()) +
                      " --repeat 3 --out out/collide.json --table out/table.md"},
  };
  for (const auto& [name, args] : commands)
    for (int delay_ms : {30, 150, 400}) {
      const Work w("killed_" + name);
      const pid_t pid = start(w, args);
      std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
      ::kill(pid, SIGKILL);
      wait_for(pid);
      SCOPED_TRACE(name + " killed after " + std::to_string(delay_ms) + " ms");
      expect_whole(w.out());
      EXPECT_TRUE(fs::is_empty(w.root / "tmp")) << "a plot folder was left in TMPDIR";
      const Result again = w.run(args);
      EXPECT_EQ(again.code, 0) << again.err;
      expect_whole(w.out());
      for (const auto& e : fs::recursive_directory_iterator(w.out()))
        EXPECT_NE(e.path().extension(), ".tmp") << "the rerun left " << e.path();
      expect_clean(w);
    }
}

}  // namespace
