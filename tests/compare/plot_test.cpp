// compare/plot.cpp: text from scene files reaches gnuplot as data, never as a
// command (a name with backticks must not run a shell command through the
// plot script).
#include "compare/plot.hpp"

#include <gtest/gtest.h>

#include <filesystem>
#include <string>
#include <unistd.h>

namespace {

using gacompare::compare::Plot;
using gacompare::compare::render_svg;
using gacompare::compare::Series;

// A title, a series and a category each carrying a backquoted command, a
// double quote, a single quote and a newline: the plot renders, the command
// never runs (its file is not created), and the quotes survive as text.
TEST(Plot, HostileNamesAreTextNotCommands) {
  namespace fs = std::filesystem;
  const fs::path marker = fs::temp_directory_path() / ("gacompare_plot_test_" + std::to_string(::getpid()));
  fs::remove(marker);
  const std::string hostile = "x`touch " + marker.string() + "`y \"q\" it's\nset output '/dev/null'";
  Plot lines{hostile, "x " + hostile, "y", false, false, {Series{hostile, {1, 2, 3}, {1, 4, 9}, false}}, {}};
  const std::string svg = render_svg(lines);
  Plot bars{hostile, "", "s", false, false, {Series{hostile, {0}, {1}, false}}, {hostile}};
  const std::string svg_bars = render_svg(bars);
  EXPECT_FALSE(fs::exists(marker)) << "a name ran a command through gnuplot";
  EXPECT_NE(svg.find("<svg"), std::string::npos);
  EXPECT_NE(svg_bars.find("<svg"), std::string::npos);
  // The quotes are kept as text and the newline became '?': one title line.
  EXPECT_NE(svg.find("\"q\" it's?set output"), std::string::npos) << "the quotes and the newline as text";
  fs::remove(marker);
}

}  // namespace
