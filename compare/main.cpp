// gacompare: runs physics scenes through the traditional and geometric-algebra
// backends and writes comparison reports. Results go to files, logs to stderr.
// Exit codes: 0 success, 1 a run or check failed, 2 bad usage or bad input.
#include "core/memory.hpp"
#include "compare/accuracy.hpp"
#include "compare/collide.hpp"
#include "compare/check.hpp"
#include "compare/cli_args.hpp"
#include "compare/diff.hpp"
#include "compare/files.hpp"
#include "compare/machine.hpp"
#include "compare/report.hpp"
#include "compare/runner.hpp"
#include "compare/suggest.hpp"
#include "compare/summary.hpp"
#include "compare/sweep.hpp"
#include "compare/escape.hpp"
#include "compare/stored.hpp"
#include "core/error.hpp"
#include "core/model/model.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/read_file.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <cmath>
#include <cstdio>
#include <tuple>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <sstream>
#include <unistd.h>

#ifndef GACOMPARE_DATA_DIR
#define GACOMPARE_DATA_DIR "data"
#endif

namespace fs = std::filesystem;
using namespace gacompare;

namespace {

// What a scene may ask of a run (core/model/budget.hpp): the defaults, raised by
// --max-samples, --max-steps and --max-memory.
core::Limits limits;

// Each scene loaded and its model compiled once, for every run of it.
std::vector<core::Compiled> load_all(const std::vector<std::string>& files) {
  std::vector<core::Compiled> scenes;
  std::set<std::string> names;
  for (const auto& f : files) {
    std::error_code ec;
    const auto& backends = compare::known_backends();
    if (std::find(backends.begin(), backends.end(), f) != backends.end() && !fs::is_regular_file(f, ec))
      throw input_error("'" + f + "' is a backend, not a scene file: give --backends comma-separated before the "
                        "scenes (--backends traditional,cga) or after them");
    scenes.push_back(core::load_compiled(f, limits));
    const std::string& name = scenes.back().scene.name;
    if (!names.insert(name).second)
      throw input_error(f + ": scene name '" + name + "' is used by another scene on the command line");
  }
  return scenes;
}

// reports/<what>-<date>, claimed so that two runs in one second get two folders.
fs::path default_out(const std::string& what) {
  std::string date = compare::machine_info().date;
  std::replace(date.begin(), date.end(), ':', '-');
  return compare::claim_default_folder(what, date);
}

// One line on stderr per round of repeats of each scene, whether stderr is a
// terminal or a log file (a long run must not look hung); nothing with --quiet.
compare::Progress progress_line(const std::string& scene, std::size_t k, std::size_t n, bool quiet) {
  if (quiet) return {};
  return [scene, k, n](int round, int rounds, const compare::SceneResult& so_far) {
    std::ostringstream o;
    o << "gacompare: [" << k + 1 << "/" << n << "] " << scene << ": repeat " << round << "/" << rounds;
    for (const auto& b : so_far.backends)
      if (!b.wall_seconds.empty()) o << ", " << b.run.backend << " " << compare::format_seconds(b.wall_seconds.back());
    std::cerr << o.str() << "\n";
  };
}

// The overview's work-precision diagrams: each rigid-body scene (bodies, no
// collisions) swept in memory with Cash–Karp 4(5) at tolerances 1e-4 … 1e-10
// through every backend and the quaternion twin, 3 timed repeats a cell,
// written beside the scene's report as <scene>/work_precision/ (sweep.md,
// sweep.html, the SVG). A scene whose sweep cannot run gets its reason in the
// caption and on stderr, and the comparison goes on.
std::vector<compare::Figure> rigid_work_precision(const std::vector<compare::SceneResult>& results,
                                                  const fs::path& dir, bool quiet) {
  std::vector<compare::Figure> figures;
  compare::SweepSpec spec;
  // Each family's representative at these tolerances: the report's Cash–Karp
  // (classical), Tsitouras 5(4) and Verner 8(7) (PI pairs; fastest at loose
  // and tight tolerances on the rigid scenes, docs/results/integrators.md),
  // and RKMK 4(5) (Lie group: the adaptive one, on the rotation's group).
  spec.solvers = {core::SolverMethod::cash_karp45, core::SolverMethod::tsit5, core::SolverMethod::vern8,
                  core::SolverMethod::rkmk45};
  spec.tol_from = 4, spec.tol_to = 10, spec.repeats = 3, spec.peer = false, spec.by_family = true;
  for (const auto& r : results) {
    if (compare::category_of(r.scene) != compare::Category::rigid_bodies) continue;
    const std::string name = compare::file_name_for(r.scene.name);
    if (!quiet) std::cerr << "gacompare: " << r.scene.name << ": work-precision diagram\n";
    try {
      const core::Scene swept = compare::swept_scene(r.scene, spec);
      const fs::path folder = dir / name / "work_precision";
      compare::write_sweep_report(folder, swept, compare::run_units(swept, spec), spec);
      const fs::path svg = folder / (name + "_work_precision.svg");
      figures.push_back({fs::exists(svg) ? core::read_file(svg, "work-precision diagram") : "",
                         compare::md_text(r.scene.name) + ": each backend's best method of each family (classical: "
                         "Cash–Karp 4(5); PI pairs: Tsitouras 5(4), Verner 8(7); Lie group: RKMK 4(5)) at tolerances 1e-4 to 1e-10, the "
                         "traditional backend as matrix and as quaternion; error against a 1e-13 reference, time the "
                         "median of 3 runs. Table, every method: [" + compare::md_text(r.scene.name) +
                             "/work_precision/sweep.md](" + name + "/work_precision/sweep.md)."});
    } catch (const Error& e) {
      std::cerr << "gacompare: " << r.scene.name << ": no work-precision diagram: " << e.what() << "\n";
      figures.push_back({"", compare::md_text(r.scene.name) + ": no work-precision diagram: " + compare::md_text(e.what())});
    }
  }
  return figures;
}

int run_and_report(const std::vector<core::Compiled>& scenes, const std::vector<std::string>& backends,
                   compare::Selection selection, int repeats, fs::path out, bool quiet, bool work_precision = false) {
  const bool claimed = out.empty();
  if (claimed) out = default_out(scenes.size() == 1 ? scenes.front().scene.name : "compare");
  compare::StagedFolder folder(out, claimed);  // before any work: a bad --out is exit 2 now, not after the runs
  const compare::MachineInfo machine = compare::machine_info();  // the load before this run adds its own
  std::vector<compare::SceneResult> results;
  bool failed = false;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const auto& scene = scenes[k].scene;
    results.push_back(compare::compare_scene(scene, scenes[k].model, backends, repeats, selection,
                                             progress_line(scene.name, k, scenes.size(), quiet)));
    for (const auto& b : results.back().backends)
      if (b.run.error) {
        std::cerr << "gacompare: " << scene.name << ": " << b.run.backend << ": " << *b.run.error << "\n";
        failed = true;
      }
  }
  std::vector<compare::Figure> figures;
  if (work_precision && results.size() > 1) figures = rigid_work_precision(results, folder.path(), quiet);
  compare::write_reports(folder.path(), results, compare::finished(machine), repeats, 0, figures);
  folder.commit();
  std::cout << out.string() << "\n";
  return failed ? 1 : 0;
}

// `compare --accuracy E`: each backend at the tolerance or step that reaches E
// (compare/accuracy.hpp), the settings cached in DIR/accuracy.json, then timed.
int run_at_accuracy(const std::vector<core::Compiled>& compiled, std::vector<std::string> backends, double target,
                    int repeats, fs::path out, bool quiet, compare::Selection selection) {
  std::vector<core::Scene> scenes;  // each trial compiles its own model (compare/accuracy.cpp)
  for (const auto& c : compiled) scenes.push_back(c.scene);
  const bool claimed = out.empty();
  if (claimed) out = default_out(scenes.size() == 1 ? scenes.front().name : "compare");
  compare::StagedFolder folder(out, claimed);
  const fs::path staged = folder.path();
  const compare::MachineInfo machine = compare::machine_info();
  std::erase(backends, "bullet");  // no tolerance to search: Bullet steps at a fixed 1/240 s with its own contacts
  if (backends.empty()) throw input_error("--accuracy: compares traditional and cga; name at least one of them");
  for (const auto& scene : scenes)  // refuse before anything runs
    if (const auto why = compare::accuracy_refusal(scene); !why.empty()) throw input_error(why);
  // The settings a previous run found go on into the new folder, checked there (compare/accuracy.hpp).
  std::error_code none;
  if (fs::exists(fs::symlink_status(out / "accuracy.json", none)))
    compare::write_file_atomically(staged / "accuracy.json", core::read_file(out / "accuracy.json", "accuracy cache"));
  std::vector<compare::SceneResult> results;
  std::vector<compare::AccuracyPlan> plans;
  bool failed = false;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const auto& scene = scenes[k];
    // The default adds the quaternion twin on a rigid-body scene (compare/runner.hpp).
    plans.push_back(compare::find_equal_accuracy(scene, target, compare::backends_for(scene, backends, selection),
                                                 staged / "accuracy.json", quiet));
    if (!quiet)
      std::cerr << "gacompare: " << scene.name << ": settings " << (plans.back().reused ? "reused" : "found") << "\n";
    results.push_back(
        compare::compare_at_accuracy(scene, plans.back(), repeats, progress_line(scene.name, k, scenes.size(), quiet)));
    for (const auto& b : results.back().backends)
      if (b.run.error) {
        std::cerr << "gacompare: " << scene.name << ": " << b.run.backend << ": " << *b.run.error << "\n";
        failed = true;
      }
  }
  compare::write_reports(staged, results, compare::finished(machine), repeats, target);
  std::string all;
  for (std::size_t k = 0; k < results.size(); ++k) {
    const std::string section = compare::accuracy_section_md(plans[k], results[k]);
    compare::insert_section(results.size() == 1 ? staged / "report.md" : staged / compare::file_name_for(results[k].scene.name) / "report.md", section);
    all += "\n# " + compare::md_text(results[k].scene.name) + "\n" + section;
  }
  compare::write_file_atomically(staged / "accuracy.md", "# Time at equal accuracy\n" + all);
  folder.commit();
  std::cout << out.string() << "\n";
  return failed ? 1 : 0;
}

// Reads a stored baseline (compare/stored.hpp); nullopt when there is none. A
// file that is there but is not a baseline is an input error naming it.
std::optional<compare::Baseline> read_baseline(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(fs::symlink_status(file, ec))) return std::nullopt;
  return compare::read_baseline(file);
}

// The table of check lines on stdout and "WHAT: n passed, m failed"; 1 when one
// failed, or when none passed: a check that compared nothing has shown nothing.
int print_lines(const std::vector<compare::CheckLine>& lines, const char* what) {
  std::cout << compare::check_table(lines);
  auto count = [&](compare::CheckLine::Verdict v) {
    return std::count_if(lines.begin(), lines.end(), [&](const auto& l) { return l.verdict == v; });
  };
  const auto failed = count(compare::CheckLine::Verdict::fail), passed = count(compare::CheckLine::Verdict::pass);
  std::cout << "\n" << what << ": " << passed << " passed, " << failed << " failed\n";
  if (passed == 0 && failed == 0)
    std::cerr << "gacompare: " << what << ": nothing was compared (0 passed): that is a failure, not a pass\n";
  return failed || passed == 0 ? 1 : 0;
}

int check_scenes(const std::vector<core::Compiled>& scenes, const fs::path& baseline_dir, bool update, int repeats,
                 std::optional<double> max_time_ratio, bool quiet) {
  std::error_code ec;
  if (max_time_ratio && update) throw input_error("--max-time-ratio: checks against a baseline; not with --update");
  if (max_time_ratio && repeats < 2)
    throw input_error("--max-time-ratio: a time's interval needs --repeat 2 or more (5 or more for a useful one)");
  if (!update && !fs::is_directory(baseline_dir, ec))
    throw input_error(baseline_dir.string() + ": no such baseline folder (create it with --update)");
  std::optional<compare::FolderLock> lock;
  if (update) lock.emplace(baseline_dir);
  std::vector<compare::CheckLine> lines;
  for (std::size_t k = 0; k < scenes.size(); ++k) {
    const auto& scene = scenes[k].scene;
    const fs::path file = compare::baseline_path(baseline_dir, scene.name);
    const auto baseline = read_baseline(file);
    if (!baseline && !update)
      throw input_error(file.string() + ": no baseline for scene '" + scene.name + "' (store one with --update)");
    // Our three backends only: their baselines and their agreement are what check
    // guards. Bullet's trajectories differ from ours by design (another
    // integrator, another contact model: compare/bullet_world.cpp), so neither a
    // Bullet baseline nor "the backends agree" with Bullet in it would mean a
    // regression; `gacompare compare` sets Bullet beside them instead.
    const auto result = compare::compare_scene(scene, scenes[k].model, {"traditional", "cga", "pga"}, repeats, compare::Selection::exactly,
                                               progress_line("check " + scene.name, k, scenes.size(), quiet));
    auto scene_lines = compare::check_scene(result, update ? std::nullopt : baseline, max_time_ratio);
    lines.insert(lines.end(), scene_lines.begin(), scene_lines.end());
    if (update) {
      compare::write_file_atomically(file, compare::baseline_json(result).dump(1) + "\n");
      lines.push_back({scene.name, "all", "baseline", 0, 0, compare::CheckLine::Verdict::info, "stored " + file.string()});
    }
  }
  return print_lines(lines, "check");
}

// `gacompare diff A B` (compare/diff.hpp): the two runs' provenance, the table,
// the count; exit 1 when a line failed.
int diff_command(const std::string& a, const std::string& b, std::optional<double> max_time_ratio,
                 std::optional<double> tolerance) {
  const auto runs_a = compare::read_runs(a), runs_b = compare::read_runs(b);
  const auto lines = compare::diff_runs(runs_a, runs_b, {max_time_ratio, tolerance});
  std::cout << compare::diff_header(runs_a, runs_b) << "\n";
  return print_lines(lines, "diff");
}

// "i/N" with 0 <= i < N.
std::pair<int, int> parse_shard(const std::string& text) {
  int i = -1, n = 0;
  char slash = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%d%c%d%c", &i, &slash, &n, &extra) != 3 || slash != '/' || n < 1 || i < 0 || i >= n)
    throw input_error("--shard '" + text + "': expected i/N with 0 <= i < N, e.g. 0/4");
  return {i, n};
}

// "1e-3:1e-12" → decades 3..12.
std::pair<int, int> parse_tolerances(const std::string& text) {
  double hi = 0, lo = 0;
  char colon = 0, extra = 0;
  auto decade = [](double x) { return static_cast<int>(std::lround(-std::log10(x))); };
  if (std::sscanf(text.c_str(), "%lf%c%lf%c", &hi, &colon, &lo, &extra) != 3 || colon != ':' || !(hi > 0) || !(lo > 0) ||
      !(lo <= hi) || std::abs(std::pow(10.0, -decade(hi)) / hi - 1) > 1e-9 || std::abs(std::pow(10.0, -decade(lo)) / lo - 1) > 1e-9)
    throw input_error("--tolerances '" + text + "': expected HI:LO, two powers of ten with HI >= LO, e.g. 1e-3:1e-12");
  return {decade(hi), decade(lo)};
}

// "1e-2:4" → first step and number of halvings.
std::pair<double, int> parse_steps(const std::string& text) {
  double dt = 0;
  int halvings = -1;
  char colon = 0, extra = 0;
  if (std::sscanf(text.c_str(), "%lf%c%d%c", &dt, &colon, &halvings, &extra) != 3 || colon != ':' || !(dt > 0) ||
      halvings < 0 || halvings > 30)
    throw input_error("--steps '" + text + "': expected DT:HALVINGS, e.g. 1e-2:4");
  return {dt, halvings};
}

nlohmann::ordered_json sweep_manifest(const core::Scene& scene, const compare::SweepSpec& spec,
                                      const std::vector<compare::Unit>& units) {
  nlohmann::ordered_json ids = nlohmann::ordered_json::array();
  for (const auto& u : units) ids.push_back(u.id);
  return {{"scene_file", fs::absolute(scene.file).string()}, {"scene_sha256", scene.sha256},
          {"repeats", spec.repeats}, {"max_duration", spec.max_duration},
          {"error", spec.error ? std::string(compare::measure_name(*spec.error)) : std::string("default")},
          {"build", spec.build}, {"units", ids}};
}

// The units' cells that are done with this key (each read and checked:
// compare/stored.hpp); `missing` counts the others, `stale` those of them whose
// cell is there but was written with another key or format (compare/sweep.hpp,
// cell_key): they are run again.
std::vector<compare::SweepCell> read_units(const fs::path& cells, const std::vector<compare::Unit>& units,
                                           const nlohmann::json& key, std::size_t& missing, std::size_t* stale = nullptr) {
  std::vector<compare::SweepCell> out;
  missing = 0;
  for (const auto& u : units) {
    const fs::path f = cells / (u.id + ".json");
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(f, ec))) {
      ++missing;
      continue;
    }
    compare::SweepCell cell = compare::parse_cell(core::read_file(f, "sweep cell"), f.string(), u.id);
    if (!compare::cell_is_current(cell, key)) {  // other settings, another build or format: run it again
      ++missing;
      if (stale) ++*stale;
      continue;
    }
    out.push_back(std::move(cell));
  }
  return out;
}

int run_sweep(const core::Scene& scene, const compare::SweepSpec& spec, const fs::path& out, std::pair<int, int> shard,
              bool quiet) {
  const core::Scene swept = compare::swept_scene(scene, spec);
  const auto units = compare::sweep_units(spec, swept);
  const compare::FolderLock lock(out);
  const fs::path cells = out / "cells";
  fs::create_directories(cells);
  compare::write_file_atomically(out / "sweep.json", sweep_manifest(scene, spec, units).dump(1) + "\n");
  std::optional<core::Run> reference;
  const nlohmann::json key = compare::cell_key(swept, spec);
  int ran = 0, skipped = 0;
  std::size_t stale = 0;
  for (std::size_t k = 0; k < units.size(); ++k) {
    if (static_cast<int>(k % static_cast<std::size_t>(shard.second)) != shard.first) continue;
    const fs::path f = cells / (units[k].id + ".json");
    std::size_t missing = 0;
    if (!read_units(cells, {units[k]}, key, missing, &stale).empty()) {  // done before: resume
      ++skipped;
      continue;
    }
    if (!reference) reference = compare::sweep_reference(swept);
    if (!quiet) std::cerr << "gacompare: sweep " << scene.name << ": " << units[k].id << "\n";
    compare::write_file_atomically(f, compare::run_unit(units[k], swept, *reference, spec).dump(1) + "\n");
    ++ran;
  }
  std::cerr << "gacompare: sweep " << scene.name << ": ran " << ran << " unit(s)"
            << (stale ? " (" + std::to_string(stale) + " done before with other settings, another build or format)" : "")
            << ", skipped " << skipped << " already done\n";
  std::size_t missing = 0;
  const auto done = read_units(cells, units, key, missing);
  if (missing == 0) compare::write_sweep_report(out, swept, done, spec);
  else std::cerr << "gacompare: sweep " << scene.name << ": " << missing << " unit(s) of other shards still to run; "
                 << "join the shards with gacompare merge\n";
  std::cout << out.string() << "\n";
  return 0;
}

int merge_sweeps(const std::vector<std::string>& dirs, const fs::path& out) {
  std::optional<compare::SweepManifest> manifest;
  for (const auto& d : dirs) {
    const fs::path file = fs::path(d) / "sweep.json";
    std::error_code ec;
    if (!fs::exists(fs::symlink_status(file, ec))) throw input_error(d + ": not a sweep folder (no sweep.json)");
    compare::SweepManifest m = compare::parse_manifest(core::read_file(file, "sweep manifest"), file.string());
    if (!manifest) manifest = std::move(m);
    else if (m.json != manifest->json)
      throw input_error(d + ": a different sweep (scene, settings, build or units) than " + dirs.front());
  }
  const core::Scene scene = core::load_scene(manifest->scene_file, limits);
  compare::StagedFolder folder(out);  // whole or not at all: a merge interrupted leaves the previous one
  if (scene.sha256 != manifest->scene_sha256)
    throw input_error(manifest->scene_file + ": the scene changed since the sweep ran (sha256 differs)");
  const fs::path cells = folder.path() / "cells";
  fs::create_directories(cells);
  // Each shard's cells, read as a sweep reads them (compare/stored.hpp: a
  // link, a device or a FIFO is refused, a cell is checked before it is copied).
  for (const auto& d : dirs) {
    const fs::path from = fs::path(d) / "cells";
    std::error_code ec;
    if (!fs::is_directory(fs::symlink_status(from, ec))) throw input_error(from.string() + ": no cells folder in this shard");
    for (fs::directory_iterator it(from, ec), end; !ec && it != end; it.increment(ec)) {
      const fs::path f = it->path();
      if (f.extension() != ".json" || f.filename().string().front() == '.') continue;  // temporaries
      const std::string text = core::read_file(f, "sweep cell");
      (void)compare::parse_cell(text, f.string(), f.stem().string());
      compare::write_file_atomically(cells / f.filename(), text);
    }
    if (ec) throw input_error(from.string() + ": cannot list the cells: " + ec.message());
  }
  compare::write_file_atomically(folder.path() / "sweep.json", manifest->json.dump(1) + "\n");
  // The units come from the manifest; their records carry everything else.
  std::vector<compare::Unit> units;
  for (const auto& id : manifest->units) units.push_back({id, "", "", {}});
  compare::SweepSpec spec;
  spec.repeats = manifest->repeats;
  spec.max_duration = manifest->max_duration;
  spec.error = compare::measure_from_string(manifest->error);  // the shards' --error ("default": none)
  spec.build = manifest->build;  // the shards' build, not this one's
  const core::Scene swept = compare::swept_scene(scene, spec);
  std::size_t missing = 0;
  const auto done = read_units(cells, units, compare::cell_key(swept, spec), missing);
  if (missing) throw run_error(out.string() + ": " + std::to_string(missing) + " unit(s) missing from the shards given");
  compare::write_sweep_report(folder.path(), swept, done, spec);
  folder.commit();
  std::cout << out.string() << "\n";
  return 0;
}

// `gacompare collide`: the JSON array on stdout (or --out), the table on stderr
// (or --table FILE). Exit 1 when a backend disagrees with the reference on a
// pair outside the touching band (the referees' disagreements are reported, not
// failed: FCL's and Bullet's answers are what the comparison is about).
int collide_files(const std::vector<std::string>& files, const compare::CollideOptions& options, const std::string& out,
                  const std::string& table) {
  std::vector<collision::CollisionCase> cases;
  for (const auto& f : files) {
    auto more = collision::load_cases(f);
    for (auto& c : more) cases.push_back(std::move(c));
  }
  const nlohmann::json entries = compare::collide(cases, options);
  if (out.empty()) std::cout << entries.dump(1) << "\n";
  else compare::write_file_atomically(out, entries.dump(1) + "\n");
  const std::string summary = compare::collide_table(entries);
  if (table.empty() || table == "-") std::cerr << summary;
  else compare::write_file_atomically(table, summary);
  int failed = 0;
  for (const auto& e : entries)
    for (const auto& m : e["disagree"])
      if (compare::our_method(m)) {
        std::cerr << "gacompare: collide: " << e["name"].get<std::string>() << ": " << m.get<std::string>()
                  << " disagrees with the separating-axis reference\n";
        ++failed;
      }
  return failed ? 1 : 0;
}

int list_scenes(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw input_error(dir.string() + ": not a folder of scenes");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  // A scene that does not load — broken, or over the run budgets (so that
  // `list` with the same --max-samples, --max-steps, --max-memory tells what
  // `run` would accept) — is named on stderr with its reason and the others
  // are still listed; then the exit code is 2.
  int broken = 0;
  for (const auto& f : files) {
    try {
      const auto s = core::load_compiled(f, limits).scene;
      std::cout << f.string() << "\t" << s.name << "\t" << s.description << "\n";
    } catch (const gacompare::Error& e) {
      if (e.kind() != ErrorKind::input) throw;
      std::cerr << "gacompare: list: " << e.what() << "\n";
      ++broken;
    }
  }
  return broken ? 2 : 0;
}

}  // namespace

// Spellings the command line no longer takes, refused with the one it does.
constexpr std::pair<const char*, const char*> kRenamed[] = {{"--repeats", "--repeat"}};

// Answers before CLI11 parses: a renamed option, or a first word that is not a
// command ("A subcommand is required" says nothing about "comapre"). Returns the
// message, or "" when the line may be parsed.
std::string precheck(int argc, char** argv, const CLI::App& app) {
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--") break;
    for (const auto& [old, now] : kRenamed)
      if (arg == old || arg.rfind(std::string(old) + "=", 0) == 0)
        return std::string(old) + " is spelt " + now + " in every command now (e.g. " + now + " 5)";
  }
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (!arg.empty() && arg[0] == '-') {  // the global flags (-q, --help, --version) and options (--max-steps N)
      const CLI::Option* o = arg.find('=') == std::string::npos ? app.get_option_no_throw(arg) : nullptr;
      if (o != nullptr && o->get_items_expected_min() > 0) ++i;  // its value is not a command
      continue;
    }
    std::vector<std::string> names;
    for (const auto* sub : app.get_subcommands([](const CLI::App*) { return true; })) names.push_back(sub->get_name());
    if (std::find(names.begin(), names.end(), arg) != names.end()) return "";
    return compare::not_one_of("command", arg, names);
  }
  return "";
}

int main(int argc, char** argv) {
  gacompare::core::keep_freed_memory();  // core/memory.hpp: a stack's solves no longer shrink and regrow the heap
  namespace cli = compare::cli;
  CLI::App app{"gacompare: traditional vs geometric-algebra physics, stage by stage"};
  // Progress goes to stderr, one line per scene and repeat, terminal or not; --quiet silences it.
  app.set_version_flag("--version", "gacompare " + compare::tool_version());
  app.require_subcommand(1);
  app.fallthrough();  // global flags (--quiet) may follow the subcommand
  app.option_defaults()->always_capture_default();  // every default shown in --help
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");
  // Budgets decided at load, before any work (core/model/budget.hpp): raise them for a scene that needs more.
  app.add_option("--max-samples", limits.max_samples, "most output samples a scene may ask for (default 1e6)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-steps", limits.max_steps, "most solver or collision steps of one run (default 1e8)")
      ->check(CLI::PositiveNumber);
  app.add_option("--max-memory", limits.max_memory_mb, "most MB the samples of one run may take (default 4096)")
      ->check(CLI::PositiveNumber);
  // Every file read (scenes, meshes, results, baselines, cells) is bounded (core/read_file.hpp).
  double max_input_mb = static_cast<double>(core::kDefaultMaxInputBytes) / 1e6;
  app.add_option("--max-input-mb", max_input_mb, "most MB one input file may hold (default 256)")
      ->check(cli::positive_number());
  // The stages' threads (core/parallel.hpp): results are the same for any number.
  int threads = 1;
  app.add_option("--threads", threads, "threads the stages may use (default 1; results are bit-identical for any)")
      ->check(cli::whole_number(1, 256));
  const auto backend_check = cli::one_of("backend", compare::known_backends());
  const auto repeat_check = cli::whole_number(1, compare::kMaxRepeats);

  std::string run_scene, run_backend, run_out;
  int run_repeat = 1;
  auto* run = app.add_subcommand("run", "run one scene through one backend");
  run->add_option("scene", run_scene, "scene file (JSON)")->required();
  run->add_option("--backend", run_backend, "traditional, traditional-matrix, traditional-quaternion, cga, pga or bullet")->required()->check(backend_check);
  run->add_option("--out", run_out, "report folder (default reports/<scene>-<date>)")->default_str("");
  run->add_option("--repeat", run_repeat, "repeats, for the timing spread")->check(repeat_check);

  std::vector<std::string> cmp_scenes, cmp_backends = compare::backend_names();
  std::string cmp_out;
  int cmp_repeat = 5;
  double cmp_accuracy = 0;
  bool cmp_no_work_precision = false;
  auto* cmp = app.add_subcommand("compare", "run scenes through every backend and compare");
  cmp->add_option("scenes", cmp_scenes, "scene files (JSON)")->required();
  cmp->add_option("--out", cmp_out, "report folder (default reports/<scene or compare>-<date>)")->default_str("");
  cmp->add_option("--repeat", cmp_repeat, "repeats per backend, interleaved")->check(repeat_check);
  // Without --backends: all of them, bullet only on the scenes it suits
  // (compare::Selection::where_supported); with it, exactly the ones named.
  // One value per occurrence (comma-separated), so an option before the scenes
  // cannot swallow them.
  auto* cmp_backends_opt = cmp->add_option("--backends", cmp_backends,
                                           "backends to run, exactly these, comma-separated (default: traditional, "
                                           "cga, pga, traditional-quaternion beside traditional on rigid-body "
                                           "scenes, and bullet on scenes with collisions that Bullet can simulate)")
                               ->delimiter(',')
                               ->allow_extra_args(false)
                               ->check(backend_check);
  cmp->add_flag("--no-work-precision", cmp_no_work_precision,
                "leave out the overview's work-precision diagrams of the rigid-body scenes (a small sweep of each: "
                "Cash-Karp at 1e-4 to 1e-10, 3 repeats)");
  cmp->add_option("--accuracy", cmp_accuracy,
                  "time at equal accuracy: each backend at the tolerance (or step) where its final error against a "
                  "1e-14 reference is <= E (rad for bodies without particles, m otherwise); cached in DIR/accuracy.json")
      ->check(cli::positive_number())
      ->default_str("off");

  std::vector<std::string> chk_scenes;
  std::string chk_baseline;
  bool chk_update = false;
  int chk_repeat = 1;
  double chk_max_time_ratio = 0;
  auto* chk = app.add_subcommand("check", "regression checks: backends against each other and against stored baselines");
  chk->add_option("scenes", chk_scenes, "scene files (JSON)")->required();
  chk->add_option("--baseline", chk_baseline, "folder of baselines, one SCENE.json per scene")->required();
  chk->add_flag("--update", chk_update, "store fresh baselines instead of comparing with them");
  chk->add_option("--repeat", chk_repeat, "repeats per backend, for the timing ratio")->check(repeat_check);
  chk->add_option("--max-time-ratio", chk_max_time_ratio,
                  "fail when the 95% interval of time / baseline time lies above R (needs --repeat 2 or more and a "
                  "baseline stored with repeats)")
      ->check(cli::positive_number())
      ->default_str("off: time is reported, not checked");

  std::string sw_scene, sw_out, sw_shard = "0/1", sw_tol = "1e-3:1e-12", sw_steps = "1e-2:4";
  std::vector<std::string> sw_solvers{"euler", "rk4", "rk4_doubling", "cash_karp45", "symplectic_euler", "velocity_verlet"};
  int sw_repeat = 3;
  double sw_max_duration = 0;
  bool sw_no_peer = false;
  std::string sw_error;
  auto* sw = app.add_subcommand("sweep", "what accuracy costs in time: every solver x tolerance or step x backend");
  sw->add_option("scene", sw_scene, "scene file (JSON)")->required();
  sw->add_option("--out", sw_out, "sweep folder (cells/, sweep.md, sweep.csv, the diagram)")->required();
  sw->add_option("--solvers", sw_solvers, "solvers to sweep, comma-separated (docs/scenes.md: solver.method)")->delimiter(',')->allow_extra_args(false);
  sw->add_option("--tolerances", sw_tol, "adaptive solvers: HI:LO, powers of ten");
  sw->add_option("--steps", sw_steps, "fixed-step solvers: DT:HALVINGS");
  sw->add_option("--repeat", sw_repeat, "timed runs per cell after one warm-up")->check(repeat_check);
  sw->add_option("--max-duration", sw_max_duration, "cut the scene to this many seconds")
      ->check(cli::positive_number())
      ->default_str("the scene's duration");
  sw->add_option("--shard", sw_shard, "run every N-th unit, starting at i: i/N (join with merge)");
  sw->add_flag("--no-peer", sw_no_peer, "leave out Boost.Odeint's Cash-Karp and Dormand-Prince");
  sw->add_option("--error", sw_error,
                 "the diagram's x-axis, the error at the end: position|orientation|velocity|angular_velocity")
      ->check(cli::one_of("measure", {"position", "orientation", "velocity", "angular_velocity"}))
      ->default_str("orientation for a scene of bodies, position with particles");

  std::vector<std::string> mg_dirs;
  std::string mg_out;
  auto* mg = app.add_subcommand("merge", "join the folders of a sharded sweep and write its report");
  mg->add_option("dirs", mg_dirs, "the shards' sweep folders")->required();
  mg->add_option("--out", mg_out, "the merged sweep folder")->required();

  std::string diff_a, diff_b;
  std::optional<double> diff_max_time_ratio, diff_tolerance;
  auto* dif = app.add_subcommand("diff", "two runs (or two commits) compared: time ratios with 95% intervals, "
                                         "state differences");
  dif->add_option("A", diff_a, "the first run: a report folder or its results.json")->required();
  dif->add_option("B", diff_b, "the second run, compared with the first (ratios are B / A)")->required();
  dif->add_option("--max-time-ratio", diff_max_time_ratio,
                  "fail when a 95% interval of B / A time lies above R")
      ->check(cli::positive_number())
      ->default_str("off: time is reported, not checked");
  dif->add_option("--tolerance", diff_tolerance,
                  "fail when B's state moves from A's by more than D m at any sample (orientation by D / r, ...: the "
                  "bounds of check)")
      ->check(cli::positive_number())
      ->default_str("each scene's check.baseline_tolerance");

  std::string list_dir = std::string(GACOMPARE_DATA_DIR) + "/scenes";
  auto* list = app.add_subcommand("list", "list the bundled scenes");
  list->add_option("--scenes", list_dir, "folder of scene files");

  std::vector<std::string> col_files;
  compare::CollideOptions col_options;
  std::string col_out, col_table, col_disagree;
  auto* col = app.add_subcommand("collide", "narrowphase of convex pairs: both backends, the exact SAT, FCL and Bullet");
  col->add_option("cases", col_files, "case files (JSON array of {\"a\": body, \"b\": body})")->required();
  col->add_option("--repeat", col_options.repeat, "timed queries per method and pair, interleaved")
      ->check(cli::whole_number(1));  // not read back by diff: not held to kMaxRepeats
  col->add_option("--out", col_out, "write the JSON array here instead of stdout")->default_str("stdout");
  col->add_option("--table", col_table, "write the agreement table (markdown) here instead of stderr")->default_str("stderr");
  col->add_option("--disagreements", col_disagree, "folder for replayable case files of every disagreement")
      ->default_str("none written");

  std::uint64_t corpus_seed = 2026;
  int corpus_count = 200;
  std::string corpus_out;
  auto* corpus = app.add_subcommand("corpus", "write the seeded random collision corpus (data/collision/random.json)");
  corpus->add_option("--seed", corpus_seed, "random seed");
  corpus->add_option("--count", corpus_count, "pairs")->check(cli::whole_number(1, 1'000'000));
  corpus->add_option("--out", corpus_out, "case file to write")->required();

  if (const std::string why = precheck(argc, argv, app); !why.empty()) {
    std::cerr << "gacompare: " << why << " (see gacompare --help)\n";
    return 2;
  }
  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "gacompare: " << e.what() << " (see gacompare --help)\n";
    return 2;
  }

  core::set_max_input_bytes(static_cast<std::uint64_t>(std::min(max_input_mb * 1e6, 1e18)));
  core::set_threads(threads);
  try {
    if (*run)
      return run_and_report(load_all({run_scene}), {run_backend}, compare::Selection::exactly, run_repeat, run_out, quiet);
    if (*cmp && cmp_accuracy > 0)
      return run_at_accuracy(load_all(cmp_scenes), cmp_backends, cmp_accuracy, cmp_repeat, cmp_out, quiet,
                             cmp_backends_opt->count() > 0 ? compare::Selection::exactly
                                                           : compare::Selection::where_supported);
    if (*cmp)
      return run_and_report(load_all(cmp_scenes), cmp_backends,
                            cmp_backends_opt->count() > 0 ? compare::Selection::exactly
                                                          : compare::Selection::where_supported,
                            cmp_repeat, cmp_out, quiet, !cmp_no_work_precision);
    if (*chk) {
      std::optional<double> max_time_ratio;
      if (chk_max_time_ratio > 0) max_time_ratio = chk_max_time_ratio;
      return check_scenes(load_all(chk_scenes), chk_baseline, chk_update, chk_repeat, max_time_ratio, quiet);
    }
    if (*dif) return diff_command(diff_a, diff_b, diff_max_time_ratio, diff_tolerance);
    if (*sw) {
      compare::SweepSpec spec;
      for (const auto& n : sw_solvers) {
        const auto m = core::solver_method_from_string(n);
        if (!m) {
          std::string names;
          for (const auto name : core::solver_method_names()) names += (names.empty() ? "" : ", ") + std::string(name);
          throw input_error("--solvers: unknown solver '" + n + "' (one of " + names + ")");
        }
        spec.solvers.push_back(*m);
      }
      std::tie(spec.tol_from, spec.tol_to) = parse_tolerances(sw_tol);
      std::tie(spec.dt_from, spec.dt_halvings) = parse_steps(sw_steps);
      spec.repeats = sw_repeat;
      spec.build = compare::build_info().commit;
      spec.max_duration = sw_max_duration;
      spec.peer = !sw_no_peer;
      if (!sw_error.empty()) spec.error = compare::measure_from_string(sw_error);
      const auto shard = parse_shard(sw_shard);
      const core::Scene scene = core::load_compiled(sw_scene, limits).scene;
      if (spec.error && compare::body_only(*spec.error) && scene.bodies.empty())
        throw input_error("--error " + sw_error + ": the scene '" + scene.name + "' has no bodies");
      return run_sweep(scene, spec, sw_out, shard, quiet);
    }
    if (*mg) return merge_sweeps(mg_dirs, mg_out);
    if (*list) return list_scenes(list_dir);
    if (*col) {
      col_options.disagreements = col_disagree;
      return collide_files(col_files, col_options, col_out, col_table);
    }
    if (*corpus) {
      compare::write_file_atomically(corpus_out, compare::random_corpus(corpus_seed, corpus_count).dump(1) + "\n");
      return 0;
    }
  } catch (const gacompare::Error& e) {
    std::cerr << "gacompare: " << e.what() << "\n";
    return e.kind() == ErrorKind::input ? 2 : 1;
  } catch (const std::exception& e) {
    std::cerr << "gacompare: internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
