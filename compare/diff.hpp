#pragma once
// `gacompare diff A B`: two runs, or the same scenes at two commits, compared
// from what they wrote (results.json), nothing run again. Per scene, backend
// and stage (and all stages together) the time ratio B / A of the median
// times per repeat, with its 95% interval: A's repeats and B's did not run side
// by side, so the interval is the two-sample bootstrap's (compare/stats.hpp,
// bootstrap_unpaired_ratio, which says why medians), not the paired one the
// reports use between backends. "Within noise" when it holds 1. And per scene and backend the largest state difference between A's
// and B's samples, measured as `check` measures one (compare/check.hpp,
// StateBounds: no point of a body may move by more than d).
#include "compare/check.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace gacompare::compare {

// One scene's results.json and where it was read from.
struct RunFile {
  std::filesystem::path file;
  nlohmann::json results;
};

// A results.json, or a report folder: its results.json (one scene) or each of
// its scene folders' (a run of several). Throws input_error naming the path
// when it is neither, or a file is not a gacompare results.json.
std::vector<RunFile> read_runs(const std::filesystem::path& path);

struct DiffOptions {
  // Fail when a time ratio's whole interval lies above this; nullopt: report only.
  std::optional<double> max_time_ratio;
  // d (m) for the state bounds; nullopt: each scene's check.baseline_tolerance, as A stored it.
  std::optional<double> tolerance;
};

// Every scene in both, in A's order: the time lines, then the state lines, of
// each backend in both; a scene or backend in one only is an info line, as is a
// scene whose file changed (sha256), whose states are then not compared. A run
// that stopped early in B (and not in A) fails. Throws input_error naming the
// file and JSON path where a results.json lacks what the diff reads (one
// written before results.json carried its scene's bodies: run it again).
std::vector<CheckLine> diff_runs(const std::vector<RunFile>& a, const std::vector<RunFile>& b,
                                 const DiffOptions& options);

// A's and B's provenance, one line each: path, commit (dirty or not), CPU,
// usable CPUs, load average at the start, date, repeats.
std::string diff_header(const std::vector<RunFile>& a, const std::vector<RunFile>& b);

}  // namespace gacompare::compare
