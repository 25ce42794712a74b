#pragma once
// Plots drawn by gnuplot (Debian's gnuplot-nox), not by hand: a series per line,
// given to gnuplot on a pipe with its script (no shell, no temporary file),
// rendered to SVG. Used for the work-precision diagrams (what accuracy costs in
// time) and report figures.
#include <filesystem>
#include <string>
#include <string_view>
#include <vector>

namespace gacompare::compare {

struct Series {
  std::string title;
  std::vector<double> x, y;
  bool highlight = false;  // drawn bold (e.g. the Pareto front)
  // Error bars from lo[i] to hi[i] (e.g. min–max over repeats), drawn on bars;
  // empty: none.
  std::vector<double> lo{}, hi{};  // (default initialisers: Series{title, x, y, highlight} stays warning-free)
  bool dashed = false;     // drawn dashed, over a line it coincides with
  // Encodings a reader can decode when many series share a plot: a colour
  // (gnuplot's rgb '#rrggbb', "" = gnuplot's own sequence) and a marker
  // (gnuplot point type, 0 = its own), and whether the series is named in the
  // key (false when the key explains colour and marker instead).
  std::string colour{};
  int marker = 0;
  bool in_key = true;
  // A key entry only: no data, drawn as a line of `colour` and/or a point of
  // `marker` beside `title` (gnuplot's keyentry).
  bool key_only = false;
};

struct Plot {
  std::string title, xlabel, ylabel;
  bool logx = false, logy = false;
  std::vector<Series> series;
  // Bars instead of lines: series k's value for category i (x = i) is drawn as a
  // box beside the other series', labelled with categories[i].
  std::vector<std::string> categories;
};

// A forest plot: one row per estimate, its 95% interval as a horizontal bar
// through its point, and the single scenes behind it as small dots on the same
// row, against a ratio axis (log scale) with a dashed line at 1 (no
// difference). Rows are drawn top to bottom in order; a row whose interval is
// NaN (too few repeats) shows its point alone.
struct ForestRow {
  std::string label;
  double ratio = 1, lo = 0, hi = 0;
  std::vector<double> scenes{};
  bool bold = false;  // a summary row (a category's whole run), drawn heavier
};
struct ForestPlot {
  std::string title, xlabel;
  std::vector<ForestRow> rows;
};
std::string render_svg(const ForestPlot& plot);

// One colour per backend in every figure, so a reader learns it once: the
// traditional backend blue (its quaternion form cyan), cga red, pga green,
// bullet purple, a peer library (Boost.Odeint) grey.
std::string backend_colour(std::string_view backend);
// Filled markers first (circle, square, triangle, diamond, ...): the k-th method's.
int method_marker(std::size_t k);

// Renders `plot` as SVG text. Throws run_error naming the cause when gnuplot is
// missing or fails: never a silent missing figure.
std::string render_svg(const Plot& plot);
// The same, written to a file atomically.
void write_svg(const Plot& plot, const std::filesystem::path& file);

}  // namespace gacompare::compare
