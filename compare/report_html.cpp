// report.html: one self-contained page per report folder — the tables of
// report.md (converted from it, so the two never disagree) and inline SVG figures
// drawn by gnuplot: invariants and divergence between backends over time.
#include "compare/metrics.hpp"
#include "compare/plot.hpp"
#include "compare/report.hpp"
#include "compare/results.hpp"
#include "compare/stats.hpp"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <sstream>

namespace gacompare::compare {

std::string html_escape(const std::string& s) {
  std::string out;
  for (char c : s) {
    if (c == '<') out += "&lt;";
    else if (c == '>') out += "&gt;";
    else if (c == '&') out += "&amp;";
    else if (c == '"') out += "&quot;";
    else out += c;
  }
  return out;
}

namespace {

// What compare/escape.hpp's md_text wrote, read back: \| and \\ as the
// characters, &lt; &gt; &amp; as <, > and &, in one pass (so "&amp;lt;" stays "&lt;").
std::string md_unescape(const std::string& text) {
  std::string out;
  for (std::size_t i = 0; i < text.size(); ++i) {
    if (text[i] == '\\' && i + 1 < text.size() && (text[i + 1] == '|' || text[i + 1] == '\\')) {
      out += text[++i];
      continue;
    }
    bool entity = false;
    for (const auto& [name, c] : {std::pair{"&lt;", '<'}, std::pair{"&gt;", '>'}, std::pair{"&amp;", '&'}})
      if (!entity && text.compare(i, std::strlen(name), name) == 0) {
        out += c;
        i += std::strlen(name) - 1;
        entity = true;
      }
    if (!entity) out += text[i];
  }
  return out;
}

// The inline markdown report.md uses: `code`, **bold**, [text](link). Text is
// escaped for HTML after md_text's escapes are read back, so markup in a name
// stays text.
std::string inline_md(const std::string& text) {
  const std::string s = html_escape(md_unescape(text));
  std::string out;
  for (std::size_t i = 0; i < s.size();) {
    if (s[i] == '`') {
      const auto end = s.find('`', i + 1);
      if (end != std::string::npos) {
        out += "<code>" + s.substr(i + 1, end - i - 1) + "</code>";
        i = end + 1;
        continue;
      }
    }
    if (s.compare(i, 2, "**") == 0) {
      const auto end = s.find("**", i + 2);
      if (end != std::string::npos) {
        out += "<strong>" + s.substr(i + 2, end - i - 2) + "</strong>";
        i = end + 2;
        continue;
      }
    }
    if (s[i] == '[') {
      const auto close = s.find("](", i);
      const auto end = close == std::string::npos ? close : s.find(')', close);
      if (end != std::string::npos) {
        std::string href = s.substr(close + 2, end - close - 2);
        if (href.size() > 3 && href.compare(href.size() - 3, 3, ".md") == 0) href.replace(href.size() - 3, 3, ".html");
        // Links are to the report's own files: a scheme (javascript:, a URL a
        // scene's name or description smuggled in) stays text.
        if (href.find(':') != std::string::npos) {
          out += s[i++];
          continue;
        }
        out += "<a href=\"" + href + "\">" + s.substr(i + 1, close - i - 1) + "</a>";
        i = end + 1;
        continue;
      }
    }
    out += s[i++];
  }
  return out;
}

// A table row's cells, split at each '|' that md_text did not escape.
std::vector<std::string> cells(const std::string& row) {
  std::vector<std::string> out;
  std::string cur;
  for (std::size_t i = 1; i < row.size(); ++i) {
    if (row[i] == '\\' && i + 1 < row.size()) {
      cur += row[i];
      cur += row[++i];
    } else if (row[i] == '|') {
      out.push_back(cur);
      cur.clear();
    } else {
      cur += row[i];
    }
  }
  for (auto& c : out) {
    c.erase(0, c.find_first_not_of(' '));
    c.erase(c.find_last_not_of(' ') + 1);
  }
  return out;
}

}  // namespace

// Headings, paragraphs, lists ("- ") and pipe tables: the markdown report.md is made of.
std::string markdown_to_html(const std::string& md) {
  std::istringstream in(md);
  std::ostringstream o;
  std::string line;
  bool in_table = false, header = false, in_list = false;
  while (std::getline(in, line)) {
    if (!line.empty() && line[0] == '|') {
      if (!in_table) {
        o << "<table>\n";
        in_table = header = true;
      }
      if (line.find("---") != std::string::npos && line.find_first_not_of("|-: ") == std::string::npos) continue;
      o << "<tr>";
      for (const auto& c : cells(line)) o << (header ? "<th>" : "<td>") << inline_md(c) << (header ? "</th>" : "</td>");
      o << "</tr>\n";
      header = false;
      continue;
    }
    if (in_table) {
      o << "</table>\n";
      in_table = false;
    }
    if (line.rfind("- ", 0) == 0) {  // a list item; the list ends at the first line that is not one
      if (!in_list) o << "<ul>\n";
      in_list = true;
      o << "<li>" << inline_md(line.substr(2)) << "</li>\n";
      continue;
    }
    if (in_list) {
      o << "</ul>\n";
      in_list = false;
    }
    if (line.rfind("## ", 0) == 0) o << "<h2>" << inline_md(line.substr(3)) << "</h2>\n";
    else if (line.rfind("# ", 0) == 0) o << "<h1>" << inline_md(line.substr(2)) << "</h1>\n";
    else if (!line.empty()) o << "<p>" << inline_md(line) << "</p>\n";
  }
  if (in_table) o << "</table>\n";
  if (in_list) o << "</ul>\n";
  return o.str();
}

namespace {

// Log axes cannot show 0: values below the floor are drawn at it (said in the axis label).
constexpr double kFloor = 1e-17;

Plot over_time(const SceneResult& r, const std::string& title, const std::string& ylabel,
               double (*value)(const core::Sample& first, const core::Sample& s)) {
  Plot p{r.scene.name + ": " + title, "t (s)", ylabel + " (values below 1e-17 drawn at 1e-17)", false, true, {}, {}};
  for (const auto& b : r.backends) {
    Series s{b.run.backend, {}, {}, false};
    for (const auto& smp : b.run.samples) {
      s.x.push_back(smp.t);
      s.y.push_back(std::max(kFloor, value(b.run.samples.front(), smp)));
    }
    p.series.push_back(s);
  }
  return p;
}

// Measure m (compare/metrics.hpp: the functions check and sweep use) between the
// first backend's samples and each other's over time, one series per other backend.
Plot divergence_over_time(const SceneResult& r, Measure m) {
  const std::string words(measure_words(m));
  Plot p{r.scene.name + ": " + (m == Measure::position ? std::string("divergence") : words + " divergence") +
             " between backends",
         "t (s)",
         (m == Measure::orientation ? std::string("largest rotation angle of q⁻¹q′")
                                    : "largest " + words + " difference") +
             " (" + std::string(measure_unit(m)) + "; below 1e-17 drawn at 1e-17)",
         false, true, {}, {}};
  for (std::size_t b = 1; b < r.backends.size(); ++b) {
    Series s{r.backends[b].run.backend + " − " + r.backends[0].run.backend, {}, {}, false};
    const auto& a = r.backends[0].run.samples;
    const auto& c = r.backends[b].run.samples;
    for (std::size_t k = 0; k < std::min(a.size(), c.size()); ++k) {
      s.x.push_back(a[k].t);
      s.y.push_back(std::max(kFloor, state_difference(a[k], c[k])[m]));
    }
    p.series.push_back(s);
  }
  return p;
}

// Lines equal at every point hide each other: each series equal to an earlier
// one is drawn dashed over it, titled "cga (= traditional)", and the figure
// says so under it. Returns that note, or "" when no two lines coincide.
std::string mark_coinciding(Plot& p) {
  if (!p.categories.empty()) return "";  // bars stand side by side: none hides another
  std::string note;
  for (std::size_t j = 1; j < p.series.size(); ++j)
    for (std::size_t i = 0; i < j; ++i) {
      Series &a = p.series[i], &b = p.series[j];
      if (a.x != b.x || a.y != b.y || a.x.empty()) continue;
      const std::string first = a.title.substr(0, a.title.find(" (="));
      note += (note.empty() ? "" : " ") + b.title + " coincides with " + first +
              " at every point (drawn dashed over it).";
      b.title += " (= " + first + ")";
      b.dashed = true;
      break;
    }
  return note;
}

}  // namespace

std::string inline_svg(const std::string& svg) {
  const auto start = svg.find("<svg");  // drop the XML prologue: the SVG is inline
  return start == std::string::npos ? svg : svg.substr(start);
}

namespace {

std::string figures(const SceneResult& r) {
  std::ostringstream o;
  bool constrained = false, bodies = false;
  for (const auto& b : r.backends)
    for (const auto& s : b.run.samples) {
      constrained = constrained || s.constraint_violation > 0;
      bodies = bodies || !s.bodies.empty();
    }
  std::vector<Plot> plots;
  plots.push_back(over_time(r, "energy change", "|E(t) − E(0)| (J)", [](const core::Sample& f, const core::Sample& s) {
    return std::abs(s.kinetic + s.potential - f.kinetic - f.potential);
  }));
  if (constrained)
    plots.push_back(over_time(r, "constraint violation", "max |C|/|∇C| (m)",
                              [](const core::Sample&, const core::Sample& s) { return s.constraint_violation; }));
  if (bodies)
    plots.push_back(over_time(r, "rotation drift", "distance of the stored rotation from a rotation",
                              [](const core::Sample&, const core::Sample& s) { return s.rotation_drift; }));
  if (r.backends.size() > 1)
    for (const Measure m : kMeasures)
      if (bodies || !body_only(m)) plots.push_back(divergence_over_time(r, m));
  // Stage times: median seconds per stage, a bar per backend.
  Plot bars{r.scene.name + ": stage times", "stage", "seconds (median over repeats)", false, false, {}, {}};
  std::vector<core::Stage> ran;
  for (int k = 0; k < core::kStageCount; ++k) {
    const auto st = static_cast<core::Stage>(k);
    for (const auto& b : r.backends)
      if (b.run.profile.ran(st)) {
        ran.push_back(st);
        break;
      }
  }
  for (const auto st : ran) bars.categories.push_back(std::string(core::stage_name(st)));
  for (const auto& b : r.backends) {
    Series s{b.run.backend, {}, {}, false};
    for (std::size_t i = 0; i < ran.size(); ++i) {
      if (!b.run.profile.ran(ran[i])) continue;  // no bar, rather than a bar of 0
      std::vector<double> secs;
      for (const auto& p : b.profiles) secs.push_back(p[ran[i]].seconds);
      const Spread sp = spread(secs);
      s.x.push_back(static_cast<double>(i));
      s.y.push_back(sp.median);
      s.lo.push_back(sp.min);
      s.hi.push_back(sp.max);
    }
    bars.series.push_back(s);
  }
  if (!ran.empty()) {
    bars.ylabel = "seconds: median over repeats, bars from min to max";
    plots.insert(plots.begin(), bars);
  }
  o << "<h2>Figures</h2>\n";
  for (auto& p : plots) {
    const std::string note = mark_coinciding(p);
    o << "<figure>" << inline_svg(render_svg(p));
    if (!note.empty()) o << "<figcaption>" << html_escape(note) << "</figcaption>";
    o << "</figure>\n";
  }
  return o.str();
}

}  // namespace

std::string html_page(const std::string& title, const std::string& body, const std::string& body_class) {
  return "<!DOCTYPE html>\n<html lang=\"en\"><head><meta charset=\"utf-8\"><title>" + html_escape(title) +
         "</title>\n<style>body{font-family:sans-serif;max-width:1100px;margin:2em auto;padding:0 1em;color:#222}"
         "table{border-collapse:collapse;margin:1em 0}th,td{border:1px solid #ccc;padding:.3em .6em}"
         "td{text-align:right}td:first-child{text-align:left}th{background:#f3f3f3}"
         "figure{margin:1em 0}figure svg{width:100%;height:auto;display:block}figcaption{font-size:.9em;color:#555}code{background:#f3f3f3;padding:0 .2em}"
         // The overview: a wider page whose table cells never wrap (its tables are laid out to fit it).
         "body.overview{max-width:1500px}body.overview td,body.overview th{white-space:nowrap}"
         "body.overview p,body.overview figure{max-width:1100px}</style>"
         "</head><body" + (body_class.empty() ? std::string() : " class=\"" + html_escape(body_class) + "\"") + ">\n" +
         body + "</body></html>\n";
}

std::string scene_report_html(const SceneResult& r, const MachineInfo& machine, int repeats) {
  return html_page(r.scene.name + " — gacompare", markdown_to_html(scene_report_md(r, machine, repeats)) + figures(r));
}

}  // namespace gacompare::compare
