// report.html rendered by a real browser: headless Chromium (Debian's chromium)
// loads the page a comparison wrote, its DOM must hold the tables and the inline
// SVG figures, and its screenshot must not be blank.
#include <gtest/gtest.h>

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

TEST(ReportRender, ChromiumShowsTablesAndFigures) {
  ASSERT_EQ(std::system("command -v chromium > /dev/null"), 0)
      << "chromium not found: scripts/install-deps.sh installs it (Debian package chromium)";
  const fs::path dir = fs::temp_directory_path() / ("gacompare_render_" + std::to_string(::getpid()));
  fs::remove_all(dir);
  const std::string scene = std::string(GACOMPARE_DATA_DIR) + "/scenes/pendulum.json";
  ASSERT_EQ(std::system((std::string(GACOMPARE_BIN) + " compare " + scene + " --repeat 1 --quiet --out " +
                         (dir / "out").string() + " > /dev/null")
                            .c_str()),
            0);
  const fs::path page = dir / "out" / "report.html";
  ASSERT_TRUE(fs::exists(page));
  // The flags the sandboxed machines need (no network, no GPU, a fresh profile).
  const std::string chromium = "chromium --headless --no-sandbox --disable-gpu --disable-quic --no-first-run "
                               "--disable-background-networking --disable-component-update --disable-sync "
                               "--user-data-dir=" + (dir / "profile").string();
  const std::string url = "file://" + fs::absolute(page).string();
  ASSERT_EQ(std::system((chromium + " --dump-dom " + url + " > " + (dir / "dom.html").string() + " 2>/dev/null").c_str()), 0);
  const std::string dom = slurp(dir / "dom.html");
  EXPECT_GE(count(dom, "<table"), 2u);             // stage times, solver and invariants
  EXPECT_GE(count(dom, "<svg"), 3u);               // energy, constraint violation, divergence
  EXPECT_NE(dom.find("integrate"), std::string::npos);
  ASSERT_EQ(std::system((chromium + " --window-size=1100,2400 --screenshot=" + (dir / "shot.png").string() + " " + url +
                         " > /dev/null 2>&1")
                            .c_str()),
            0);
  // Not blank: a white 1100×2400 page compresses to a few kB; tables, text and
  // three plotted figures take well over 50 kB (this page measures ~250 kB).
  const auto size = fs::file_size(dir / "shot.png");
  EXPECT_GT(size, 50'000u);
  fs::remove_all(dir);
}

}  // namespace
