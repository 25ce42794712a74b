#include "compare/diff.hpp"

#include "compare/report.hpp"
#include "compare/stats.hpp"
#include "core/error.hpp"
#include "core/stage.hpp"

#include <cstdio>
#include <fstream>
#include <map>
#include <set>
#include <sstream>

namespace gacompare::compare {

namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// A JSON path's value, or an input_error naming the file and the path.
const json& at(const RunFile& f, const json& j, const std::string& key, const std::string& path) {
  if (!j.is_object() || !j.contains(key))
    throw input_error(f.file.string() + ": " + path + "/" + key + ": missing" +
                      (key == "bodies" || key == "check" ? " (written before results.json carried it: run it again)" : ""));
  return j.at(key);
}

RunFile read_one(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw input_error(file.string() + ": cannot read");
  RunFile f{file, {}};
  try {
    f.results = json::parse(in);
  } catch (const json::exception& e) {
    throw input_error(file.string() + ": cannot parse: " + e.what());
  }
  if (!f.results.is_object() || f.results.value("tool", json::object()).value("name", "") != "gacompare" ||
      !f.results.contains("runs"))
    throw input_error(file.string() + ": not a gacompare results.json");
  return f;
}

Eigen::Vector3d vec3(const json& j) { return {j.at(0).get<double>(), j.at(1).get<double>(), j.at(2).get<double>()}; }

// A run's samples as core::Samples, objects in the scene record's order.
std::vector<core::Sample> samples_of(const RunFile& f, const json& run, const StateObjects& objects) {
  std::vector<core::Sample> out;
  const json& samples = at(f, run, "samples", "/runs/*");
  for (std::size_t k = 0; k < samples.size(); ++k) {
    const json& s = samples[k];
    const std::string path = "/runs/*/samples/" + std::to_string(k);
    core::Sample x;
    x.t = at(f, s, "t", path).get<double>();
    const json& ps = at(f, s, "particles", path);
    for (const auto& name : objects.particles) {
      const json& p = at(f, ps, name, path + "/particles");
      x.particles.push_back({vec3(p.at("position")), vec3(p.at("velocity"))});
    }
    const json& bs = at(f, s, "bodies", path);
    for (const auto& body : objects.bodies) {
      const json& b = at(f, bs, body.name, path + "/bodies");
      const json& q = b.at("orientation");
      x.bodies.push_back({vec3(b.at("position")),
                          {q.at(0).get<double>(), q.at(1).get<double>(), q.at(2).get<double>(), q.at(3).get<double>()},
                          vec3(b.at("velocity")),
                          vec3(b.at("angular_velocity"))});
    }
    out.push_back(std::move(x));
  }
  return out;
}

StateObjects objects_of(const RunFile& f) {
  const json& scene = at(f, f.results, "scene", "");
  StateObjects o;
  o.scene = at(f, scene, "name", "/scene").get<std::string>();
  o.output_every = at(f, scene, "output_every", "/scene").get<double>();
  o.particles = at(f, scene, "particles", "/scene").get<std::vector<std::string>>();
  for (const json& b : at(f, scene, "bodies", "/scene"))
    o.bodies.push_back({b.at("name").get<std::string>(), b.at("radius").get<double>(), b.at("static").get<bool>()});
  return o;
}

// Seconds per repeat: of one stage, or (stage "") of all stages together.
std::vector<double> repeat_seconds(const json& run, const std::string& stage) {
  std::vector<double> out;
  for (const auto& [name, s] : run.at("stages").items()) {
    if (!stage.empty() && name != stage) continue;
    const auto each = s.at("seconds_each_repeat").get<std::vector<double>>();
    if (out.size() < each.size()) out.resize(each.size(), 0.0);
    for (std::size_t i = 0; i < each.size(); ++i) out[i] += each[i];
  }
  return out;
}

const json* find_run(const json& results, const std::string& backend) {
  for (const auto& r : results.at("runs"))
    if (r.value("backend", "") == backend) return &r;
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

void diff_scene(const RunFile& a, const RunFile& b, const DiffOptions& options, std::vector<CheckLine>& out) {
  const StateObjects objects = objects_of(a);
  const std::string& name = objects.scene;
  const bool same_scene = a.results.at("scene").value("sha256", "") == b.results.at("scene").value("sha256", "");
  if (!same_scene)
    out.push_back(info(name, "all", "scene", "the scene file differs between A and B (sha256): times compared, "
                                             "states not"));
  const double d = options.tolerance.value_or(
      at(a, at(a, a.results.at("scene"), "check", "/scene"), "baseline_tolerance", "/scene/check").get<double>());
  const std::string d_name = options.tolerance ? "--tolerance" : "check.baseline_tolerance";
  for (const auto& run_a : a.results.at("runs")) {
    const std::string backend = run_a.value("backend", "");
    const json* run_b = find_run(b.results, backend);
    if (!run_b) {
      out.push_back(info(name, backend, "run", "in A only"));
      continue;
    }
    // Time: each stage either ran, then all stages together.
    std::set<std::string> stages;
    for (const auto& [stage, _] : run_a.at("stages").items()) stages.insert(stage);
    for (const auto& [stage, _] : run_b->at("stages").items()) stages.insert(stage);
    for (int k = 0; k <= core::kStageCount; ++k) {
      const std::string stage = k < core::kStageCount ? std::string(core::stage_name(static_cast<core::Stage>(k))) : "";
      if (!stage.empty() && !stages.count(stage)) continue;
      const std::string what = (stage.empty() ? std::string("all stages") : "`" + stage + "`") + " time, B / A";
      const bool in_a = stage.empty() || run_a.at("stages").contains(stage);
      const bool in_b = stage.empty() || run_b->at("stages").contains(stage);
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
    const bool stopped_a = run_a.contains("error"), stopped_b = run_b->contains("error");
    if (stopped_b && !stopped_a)
      out.push_back({name, backend, "run", 0, 0, CheckLine::Verdict::fail,
                     "B stopped early: " + run_b->at("error").get<std::string>()});
    if (!same_scene) continue;
    const auto sa = samples_of(a, run_a, objects), sb = samples_of(b, *run_b, objects);
    StateBounds bounds(objects, d);
    std::size_t compared = 0;
    for (; compared < std::min(sa.size(), sb.size()) && sa[compared].t == sb[compared].t; ++compared)
      bounds.add(sa[compared], sb[compared]);
    if (compared < std::max(sa.size(), sb.size()))
      out.push_back(info(name, backend, "samples",
                         "compared the first " + std::to_string(compared) + " (A has " + std::to_string(sa.size()) +
                             ", B " + std::to_string(sb.size()) + (compared < std::min(sa.size(), sb.size())
                                                                      ? "; their times part there)"
                                                                      : ")")));
    for (const Measure m : kMeasures) {
      const std::string what = m == Measure::position ? std::string("largest position difference, B − A (m)")
                                                      : "largest " + std::string(measure_words(m)) + " difference, B − A (" +
                                                            std::string(measure_unit(m)) + ")";
      if (auto l = bounds.line(m, backend, what, d_name + " = " + fmt(d) + " m")) out.push_back(*l);
    }
  }
  for (const auto& run_b : b.results.at("runs"))
    if (!find_run(a.results, run_b.value("backend", "")))
      out.push_back(info(name, run_b.value("backend", ""), "run", "in B only"));
}

std::string provenance(const std::vector<RunFile>& runs) {
  if (runs.empty()) return "nothing";
  const json& r = runs.front().results;
  const json m = r.value("machine", json::object());
  const json git = m.value("git", json::object());
  std::ostringstream o;
  o << runs.front().file.parent_path().string() << (runs.size() > 1 ? " and " + std::to_string(runs.size() - 1) + " more" : "")
    << ": commit " << git.value("commit", std::string("unknown")).substr(0, 12);
  if (git.contains("dirty") && git.at("dirty").is_boolean()) o << (git.at("dirty").get<bool>() ? " (dirty)" : "");
  else o << " (tree state unknown)";
  o << ", " << m.value("cpu", std::string("unknown CPU"));
  if (m.contains("usable_cpus")) o << ", " << m.at("usable_cpus").get<int>() << " CPUs usable";
  if (m.contains("load_average")) o << ", load " << fmt(m.at("load_average").at("start").at(0).get<double>()) << " at the start";
  o << ", " << m.value("date", std::string("no date")) << ", " << r.value("repeats", 0) << " repeats";
  return o.str();
}
}  // namespace

std::vector<RunFile> read_runs(const fs::path& path) {
  std::error_code ec;
  if (fs::is_regular_file(path, ec)) return {read_one(path)};
  if (!fs::is_directory(path, ec)) throw input_error(path.string() + ": no such results.json or report folder");
  if (fs::exists(path / "results.json", ec)) return {read_one(path / "results.json")};
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(path, ec))
    if (e.is_directory() && fs::exists(e.path() / "results.json")) files.push_back(e.path() / "results.json");
  if (files.empty()) throw input_error(path.string() + ": no results.json in it or in its folders");
  std::sort(files.begin(), files.end());
  std::vector<RunFile> out;
  for (const auto& f : files) out.push_back(read_one(f));
  return out;
}

std::vector<CheckLine> diff_runs(const std::vector<RunFile>& a, const std::vector<RunFile>& b, const DiffOptions& options) {
  std::map<std::string, const RunFile*> in_b;
  for (const auto& f : b) in_b[objects_of(f).scene] = &f;
  std::vector<CheckLine> out;
  std::set<std::string> seen;
  for (const auto& f : a) {
    const std::string name = objects_of(f).scene;
    seen.insert(name);
    const auto it = in_b.find(name);
    if (it == in_b.end()) out.push_back(info(name, "all", "scene", "in A only"));
    else diff_scene(f, *it->second, options, out);
  }
  for (const auto& [name, _] : in_b)
    if (!seen.count(name)) out.push_back(info(name, "all", "scene", "in B only"));
  return out;
}

std::string diff_header(const std::vector<RunFile>& a, const std::vector<RunFile>& b) {
  return "A: " + provenance(a) + "\nB: " + provenance(b) + "\n";
}

}  // namespace gacompare::compare
