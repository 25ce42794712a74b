// Every input bounded, regression checks that cannot pass vacuously, reports
// that escape what they quote, end to end through the gacompare
// binary as a new user, or someone handing over a tampered folder, would run
// it: each case with its exit code and its one line, within seconds (each
// timed here; the `reliability` label's TIMEOUT catches a hang), nothing
// written outside --out.
#include "csv_fields.hpp"
#include "reliability_work.hpp"

#include <chrono>
#include <csignal>
#include <cstdlib>
#include <set>
#include <sys/stat.h>
#include <thread>
#include <tuple>
#include <unistd.h>

namespace {

const std::string kShot = (kScenes / "projectile_linear_drag.json").string();  // 3 particles, 2 s, 41 samples

// Seconds a refusal may take: each is decided before any work, in under a
// second here (the 7 MB file of a million timings: 0.3 s to read); the margin
// is for a loaded CI machine and the AddressSanitizer build. Before, these ran
// for minutes or for ever.
constexpr double kPrompt = 10;

struct Timed {
  Result r;
  double seconds;
};
Timed timed(const Work& w, const std::string& args) {
  const auto t0 = std::chrono::steady_clock::now();
  Result r = w.run(args);
  return {std::move(r), std::chrono::duration<double>(std::chrono::steady_clock::now() - t0).count()};
}

// Refused with exit 2, one line holding each of `parts`, within kPrompt s.
void expect_prompt_refusal(const Work& w, const std::string& args, const std::vector<std::string>& parts) {
  SCOPED_TRACE(args);
  const Timed t = timed(w, args);
  expect_one_line(t.r, 2, parts);
  EXPECT_LT(t.seconds, kPrompt);
}

void write(const fs::path& p, const std::string& text) {
  fs::create_directories(p.parent_path());
  std::ofstream(p, std::ios::binary) << text;
}
void write(const fs::path& p, const json& j) { write(p, j.dump()); }

// ---- one bounded reader ---------------------------------------------------------------------

// A device or a FIFO given as a scene, a baseline or a results.json is refused
// at once (/dev/zero used to reach bad_alloc after 20 s; a FIFO blocked
// forever), as is a folder where a file belongs and a baseline that is a link.
TEST(ReliabilityInputs, DevicesFifosFoldersAndLinksAreRefusedAtOnce) {
  const Work w("devices");
  const fs::path fifo = w.root / "in" / "fifo.json";
  ASSERT_EQ(::mkfifo(fifo.c_str(), 0600), 0);
  expect_prompt_refusal(w, "compare /dev/zero --repeat 1 --quiet --out out", {"/dev/zero: expected a scene file, got a character device"});
  expect_prompt_refusal(w, "compare /dev/urandom --repeat 1 --quiet --out out", {"/dev/urandom: expected a scene file, got a character device"});
  expect_prompt_refusal(w, "run " + sh(fifo.string()) + " --backend cga --quiet --out out", {fifo.string() + ": expected a scene file, got a FIFO"});
  expect_prompt_refusal(w, "diff " + sh(fifo.string()) + " " + sh(fifo.string()), {fifo.string() + ": expected a results.json, got a FIFO"});
  // A baseline folder whose baseline is a FIFO, a folder, a link.
  const fs::path base = w.root / "in" / "base" / "projectile_linear_drag.json";
  fs::create_directories(base.parent_path());
  ASSERT_EQ(::mkfifo(base.c_str(), 0600), 0);
  const std::string check = "check " + sh(kShot) + " --baseline in/base --quiet";
  expect_prompt_refusal(w, check, {base.filename().string() + ": expected a baseline, got a FIFO"});
  fs::remove(base);
  fs::create_directory(base);
  expect_prompt_refusal(w, check, {base.filename().string() + ": expected a baseline, got a directory"});
  fs::remove(base);
  fs::create_symlink("/etc/passwd", base);
  expect_prompt_refusal(w, check, {base.filename().string() + ": expected a baseline, got a symbolic link (not followed"});
  fs::remove(base);
  EXPECT_FALSE(fs::exists(w.out()));
  expect_clean(w);
}

// Every file read is held to --max-input-mb (default 256 MB): stated, overridable.
TEST(ReliabilityInputs, FilesAboveTheSizeLimitAreRefused) {
  const Work w("size");
  expect_prompt_refusal(w, "--max-input-mb 0.0005 run " + sh(kShot) + " --backend traditional --quiet --out out",
                        {kShot + ": the scene file is ", "above the limit of 0.0005 MB (--max-input-mb raises it)"});
  const Result ok = w.run("--max-input-mb 0.001 run " + sh(kShot) + " --backend traditional --quiet --out out");
  EXPECT_EQ(ok.code, 0) << ok.err;
  expect_clean(w);
}

// ---- merge copies nothing it has not read and checked -----------------------------------

TEST(ReliabilityInputs, MergeFollowsNoLinkAndReadsNoDeviceOrFifo) {
  const Work w("merge");
  for (const std::string shard : {"0", "1"}) {
    const Result r = w.run("sweep " + sh(kShot) + " --out out/S" + shard + " --solvers rk4 --steps 1e-2:1 --repeat 1 --no-peer --quiet --shard " + shard + "/2");
    ASSERT_EQ(r.code, 0) << r.err;
  }
  const std::string merge = "merge out/S0 out/S1 --out out/M";
  ASSERT_EQ(w.run(merge).code, 0);
  const std::string merged = slurp(w.out() / "M" / "sweep.md");
  const fs::path x = w.out() / "S0" / "cells" / "x.json";
  const std::string said = "out/S0/cells/x.json: ";  // as gacompare, working in w.root, names it
  for (const std::string target : {"/etc/passwd", "/dev/zero"}) {
    fs::create_symlink(target, x);
    expect_prompt_refusal(w, merge, {said + "expected a sweep cell, got a symbolic link (not followed"});
    fs::remove(x);
  }
  ASSERT_EQ(::mkfifo(x.c_str(), 0600), 0);
  expect_prompt_refusal(w, merge, {said + "expected a sweep cell, got a FIFO"});
  fs::remove(x);
  write(x, std::string("root:x:0:0:root:/root:/bin/bash\n"));
  expect_prompt_refusal(w, merge, {said + "malformed JSON"});
  fs::remove(x);
  // The merged folder is the earlier merge's, whole, and holds nothing of x.
  EXPECT_EQ(slurp(w.out() / "M" / "sweep.md"), merged);
  EXPECT_FALSE(fs::exists(w.out() / "M" / "cells" / "x.json"));
  // A manifest naming /dev/zero as its scene, with repeats as a string, with a unit id that is a path.
  const json manifest = read_json(w.out() / "S0" / "sweep.json");
  for (const auto& [key, value, expected] : std::vector<std::tuple<std::string, json, std::string>>{
           {"scene_file", "/dev/zero", "/dev/zero: expected a scene file, got a character device"},
           {"repeats", "1", "/repeats: expected a whole number from 1 to 200, got \"1\""},
           {"units", json::array({"../../escape"}), "/units/0: expected a unit id"}}) {
    for (const std::string shard : {"S0", "S1"}) {
      json m = manifest;
      m[key] = value;
      write(w.out() / shard / "sweep.json", m);
    }
    expect_prompt_refusal(w, merge, {expected});
  }
  expect_clean(w);
}

// ---- results read back are checked before they are trusted -------------------------------

// A's results.json (traditional and cga, 3 repeats), tampered with as B.
struct Diffed {
  Work w;
  json a;
  explicit Diffed(const std::string& name) : w("diff_" + name) {
    const Result r = w.run("compare " + sh(kShot) + " --backends traditional,cga --repeat 3 --quiet --out out/A");
    EXPECT_EQ(r.code, 0) << r.err;
    a = read_json(w.out() / "A" / "results.json");
  }
  Timed diff(const json& b) const {
    write(w.root / "in" / "B.json", b);
    return timed(w, "diff out/A in/B.json");
  }
  void refused(const json& b, const std::vector<std::string>& parts) const {
    const Timed t = diff(b);
    std::vector<std::string> all{"in/B.json: "};
    all.insert(all.end(), parts.begin(), parts.end());
    expect_one_line(t.r, 2, all);
    EXPECT_LT(t.seconds, kPrompt);
  }
  void failed(const json& b, const std::string& why) const {
    const Timed t = diff(b);
    EXPECT_EQ(t.r.code, 1) << t.r.err;
    EXPECT_NE(t.r.out.find(why), std::string::npos) << t.r.out;
    EXPECT_LT(t.seconds, kPrompt);
  }
};

TEST(ReliabilityInputs, DiffFailsOnTruncatedEmptiedOrUnrelatedResults) {
  const Diffed d("vacuous");
  const Timed same = d.diff(d.a);
  EXPECT_EQ(same.r.code, 0) << same.r.err << same.r.out;
  EXPECT_NE(same.r.out.find("diff: "), std::string::npos);
  json b = d.a;
  auto& samples = b["runs"][1]["samples"];
  samples.erase(samples.begin() + 10, samples.end());  // 10 of its 41 samples, not marked as stopped
  d.refused(b, {"/runs/1/samples: expected exactly 41 samples"});
  b["runs"][1]["error"] = "stopped";  // now it says it stopped early: a valid file, and a failed diff
  d.failed(b, "B stopped early");
  b = d.a;
  b["runs"][0]["samples"] = json::array();
  d.refused(b, {"/runs/0/samples: expected an array of 1 to"});
  b = d.a;
  std::reverse(b["runs"][0]["samples"].begin(), b["runs"][0]["samples"].end());
  d.refused(b, {"/runs/0/samples/0/t: expected 0"});
  b = d.a;
  std::swap(b["runs"][0]["samples"][3]["t"], b["runs"][0]["samples"][4]["t"]);
  d.refused(b, {"/runs/0/samples/4/t: expected a number in [0.2"});
  b = d.a;
  b["scene"]["name"] = "another scene";
  d.failed(b, "A and B have no scene in common: nothing was compared");
  b = d.a;
  b["runs"].erase(1);  // B lacks A's cga run
  d.failed(b, "in A only: B has no run of this backend");
  b = d.a;
  b["runs"] = json::array();
  d.refused(b, {"/runs: expected an array of 1 to 4 elements"});
  expect_clean(d.w);
}

TEST(ReliabilityInputs, StoredTimesAndRepeatsAreRangeChecked) {
  const Diffed d("times");
  json b = d.a;
  const std::string stage = b["runs"][0]["stages"].begin().key();
  b["runs"][0]["stages"][stage]["seconds_each_repeat"][0] = -1e-3;  // read as a ratio of -1e3, "faster"
  d.refused(b, {"/runs/0/stages/" + stage + "/seconds_each_repeat/0: expected a number in [0, 1e+09], got -0.001"});
  b = d.a;
  b["runs"][0]["stages"][stage]["seconds_each_repeat"][1] = 1e300;
  d.refused(b, {"/seconds_each_repeat/1: expected a number in [0, 1e+09]"});
  // A million repeat timings (7.6 MB) took diff past a minute.
  b = d.a;
  b["repeats"] = 1000000;
  b["runs"][0]["stages"][stage]["seconds_each_repeat"] = std::vector<double>(1000000, 1e-3);
  d.refused(b, {"/repeats: expected a whole number from 1 to 200, got 1000000"});
  b["repeats"] = 3;
  d.refused(b, {"/runs/0/stages/" + stage + "/seconds_each_repeat: expected an array of 3 elements"});
  expect_clean(d.w);
}

// Tampered values that reached nlohmann's own exceptions ("internal error
// [json.exception...]", exit 1) are input errors naming the file and path.
TEST(ReliabilityInputs, TamperedResultsAreInputErrorsWithTheirPath) {
  const Diffed d("types");
  json b = d.a;
  b["runs"] = "runs";
  d.refused(b, {"/runs: expected an array of 1 to 4 elements, got \"runs\""});
  b = d.a;
  b["runs"][0]["samples"] = 3;
  d.refused(b, {"/runs/0/samples: expected an array of 1 to", "got 3"});
  b = d.a;
  b["runs"][0]["samples"][3]["t"] = "0.15";
  d.refused(b, {"/runs/0/samples/3/t: expected a number in [", "got \"0.15\""});
  b = d.a;
  b["runs"][0]["samples"][3]["particles"]["shot"]["position"] = {1, 2};
  d.refused(b, {"/runs/0/samples/3/particles/shot/position: expected [x, y, z], got an array of 2"});
  b = d.a;
  b["scene"]["bodies"] = {{{"name", "ghost"}}};
  d.refused(b, {"/scene/bodies/0/radius: missing"});
  expect_clean(d.w);
}

// ---- check against baselines that hold less than they should ------------------------------

TEST(ReliabilityInputs, CheckFailsOnEmptiedOrShortBaselines) {
  const Work w("baseline");
  ASSERT_EQ(w.run("check " + sh(kShot) + " --baseline out --update --quiet").code, 0);
  const fs::path file = w.out() / "projectile_linear_drag.json";
  const std::string named = "out/projectile_linear_drag.json";  // as gacompare, working in w.root, names it
  const json stored = read_json(file);
  const std::string check = "check " + sh(kShot) + " --baseline out --quiet";
  ASSERT_EQ(w.run(check).code, 0);
  json b = stored;
  b["runs"] = json::array();  // was "6 passed", exit 0
  write(file, b);
  expect_prompt_refusal(w, check, {named + ": /runs: expected an array of 1 to 4 elements, got an array of 0"});
  b = stored;
  b["runs"].erase(1);
  write(file, b);
  Result r = w.run(check);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("the baseline stores no run of this backend"), std::string::npos) << r.out;
  b = stored;
  b["runs"][0]["final"]["t"] = 1.0;
  write(file, b);
  r = w.run(check);
  EXPECT_EQ(r.code, 1) << r.err;
  EXPECT_NE(r.out.find("the baseline's final state is at t = 1 s, this run's at t = 2 s"), std::string::npos) << r.out;
  b = stored;
  b["runs"][0]["wall_seconds"] = -1;
  write(file, b);
  expect_prompt_refusal(w, check, {named + ": /runs/0/wall_seconds: expected a number in [0, 1e+09], got -1"});
  b = stored;
  b["runs"][0]["final"]["particles"]["shot"]["position"] = "here";
  write(file, b);
  expect_prompt_refusal(w, check, {named + ": /runs/0/final/particles/shot/position: expected [x, y, z]"});
  expect_clean(w);
}

// A cached accuracy setting out of the search's range (1e300, -1) is not
// trusted: searched again, and the report shows what was measured.
TEST(ReliabilityInputs, ATamperedAccuracyCacheIsSearchedAgain) {
  const Work w("accuracy");
  const std::string cmd = "compare " + sh(kShot) + " --accuracy 1e-6 --backends traditional,cga --repeat 1 --out out";
  Result r = w.run(cmd + " --quiet");
  ASSERT_EQ(r.code, 0) << r.err;
  const json good = read_json(w.out() / "accuracy.json");
  const double found = good["scenes"]["projectile_linear_drag"]["backends"]["cga"]["setting"];
  for (const double bad : {1e300, -1.0}) {
    json cache = good;
    cache["scenes"]["projectile_linear_drag"]["backends"]["cga"]["setting"] = bad;
    write(w.out() / "accuracy.json", cache);
    r = w.run(cmd);
    ASSERT_EQ(r.code, 0) << r.err;
    EXPECT_NE(r.err.find("/scenes/projectile_linear_drag/backends/cga/setting: expected a number in"), std::string::npos) << r.err;
    EXPECT_NE(r.err.find("searching again"), std::string::npos) << r.err;
    EXPECT_EQ(read_json(w.out() / "accuracy.json")["scenes"]["projectile_linear_drag"]["backends"]["cga"]["setting"], found);
    EXPECT_EQ(slurp(w.out() / "accuracy.md").find("e+300"), std::string::npos);
  }
  expect_clean(w);
}

// ---- reports escape what they quote -------------------------------------------------------

// The folder under `out` whose results.json is of scene `name`.
fs::path scene_folder(const fs::path& out, const std::string& name) {
  for (const auto& e : fs::directory_iterator(out))
    if (fs::exists(e.path() / "results.json") && read_json(e.path() / "results.json")["scene"]["name"] == name) return e.path();
  return out / "none";
}

// Every table row of a markdown file has as many cells as its table's header.
void expect_tables_whole(const fs::path& md) {
  std::istringstream in(slurp(md));
  std::string line;
  long header = -1;
  const auto cells = [](const std::string& row) {
    long n = 0;
    for (std::size_t i = 0; i < row.size(); ++i) {
      if (row[i] == '\\') ++i;  // an escaped character: never a cell's end
      else if (row[i] == '|') ++n;
    }
    return n;
  };
  while (std::getline(in, line)) {
    if (line.empty() || line[0] != '|') {
      header = -1;
      continue;
    }
    if (header < 0) header = cells(line);
    EXPECT_EQ(cells(line), header) << md << ": " << line;
  }
}

// A text field a spreadsheet would read as a formula: '=', '+', '-' or '@' first, and not a number.
bool formula(const std::string& f) {
  if (f.empty() || std::string("=+-@").find(f[0]) == std::string::npos) return false;
  char* end = nullptr;
  std::strtod(f.c_str(), &end);
  return end != f.c_str() + f.size();
}

void expect_reports_escaped(const fs::path& dir) {
  int md = 0, csv = 0;
  for (const auto& e : fs::recursive_directory_iterator(dir)) {
    const std::string text = slurp(e.path()), ext = e.path().extension().string();
    if (ext == ".md") {
      ++md;
      for (const std::string raw : {"<script", "<img", "<!--"}) EXPECT_EQ(text.find(raw), std::string::npos) << e.path() << " holds " << raw;
      expect_tables_whole(e.path());
    }
    if (ext == ".csv") {
      ++csv;
      const auto rows = csv_rows(text);
      ASSERT_FALSE(rows.empty()) << e.path() << " is not RFC 4180";
      for (const auto& row : rows) {
        EXPECT_EQ(row.size(), rows.front().size()) << e.path();
        for (const auto& f : row) EXPECT_FALSE(formula(f)) << e.path() << ": " << f;
      }
    }
  }
  EXPECT_GT(md, 0);
  EXPECT_GT(csv, 0);
}

TEST(ReliabilityInputs, ReportsEscapeWhatTheyQuote) {
  const Work w("escape");
  json a = bundled("projectile_linear_drag");
  a["name"] = "=1+2,x,\"y\" <script>alert(1) |";
  a["description"] = "<img src=x onerror=alert(1)> | a\nb </script><!--";
  a["particles"][0]["name"] = "@SUM(1+1),\"q\"";
  json c = bundled("cube_drop_flat");
  c["name"] = "-2+3 <b>|";
  c["duration"] = 0.2;
  c["bodies"][1]["name"] = "<!--<script>";
  const Result r = w.run("compare " + sh(w.scene("a.json", a).string()) + " " + sh(w.scene("c.json", c).string()) +
                         " --repeat 1 --quiet --out out");
  ASSERT_EQ(r.code, 0) << r.err;
  expect_reports_escaped(w.out());
  const Result s = w.run("sweep " + sh(w.scene("a.json", a).string()) +
                         " --out out/sweep --solvers rk4 --steps 1e-2:1 --repeat 1 --no-peer --quiet");
  ASSERT_EQ(s.code, 0) << s.err;
  expect_reports_escaped(w.out() / "sweep");
  // The replay of the body named "<!--<script>": its data holds no '<' at
  // all, so it cannot open a comment or a script, and it reads back whole.
  const std::string page = slurp(scene_folder(w.out(), c["name"]) / "replay.html");
  const std::string open = "<script type=\"application/json\" id=\"replay-data\">";
  const auto from = page.find(open), to = page.find("</script>", from);
  ASSERT_NE(from, std::string::npos);
  const std::string data = page.substr(from + open.size(), to - from - open.size());
  EXPECT_EQ(data.find('<'), std::string::npos);
  EXPECT_EQ(json::parse(data)["bodies"][1]["name"], "<!--<script>");
  // Three script elements (three.js, the data, the player), each closed once.
  std::size_t opened = 0, closed = 0;
  for (auto at = page.find("<script"); at != std::string::npos; at = page.find("<script", at + 1)) ++opened;
  for (auto at = page.find("</script>"); at != std::string::npos; at = page.find("</script>", at + 1)) ++closed;
  EXPECT_EQ(opened, 3u);
  EXPECT_EQ(closed, 3u);
  // And headless Chromium runs the player to its first drawing: a view per
  // backend, and the clock draw() sets (report_render_test.cpp reads the pixels).
  ASSERT_EQ(std::system("command -v chromium > /dev/null"), 0) << "chromium not found: scripts/install-deps.sh installs it";
  const fs::path browser = scratch() / "chromium_escape";
  fs::remove_all(browser);
  fs::create_directories(browser);
  ASSERT_EQ(std::system(("chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
                         "--disable-background-networking --disable-component-update --disable-sync "
                         "--enable-unsafe-swiftshader --user-data-dir=" + sh((browser / "profile").string()) +
                         " --dump-dom " + sh("file://" + (scene_folder(w.out(), c["name"]) / "replay.html").string()) +
                         " > " + sh((browser / "dom.html").string()) + " 2>/dev/null")
                            .c_str()),
            0);
  const std::string dom = slurp(browser / "dom.html");
  std::size_t views = 0;
  for (auto at = dom.find("class=\"view\""); at != std::string::npos; at = dom.find("class=\"view\"", at + 1)) ++views;
  EXPECT_EQ(views, json::parse(data)["backends"].size());
  EXPECT_NE(dom.find("(sample "), std::string::npos) << "the player never drew";
  fs::remove_all(browser);
  expect_clean(w);
}

// ---- meshes in bounded time -----------------------------------------------------------------

TEST(ReliabilityInputs, ObjFacesAreBoundedAsTheyAreRead) {
  const Work w("obj_faces");
  std::ostringstream big;
  for (int i = 0; i < 200000; ++i) big << "v " << std::cos(i * 3e-5) << " " << std::sin(i * 3e-5) << " 0\n";
  big << "f";
  for (int i = 1; i <= 200000; ++i) big << " " << i;
  big << "\n";
  write(w.root / "in" / "big.obj", big.str());
  json scene = bundled("spinning_top");
  scene["bodies"][0]["shape"] = {{"mesh", "big.obj"}};
  expect_prompt_refusal(w, "run " + sh(w.scene("big.json", scene).string()) + " --backend traditional --quiet --out out",
                        {"/bodies/0/shape/mesh: ", "big.obj: line 200001: expected at most 1000 corners on one 'f' line, got 200000"});
  // 101 faces of 1,000 corners: each allowed, together over the triangulation budget (Σ corners² ≤ 1e8).
  std::ostringstream many;
  for (int i = 0; i < 1000; ++i) many << "v " << std::cos(i * 6e-3) << " " << std::sin(i * 6e-3) << " 0\n";
  for (int k = 0; k < 101; ++k) {
    many << "f";
    for (int i = 1; i <= 1000; ++i) many << " " << i;
    many << "\n";
  }
  write(w.root / "in" / "many.obj", many.str());
  scene["bodies"][0]["shape"] = {{"mesh", "many.obj"}};
  expect_prompt_refusal(w, "run " + sh(w.scene("many.json", scene).string()) + " --backend traditional --quiet --out out",
                        {"many.obj: line 1101: expected polygons whose corners, squared and summed, come to at most 1e8"});
  std::string cube = slurp(kMeshes / "cube.obj");
  const auto f = cube.find("\nf ");
  ASSERT_NE(f, std::string::npos);
  cube.insert(f + 3, "4294967300");  // the first face's first corner: once wrapped to 4
  cube.erase(f + 3 + 10, cube.find(' ', f + 3 + 10) - (f + 3 + 10));
  write(w.root / "in" / "wrap.obj", cube);
  scene["bodies"][0]["shape"] = {{"mesh", "wrap.obj"}};
  expect_prompt_refusal(w, "run " + sh(w.scene("wrap.json", scene).string()) + " --backend traditional --quiet --out out",
                        {"wrap.obj: line ", "expected indices that are whole numbers from 1 to 2147483647", "got '4294967300"});
  expect_clean(w);
}

// A box too thin for its faces to have area was refused with the mesh's
// message alone: now with the scene file and the JSON path.
TEST(ReliabilityInputs, AThinBoxIsRefusedAtItsPath) {
  json scene = bundled("cube_drop_flat");
  scene["bodies"][1]["shape"] = {{"box", {1, 1, 1e-12}}};
  expect_refused("thin_box", scene, {"/bodies/1/shape: box 1 x 1 x 1e-12: degenerate (zero-area) triangle"});
}

// ---- whole-or-nothing output folders ------------------------------------------------------

// Which scene each of a report folder's files is of ("" where a file is missing).
std::set<std::string> scenes_in(const fs::path& out) {
  std::set<std::string> names;
  names.insert(read_json(out / "results.json")["scene"]["name"].get<std::string>());
  const std::string md = slurp(out / "report.md");
  names.insert(md.substr(2, md.find('\n') - 2));
  const std::string replay = slurp(out / "replay.html");
  const auto title = replay.find("<title>") + 7;
  names.insert(replay.substr(title, replay.find(" — replay", title) - title));
  const auto rows = csv_rows(slurp(out / "stages.csv"));
  names.insert(rows.size() > 1 ? rows[1][0] : "");
  const auto traj = csv_rows(slurp(out / "trajectories.csv"));
  names.insert(traj.size() > 1 ? traj[1][3] == "shot" ? "projectile_linear_drag" : "cube_drop_flat" : "");
  const std::string html = slurp(out / "report.html");
  names.insert(html.find("<h1>projectile_linear_drag</h1>") != std::string::npos ? "projectile_linear_drag"
               : html.find("<h1>cube_drop_flat</h1>") != std::string::npos    ? "cube_drop_flat"
                                                                               : "");
  return names;
}

// A rerun into a complete folder killed (SIGTERM) at any moment leaves the
// previous folder whole, or the new one whole: never one run's results.json
// beside the other's replay.
TEST(ReliabilityInputs, AnInterruptedRerunLeavesThePreviousFolderWhole) {
  const Work w("interrupted");
  ASSERT_EQ(w.run("run " + sh(kShot) + " --backend traditional --quiet --out out").code, 0);
  const std::string drop = (kScenes / "cube_drop_flat.json").string();
  for (const int delay_ms : {20, 80, 200, 400, 700, 1000}) {
    const std::string cmd = w.command("run " + sh(drop) + " --backend cga --quiet --out out");
    const pid_t pid = ::fork();
    if (pid == 0) {
      ::execl("/bin/sh", "sh", "-c", cmd.c_str(), static_cast<char*>(nullptr));
      ::_exit(127);
    }
    std::this_thread::sleep_for(std::chrono::milliseconds(delay_ms));
    ::kill(pid, SIGTERM);
    ::waitpid(pid, nullptr, 0);
    SCOPED_TRACE("killed after " + std::to_string(delay_ms) + " ms");
    const auto names = scenes_in(w.out());
    EXPECT_EQ(names.size(), 1u) << "a mixed folder: " << *names.begin() << " and " << *names.rbegin();
  }
  ASSERT_EQ(w.run("run " + sh(drop) + " --backend cga --quiet --out out").code, 0);
  EXPECT_EQ(scenes_in(w.out()), std::set<std::string>{"cube_drop_flat"});
  expect_clean(w);  // the sibling folders the killed runs left are gone
}

// --out is checked writable before any simulation: under /proc (where root
// passes access(2)), and a folder of someone's own files is never replaced.
TEST(ReliabilityInputs, OutIsCheckedBeforeAnyWork) {
  const Work w("out_checked");
  const std::string run = "--max-steps 10 run " + sh((kScenes / "spinning_top.json").string()) + " --backend traditional --quiet --out ";
  expect_prompt_refusal(w, run + "/proc/gacompare-out", {"/proc/gacompare-out: cannot create the output folder"});
  expect_prompt_refusal(w, run + "/proc/self/fdinfo", {"/proc/self/fdinfo: cannot "});
  write(w.root / "in" / "mine" / "notes.txt", std::string("mine\n"));
  expect_prompt_refusal(w, run + "in/mine", {"in/mine: holds ", "notes.txt, which gacompare did not write there"});
  EXPECT_EQ(slurp(w.root / "in" / "mine" / "notes.txt"), "mine\n");
  expect_clean(w);
}

}  // namespace
