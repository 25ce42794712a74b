#include "compare/stored.hpp"

#include "compare/metrics.hpp"
#include "core/error.hpp"
#include "core/model/scene.hpp"
#include "core/dynamics/simulator.hpp"
#include "core/stage.hpp"

#include <algorithm>
#include <cmath>
#include <limits>
#include <set>

namespace gacompare::compare {

namespace {
using nlohmann::json;

// A JSON-pointer reference token ("~" → "~0", "/" → "~1"), at most 80 bytes.
std::string token(std::string_view key) {
  std::string out;
  for (char c : key.substr(0, 80)) out += c == '~' ? std::string("~0") : c == '/' ? std::string("~1") : std::string(1, c);
  return key.size() > 80 ? out + "..." : out;
}

std::string describe(const json& j) {
  switch (j.type()) {
    case json::value_t::null: return "null";
    case json::value_t::object: return "an object";
    case json::value_t::array: return "an array of " + std::to_string(j.size());
    case json::value_t::string: {
      const auto& s = j.get_ref<const std::string&>();
      return json(s.substr(0, 60) + (s.size() > 60 ? "..." : "")).dump(-1, ' ', false, json::error_handler_t::replace);
    }
    default: return j.dump();
  }
}

std::string g(double x) {
  char buffer[32];
  std::snprintf(buffer, sizeof buffer, "%g", x);
  return buffer;
}

// The deepest nesting any file gacompare writes has is 6; anything much deeper is not one of them.
constexpr int kMaxDepth = 64;
}  // namespace

[[noreturn]] void Field::fail(const std::string& expected) const {
  throw input_error(core::one_line(file_ + ": " + (path_.empty() ? "/" : path_) + ": expected " + expected + ", got " +
                                   describe(*j_)));
}

const nlohmann::json& Field::object() const {
  if (!j_->is_object()) fail("an object");
  return *j_;
}

Field Field::operator[](std::string_view key) const {
  const nlohmann::json& o = object();
  const auto it = o.find(key);
  if (it == o.end())
    throw input_error(core::one_line(file_ + ": " + path_ + "/" + token(key) + ": missing (expected in " +
                                     (path_.empty() ? "/" : path_) + ")"));
  return {file_, *it, path_ + "/" + token(key)};
}

std::optional<Field> Field::find(std::string_view key) const {
  const nlohmann::json& o = object();
  const auto it = o.find(key);
  if (it == o.end() || it->is_null()) return std::nullopt;
  return Field{file_, *it, path_ + "/" + token(key)};
}

Field Field::operator[](std::size_t i) const { return {file_, j_->at(i), path_ + "/" + std::to_string(i)}; }

std::size_t Field::size(std::size_t lo, std::size_t hi) const {
  if (!j_->is_array() || j_->size() < lo || j_->size() > hi)
    fail("an array of " + (lo == hi ? std::to_string(lo) : std::to_string(lo) + " to " + std::to_string(hi)) + " elements");
  return j_->size();
}

std::vector<std::pair<std::string, Field>> Field::members() const {
  std::vector<std::pair<std::string, Field>> out;
  for (const auto& [k, v] : object().items()) out.emplace_back(k, Field{file_, v, path_ + "/" + token(k)});
  return out;
}

double Field::number(double lo, double hi) const {
  if (!j_->is_number() || !std::isfinite(j_->get<double>()) || j_->get<double>() < lo || j_->get<double>() > hi) {
    char range[64];
    std::snprintf(range, sizeof range, "a number in [%g, %g]", lo, hi);
    fail(range);
  }
  return j_->get<double>();
}

double Field::number_or_null(double lo, double hi, double null_is) const {
  return j_->is_null() ? null_is : number(lo, hi);
}

std::uint64_t Field::whole(std::uint64_t lo, std::uint64_t hi) const {
  if (!j_->is_number_unsigned() || j_->get<std::uint64_t>() < lo || j_->get<std::uint64_t>() > hi)
    fail("a whole number from " + std::to_string(lo) + " to " + std::to_string(hi));
  return j_->get<std::uint64_t>();
}

std::string Field::text(std::size_t max_bytes) const {
  if (!j_->is_string() || j_->get_ref<const std::string&>().size() > max_bytes)
    fail("a string of at most " + std::to_string(max_bytes) + " bytes");
  return j_->get<std::string>();
}

bool Field::boolean() const {
  if (!j_->is_boolean()) fail("true or false");
  return j_->get<bool>();
}

Eigen::Vector3d Field::vec3() const {
  if (!j_->is_array() || j_->size() != 3) fail("[x, y, z]");
  Eigen::Vector3d v;
  for (int i = 0; i < 3; ++i) v[i] = (*this)[static_cast<std::size_t>(i)].number_or_null(-INFINITY, INFINITY, NAN);
  return v;
}

Eigen::Vector4d Field::vec4() const {
  if (!j_->is_array() || j_->size() != 4) fail("[w, x, y, z]");
  Eigen::Vector4d v;
  for (int i = 0; i < 4; ++i) v[i] = (*this)[static_cast<std::size_t>(i)].number_or_null(-INFINITY, INFINITY, NAN);
  return v;
}

json parse_stored(const std::string& text, const std::string& file) {
  int depth = 0;
  const auto callback = [&](int, json::parse_event_t event, json&) {
    if (event == json::parse_event_t::object_start || event == json::parse_event_t::array_start) {
      if (++depth > kMaxDepth)
        throw input_error(core::one_line(file + ": malformed: nested more than " + std::to_string(kMaxDepth) + " deep"));
    } else if (event == json::parse_event_t::object_end || event == json::parse_event_t::array_end) {
      --depth;
    }
    return true;
  };
  try {
    return json::parse(text, callback, /*allow_exceptions=*/true, /*ignore_comments=*/false);
  } catch (const json::exception& e) {
    std::string detail = e.what();  // "[json.exception.parse_error.101] parse error at line 2, column 3: ..."
    if (const auto p = detail.find("] "); p != std::string::npos) detail = detail.substr(p + 2);
    throw input_error(core::one_line(file + ": malformed JSON: " + detail.substr(0, 300)));
  }
}

// ---- results.json ------------------------------------------------------------------------

namespace {

// Names of a scene's objects: each a non-empty string, each once.
std::vector<std::string> names(const Field& list) {
  std::vector<std::string> out;
  std::set<std::string> seen;
  for (std::size_t i = 0, n = list.size(0, std::numeric_limits<std::size_t>::max()); i < n; ++i) {
    const Field f = list[i];
    out.push_back(f.text());
    if (out.back().empty() || !seen.insert(out.back()).second) f.fail("a name not empty and not used before");
  }
  return out;
}

StateObjects objects_of(const Field& scene) {
  StateObjects o;
  o.scene = scene["name"].text();
  if (o.scene.empty()) scene["name"].fail("a scene name");
  o.output_every = scene["output_every"].number(std::numeric_limits<double>::min(), INFINITY);
  o.particles = names(scene["particles"]);
  const Field bodies = scene["bodies"];
  std::set<std::string> seen(o.particles.begin(), o.particles.end());
  for (std::size_t i = 0, n = bodies.size(0, std::numeric_limits<std::size_t>::max()); i < n; ++i) {
    const Field b = bodies[i];
    o.bodies.push_back({b["name"].text(), b["radius"].number(std::numeric_limits<double>::min(), INFINITY),
                        b["static"].boolean()});
    if (o.bodies.back().name.empty() || !seen.insert(o.bodies.back().name).second)
      b["name"].fail("a name not empty and not used before");
  }
  return o;
}

// The number of samples a complete run of this duration and interval records
// (core::output_times), or SIZE_MAX when it is above both the `n` the file
// holds and a million (the times are never all made: a tampered interval
// could ask for 1e300).
std::size_t expected_samples(double duration, double every, std::size_t n) {
  if (duration / every > static_cast<double>(std::max<std::size_t>(n, 1'000'000)) + 2)
    return std::numeric_limits<std::size_t>::max();
  core::Scene s;
  s.duration = duration;
  s.output_every = every;
  return core::output_times(s).size();
}

core::Sample sample_of(const Field& s, const StateObjects& o) {
  core::Sample x;
  const Field ps = s["particles"], bs = s["bodies"];
  if (ps.members().size() != o.particles.size()) ps.fail(std::to_string(o.particles.size()) + " particles, the scene's");
  if (bs.members().size() != o.bodies.size()) bs.fail(std::to_string(o.bodies.size()) + " bodies, the scene's");
  for (const auto& name : o.particles) {
    const Field p = ps[name];
    x.particles.push_back({p["position"].vec3(), p["velocity"].vec3()});
  }
  for (const auto& body : o.bodies) {
    const Field b = bs[body.name];
    x.bodies.push_back({b["position"].vec3(), b["orientation"].vec4(), b["velocity"].vec3(), b["angular_velocity"].vec3()});
  }
  return x;
}

StoredRun run_of(const Field& r, const StateObjects& o, double duration, int repeats) {
  StoredRun run;
  run.backend = r["backend"].text(100);
  if (const auto e = r.find("error")) run.error = e->text(100000);
  const Field samples = r["samples"];
  const std::size_t n = samples.size(1, std::numeric_limits<std::size_t>::max());
  const std::size_t expected = expected_samples(duration, o.output_every, n);
  if (run.error ? n > expected : n != expected)
    samples.fail(expected == std::numeric_limits<std::size_t>::max()
                     ? "as many samples as duration / output_every gives"
                     : (run.error ? "at most " : "exactly ") + std::to_string(expected) + " samples (duration " +
                           g(duration) + " s, one every " + g(o.output_every) + " s" +
                           (run.error ? ", stopped early" : ", not stopped early") + ")");
  for (std::size_t k = 0; k < n; ++k) {
    const Field s = samples[k];
    core::Sample x = sample_of(s, o);
    x.t = s["t"].number(run.samples.empty() ? 0 : run.samples.back().t, duration);
    if (k == 0 && x.t != 0) s["t"].fail("0 (the first sample is the start)");
    if (k > 0 && !(x.t > run.samples.back().t)) s["t"].fail("a time after the sample before's");
    run.samples.push_back(std::move(x));
  }
  for (const auto& [name, stage] : r["stages"].members()) {
    if (!core::stage_from_name(name)) {
      std::string all;
      for (int k = 0; k < core::kStageCount; ++k) all += (k ? ", " : "") + std::string(core::stage_name(static_cast<core::Stage>(k)));
      throw input_error(core::one_line(r.file() + ": " + stage.path() + ": expected the name of a stage (" + all + ")"));
    }
    const Field each = stage["seconds_each_repeat"];
    std::vector<double>& secs = run.stage_seconds[name];
    for (std::size_t i = 0, m = each.size(static_cast<std::size_t>(repeats), static_cast<std::size_t>(repeats)); i < m; ++i)
      secs.push_back(each[i].number(0, kMaxSeconds));
    (void)stage["calls"].whole(0, std::numeric_limits<std::uint64_t>::max());
  }
  return run;
}

StoredMachine machine_of(const Field& root) {
  StoredMachine m;
  const auto machine = root.find("machine");
  if (!machine) return m;
  if (const auto x = machine->find("cpu")) m.cpu = x->text();
  if (const auto x = machine->find("date")) m.date = x->text();
  if (const auto x = machine->find("usable_cpus")) m.usable_cpus = x->whole(0, 1u << 20);
  if (const auto x = machine->find("load_average"))
    if (const auto start = x->find("start"); start && start->size(1, 3) > 0) m.load = (*start)[0].number(0, 1e6);
  if (const auto git = machine->find("git")) {
    if (const auto x = git->find("commit")) m.commit = x->text(100);
    if (const auto x = git->find("dirty")) m.dirty = x->boolean();
  }
  return m;
}

}  // namespace

StoredResults parse_results(const std::string& text, const std::filesystem::path& file) {
  const json j = parse_stored(text, file.string());
  const Field root(file.string(), j);
  if (!j.is_object() || !j.contains("tool") || !j["tool"].is_object() || j["tool"].value("name", json()) != "gacompare" ||
      !j.contains("runs"))
    throw input_error(core::one_line(file.string() + ": not a gacompare results.json"));
  StoredResults r;
  r.file = file;
  const Field scene = root["scene"];
  for (const char* key : {"bodies", "check"})  // results.json did not always carry these
    if (scene.json().is_object() && !scene.json().contains(key))
      throw input_error(core::one_line(file.string() + ": /scene/" + key + ": missing (written before results.json carried it: run it again)"));
  r.objects = objects_of(scene);
  r.sha256 = scene["sha256"].text(64);
  r.duration = scene["duration"].number(std::numeric_limits<double>::min(), INFINITY);
  r.baseline_tolerance = scene["check"]["baseline_tolerance"].number(std::numeric_limits<double>::min(), INFINITY);
  r.repeats = static_cast<int>(root["repeats"].whole(1, kMaxRepeats));
  r.machine = machine_of(root);
  const Field runs = root["runs"];
  std::set<std::string> backends;
  for (std::size_t i = 0, n = runs.size(1, kMaxRuns); i < n; ++i) {
    r.runs.push_back(run_of(runs[i], r.objects, r.duration, r.repeats));
    if (!backends.insert(r.runs.back().backend).second) runs[i]["backend"].fail("each backend once");
  }
  return r;
}

StoredResults read_results(const std::filesystem::path& file, core::Links links) {
  return parse_results(core::read_file(file, "results.json", links), file);
}

// ---- baselines ----------------------------------------------------------------------------

Baseline parse_baseline(const json& j, const std::string& file) {
  const Field root(file, j);
  if (!j.is_object() || !j.contains("runs"))
    throw input_error(core::one_line(file + ": not a gacompare baseline (expected an object with \"runs\")"));
  Baseline b;
  b.file = file;
  b.scene = root["scene"].text();
  b.sha256 = root["sha256"].text(64);
  const Field runs = root["runs"];
  std::set<std::string> backends;
  for (std::size_t i = 0, n = runs.size(1, kMaxRuns); i < n; ++i) {
    const Field r = runs[i];
    BaselineRun run;
    run.backend = r["backend"].text(100);
    if (!backends.insert(run.backend).second) r["backend"].fail("each backend once");
    const Field fin = r["final"];
    run.t = fin["t"].number(0, INFINITY);
    for (const auto& [name, p] : fin["particles"].members()) {
      core::ParticleSample x;
      if (p.json().is_array()) {  // the first format: the position alone
        x.position = p.vec3();
        run.velocities = false;
      } else {
        x.position = p["position"].vec3();
        x.velocity = p["velocity"].vec3();
      }
      run.particles[name] = x;
    }
    for (const auto& [name, body] : fin["bodies"].members()) {
      core::BodySample x;
      x.position = body["position"].vec3();
      x.orientation = body["orientation"].vec4();
      const auto v = body.find("velocity"), w = body.find("angular_velocity");
      if (v && w) {
        x.velocity = v->vec3();
        x.angular_velocity = w->vec3();
      } else {
        run.velocities = false;
      }
      run.bodies[name] = x;
    }
    run.wall_seconds = r["wall_seconds"].number(0, kMaxSeconds);
    if (const auto each = r.find("wall_seconds_each_repeat"))
      for (std::size_t k = 0, m = each->size(0, kMaxRepeats); k < m; ++k)
        run.wall_seconds_each_repeat.push_back((*each)[k].number(0, kMaxSeconds));
    b.runs.push_back(std::move(run));
  }
  return b;
}

Baseline read_baseline(const std::filesystem::path& file) {
  return parse_baseline(parse_stored(core::read_file(file, "baseline", core::Links::refuse), file.string()), file.string());
}

// ---- sweep cells and manifests ---------------------------------------------------------------

namespace {

bool is_measure(const std::string& name) { return measure_from_string(name).has_value(); }

// A unit id is a file name's stem: letters, digits, '.', '-', '_', not hidden.
bool plain_name(const std::string& s) {
  return !s.empty() && s.front() != '.' && s.find_first_not_of("abcdefghijklmnopqrstuvwxyzABCDEFGHIJKLMNOPQRSTUVWXYZ0123456789._-") == std::string::npos;
}

int repeats_of(const Field& f) { return static_cast<int>(f.whole(1, kMaxRepeats)); }

SweepCellResult cell_result(const Field& c, int repeats) {
  SweepCellResult r;
  r.backend = c["backend"].text(100);
  if (const auto f = c.find("failure")) r.failure = f->text(100000);
  for (const auto& [name, e] : c["errors"].members()) {
    if (!is_measure(name)) e.fail("the errors of position, orientation, velocity or angular_velocity");
    r.errors[name] = {e["final"].number_or_null(0, INFINITY, INFINITY), e["rms"].number_or_null(0, INFINITY, INFINITY)};
  }
  const Field seconds = c["seconds"];
  const auto n = r.failure.empty() ? seconds.size(static_cast<std::size_t>(repeats), static_cast<std::size_t>(repeats))
                                   : seconds.size(0, static_cast<std::size_t>(repeats));
  for (std::size_t k = 0; k < n; ++k) r.seconds.push_back(seconds[k].number(0, kMaxSeconds));
  r.steps = c["steps"].whole(0, std::numeric_limits<std::uint64_t>::max());
  r.evaluations = c["derivative_evaluations"].whole(0, std::numeric_limits<std::uint64_t>::max());
  return r;
}

}  // namespace

SweepCell parse_cell(const std::string& text, const std::string& file, const std::string& unit) {
  const json j = parse_stored(text, file);
  const Field root(file, j);
  if (!j.is_object()) root.fail("a sweep cell (an object)");
  SweepCell c;
  if (const auto f = root.find("format")) c.format = static_cast<int>(f->whole(0, 1000));
  if (c.format != kSweepCellFormat) return c;  // an older format: its unit is run again
  c.unit = root["unit"].text(200);
  if (c.unit != unit) root["unit"].fail(json(unit).dump() + ", the unit its file is named after");
  c.solver = root["solver"].text(100);
  c.setting = root["setting"].text(100);
  const Field key = root["key"];
  (void)key["scene_sha256"].text(64);
  (void)key["duration"].number(std::numeric_limits<double>::min(), INFINITY);
  (void)key["output_every"].number(std::numeric_limits<double>::min(), INFINITY);
  (void)key["build"].text(100);
  const int repeats = repeats_of(key["repeats"]);
  c.key = key.json();
  for (const auto& [name, e] : root["error_of_nothing"].members()) {
    if (!is_measure(name)) e.fail("the error of position, orientation, velocity or angular_velocity");
    c.error_of_nothing[name] = e.number_or_null(0, INFINITY, INFINITY);
  }
  const Field cells = root["cells"];
  std::set<std::string> backends;
  for (std::size_t i = 0, n = cells.size(1, kMaxRuns); i < n; ++i) {
    c.cells.push_back(cell_result(cells[i], repeats));
    if (!backends.insert(c.cells.back().backend).second) cells[i]["backend"].fail("each backend once");
  }
  return c;
}

SweepManifest parse_manifest(const std::string& text, const std::string& file) {
  SweepManifest m;
  m.json = parse_stored(text, file);
  const Field root(file, m.json);
  m.scene_file = root["scene_file"].text(4096);
  if (m.scene_file.empty()) root["scene_file"].fail("the scene file's path");
  m.scene_sha256 = root["scene_sha256"].text(64);
  m.repeats = repeats_of(root["repeats"]);
  m.max_duration = root["max_duration"].number(0, INFINITY);
  m.error = root["error"].text(100);
  if (m.error != "default" && !is_measure(m.error))
    root["error"].fail("\"default\" or one of position, orientation, velocity, angular_velocity");
  m.build = root["build"].text(100);
  const Field units = root["units"];
  std::set<std::string> seen;
  for (std::size_t i = 0, n = units.size(1, 1000000); i < n; ++i) {
    m.units.push_back(units[i].text(200));
    if (!plain_name(m.units.back()) || !seen.insert(m.units.back()).second)
      units[i].fail("a unit id (letters, digits, '.', '-', '_'; a file name in cells/), each once");
  }
  return m;
}

}  // namespace gacompare::compare
