#include "compare/plot.hpp"

#include "compare/machine.hpp"
#include "core/error.hpp"

#include <algorithm>
#include <cstdio>
#include <cstdlib>
#include <fstream>
#include <sstream>
#include <unistd.h>

namespace gacompare::compare {

namespace {
// Text (scene and body names come from other people's files) as a gnuplot
// single-quoted string: gnuplot runs `backquoted` commands inside double
// quotes but not inside single quotes, where the only escape is '' for a
// quote. A control character (a newline would end the command and start
// another) becomes '?'. Tested with a name that would touch a file.
std::string quoted(const std::string& s) {
  std::string out = "'";
  for (const char c : s) {
    const auto u = static_cast<unsigned char>(c);
    if (c == '\'') out += "''";
    else if (u < 0x20 || u == 0x7f) out += '?';
    else out += c;
  }
  return out + "'";
}
}  // namespace

void write_svg(const Plot& plot, const std::filesystem::path& file) { write_file_atomically(file, render_svg(plot)); }

std::string render_svg(const Plot& plot) {
  namespace fs = std::filesystem;
  const fs::path dir = fs::temp_directory_path() / ("gacompare_plot_" + std::to_string(::getpid()));
  fs::create_directories(dir);
  std::ostringstream script;
  // 1000 × 560 at 12 pt: drawn at the page's full width (report.html) the text
  // stays the size of the page's, and pasted into a paper's column it scales.
  script << "set terminal svg size 1000,560 dynamic enhanced font 'sans,12' background rgb 'white'\n"
         << "set output " << quoted((dir / "plot.svg").string()) << "\n"
         << "set title " << quoted(plot.title) << " noenhanced\n"
         << "set xlabel " << quoted(plot.xlabel) << "\nset ylabel " << quoted(plot.ylabel) << "\n"
         << "set key outside right top\nset grid\n";
  const bool bars = !plot.categories.empty();
  if (bars) {
    const double width = 0.8 / static_cast<double>(std::max<std::size_t>(1, plot.series.size()));
    script << "set style fill solid 0.8 border -1\nset boxwidth " << width << "\nset xrange [-0.6:"
           << static_cast<double>(plot.categories.size()) - 0.4 << "]\nset xtics (";
    for (std::size_t i = 0; i < plot.categories.size(); ++i)
      script << (i ? ", " : "") << quoted(plot.categories[i]) << " " << i;
    script << ") noenhanced\nset yrange [0:*]\n";
  }
  if (plot.logx) script << "set logscale x\nset format x '10^{%L}'\n";
  if (plot.logy) script << "set logscale y\nset format y '10^{%L}'\n";
  script << "plot ";
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    const fs::path data = dir / ("series" + std::to_string(i) + ".dat");
    const bool errors = s.lo.size() == s.x.size() && s.hi.size() == s.x.size() && !s.x.empty();
    std::ofstream out(data);
    out.precision(17);
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      out << s.x[k] << ' ' << s.y[k];
      if (errors) out << ' ' << s.lo[k] << ' ' << s.hi[k];
      out << '\n';
    }
    if (bars) {  // boxes side by side around each category, error bars over them
      const double width = 0.8 / static_cast<double>(plot.series.size());
      const double shift = (static_cast<double>(i) - 0.5 * static_cast<double>(plot.series.size() - 1)) * width;
      script << (i ? ", " : "") << quoted(data.string()) << " using ($1+" << shift << "):2 with boxes title "
             << quoted(s.title) << " noenhanced";
      if (errors)
        script << ", " << quoted(data.string()) << " using ($1+" << shift
               << "):2:3:4 with yerrorbars lc rgb 'black' pt 0 ps 0 lw 1 notitle";
      continue;
    }
    // Markers only where points are few enough to read; a time series is a line.
    const bool markers = s.x.size() <= 60;
    script << (i ? ", " : "") << quoted(data.string()) << " using 1:2 with " << (markers ? "linespoints" : "lines")
           << " title " << quoted(s.title) << " noenhanced"
           << (s.highlight ? " lw 3 pt 7 ps 1.2" : markers ? " lw 1 pt " + std::to_string(1 + i % 12) : " lw 2")
           << (s.dashed ? " dt 2" : "");
  }
  script << "\n";
  { std::ofstream(dir / "plot.gp") << script.str(); }
  const std::string cmd = "gnuplot " + quoted((dir / "plot.gp").string()) + " 2> " + quoted((dir / "gnuplot.err").string());
  const int rc = std::system(cmd.c_str());
  std::error_code ec;
  if (rc != 0 || !fs::exists(dir / "plot.svg", ec)) {
    std::ifstream err(dir / "gnuplot.err");
    std::string first;
    std::getline(err, first);
    fs::remove_all(dir, ec);
    throw run_error("plot '" + plot.title + "': gnuplot failed" +
                    (rc == 127 * 256 ? " (is it installed? scripts/install-deps.sh installs gnuplot-nox)" : ": " + first));
  }
  std::ifstream svg(dir / "plot.svg");
  std::stringstream text;
  text << svg.rdbuf();
  fs::remove_all(dir, ec);
  return text.str();
}

}  // namespace gacompare::compare
