// The gacompare command line end to end: the files it writes, their fields, and
// its exit codes (0 success, 1 a run failed, 2 bad usage or input).
#include "cli_run.hpp"
#include "csv_fields.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <sys/wait.h>
#include <vector>

namespace {
namespace fs = std::filesystem;
using nlohmann::json;


std::string read_text(const fs::path& p) {
  std::ifstream in(p);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}


TEST(Cli, CompareWritesResultsAndReportForEveryBackend) {
  const fs::path out = fresh_dir("compare");
  const Result r = gacompare("compare " + kScene + " --repeat 3 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_EQ(r.out, out.string() + "\n");  // the report folder's path, alone on stdout
  const json j = read_json(out / "results.json");
  EXPECT_EQ(j["tool"]["name"], "gacompare");
  EXPECT_FALSE(j["tool"]["version"].get<std::string>().empty());
  EXPECT_EQ(j["scene"]["name"], "projectile_linear_drag");
  EXPECT_EQ(j["scene"]["sha256"].get<std::string>().size(), 64u);
  for (const char* k : {"cpu", "compiler", "date", "flags", "build_type", "allocator"})
    EXPECT_FALSE(j["machine"][k].get<std::string>().empty()) << k;
  // The allocator the binary runs on, as its build linked it (CMakeLists.txt).
  EXPECT_TRUE(j["machine"]["allocator"].get<std::string>().starts_with(std::string(GACOMPARE_ALLOCATOR_NAME) + " ("))
      << j["machine"]["allocator"];
  EXPECT_GE(j["machine"]["logical_cpus"].get<int>(), 1);
  EXPECT_GE(j["machine"]["usable_cpus"].get<int>(), 1);
  EXPECT_LE(j["machine"]["usable_cpus"].get<int>(), j["machine"]["logical_cpus"].get<int>());
  for (const char* when : {"start", "end"}) {
    ASSERT_EQ(j["machine"]["load_average"][when].size(), 3u) << when;
    EXPECT_GE(j["machine"]["load_average"][when][0].get<double>(), 0.0) << when;
  }
  EXPECT_NE(j["machine"]["flags"].get<std::string>().find("-O"), std::string::npos);  // a Release build
  // The commit this binary was built at: the test command builds before it
  // tests, so it is the checkout's HEAD (a stale binary after a commit fails
  // here until it is rebuilt). Dirty is a boolean in a git checkout.
  FILE* git = ::popen(("git -C " + std::string(GACOMPARE_SOURCE_DIR) + " rev-parse HEAD 2>/dev/null").c_str(), "r");
  char head[64] = {0};
  const bool have_git = git && std::fgets(head, sizeof head, git) != nullptr;
  if (git) ::pclose(git);
  if (have_git) {
    EXPECT_EQ(j["machine"]["git"]["commit"], std::string(head, 40));
    EXPECT_TRUE(j["machine"]["git"]["dirty"].is_boolean());
  } else {
    EXPECT_EQ(j["machine"]["git"]["commit"], "unknown");
  }
  ASSERT_EQ(j["runs"].size(), 3u);  // no Bullet: a particle scene
  EXPECT_EQ(j["runs"][0]["backend"], "traditional");
  EXPECT_EQ(j["runs"][1]["backend"], "cga");
  EXPECT_EQ(j["runs"][2]["backend"], "pga");
  for (const auto& run : j["runs"]) {
    const auto& s0 = run["samples"][0];
    EXPECT_EQ(s0["t"], 0.0);
    EXPECT_EQ(run["samples"].back()["t"], 2.0);
    EXPECT_EQ(s0["particles"]["shot"]["position"].size(), 3u);
    EXPECT_EQ(s0["particles"]["shot"]["velocity"], json::array({10.0, 0.0, 10.0}));
    EXPECT_TRUE(s0["energy"].contains("kinetic"));
    EXPECT_TRUE(s0["energy"].contains("potential"));
    EXPECT_EQ(s0["linear_momentum"].size(), 3u);
    EXPECT_EQ(s0["angular_momentum"].size(), 3u);
    EXPECT_TRUE(run["stages"].contains("integrate"));
    EXPECT_TRUE(run["stages"].contains("forces"));
    EXPECT_FALSE(run["stages"].contains("narrowphase"));  // a stage that did not run is absent
    EXPECT_GT(run["stages"]["integrate"]["calls"].get<int>(), 0);
    EXPECT_EQ(run["stages"]["integrate"]["seconds_each_repeat"].size(), 3u);
    EXPECT_GT(run["solver"]["steps_accepted"].get<int>(), 0);
    EXPECT_TRUE(run["solver"].contains("steps_rejected"));
    EXPECT_GT(run["solver"]["derivative_evaluations"].get<int>(), 0);
    EXPECT_TRUE(run["counters"].is_object());
  }
  // Each run's state hash is the one gacompare-state-hash prints for the same
  // scene and backend (a separate run in another process).
  FILE* tool = ::popen((std::string(GACOMPARE_STATE_HASH_BIN) + " " + kScene + " --backends traditional,cga,pga").c_str(), "r");
  ASSERT_NE(tool, nullptr);
  std::array<char, 256> line{};
  for (const auto& run : j["runs"]) {
    ASSERT_NE(std::fgets(line.data(), line.size(), tool), nullptr) << run["backend"];
    const std::string printed(line.data());
    EXPECT_EQ(run["state_hash"].get<std::string>().size(), 64u);
    EXPECT_EQ(printed.substr(0, 64), run["state_hash"].get<std::string>()) << run["backend"];
    EXPECT_NE(printed.find(run["backend"].get<std::string>()), std::string::npos) << printed;
  }
  EXPECT_EQ(::pclose(tool), 0);
  const std::string md = read_text(out / "report.md");
  EXPECT_NE(md.find("| `integrate` |"), std::string::npos) << md;
  EXPECT_NE(md.find("| `forces` |"), std::string::npos) << md;
  EXPECT_NE(md.find("cga / traditional"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(out / "stages.csv"));
  const std::string html = read_text(out / "report.html");  // rendered by report_render_test
  EXPECT_NE(html.find("<table>"), std::string::npos);
  EXPECT_NE(html.find("<svg"), std::string::npos);
  for (const auto& e : fs::directory_iterator(out))  // no temporary files left behind
    EXPECT_NE(e.path().filename().string().front(), '.') << e.path();
}

// The overview draws each rigid-body scene's work-precision diagram (a small
// sweep, its table beside the scene's report) and none of a scene of another
// category; --no-work-precision leaves them out.
TEST(Cli, TheOverviewDrawsTheRigidScenesWorkPrecision) {
  const fs::path out = fresh_dir("wp"), bare = fresh_dir("no_wp");
  const std::string data = std::string(GACOMPARE_DATA_DIR) + "/scenes/";
  const std::string scenes = data + "tumbling_box.json " + kScene;
  Result r = gacompare("compare " + scenes + " --repeat 1 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "tumbling_box" / "work_precision" / "sweep.md"));
  EXPECT_FALSE(fs::exists(out / "projectile_linear_drag" / "work_precision"));
  const std::string html = read_text(out / "report.html");
  EXPECT_NE(html.find("tumbling_box: what accuracy costs in time"), std::string::npos);
  EXPECT_LT(html.find("id=\"forest\""), html.find("<table"));  // the answer before the tables
  // report.md shows the same forest plot first, from the file beside it.
  EXPECT_TRUE(fs::exists(out / "forest.svg"));
  const std::string md = read_text(out / "report.md");
  EXPECT_LT(md.find("](forest.svg)"), md.find("**Verdict"));
  const std::string sweep = read_text(out / "tumbling_box" / "work_precision" / "sweep.md");
  for (const char* b : {"| traditional |", "| traditional-quaternion |", "| cga |", "| pga |"})
    EXPECT_NE(sweep.find(b), std::string::npos) << b;
  // Every method is in the table; the diagram draws each backend's best of
  // each family, and its key names the families, not the methods.
  for (const char* m : {"| cash_karp45 |", "| tsit5 |", "| vern8 |", "| rkmk45 |"})
    EXPECT_NE(sweep.find(m), std::string::npos) << m;
  const std::string svg = read_text(out / "tumbling_box" / "work_precision" / "tumbling_box_work_precision.svg");
  EXPECT_NE(svg.find("classical"), std::string::npos);
  EXPECT_NE(svg.find("PI pairs"), std::string::npos);
  EXPECT_NE(svg.find("Lie group"), std::string::npos);
  EXPECT_EQ(svg.find("vern8"), std::string::npos);
  r = gacompare("compare " + scenes + " --repeat 1 --quiet --no-work-precision --out " + bare.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_FALSE(fs::exists(bare / "tumbling_box" / "work_precision"));
  EXPECT_EQ(read_text(bare / "report.html").find("what accuracy costs in time"), std::string::npos);
}

TEST(Cli, SeveralScenesGetOneFolderEachAndASummary) {
  const fs::path out = fresh_dir("many");
  const std::string data = std::string(GACOMPARE_DATA_DIR) + "/scenes/";
  const Result r = gacompare("compare " + kScene + " " + data + "falling_quadratic_drag.json " + data +
                             "elastic_pair.json --repeat 5 --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(out / "projectile_linear_drag" / "results.json"));
  EXPECT_TRUE(fs::exists(out / "falling_quadratic_drag" / "report.md"));
  const std::string md = read_text(out / "report.md");
  EXPECT_NE(md.find("projectile_linear_drag"), std::string::npos);
  EXPECT_NE(md.find("falling_quadratic_drag"), std::string::npos);
  EXPECT_NE(md.find("## cga / traditional by category and stage"), std::string::npos) << md;
  EXPECT_NE(md.find("| collisions | **all stages** | 1 |"), std::string::npos) << md;
  EXPECT_NE(md.find("| particles (not evidence) | **all stages** | 2 |"), std::string::npos) << md;
  EXPECT_NE(md.find("**Verdict, from these numbers:**\n\n- collisions (1 scene): "), std::string::npos) << md;
  EXPECT_NE(read_text(out / "report.html").find("<h2>cga / traditional by category and stage</h2>"),
            std::string::npos);

  // summary.json: the same numbers, per category and stage, with intervals.
  const json j = read_json(out / "summary.json");
  EXPECT_EQ(j["repeats"], 5);
  EXPECT_EQ(j["method"]["resamples"].get<int>(), 20000);
  ASSERT_EQ(j["scenes"].size(), 3u);
  for (const auto& s : j["scenes"]) {
    EXPECT_EQ(s["ci95"].size(), 2u) << s;
    EXPECT_LE(s["ci95"][0].get<double>(), s["ratio"].get<double>()) << s;
    EXPECT_GE(s["ci95"][1].get<double>(), s["ratio"].get<double>()) << s;
  }
  EXPECT_EQ(j["scenes"][0]["category"], "particles");
  EXPECT_EQ(j["scenes"][0]["trajectories"], "identical");  // the same code in both backends
  EXPECT_EQ(j["scenes"][2]["category"], "collisions");
  EXPECT_EQ(j["scenes"][2]["tolerance"].get<double>(), 1e-6);  // CheckSpec's default
  const json& particles = j["categories"]["particles"];
  EXPECT_FALSE(particles["evidence"].get<bool>());
  EXPECT_EQ(particles["scenes"].size(), 2u);
  EXPECT_TRUE(particles["stages"].contains("forces"));
  const json& collisions = j["categories"]["collisions"];
  EXPECT_TRUE(collisions["evidence"].get<bool>());
  EXPECT_TRUE(collisions["stages"].contains("narrowphase"));
  EXPECT_EQ(collisions["overall"]["ci95"].size(), 2u);
  const std::string verdict = collisions["overall"]["verdict"];
  EXPECT_TRUE(verdict == "within noise" || verdict == "cga faster" || verdict == "cga slower") << verdict;
}

TEST(Cli, RunUsesOneBackend) {
  const fs::path out = fresh_dir("run");
  const Result r = gacompare("run " + kScene + " --backend cga --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = read_json(out / "results.json");
  ASSERT_EQ(j["runs"].size(), 1u);
  EXPECT_EQ(j["runs"][0]["backend"], "cga");
}

TEST(Cli, BadSceneIsOneLineAndExitTwo) {
  const fs::path bad = fresh_dir("bad") / "broken.json";
  write_text(bad, R"({"name": "x", "duration": -1, "output": {"every": 0.1}, "solver": {"method": "rk4"}})");
  const Result r = gacompare("compare " + bad.string() + " --out " + fresh_dir("bad_out").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("broken.json: /duration:"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(fresh_dir("bad_out")));
}

TEST(Cli, BadUsageExitsTwo) {
  EXPECT_EQ(gacompare("compare").code, 2);
  EXPECT_EQ(gacompare("frobnicate").code, 2);
  EXPECT_EQ(gacompare("run " + kScene + " --backend quaternions").code, 2);
  EXPECT_EQ(gacompare("compare /no/such/scene.json").code, 2);
  EXPECT_EQ(gacompare("compare " + kScene + " --repeat 0").code, 2);
}

// Every refusal is one line naming what was wrong and what would be right.
TEST(Cli, MistakesGetOneLineSayingWhatWasMeant) {
  auto one_line = [](const Result& r, const std::string& says) {
    EXPECT_EQ(r.code, 2) << r.err;
    EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
    EXPECT_NE(r.err.find(says), std::string::npos) << r.err;
  };
  one_line(gacompare("comapre " + kScene), "'comapre' is not a command (run, compare, check, sweep, merge, diff, list, "
                                           "collide or corpus); did you mean 'compare'?");
  one_line(gacompare("--quiet frobnicate"), "'frobnicate' is not a command");
  one_line(gacompare("run " + kScene + " --backend cgaa"), "--backend: 'cgaa' is not a backend (traditional, "
                                                           "traditional-matrix, traditional-quaternion, cga, pga or "
                                                           "bullet); did you mean 'cga'?");
  one_line(gacompare("run " + kScene), "--backend is required");
  one_line(gacompare("compare " + kScene + " --repeat 0"), "--repeat: expected a whole number from 1 to 200, got 0");
  one_line(gacompare("compare " + kScene + " --repeat 99999999999999"), "got 99999999999999, above 200");
  one_line(gacompare("compare " + kScene + " --repeat x"), "--repeat: expected a whole number from 1 to 200, got 'x'");
  one_line(gacompare("compare " + kScene + " --accuracy -1"), "--accuracy: expected a number > 0, got '-1'");
  one_line(gacompare("sweep " + kScene + " --repeats 3 --out x"), "--repeats is spelt --repeat in every command now");
  one_line(gacompare("compare --backends cga traditional " + kScene), "'traditional' is a backend, not a scene file");
}

// A list option takes one value per use (comma-separated), so it cannot
// swallow the scenes after it; --help shows every default.
TEST(Cli, OptionsBeforeTheScenesLeaveThemAloneAndHelpShowsDefaults) {
  const fs::path out = fresh_dir("backends_first");
  const Result r = gacompare("compare --backends cga,traditional --repeat 1 " + kScene + " --quiet --out " + out.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json j = read_json(out / "results.json");
  ASSERT_EQ(j["runs"].size(), 2u);
  EXPECT_EQ(j["runs"][0]["backend"], "cga");
  const Result help = gacompare("compare --help");
  EXPECT_NE(help.out.find("--repeat INT=5"), std::string::npos) << help.out;
  EXPECT_NE(help.out.find("--backends TEXT=[traditional,cga,pga,bullet]"), std::string::npos) << help.out;
  EXPECT_NE(gacompare("sweep --help").out.find("--repeat INT=3"), std::string::npos);
}

// Progress: one line per scene and repeat on stderr even when it is a file (as
// here), none with --quiet; stdout holds the report folder alone either way.
TEST(Cli, ProgressOnStderrUnlessQuiet) {
  const std::string data = std::string(GACOMPARE_DATA_DIR) + "/scenes/";
  const std::string cmd = "compare " + kScene + " " + data + "falling_quadratic_drag.json --repeat 2 --out ";
  const fs::path loud_out = fresh_dir("loud");
  const Result loud = gacompare(cmd + loud_out.string());
  ASSERT_EQ(loud.code, 0) << loud.err;
  EXPECT_EQ(std::count(loud.err.begin(), loud.err.end(), '\n'), 4) << loud.err;  // 2 scenes x 2 repeats
  EXPECT_NE(loud.err.find("gacompare: [2/2] falling_quadratic_drag: repeat 2/2, traditional "), std::string::npos)
      << loud.err;
  EXPECT_EQ(loud.out, loud_out.string() + "\n");
  const Result quiet = gacompare(cmd + fresh_dir("quiet").string() + " --quiet");
  ASSERT_EQ(quiet.code, 0) << quiet.err;
  EXPECT_EQ(quiet.err, "");
}

TEST(Cli, FailedRunExitsOneAndKeepsItsResults) {
  const fs::path dir = fresh_dir("nan");
  write_text(dir / "nan.json", R"({"name": "nan", "duration": 1.0, "output": {"every": 0.5},
    "solver": {"method": "rk4", "dt": 0.01},
    "effects": [{"type": "attraction_to_point", "point": [0, 0, 0], "D": 1.0}],
    "particles": [{"name": "doomed", "mass": 1.0, "position": [0, 0, 0]}]})");
  const Result r = gacompare("compare " + (dir / "nan.json").string() + " --repeat 1 --quiet --out " + (dir / "out").string());
  EXPECT_EQ(r.code, 1);
  EXPECT_NE(r.err.find("particle 'doomed'"), std::string::npos) << r.err;
  const json j = read_json(dir / "out" / "results.json");
  EXPECT_NE(j["runs"][0]["error"].get<std::string>().find("doomed"), std::string::npos);
  EXPECT_EQ(j["runs"][0]["samples"].size(), 1u);
}

TEST(Cli, CheckPassesOnAFreshBaselineAndFailsOnADoctoredOne) {
  const fs::path dir = fresh_dir("check");
  const Result update = gacompare("check " + kScene + " --baseline " + dir.string() + " --update --quiet");
  ASSERT_EQ(update.code, 0) << update.err << update.out;
  const fs::path file = dir / "projectile_linear_drag.json";
  ASSERT_TRUE(fs::exists(file));
  const Result fresh = gacompare("check " + kScene + " --baseline " + dir.string() + " --quiet");
  EXPECT_EQ(fresh.code, 0) << fresh.out;
  EXPECT_NE(fresh.out.find(" passed, 0 failed"), std::string::npos) << fresh.out;
  EXPECT_NE(fresh.out.find("time / baseline time"), std::string::npos) << fresh.out;  // reported, not checked

  // Move one particle's stored final position by 1 µm: beyond the 1e-9 m tolerance.
  json j = read_json(file);
  auto& shot = j["runs"][1]["final"]["particles"]["shot"];
  shot["position"][0] = shot["position"][0].get<double>() + 1e-6;
  write_text(file, j.dump());
  const Result doctored = gacompare("check " + kScene + " --baseline " + dir.string() + " --quiet");
  EXPECT_EQ(doctored.code, 1) << doctored.out;
  EXPECT_NE(doctored.out.find("| cga | distance from baseline, final state (m) | 1e-06 | 1e-09 | **FAIL**"),
            std::string::npos)
      << doctored.out;

  // A doctored scene hash says the scene changed, not that physics did.
  j = read_json(file);
  j["sha256"] = "0";
  write_text(file, j.dump());
  const Result changed = gacompare("check " + kScene + " --baseline " + dir.string() + " --quiet");
  EXPECT_EQ(changed.code, 1);
  EXPECT_NE(changed.out.find("scene file changed"), std::string::npos) << changed.out;
}

TEST(Cli, CheckWithoutOrWithABrokenBaselineExitsTwo) {
  const fs::path dir = fresh_dir("check_missing");
  const Result none = gacompare("check " + kScene + " --baseline " + dir.string());
  EXPECT_EQ(none.code, 2);
  EXPECT_NE(none.err.find("--update"), std::string::npos) << none.err;
  write_text(dir / "projectile_linear_drag.json", "{ not json");
  const Result broken = gacompare("check " + kScene + " --baseline " + dir.string());
  EXPECT_EQ(broken.code, 2);
  EXPECT_NE(broken.err.find("projectile_linear_drag.json: malformed JSON: parse error at line 1"), std::string::npos) << broken.err;
}

// check --max-time-ratio: a run against its own fresh baseline passes; a
// baseline doctored to have run 100 times faster fails; one stored without its
// repeats' times cannot be held to a ratio and says so.
TEST(Cli, CheckMaxTimeRatioFailsOnASlowerRun) {
  const fs::path dir = fresh_dir("check_time");
  ASSERT_EQ(gacompare("check " + kScene + " --baseline " + dir.string() + " --update --repeat 3 --quiet").code, 0);
  const std::string check = "check " + kScene + " --baseline " + dir.string() + " --repeat 3 --quiet --max-time-ratio ";
  const Result same = gacompare(check + "5");
  EXPECT_EQ(same.code, 0) << same.out;
  EXPECT_NE(same.out.find("| time / baseline time |"), std::string::npos) << same.out;
  const fs::path file = dir / "projectile_linear_drag.json";
  json j = read_json(file);
  for (auto& run : j["runs"])
    for (auto& t : run["wall_seconds_each_repeat"]) t = t.get<double>() / 100;
  write_text(file, j.dump());
  const Result slower = gacompare(check + "5");
  EXPECT_EQ(slower.code, 1) << slower.out;
  EXPECT_NE(slower.out.find("the whole interval lies above 5"), std::string::npos) << slower.out;
  for (auto& run : j["runs"]) run.erase("wall_seconds_each_repeat");
  write_text(file, j.dump());
  const Result old = gacompare(check + "5");
  EXPECT_EQ(old.code, 1) << old.out;
  EXPECT_NE(old.out.find("this baseline stores no repeats' times"), std::string::npos) << old.out;
  EXPECT_EQ(gacompare("check " + kScene + " --baseline " + dir.string() + " --max-time-ratio 2").code, 2);  // 1 repeat
}

// The error columns of a sweep.md's table rows (all but the last four: time,
// steps, f evals, Pareto mark): deterministic, unlike the times.
std::string error_columns(const fs::path& md) {
  std::istringstream in(read_text(md));
  std::string line, out;
  while (std::getline(in, line)) {
    if (line.rfind("## Time at equal accuracy", 0) == 0) break;  // read off the timings: not reproducible
    if (line.rfind("| ", 0) != 0) continue;
    std::size_t bar = line.size();
    for (int k = 0; k < 5 && bar != std::string::npos; ++k) bar = line.rfind('|', bar - 1);
    out += line.substr(0, bar) + "\n";
  }
  return out;
}


TEST(Cli, ShardedSweepMergesIntoTheUnshardedOneAndResumes) {
  const std::string sweep = "sweep " + std::string(GACOMPARE_DATA_DIR) +
                            "/scenes/kepler.json --solvers cash_karp45,rk4 --tolerances 1e-4:1e-7 --steps 1e-2:1 "
                            "--repeat 1 --quiet --out ";
  const fs::path whole = fresh_dir("sweep_whole");
  const Result r = gacompare(sweep + whole.string());
  ASSERT_EQ(r.code, 0) << r.err;
  EXPECT_TRUE(fs::exists(whole / "sweep.csv"));
  EXPECT_TRUE(fs::exists(whole / "kepler_work_precision.svg"));
  EXPECT_NE(read_text(whole / "sweep.html").find("<svg"), std::string::npos);
  EXPECT_NE(r.err.find("ran 14 unit(s), skipped 0"), std::string::npos) << r.err;  // 4 + 2 + 4 + 4 odeint

  // Run again: every unit is done, nothing reruns.
  const Result again = gacompare(sweep + whole.string());
  EXPECT_NE(again.err.find("ran 0 unit(s), skipped 14"), std::string::npos) << again.err;

  std::string dirs;
  for (int i = 0; i < 3; ++i) {
    const fs::path d = fresh_dir("sweep_shard" + std::to_string(i));
    ASSERT_EQ(gacompare(sweep + d.string() + " --shard " + std::to_string(i) + "/3").code, 0);
    EXPECT_FALSE(fs::exists(d / "sweep.md"));  // a shard alone is incomplete
    dirs += ' ';
    dirs += d.string();
  }
  const fs::path merged = fresh_dir("sweep_merged");
  const Result m = gacompare(std::string("merge") + dirs + " --out " + merged.string());
  ASSERT_EQ(m.code, 0) << m.err;
  EXPECT_EQ(error_columns(merged / "sweep.md"), error_columns(whole / "sweep.md"));

  const Result partial = gacompare(std::string("merge ") + fresh_dir("sweep_shard0").string() + " --out " + fresh_dir("x").string());
  EXPECT_EQ(partial.code, 2);  // sweep_shard0 was just emptied: not a sweep folder
}

TEST(Cli, SweepNamesTheSolversItKnows) {
  const Result r = gacompare("sweep " + std::string(GACOMPARE_DATA_DIR) + "/scenes/kepler.json --solvers rk5 --out " +
                             fresh_dir("sweep_unknown").string());
  EXPECT_EQ(r.code, 2);
  EXPECT_NE(r.err.find("--solvers: unknown solver 'rk5' (one of euler, rk4, rk4_doubling, cash_karp45, bs3, dopri5, "
                       "tsit5, vern6, vern7, vern8, vern9, symplectic_euler, velocity_verlet, rkmk4, rkmk45, "
                       "crouch_grossman4)"),
            std::string::npos)
      << r.err;
}

// A sweep of a rigid scene measures the four errors; its diagram is drawn on the
// orientation error by default (the centre of a spinning body never moves, and
// a position-only sweep read 0 in every cell) and on what --error names.
// With the Boost.Odeint peers, sweep.md sets every method against each peer
// on the traditional state at each error level a peer reaches: the peer
// against itself reads 1.00, and every row has a ratio for each peer.
TEST(Cli, SweepSetsEveryMethodAgainstThePeers) {
  const fs::path dir = fresh_dir("sweep_peers");
  ASSERT_EQ(gacompare("sweep " + std::string(GACOMPARE_DATA_DIR) +
                      "/scenes/tumbling_box.json --solvers cash_karp45,tsit5 --tolerances 1e-4:1e-8 --repeat 1 "
                      "--quiet --out " + dir.string())
                .code,
            0);
  const std::string md = read_text(dir / "sweep.md");
  const auto at = md.find("## Method against method");
  ASSERT_NE(at, std::string::npos) << md;
  const std::string section = md.substr(at);
  EXPECT_NE(section.find("| time / odeint_cash_karp54 | time / odeint_dopri5 |"), std::string::npos) << section;
  int rows = 0, selves = 0;
  std::istringstream lines(section);
  for (std::string line; std::getline(lines, line);) {
    if (line.rfind("| 1e-", 0) != 0) continue;
    ++rows;
    std::vector<std::string> cells;
    std::istringstream c(line);
    for (std::string cell; std::getline(c, cell, '|');) cells.push_back(cell);
    ASSERT_EQ(cells.size(), 7u) << line;  // "", E, method, time, evals, two ratios
    if (cells[2] == " odeint_cash_karp54 ") selves += cells[5] == " 1.00 ";
    if (cells[2] == " odeint_dopri5 ") selves += cells[6] == " 1.00 ";
  }
  EXPECT_GT(rows, 4) << section;
  EXPECT_GE(selves, 2) << section;  // each peer against itself, at one level at least
}

TEST(Cli, SweepOfABodyMeasuresEveryErrorAndDrawsOrientation) {
  const std::string sweep = "sweep " + std::string(GACOMPARE_DATA_DIR) +
                            "/scenes/dzhanibekov.json --solvers rk4 --steps 1e-2:1 --no-peer --max-duration 2 "
                            "--repeat 1 --quiet --out ";
  const fs::path dir = fresh_dir("sweep_body");
  ASSERT_EQ(gacompare(sweep + dir.string()).code, 0);
  std::istringstream csv(read_text(dir / "sweep.csv"));
  std::string header, row;
  std::getline(csv, header);
  const auto names = csv_fields(header);
  for (const char* c : {"position_error", "orientation_error", "velocity_error", "angular_velocity_error"})
    EXPECT_NE(std::find(names.begin(), names.end(), c), names.end()) << c << " in " << header;
  int rows = 0;
  while (std::getline(csv, row)) {
    const auto f = csv_fields(row);
    ASSERT_EQ(f.size(), names.size()) << row;
    auto at = [&](const char* c) { return std::stod(f[std::find(names.begin(), names.end(), c) - names.begin()]); };
    EXPECT_EQ(at("position_error"), 0.0);  // the racket spins about its fixed centre
    EXPECT_GT(at("orientation_error"), 0.0) << row;
    EXPECT_GT(at("angular_velocity_error"), 0.0) << row;
    ++rows;
  }
  EXPECT_EQ(rows, 8);  // rk4 at two steps; matrix, quaternion (traditional), rotor (cga) and motor (pga)
  const std::string md = read_text(dir / "sweep.md");
  EXPECT_NE(md.find("| rk4 | traditional-quaternion | dt 0.01 |"), std::string::npos) << md;
  EXPECT_NE(md.find("## Time at equal accuracy"), std::string::npos) << md;
  EXPECT_NE(md.find("orientation error at the end (rad)**, the default"), std::string::npos) << md;
  EXPECT_TRUE(fs::exists(dir / "dzhanibekov_work_precision.svg"));

  // The same cells (nothing reruns), drawn on the velocity error: 0 everywhere, so no diagram.
  const Result v = gacompare(sweep + dir.string() + " --error velocity");
  EXPECT_NE(v.err.find("ran 0 unit(s)"), std::string::npos) << v.err;
  EXPECT_NE(read_text(dir / "sweep.md").find("velocity error at the end (m/s)**, chosen with --error"), std::string::npos);
  EXPECT_NE(read_text(dir / "sweep.md").find("there is no diagram"), std::string::npos);
  EXPECT_FALSE(fs::exists(dir / "dzhanibekov_work_precision.svg"));

  // A cell written by the position-only format is run again, not read as done.
  for (const auto& e : fs::directory_iterator(dir / "cells")) {
    json cell = read_json(e.path());
    cell.erase("format");
    write_text(e.path(), cell.dump());
    break;
  }
  EXPECT_NE(gacompare(sweep + dir.string()).err.find("ran 1 unit(s) (1 done before with other settings, another build "
                                                     "or format), skipped 1"),
            std::string::npos);

  EXPECT_EQ(gacompare("sweep " + kScene + " --error orientation --out " + fresh_dir("bad_error").string()).code, 2);
}

// The Lie-group methods sweep like the others: the fixed-step ones over the
// steps, rkmk45 over the tolerances, in every representation (matrix,
// quaternion, rotor, motor), every cell with an error and no failure; the
// diagram's key names their family. A particle scene's cells carry the
// loader's refusal instead.
TEST(Cli, SweepOffersTheLieGroupMethods) {
  const fs::path dir = fresh_dir("sweep_lie");
  const Result r = gacompare("sweep " + std::string(GACOMPARE_DATA_DIR) +
                             "/scenes/dzhanibekov.json --solvers rkmk4,crouch_grossman4,rkmk45 --steps 1e-2:1 "
                             "--tolerances 1e-5:1e-6 --no-peer --max-duration 2 --repeat 1 --quiet --out " +
                             dir.string());
  ASSERT_EQ(r.code, 0) << r.err;
  std::istringstream csv(read_text(dir / "sweep.csv"));
  std::string header, row;
  std::getline(csv, header);
  const auto names = csv_fields(header);
  int rows = 0;
  while (std::getline(csv, row)) {
    const auto f = csv_fields(row);
    ASSERT_EQ(f.size(), names.size()) << row;
    const double e = std::stod(f[std::find(names.begin(), names.end(), "orientation_error") - names.begin()]);
    EXPECT_GT(e, 0.0) << row;
    EXPECT_LT(e, 1e-3) << row;  // a 4th-order step of 0.005 s over 2 s is far below this
    ++rows;
  }
  EXPECT_EQ(rows, 24);  // three methods at two settings, in four representations
  const std::string md = read_text(dir / "sweep.md");
  for (const char* cell : {"| rkmk4 | traditional | dt 0.01 |", "| crouch_grossman4 | pga | dt 0.005 |",
                           "| rkmk45 | traditional-quaternion | tol 1e-05 |", "| rkmk45 | cga | tol 1e-06 |"})
    EXPECT_NE(md.find(cell), std::string::npos) << cell << "\n" << md;
  const std::string svg = read_text(dir / "dzhanibekov_work_precision.svg");
  EXPECT_NE(svg.find("rkmk45"), std::string::npos);

  const fs::path particles = fresh_dir("sweep_lie_particles");
  ASSERT_EQ(gacompare("sweep " + kScene + " --solvers rkmk4 --steps 1e-2:0 --no-peer --repeat 1 --quiet --out " +
                      particles.string())
                .code,
            0);
  EXPECT_NE(read_text(particles / "sweep.md").find("cannot integrate particles"), std::string::npos)
      << read_text(particles / "sweep.md");
}

// A cell is keyed by everything that changes it (compare/sweep.hpp, cell_key):
// a resumed sweep with another --max-duration or --repeat runs it again
// instead of mixing it in.
TEST(Cli, SweepCellsWithOtherSettingsRunAgain) {
  const fs::path dir = fresh_dir("sweep_keys");
  const std::string sweep = "sweep " + std::string(GACOMPARE_DATA_DIR) +
                            "/scenes/kepler.json --solvers rk4 --steps 1e-2:0 --no-peer --quiet --out " + dir.string();
  EXPECT_NE(gacompare(sweep + " --repeat 1").err.find("ran 1 unit(s), skipped 0"), std::string::npos);
  EXPECT_NE(gacompare(sweep + " --repeat 1").err.find("ran 0 unit(s), skipped 1"), std::string::npos);
  const std::string again = " (1 done before with other settings, another build or format), skipped 0";
  EXPECT_NE(gacompare(sweep + " --repeat 2").err.find("ran 1 unit(s)" + again), std::string::npos);
  const Result cut = gacompare(sweep + " --repeat 2 --max-duration 1");
  EXPECT_NE(cut.err.find("ran 1 unit(s)" + again), std::string::npos) << cut.err;
  const json cell = read_json(dir / "cells" / "rk4-dt0.01.json");
  EXPECT_EQ(cell["key"]["repeats"], 2);
  EXPECT_EQ(cell["key"]["duration"], 1.0);
}

TEST(Cli, SweepRejectsBadSpecs) {
  const std::string scene = std::string(GACOMPARE_DATA_DIR) + "/scenes/kepler.json --out " + fresh_dir("bad").string();
  EXPECT_EQ(gacompare("sweep " + scene + " --shard 3/3").code, 2);
  EXPECT_EQ(gacompare("sweep " + scene + " --shard x").code, 2);
  EXPECT_EQ(gacompare("sweep " + scene + " --tolerances 1e-12:1e-3").code, 2);
  EXPECT_EQ(gacompare("sweep " + scene + " --tolerances 2e-3:1e-6").code, 2);
  EXPECT_EQ(gacompare("sweep " + scene + " --solvers rk5").code, 2);
}

TEST(Cli, VersionHelpAndList) {
  const Result v = gacompare("--version");
  EXPECT_EQ(v.code, 0);
  EXPECT_NE(v.out.find("gacompare "), std::string::npos);
  EXPECT_EQ(gacompare("--help").code, 0);
  const Result l = gacompare("list");
  EXPECT_EQ(l.code, 0) << l.err;
  EXPECT_NE(l.out.find("projectile_linear_drag"), std::string::npos);
}

// `list` names each scene that does not load — broken, or over the run
// budgets, as `run` would refuse it — in one line on stderr and still lists
// the others, exit 2.
TEST(Cli, ListNamesBrokenAndOverBudgetScenesAndListsTheRest) {
  const fs::path dir = fresh_dir("list");
  fs::create_directories(dir);
  std::ifstream in(std::string(GACOMPARE_DATA_DIR) + "/scenes/kepler.json");
  nlohmann::json scene = nlohmann::json::parse(in);
  std::ofstream(dir / "a_fine.json") << scene.dump();
  scene["name"] = "very_long";
  scene["duration"] = 1e9;
  std::ofstream(dir / "b_long.json") << scene.dump();
  std::ofstream(dir / "c_broken.json") << "{\"name\": \"broken\", \"duration\": ";
  const Result l = gacompare("list --scenes " + dir.string());
  EXPECT_EQ(l.code, 2) << l.err;
  EXPECT_NE(l.out.find("kepler"), std::string::npos) << l.out;
  EXPECT_EQ(l.out.find("very_long"), std::string::npos) << l.out;
  EXPECT_EQ(std::count(l.err.begin(), l.err.end(), '\n'), 2) << l.err;
  EXPECT_NE(l.err.find("b_long.json"), std::string::npos) << l.err;
  EXPECT_NE(l.err.find("--max-samples"), std::string::npos) << l.err;
  EXPECT_NE(l.err.find("c_broken.json"), std::string::npos) << l.err;
}

}  // namespace

// compare --accuracy (compare/accuracy.hpp): a scene with collisions is refused
// in one line before anything runs; a fixed-step particle scene gets its step
// from the cache on a rerun, and the report leads with the equal-accuracy table.
TEST(Cli, CompareAtAccuracyRefusesCollisionsAndReusesItsCache) {
  const fs::path refused = fresh_dir("accuracy_refused");
  const Result r = gacompare("compare " + std::string(GACOMPARE_DATA_DIR) + "/scenes/cube_drop_flat.json --accuracy 1e-6 --quiet --out " +
                             refused.string());
  EXPECT_EQ(r.code, 2) << r.err;
  EXPECT_NE(r.err.find("collisions"), std::string::npos) << r.err;
  EXPECT_EQ(std::count(r.err.begin(), r.err.end(), '\n'), 1) << r.err;
  EXPECT_FALSE(fs::exists(refused));

  const fs::path out = fresh_dir("accuracy");
  const std::string cmd = "compare " + std::string(GACOMPARE_DATA_DIR) +
                          "/scenes/falling_quadratic_drag.json --accuracy 1e-9 --repeat 1 --quiet --out " + out.string();
  const Result first = gacompare(cmd);
  ASSERT_EQ(first.code, 0) << first.err;
  const json plan = read_json(out / "accuracy.json");
  const auto& entry = plan["scenes"]["falling_quadratic_drag"];
  EXPECT_EQ(entry["measure"], "position");
  EXPECT_EQ(entry["adaptive"], false);
  for (const char* b : {"traditional", "cga"}) EXPECT_LE(entry["backends"][b]["error"].get<double>(), 1e-9) << b;
  std::ifstream md(out / "report.md");
  std::stringstream text;
  text << md.rdbuf();
  EXPECT_NE(text.str().find("## Time at equal accuracy"), std::string::npos);
  EXPECT_NE(text.str().find("settings differ per backend"), std::string::npos);
  EXPECT_EQ(text.str().find("read from accuracy.json"), std::string::npos);
  const Result again = gacompare(cmd);
  ASSERT_EQ(again.code, 0) << again.err;
  EXPECT_EQ(read_json(out / "accuracy.json"), plan);
  std::ifstream md_again(out / "report.md");
  std::stringstream text_again;
  text_again << md_again.rdbuf();
  EXPECT_NE(text_again.str().find("read from accuracy.json"), std::string::npos);  // reused, not searched again
}
