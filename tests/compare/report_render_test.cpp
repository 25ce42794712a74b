// report.html and replay.html rendered by a real browser: headless Chromium
// (Debian's chromium) loads the pages a comparison wrote; the report's DOM must
// hold the tables and the inline SVG figures and its screenshot must not be
// blank; the overview of several scenes must put its forest plot and verdict
// before its tables, and its tables must fit the page; the replay's WebGL views must show the bodies at t = 0, change by the
// end, and be there for every backend.
#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <cstdlib>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace {
namespace fs = std::filesystem;

std::string slurp(const fs::path& p) {
  std::ifstream in(p, std::ios::binary);
  std::stringstream s;
  s << in.rdbuf();
  return s.str();
}

std::size_t count(const std::string& text, const std::string& what) {
  std::size_t n = 0;
  for (auto at = text.find(what); at != std::string::npos; at = text.find(what, at + 1)) ++n;
  return n;
}

// Headless Chromium with the flags the sandboxed machines need (no network, no
// GPU, a fresh profile in `dir`). WebGL runs on SwiftShader, Chromium's
// software renderer: --enable-unsafe-swiftshader asks for it by name, since
// newer Chromium no longer falls back to it on its own.
std::string chromium(const fs::path& dir) {
  return "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
         "--disable-background-networking --disable-component-update --disable-sync --enable-unsafe-swiftshader "
         "--user-data-dir=" + (dir / "profile").string();
}

fs::path scratch(const std::string& what) {
  const fs::path dir = fs::temp_directory_path() / ("gacompare_" + what + "_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  return dir;
}

TEST(ReportRender, ChromiumShowsTablesAndFigures) {
  ASSERT_EQ(std::system("command -v chromium > /dev/null"), 0)
      << "chromium not found: scripts/install-deps.sh installs it (Debian package chromium)";
  const fs::path dir = scratch("render");
  const std::string scene = std::string(GACOMPARE_DATA_DIR) + "/scenes/pendulum.json";
  ASSERT_EQ(std::system((std::string(GACOMPARE_BIN) + " compare " + scene + " --repeat 1 --quiet --out " +
                         (dir / "out").string() + " > /dev/null")
                            .c_str()),
            0);
  const fs::path page = dir / "out" / "report.html";
  ASSERT_TRUE(fs::exists(page));
  const std::string browser = chromium(dir);
  const std::string url = "file://" + fs::absolute(page).string();
  ASSERT_EQ(std::system((browser + " --dump-dom " + url + " > " + (dir / "dom.html").string() + " 2>/dev/null").c_str()), 0);
  const std::string dom = slurp(dir / "dom.html");
  EXPECT_GE(count(dom, "<table"), 2u);             // stage times, solver and invariants
  EXPECT_GE(count(dom, "<svg"), 3u);               // energy, constraint violation, divergence
  EXPECT_NE(dom.find("integrate"), std::string::npos);
  EXPECT_NE(dom.find("<th>pga / cga</th>"), std::string::npos);  // every pair that ran has its ratio column
  ASSERT_EQ(std::system((browser + " --window-size=1100,2400 --screenshot=" + (dir / "shot.png").string() + " " + url +
                         " > /dev/null 2>&1")
                            .c_str()),
            0);
  // Not blank: a white 1100×2400 page compresses to a few kB; tables, text and
  // three plotted figures take well over 50 kB (this page measures ~250 kB).
  const auto size = fs::file_size(dir / "shot.png");
  EXPECT_GT(size, 50'000u);
  fs::remove_all(dir);
}

// The overview of several scenes answers first: the forest plot of the
// ratios, drawn, and the verdict come before any table, and every table fits
// the page's width at a common laptop width (1440 px) with no cell wrapped.
// Measured in the browser's own layout by a probe page that holds the report
// in a frame.
TEST(ReportRender, OverviewAnswersFirstAndItsTablesFitThePage) {
  ASSERT_EQ(std::system("command -v chromium > /dev/null"), 0)
      << "chromium not found: scripts/install-deps.sh installs it (Debian package chromium)";
  const fs::path dir = scratch("overview");
  const std::string scenes = std::string(GACOMPARE_DATA_DIR) + "/scenes/";
  ASSERT_EQ(std::system((std::string(GACOMPARE_BIN) + " compare " + scenes + "spinning_top.json " + scenes +
                         "contact_row.json " + scenes + "kepler.json --repeat 5 --quiet --out " + (dir / "out").string() +
                         " > /dev/null")
                            .c_str()),
            0);
  std::ofstream(dir / "probe.html") << R"(<!DOCTYPE html><html><body style="margin:0"><pre id="probe">no answer</pre>
<iframe id="report" src="out/report.html" width="1440" height="900" style="border:0"></iframe>
<script>
document.getElementById("report").addEventListener("load", function () {
  var out = document.getElementById("probe");
  try {
    var doc = this.contentDocument, page = doc.documentElement.clientWidth;
    var forest = doc.getElementById("forest"), tables = doc.querySelectorAll("table");
    var svg = forest ? forest.querySelector("svg") : null;
    var verdict = null;
    doc.querySelectorAll("strong").forEach(function (s) { if (!verdict && s.textContent.indexOf("Verdict") === 0) verdict = s; });
    var before = function (a, b) { return !!(a && b && (a.compareDocumentPosition(b) & Node.DOCUMENT_POSITION_FOLLOWING)); };
    var widest = 0, tallest = 0, lowest = 1e9;
    tables.forEach(function (t) {
      widest = Math.max(widest, t.getBoundingClientRect().right);
      t.querySelectorAll("td,th").forEach(function (c) {
        var h = c.getBoundingClientRect().height;
        tallest = Math.max(tallest, h);
        lowest = Math.min(lowest, h);
      });
    });
    out.textContent = JSON.stringify({
      page: page, tables: tables.length, widest: widest, tallest_cell: tallest, lowest_cell: lowest,
      forest: !!svg, forest_height: svg ? svg.getBoundingClientRect().height : 0,
      forest_marks: svg ? svg.querySelectorAll("path, use").length : 0,
      forest_first: before(forest, tables[0]), verdict_first: before(verdict, tables[0])
    });
  } catch (e) { out.textContent = "error: " + e; }
});
</script></body></html>
)";
  const fs::path dom_file = dir / "dom.html";
  ASSERT_EQ(std::system((chromium(dir) + " --allow-file-access-from-files --window-size=1460,1000 --dump-dom file://" +
                         fs::absolute(dir / "probe.html").string() + " > " + dom_file.string() + " 2>/dev/null")
                            .c_str()),
            0);
  const std::string dom = slurp(dom_file);
  const std::string tag = "<pre id=\"probe\">";
  const auto open = dom.find(tag), close = dom.find("</pre>", open);
  ASSERT_NE(open, std::string::npos) << dom.substr(0, 2000);
  const std::string answer = dom.substr(open + tag.size(), close - open - tag.size());
  ASSERT_EQ(answer.rfind("{", 0), 0u) << answer;
  const auto j = nlohmann::json::parse(answer);
  EXPECT_TRUE(j["forest"].get<bool>()) << j;
  // Drawn, not an empty frame: a row per category and stage (a dozen here),
  // each with its interval, point and scene dots, is well over 40 marks.
  EXPECT_GT(j["forest_marks"].get<int>(), 40) << j;
  EXPECT_GT(j["forest_height"].get<double>(), 200) << j;
  EXPECT_TRUE(j["forest_first"].get<bool>()) << j;
  EXPECT_TRUE(j["verdict_first"].get<bool>()) << j;
  EXPECT_GE(j["tables"].get<int>(), 4) << j;  // times, energy, pairs, categories
  EXPECT_LE(j["widest"].get<double>(), j["page"].get<double>()) << j;
  // No cell wraps: every cell is one line high (a wrapped one is two).
  EXPECT_LT(j["tallest_cell"].get<double>(), 1.5 * j["lowest_cell"].get<double>()) << j;
  ASSERT_EQ(std::system((chromium(dir) + " --window-size=1440,2400 --screenshot=" + (dir / "shot.png").string() +
                         " file://" + fs::absolute(dir / "out" / "report.html").string() + " > /dev/null 2>&1")
                            .c_str()),
            0);
  EXPECT_GT(fs::file_size(dir / "shot.png"), 50'000u);  // not blank (measured: ~500 kB)
  fs::remove_all(dir);
}

// The replay of a cube dropped corner first onto a slab, read back pixel by
// pixel from each backend's WebGL canvas (gl.readPixels) by a page of this
// test's that holds replay.html in a frame and drives it through
// window.replay: first frame, then last, camera fixed. A body is drawn in a
// saturated colour (max − min channel > 60) and nothing else is: the grid,
// edges and the see-through static slab are grey.
TEST(ReplayRender, EveryBackendShowsTheBodiesAndTheirMotion) {
  ASSERT_EQ(std::system("command -v chromium > /dev/null"), 0)
      << "chromium not found: scripts/install-deps.sh installs it (Debian package chromium)";
  const fs::path dir = scratch("replay");
  const std::string scene = std::string(GACOMPARE_DATA_DIR) + "/scenes/cube_drop_corner.json";
  ASSERT_EQ(std::system((std::string(GACOMPARE_BIN) + " compare " + scene + " --repeat 1 --quiet --out " +
                         (dir / "out").string() + " > /dev/null")
                            .c_str()),
            0);
  ASSERT_TRUE(fs::exists(dir / "out" / "replay.html"));
  std::ofstream(dir / "probe.html") << R"(<!DOCTYPE html><html><body><pre id="probe">no answer</pre>
<iframe id="replay" src="out/replay.html" width="1200" height="800"></iframe>
<script>
document.getElementById("replay").addEventListener("load", function () {
  var out = document.getElementById("probe");
  try {
    var r = this.contentWindow.replay;
    r.pause();
    r.stopOrbit();
    var grab = function (k) {
      r.show(k);
      return r.views.map(function (v) {
        var gl = v.renderer.getContext(), w = gl.drawingBufferWidth, h = gl.drawingBufferHeight;
        var px = new Uint8Array(4 * w * h);
        gl.readPixels(0, 0, w, h, gl.RGBA, gl.UNSIGNED_BYTE, px);
        return { backend: v.backend, w: w, n: w * h, px: px };
      });
    };
    var first = grab(0), last = grab(r.frames - 1);
    var views = first.map(function (a, i) {
      var b = last[i], coloured = [0, 0], rows = [0, 0], changed = 0;
      [a, b].forEach(function (s, j) {
        for (var p = 0; p < s.n; ++p) {
          var R = s.px[4 * p], G = s.px[4 * p + 1], B = s.px[4 * p + 2];
          if (Math.max(R, G, B) - Math.min(R, G, B) > 60) { coloured[j]++; rows[j] += Math.floor(p / s.w); }
        }
      });
      for (var p = 0; p < a.n; ++p)
        for (var c = 0; c < 3; ++c)
          if (Math.abs(a.px[4 * p + c] - b.px[4 * p + c]) > 16) { changed++; break; }
      return { backend: a.backend, pixels: a.n, coloured_first: coloured[0], coloured_last: coloured[1],
               row_first: rows[0] / Math.max(1, coloured[0]), row_last: rows[1] / Math.max(1, coloured[1]),
               changed: changed };
    });
    out.textContent = JSON.stringify({ frames: r.frames, views: views });
  } catch (e) { out.textContent = "error: " + e; }
});
</script></body></html>
)";
  // --allow-file-access-from-files: the probe and the replay are both file://
  // pages, which Chromium otherwise treats as of different origins.
  ASSERT_EQ(std::system((chromium(dir) + " --allow-file-access-from-files --window-size=1300,900 --dump-dom file://" +
                         fs::absolute(dir / "probe.html").string() + " > " + (dir / "dom.html").string() + " 2>/dev/null")
                            .c_str()),
            0);
  const std::string dom = slurp(dir / "dom.html");
  const std::string tag = "<pre id=\"probe\">";
  const auto open = dom.find(tag), close = dom.find("</pre>", open);
  ASSERT_NE(open, std::string::npos) << dom.substr(0, 2000);
  const std::string answer = dom.substr(open + tag.size(), close - open - tag.size());
  ASSERT_EQ(answer.rfind("{", 0), 0u) << answer;  // not "no answer" nor "error: ..."
  const auto j = nlohmann::json::parse(answer);
  EXPECT_EQ(j["frames"], 1251);  // every sample of 2.5 s at 0.002 s: under the 2,000-frame cap
  ASSERT_EQ(j["views"].size(), 4u);  // Bullet runs this collision scene beside our three
  EXPECT_EQ(j["views"][0]["backend"], "traditional");
  EXPECT_EQ(j["views"][1]["backend"], "cga");
  EXPECT_EQ(j["views"][2]["backend"], "pga");
  EXPECT_EQ(j["views"][3]["backend"], "bullet");
  for (const auto& v : j["views"]) {
    const double n = v["pixels"].get<double>();
    // The 0.2 m cube covers 6.4% of each view at t = 0 and 4% resting at the
    // end (measured); 1% is a cube drawn, not a stray pixel.
    EXPECT_GT(v["coloured_first"].get<double>(), 0.01 * n) << v;
    EXPECT_GT(v["coloured_last"].get<double>(), 0.01 * n) << v;
    // The picture changes: 11% of the pixels differ (measured); 2% is more
    // than antialiasing could move.
    EXPECT_GT(v["changed"].get<double>(), 0.02 * n) << v;
    // Drawn from the samples: the cube falls 0.6 m onto the slab, so its pixels
    // move down the view (readPixels counts rows from the bottom: 395 -> 113
    // measured; 50 rows is a fall, not jitter).
    EXPECT_LT(v["row_last"].get<double>(), v["row_first"].get<double>() - 50) << v;
    // Every backend starts from the scene's initial state: the same picture.
    EXPECT_EQ(v["coloured_first"], j["views"][0]["coloured_first"]) << v;
  }
  fs::remove_all(dir);
}

}  // namespace
