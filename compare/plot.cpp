#include "compare/plot.hpp"

#include "compare/machine.hpp"
#include "core/error.hpp"

#include <algorithm>
#include <cmath>
#include <cerrno>
#include <chrono>
#include <csignal>
#include <cstring>
#include <fcntl.h>
#include <poll.h>
#include <pthread.h>
#include <spawn.h>
#include <sstream>
#include <sys/wait.h>
#include <unistd.h>

extern char** environ;

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

// Runs gnuplot on `script` (its standard input) and returns what it writes on
// standard output. No shell, no file: a scene's text never meets a command
// line, and a run killed while plotting leaves nothing in the temporary folder
// (no gacompare_plot_PID folders left behind). gnuplot -d reads no init
// file, so what a user's ~/.gnuplot says changes nothing either. Throws
// run_error with gnuplot's first line on stderr when it fails, and stops it
// after kTimeoutSeconds.
constexpr int kTimeoutSeconds = 120;

std::string run_gnuplot(const std::string& script, const std::string& title) {
  int in[2], out[2], err[2];
  if (::pipe2(in, O_CLOEXEC) != 0 || ::pipe2(out, O_CLOEXEC) != 0 || ::pipe2(err, O_CLOEXEC) != 0)
    throw run_error("plot '" + title + "': cannot make pipes for gnuplot: " + std::strerror(errno));
  posix_spawn_file_actions_t actions;
  posix_spawn_file_actions_init(&actions);
  posix_spawn_file_actions_adddup2(&actions, in[0], 0);
  posix_spawn_file_actions_adddup2(&actions, out[1], 1);
  posix_spawn_file_actions_adddup2(&actions, err[1], 2);
  char name[] = "gnuplot", defaults[] = "-d";
  char* argv[] = {name, defaults, nullptr};
  pid_t pid = 0;
  const int spawned = posix_spawnp(&pid, "gnuplot", &actions, nullptr, argv, environ);
  posix_spawn_file_actions_destroy(&actions);
  for (int fd : {in[0], out[1], err[1]}) ::close(fd);
  if (spawned != 0) {
    for (int fd : {in[1], out[0], err[0]}) ::close(fd);
    throw run_error("plot '" + title + "': cannot run gnuplot: " + std::strerror(spawned) +
                    (spawned == ENOENT ? " (is it installed? scripts/install-deps.sh installs gnuplot-nox)" : ""));
  }
  // A gnuplot that stops reading must not kill us with SIGPIPE: blocked here,
  // and a pending one taken back below.
  sigset_t pipe_signal, old_mask;
  sigemptyset(&pipe_signal);
  sigaddset(&pipe_signal, SIGPIPE);
  pthread_sigmask(SIG_BLOCK, &pipe_signal, &old_mask);
  ::fcntl(in[1], F_SETFL, O_NONBLOCK);
  std::string svg, messages;
  std::size_t written = 0;
  bool timed_out = false;
  pollfd fds[3] = {{in[1], POLLOUT, 0}, {out[0], POLLIN, 0}, {err[0], POLLIN, 0}};
  const auto deadline = std::chrono::steady_clock::now() + std::chrono::seconds(kTimeoutSeconds);
  while (fds[0].fd >= 0 || fds[1].fd >= 0 || fds[2].fd >= 0) {
    const auto left = std::chrono::duration_cast<std::chrono::milliseconds>(deadline - std::chrono::steady_clock::now());
    if (left.count() <= 0) {
      timed_out = true;
      break;
    }
    if (::poll(fds, 3, static_cast<int>(left.count())) < 0 && errno != EINTR) break;
    if (fds[0].fd >= 0 && fds[0].revents) {
      const ssize_t n = (fds[0].revents & POLLOUT) ? ::write(in[1], script.data() + written, script.size() - written) : -1;
      if (n > 0) written += static_cast<std::size_t>(n);
      if (written == script.size() || (n < 0 && errno != EAGAIN && errno != EINTR)) ::close(in[1]), fds[0].fd = -1;
    }
    for (int k : {1, 2})
      if (fds[k].fd >= 0 && fds[k].revents) {
        char buffer[65536];
        const ssize_t n = ::read(fds[k].fd, buffer, sizeof buffer);
        if (n > 0) (k == 1 ? svg : messages).append(buffer, static_cast<std::size_t>(n));
        else if (n == 0 || (errno != EINTR && errno != EAGAIN)) ::close(fds[k].fd), fds[k].fd = -1;
      }
  }
  for (const auto& f : fds)
    if (f.fd >= 0) ::close(f.fd);
  if (timed_out) ::kill(pid, SIGKILL);
  int status = 0;
  while (::waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  const timespec zero{0, 0};
  while (sigtimedwait(&pipe_signal, nullptr, &zero) > 0) {
  }
  pthread_sigmask(SIG_SETMASK, &old_mask, nullptr);
  if (timed_out) throw run_error("plot '" + title + "': gnuplot did not finish in " + std::to_string(kTimeoutSeconds) + " s");
  if (!WIFEXITED(status) || WEXITSTATUS(status) != 0 || svg.find("</svg>") == std::string::npos) {
    const auto first = messages.find_first_not_of(" \n");
    const std::string line = first == std::string::npos ? "" : messages.substr(first, messages.find('\n', first) - first);
    throw run_error("plot '" + title + "': gnuplot failed: " + (line.empty() ? "no SVG written" : line));
  }
  return svg;
}

}  // namespace

std::string backend_colour(std::string_view b) {
  if (b == "traditional-quaternion") return "#17becf";
  if (b.starts_with("traditional")) return "#1f77b4";
  if (b == "cga") return "#d62728";
  if (b == "pga") return "#2ca02c";
  if (b == "bullet") return "#9467bd";
  return "#7f7f7f";
}

int method_marker(std::size_t k) {
  constexpr int kMarkers[] = {7, 5, 9, 13, 11, 15, 4, 6, 8, 12, 10, 14, 1, 2, 3};
  return kMarkers[k % std::size(kMarkers)];
}

std::string render_svg(const ForestPlot& plot) {
  if (plot.rows.empty()) throw run_error("plot '" + plot.title + "': a forest plot needs a row");
  std::ostringstream script;
  script.precision(17);
  double lo = 1, hi = 1;  // the axis always shows 1
  const auto take = [&](double x) {
    if (std::isfinite(x) && x > 0) lo = std::min(lo, x), hi = std::max(hi, x);
  };
  // Rows at y = 0, 1, ...; intervals and points in one block, scene dots in another.
  // Summary rows and the others in two blocks, drawn with two line widths.
  for (const bool bold : {true, false}) {
    script << (bold ? "$summary" : "$rows") << " << EOD\n";
    for (std::size_t i = 0; i < plot.rows.size(); ++i) {
      const ForestRow& r = plot.rows[i];
      if (r.bold != bold) continue;
      const bool interval = std::isfinite(r.lo) && std::isfinite(r.hi);
      script << r.ratio << ' ' << i << ' ' << (interval ? r.lo : r.ratio) << ' ' << (interval ? r.hi : r.ratio) << '\n';
      take(r.ratio), take(r.lo), take(r.hi);
    }
    script << "EOD\n";
  }
  script << "$scenes << EOD\n";
  bool dots = false;
  for (std::size_t i = 0; i < plot.rows.size(); ++i)
    for (const double x : plot.rows[i].scenes)
      if (std::isfinite(x) && x > 0) script << x << ' ' << i << '\n', take(x), dots = true;
  script << "EOD\n";
  const double rows = static_cast<double>(plot.rows.size());
  // Height grows with the rows, so the labels never overlap; 1000 wide, as every figure.
  const int height = 150 + 26 * static_cast<int>(plot.rows.size());
  script << "set terminal svg size 1000," << height << " dynamic enhanced font 'sans,12' background rgb 'white'\n"
         << "set title " << quoted(plot.title) << " noenhanced\nset xlabel " << quoted(plot.xlabel) << "\n"
         << "set logscale x\nset xrange [" << lo / 1.15 << ":" << hi * 1.15 << "]\nset yrange [" << rows - 0.5
         << ":-0.5]\nset grid xtics\nset key below\nset format x '%.2g'\n"
         << "set arrow from 1, graph 0 to 1, graph 1 nohead dt 2 lc rgb '#555555'\nset xtics (";
  // Ticks a reader can read off a narrow log range (gnuplot's own fall on decades only).
  // Over a wide range the fine ticks would overlap: coarse ones then.
  const bool wide = hi / lo > 3;
  bool first_tick = true;
  for (const double t : {0.01, 0.02, 0.05, 0.1, 0.2, 0.3, 0.5, 0.6, 0.7, 0.8, 0.9, 1.0, 1.1, 1.2, 1.3, 1.5, 2.0, 3.0,
                         5.0, 10.0, 20.0, 50.0, 100.0}) {
    const bool coarse = t == 0.01 || t == 0.02 || t == 0.05 || t == 0.1 || t == 0.2 || t == 0.5 || t == 1.0 ||
                        t == 2.0 || t == 5.0 || t == 10.0 || t == 20.0 || t == 50.0 || t == 100.0;
    if ((coarse || !wide) && t >= lo / 1.15 && t <= hi * 1.15) script << (first_tick ? "" : ", ") << t, first_tick = false;
  }
  script << ")\nset ytics (";
  for (std::size_t i = 0; i < plot.rows.size(); ++i)
    script << (i ? ", " : "") << quoted(plot.rows[i].label) << " " << i;
  script << ") noenhanced\nset lmargin 34\n"
         << "plot ";
  const bool summary = std::any_of(plot.rows.begin(), plot.rows.end(), [](const ForestRow& r) { return r.bold; });
  const bool others = std::any_of(plot.rows.begin(), plot.rows.end(), [](const ForestRow& r) { return !r.bold; });
  if (summary)
    script << "$summary using 1:2:3:4 with xerrorbars lc rgb '#1f4e9c' pt 7 ps 1.3 lw 3 "
              "title 'all stages: ratio and 95% interval'"
           << (others ? ", " : "");
  if (others) script << "$rows using 1:2:3:4 with xerrorbars lc rgb '#4a90d9' pt 7 ps 0.9 lw 1.5 title 'one stage'";
  if (dots) script << ", $scenes using 1:2 with points pt 6 ps 0.7 lc rgb '#999999' title 'one scene'";
  script << "\n";
  return run_gnuplot(script.str(), plot.title);
}

void write_svg(const Plot& plot, const std::filesystem::path& file) { write_file_atomically(file, render_svg(plot)); }

// The data go in the script as datablocks ($series0 << EOD ... EOD): numbers
// only, written by us.
std::string render_svg(const Plot& plot) {
  std::ostringstream script;
  script.precision(17);
  const auto has_errors = [](const Series& s) {
    return s.lo.size() == s.x.size() && s.hi.size() == s.x.size() && !s.x.empty();
  };
  for (std::size_t i = 0; i < plot.series.size(); ++i) {
    const Series& s = plot.series[i];
    const bool errors = has_errors(s);
    script << "$series" << i << " << EOD\n";
    for (std::size_t k = 0; k < s.x.size(); ++k) {
      script << s.x[k] << ' ' << s.y[k];
      if (errors) script << ' ' << s.lo[k] << ' ' << s.hi[k];
      script << '\n';
    }
    script << "EOD\n";
  }
  // 1000 × 560 at 12 pt: drawn at the page's full width (report.html) the text
  // stays the size of the page's, and pasted into a paper's column it scales.
  script << "set terminal svg size 1000,560 dynamic enhanced font 'sans,12' background rgb 'white'\n"
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
    const std::string data = "$series" + std::to_string(i);
    if (bars) {  // boxes side by side around each category, error bars over them
      const double width = 0.8 / static_cast<double>(plot.series.size());
      const double shift = (static_cast<double>(i) - 0.5 * static_cast<double>(plot.series.size() - 1)) * width;
      script << (i ? ", " : "") << data << " using ($1+" << shift << "):2 with boxes title " << quoted(s.title)
             << " noenhanced";
      if (has_errors(s))
        script << ", " << data << " using ($1+" << shift << "):2:3:4 with yerrorbars lc rgb 'black' pt 0 ps 0 lw 1 notitle";
      continue;
    }
    const std::string colour = s.colour.empty() ? "" : " lc rgb " + quoted(s.colour);
    const std::string title = s.in_key ? " title " + quoted(s.title) + " noenhanced" : " notitle";
    if (s.key_only) {  // a legend line: what a colour or a marker means
      script << (i ? ", " : "") << "keyentry with " << (s.marker ? (s.colour.empty() ? "points" : "linespoints") : "lines")
             << colour << (s.colour.empty() ? " lc rgb 'black'" : "") << (s.marker ? " pt " + std::to_string(s.marker) : "")
             << " lw 2" << title;
      continue;
    }
    // Markers only where points are few enough to read; a time series is a line.
    const bool markers = s.x.size() <= 60;
    const int pt = s.marker ? s.marker : 1 + static_cast<int>(i % 12);
    script << (i ? ", " : "") << data << " using 1:2 with " << (markers ? "linespoints" : "lines") << title << colour
           << (s.highlight ? " lw 3 pt 7 ps 1.2" : markers ? " lw 1.5 pt " + std::to_string(pt) : " lw 2")
           << (s.dashed ? " dt 2" : "");
  }
  script << "\n";
  return run_gnuplot(script.str(), plot.title);
}

}  // namespace gacompare::compare
