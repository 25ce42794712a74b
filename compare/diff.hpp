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

// A results.json (followed if a link: the user named it), or a report folder:
// its results.json (one scene) or each of its scene folders' (a run of
// several), never through a link. Each is read and checked as
// compare/stored.hpp says; throws input_error naming the path when it is
// neither, or the file and JSON path of what is wrong in one.
std::vector<StoredResults> read_runs(const std::filesystem::path& path);

struct DiffOptions {
  // Fail when a time ratio's whole interval lies above this; nullopt: report only.
  std::optional<double> max_time_ratio;
  // d (m) for the state bounds; nullopt: each scene's check.baseline_tolerance, as A stored it.
  std::optional<double> tolerance;
};

// Every scene in both, in A's order: the time lines, then the state lines, of
// each backend in both. What B lacks fails (a scene or a backend's run in A
// only, samples B does not have or at other times, a run that stopped early in
// B and not in A, no scene in common at all); what B adds is an info line, as
// is a scene whose file changed (sha256), whose states are then not compared.
std::vector<CheckLine> diff_runs(const std::vector<StoredResults>& a, const std::vector<StoredResults>& b,
                                 const DiffOptions& options);

// A's and B's provenance, one line each: path, commit (dirty or not), CPU,
// usable CPUs, load average at the start, date, repeats.
std::string diff_header(const std::vector<StoredResults>& a, const std::vector<StoredResults>& b);

}  // namespace gacompare::compare
