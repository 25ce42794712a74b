#pragma once
// report.md (tables readable on GitHub) and one CSV per table.
#include "compare/machine.hpp"
#include "compare/runner.hpp"

#include <filesystem>
#include <string>
#include <vector>

namespace gacompare::compare {

// Per-stage timing (median and min–max over the repeats, calls, share of the
// total, a ratio over paired repeats for each pair of summary.hpp's kPairs that
// ran), solver counters, invariants and the divergence between backends, for
// one scene.
std::string scene_report_md(const SceneResult& r, const MachineInfo& machine, int repeats);
// The stage table as CSV: scene,backend,stage,median_s,min_s,max_s,calls.
std::string stage_csv(const std::vector<SceneResult>& results);
// One line per scene: total time per backend, each pair's ratio, divergence;
// then each pair's ratios by category and stage, and the verdict.
// `equal_accuracy` > 0: the backends ran at their own settings reaching that
// error (`compare --accuracy`): they differ by design and are not classified.
std::string summary_report_md(const std::vector<SceneResult>& results, const MachineInfo& machine, int repeats,
                              double equal_accuracy = 0);

// report.html: the same tables (converted from the markdown, so they never
// disagree) and inline SVG figures drawn by gnuplot — energy change, constraint
// violation, rotation drift and the divergence between backends over time.
// The summary's page answers first: the forest plot of the ratios, the
// verdict, then the tables.
std::string scene_report_html(const SceneResult& r, const MachineInfo& machine, int repeats);
// `work_precision`: figures (inline SVG and a caption) drawn before the
// verdict, after the forest plot: the rigid scenes' work-precision diagrams.
struct Figure {
  std::string svg, caption;
};
std::string summary_report_html(const std::vector<SceneResult>& results, const MachineInfo& machine, int repeats,
                                double equal_accuracy = 0, const std::vector<Figure>& work_precision = {});
// The pieces: markdown (headings, paragraphs, pipe tables) as HTML, and a
// self-contained page around a body.
std::string markdown_to_html(const std::string& md);
std::string html_escape(const std::string& text);  // <, >, & and " as entities
// `body_class` "overview": the summary's wider page, whose table cells never wrap.
std::string html_page(const std::string& title, const std::string& body, const std::string& body_class = "");
// An SVG document as an element to inline in a page (its XML prologue dropped).
std::string inline_svg(const std::string& svg);

// Writes results.json, report.md, report.html, stages.csv, trajectories.csv and
// replay.html (compare/replay.hpp) for one scene into `dir`, or, for
// several, one such folder per scene under `dir` plus dir/report.md and
// dir/stages.csv summarising them. Every file is written atomically.
// `equal_accuracy`: as for summary_report_md (and summary.json).
void write_reports(const std::filesystem::path& dir, const std::vector<SceneResult>& results,
                   const MachineInfo& machine, int repeats, double equal_accuracy = 0,
                   const std::vector<Figure>& work_precision = {});

// A time in the unit that suits it: "812 ns", "3.41 µs", "12.5 ms", "2.04 s".
std::string format_seconds(double s);

}  // namespace gacompare::compare
