#pragma once
// What gacompare reads back from files it wrote (results.json, baselines,
// sweep cells and manifests, accuracy caches), checked before it is trusted: a
// folder handed over may be truncated, emptied, edited or hostile. Each file
// is read as core/read_file.hpp reads (regular, bounded, links refused where
// the path was found in a folder), parsed, and turned into plain records here,
// so that nothing after this reads JSON: anything missing, of the wrong type
// or out of range is an input_error (exit 2) naming the file and its JSON path.
// The checks are of what the file itself must hold: sample times finite and
// increasing, as many samples as the run's duration gives unless it stopped
// early, every object's state in every sample, one time per repeat for every
// stage, times in [0, 1e9] s, repeats in [1, kMaxRepeats].
#include "core/read_file.hpp"
#include "core/run.hpp"

#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace gacompare::compare {

// The most repeats a run may ask for (--repeat) and a file may hold: diff's
// bootstrap recomputes the medians 20,000 times per line, in time linear in the
// repeats (measured on this 2-core machine under load: 0.9 s a line at 1,000),
// and a diff has up to 40 lines (4 backends × 9 stages and all together), so
// 200 keeps the slowest diff a file can ask for to seconds.
inline constexpr int kMaxRepeats = 200;
// The most runs a results.json or a baseline holds: one per backend
// (traditional, cga, pga, bullet); a cell's variants of one setting are as many.
inline constexpr std::size_t kMaxRuns = 4;
// The longest time a file may store, s (31 years): anything above is not a measurement.
inline constexpr double kMaxSeconds = 1e9;

// A JSON value with where it came from: every accessor checks what it reads
// and throws input_error "FILE: /json/path: expected ..., got ..." otherwise.
class Field {
 public:
  Field(std::string file, const nlohmann::json& j, std::string path = "") : file_(std::move(file)), j_(&j), path_(std::move(path)) {}
  Field operator[](std::string_view key) const;              // a member that must be there
  std::optional<Field> find(std::string_view key) const;     // a member that may be absent (or null)
  Field operator[](std::size_t i) const;                     // an element of an array
  std::size_t size(std::size_t lo, std::size_t hi) const;    // an array of lo to hi elements
  std::vector<std::pair<std::string, Field>> members() const;  // an object's members, in file order
  double number(double lo, double hi) const;                 // a finite number in [lo, hi]
  double number_or_null(double lo, double hi, double null_is) const;
  std::uint64_t whole(std::uint64_t lo, std::uint64_t hi) const;  // a whole number in [lo, hi]
  std::string text(std::size_t max_bytes = 1000) const;      // a string
  bool boolean() const;
  Eigen::Vector3d vec3() const;                              // [x, y, z], each finite or null (NaN)
  Eigen::Vector4d vec4() const;
  [[noreturn]] void fail(const std::string& expected) const;  // "expected " + expected + ", got ..."
  const nlohmann::json& json() const { return *j_; }
  const std::string& path() const { return path_; }
  const std::string& file() const { return file_; }

 private:
  const nlohmann::json& object() const;
  std::string file_;
  const nlohmann::json* j_;
  std::string path_;
};

// JSON text parsed, or input_error "FILE: malformed JSON: ..." (nlohmann's message kept to one line).
nlohmann::json parse_stored(const std::string& text, const std::string& file);

// What the state bounds need to know of a scene's objects, in scene order:
// from a Scene (state_objects) or from a results.json (`gacompare diff`).
struct StateObjects {
  std::string scene;
  double output_every = 0;  // Δt, s
  std::vector<std::string> particles;
  struct Body {
    std::string name;
    double radius = 0;  // compare/metrics.hpp's body_radii
    bool is_static = false;
  };
  std::vector<Body> bodies;
};

// ---- results.json ---------------------------------------------------------------------

struct StoredRun {
  std::string backend;
  std::vector<core::Sample> samples;  // position, orientation, velocity, angular velocity; objects in scene order
  std::map<std::string, std::vector<double>> stage_seconds;  // each stage that ran: seconds of each repeat
  std::optional<std::string> error;   // why it stopped early
};

struct StoredMachine {  // what `diff` prints of where a run was made (absent: unknown)
  std::optional<std::string> commit, cpu, date;
  std::optional<bool> dirty;
  std::optional<std::uint64_t> usable_cpus;
  std::optional<double> load;  // the 1-minute load average at the start
};

struct StoredResults {
  std::filesystem::path file;
  StateObjects objects;
  std::string sha256;
  double duration = 0, baseline_tolerance = 0;
  StoredMachine machine;
  int repeats = 0;
  std::vector<StoredRun> runs;  // one per backend
};

StoredResults parse_results(const std::string& text, const std::filesystem::path& file);
StoredResults read_results(const std::filesystem::path& file, core::Links links);

// ---- baselines (check --baseline DIR: DIR/<scene>.json) --------------------------------

struct BaselineRun {
  std::string backend;
  double t = 0;  // the final sample's time
  std::map<std::string, core::ParticleSample> particles;
  std::map<std::string, core::BodySample> bodies;
  bool velocities = true;  // false: stored before baselines kept velocities
  double wall_seconds = 0;
  std::vector<double> wall_seconds_each_repeat;  // empty: stored before they were kept
};

struct Baseline {
  std::string file, scene, sha256;
  std::vector<BaselineRun> runs;  // at least one; one per backend
};

Baseline parse_baseline(const nlohmann::json& j, const std::string& file);
Baseline read_baseline(const std::filesystem::path& file);

// ---- sweep cells (DIR/cells/<unit>.json) and manifests (DIR/sweep.json) -----------------

// A unit's record is reused by a resumed sweep or a merge only when it was
// written by this format (1 measured position alone; 2 had no traditional
// cell with the other rotation representation; 3 had no key) with this key.
inline constexpr int kSweepCellFormat = 4;

struct SweepCellResult {  // one backend at the unit's setting
  std::string backend;
  std::map<std::string, std::pair<double, double>> errors;  // measure name → final, RMS (infinite: stopped early)
  std::vector<double> seconds;                              // each timed repeat
  std::uint64_t steps = 0, evaluations = 0;
  std::string failure;  // empty unless the setting was refused or failed
};

struct SweepCell {
  int format = 1;  // older formats hold nothing else that is read: the unit is run again
  std::string unit, solver, setting;
  nlohmann::json key;  // compare/sweep.hpp's cell_key
  std::map<std::string, double> error_of_nothing;
  std::vector<SweepCellResult> cells;
};

// A cell file, checked against the unit it must be (its file name's stem).
SweepCell parse_cell(const std::string& text, const std::string& file, const std::string& unit);

struct SweepManifest {
  nlohmann::json json;  // as read: shards are the same sweep when these are equal
  std::string scene_file, scene_sha256, error, build;
  int repeats = 0;
  double max_duration = 0;
  std::vector<std::string> units;  // plain file-name stems, each once
};

SweepManifest parse_manifest(const std::string& text, const std::string& file);

}  // namespace gacompare::compare
