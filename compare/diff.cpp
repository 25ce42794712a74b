#include "compare/diff.hpp"

#include "compare/report.hpp"
#include "compare/stats.hpp"
#include "core/error.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <cstdio>
#include <map>
#include <set>
#include <sstream>

namespace gacompare::compare {

namespace {
namespace fs = std::filesystem;

// Seconds per repeat: of one stage, or (stage "") of all stages together.
std::vector<double> repeat_seconds(const StoredRun& run, const std::string& stage) {
  std::vector<double> out;
  for (const auto& [name, each] : run.stage_seconds) {
    if (!stage.empty() && name != stage) continue;
    if (out.size() < each.size()) out.resize(each.size(), 0.0);
    for (std::size_t i = 0; i < each.size(); ++i) out[i] += each[i];
  }
  return out;
}

const StoredRun* find_run(const StoredResults& results, const std::string& backend) {
  for (const auto& r : results.runs)
    if (r.backend == backend) return &r;
  return nullptr;
}

std::string fmt(double x) {
  char buf[32];
  std::snprintf(buf, sizeof buf, "%.3g", x);
  return buf;
}

CheckLine info(const std::string& scene, const std::string& backend, const std::string& what, const std::string& note) {
  return {scene, backend, what, 0, 0, CheckLine::Verdict::info, note};
}

CheckLine fail(const std::string& scene, const std::string& backend, const std::string& what, const std::string& note) {
  return {scene, backend, what, 0, 0, CheckLine::Verdict::fail, note};
}

void diff_scene(const StoredResults& a, const StoredResults& b, const DiffOptions& options, std::vector<CheckLine>& out) {
  const StateObjects& objects = a.objects;
  const std::string& name = objects.scene;
  const bool same_scene = a.sha256 == b.sha256;
  if (!same_scene)
    out.push_back(info(name, "all", "scene", "the scene file differs between A and B (sha256): times compared, "
                                             "states not"));
  const double d = options.tolerance.value_or(a.baseline_tolerance);
  const std::string d_name = options.tolerance ? "--tolerance" : "check.baseline_tolerance";
  for (const auto& run_a : a.runs) {
    const std::string& backend = run_a.backend;
    const StoredRun* run_b = find_run(b, backend);
    if (!run_b) {
      out.push_back(fail(name, backend, "run", "in A only: B has no run of this backend to compare"));
      continue;
    }
    // Time: each stage either ran, then all stages together.
    std::set<std::string> stages;
    for (const auto& [stage, _] : run_a.stage_seconds) stages.insert(stage);
    for (const auto& [stage, _] : run_b->stage_seconds) stages.insert(stage);
    for (int k = 0; k <= core::kStageCount; ++k) {
      const std::string stage = k < core::kStageCount ? std::string(core::stage_name(static_cast<core::Stage>(k))) : "";
      if (!stage.empty() && !stages.count(stage)) continue;
      const std::string what = (stage.empty() ? std::string("all stages") : "`" + stage + "`") + " time, B / A";
      const bool in_a = stage.empty() || run_a.stage_seconds.count(stage);
      const bool in_b = stage.empty() || run_b->stage_seconds.count(stage);
      if (!in_a || !in_b) {
        out.push_back(info(name, backend, what, std::string("ran in ") + (in_a ? "A" : "B") + " only"));
        continue;
      }
      const auto ta = repeat_seconds(run_a, stage), tb = repeat_seconds(*run_b, stage);
      CheckLine l = time_ratio_line(name, backend, what, ta, tb, options.max_time_ratio);
      // The ratio is of medians (what the interval is of), with each side's
      // spread: a slow repeat shows as a max far from its median.
      const auto times = [](const std::vector<double>& t) {
        const Spread sp = spread(t);
        return format_seconds(sp.median) + " (" + format_seconds(sp.min) + "–" + format_seconds(sp.max) + ")";
      };
      l.note = "A " + times(ta) + ", B " + times(tb) + "; " + l.note;
      out.push_back(std::move(l));
    }
    // State: B's samples against A's, pair by pair.
    const bool stopped_a = run_a.error.has_value(), stopped_b = run_b->error.has_value();
    if (stopped_b && !stopped_a) out.push_back(fail(name, backend, "run", "B stopped early: " + *run_b->error));
    if (!same_scene) continue;
    const auto& sa = run_a.samples;
    const auto& sb = run_b->samples;
    StateBounds bounds(objects, d);
    std::size_t compared = 0;
    for (; compared < std::min(sa.size(), sb.size()) && sa[compared].t == sb[compared].t; ++compared)
      bounds.add(sa[compared], sb[compared]);
    if (compared < std::max(sa.size(), sb.size())) {
      // Fewer samples in B than in A, or samples at other times, is less than
      // B should have (B stopping early has failed above); more in B, where A
      // stopped early, is an improvement.
      const bool parted = compared < std::min(sa.size(), sb.size());
      const bool b_short = sb.size() < sa.size() && !stopped_b;
      CheckLine l = info(name, backend, "samples",
                         "compared the first " + std::to_string(compared) + " (A has " + std::to_string(sa.size()) +
                             ", B " + std::to_string(sb.size()) + (parted ? "; their times part there)" : ")"));
      if (parted || b_short) l.verdict = CheckLine::Verdict::fail;
      out.push_back(std::move(l));
    }
    for (const Measure m : kMeasures) {
      const std::string what = m == Measure::position ? std::string("largest position difference, B − A (m)")
                                                      : "largest " + std::string(measure_words(m)) + " difference, B − A (" +
                                                            std::string(measure_unit(m)) + ")";
      if (auto l = bounds.line(m, backend, what, d_name + " = " + fmt(d) + " m")) out.push_back(*l);
    }
  }
  for (const auto& run_b : b.runs)
    if (!find_run(a, run_b.backend)) out.push_back(info(name, run_b.backend, "run", "in B only"));
}

std::string provenance(const std::vector<StoredResults>& runs) {
  if (runs.empty()) return "nothing";
  const StoredResults& r = runs.front();
  const StoredMachine& m = r.machine;
  std::ostringstream o;
  o << r.file.parent_path().string() << (runs.size() > 1 ? " and " + std::to_string(runs.size() - 1) + " more" : "")
    << ": commit " << m.commit.value_or("unknown").substr(0, 12);
  if (m.dirty) o << (*m.dirty ? " (dirty)" : "");
  else o << " (tree state unknown)";
  o << ", " << m.cpu.value_or("unknown CPU");
  if (m.usable_cpus) o << ", " << *m.usable_cpus << " CPUs usable";
  if (m.load) o << ", load " << fmt(*m.load) << " at the start";
  o << ", " << m.date.value_or("no date") << ", " << r.repeats << " repeats";
  return o.str();
}
}  // namespace

std::vector<StoredResults> read_runs(const fs::path& path) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(path, ec)))
    throw input_error(core::one_line(path.string() + ": no such results.json or report folder"));
  if (!fs::is_directory(path, ec)) return {read_results(path, core::Links::follow)};  // the user named it
  if (fs::exists(fs::symlink_status(path / "results.json", ec))) return {read_results(path / "results.json", core::Links::refuse)};
  std::vector<fs::path> files;
  for (fs::directory_iterator it(path, ec), end; !ec && it != end; it.increment(ec)) {
    const auto status = it->symlink_status(ec);
    if (fs::is_symlink(status))
      throw input_error(core::one_line(it->path().string() + ": a symbolic link in a report folder (not followed: it could lead anywhere)"));
    if (fs::is_directory(status) && fs::exists(fs::symlink_status(it->path() / "results.json", ec)))
      files.push_back(it->path() / "results.json");
  }
  if (ec) throw input_error(core::one_line(path.string() + ": cannot list the report folder: " + ec.message()));
  if (files.empty()) throw input_error(core::one_line(path.string() + ": no results.json in it or in its folders"));
  std::sort(files.begin(), files.end());
  std::vector<StoredResults> out;
  for (const auto& f : files) out.push_back(read_results(f, core::Links::refuse));
  return out;
}

std::vector<CheckLine> diff_runs(const std::vector<StoredResults>& a, const std::vector<StoredResults>& b,
                                 const DiffOptions& options) {
  std::map<std::string, const StoredResults*> in_b;
  for (const auto& f : b) in_b[f.objects.scene] = &f;
  std::vector<CheckLine> out;
  std::set<std::string> seen;
  for (const auto& f : a) {
    const std::string& name = f.objects.scene;
    seen.insert(name);
    const auto it = in_b.find(name);
    if (it == in_b.end()) out.push_back(fail(name, "all", "scene", "in A only: B has no run of this scene to compare"));
    else diff_scene(f, *it->second, options, out);
  }
  for (const auto& [name, _] : in_b)
    if (!seen.count(name)) out.push_back(info(name, "all", "scene", "in B only"));
  if (std::none_of(a.begin(), a.end(), [&](const StoredResults& f) { return in_b.count(f.objects.scene) > 0; }))
    out.push_back(fail("all", "all", "scenes", "A and B have no scene in common: nothing was compared"));
  return out;
}

std::string diff_header(const std::vector<StoredResults>& a, const std::vector<StoredResults>& b) {
  return "A: " + provenance(a) + "\nB: " + provenance(b) + "\n";
}

}  // namespace gacompare::compare
