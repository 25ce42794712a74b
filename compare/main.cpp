// gacompare: runs physics scenes through the traditional and geometric-algebra
// backends and writes comparison reports. Results go to files, logs to stderr.
// Exit codes: 0 success, 1 a run or check failed, 2 bad usage or bad input.
#include "compare/check.hpp"
#include "compare/machine.hpp"
#include "compare/report.hpp"
#include "compare/runner.hpp"
#include "core/error.hpp"
#include "core/scene.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <fstream>
#include <iostream>
#include <optional>
#include <set>
#include <unistd.h>

#ifndef GACOMPARE_DATA_DIR
#define GACOMPARE_DATA_DIR "data"
#endif

namespace fs = std::filesystem;
using namespace gacompare;

namespace {

std::vector<core::Scene> load_all(const std::vector<std::string>& files) {
  std::vector<core::Scene> scenes;
  std::set<std::string> names;
  for (const auto& f : files) {
    scenes.push_back(core::load_scene(f));
    if (!names.insert(scenes.back().name).second)
      throw input_error(f + ": scene name '" + scenes.back().name + "' is used by another scene on the command line");
  }
  return scenes;
}

fs::path default_out(const std::string& what) {
  std::string date = compare::machine_info().date;
  std::replace(date.begin(), date.end(), ':', '-');
  return fs::path("reports") / (what + "-" + date);
}

int run_and_report(const std::vector<core::Scene>& scenes, const std::vector<std::string>& backends, int repeats,
                   fs::path out, bool quiet) {
  if (out.empty()) out = default_out(scenes.size() == 1 ? scenes.front().name : "compare");
  std::vector<compare::SceneResult> results;
  bool failed = false;
  for (const auto& scene : scenes) {
    if (!quiet) std::cerr << "gacompare: " << scene.name << ": " << repeats << " repeat(s) of " << backends.size() << " backend(s)\n";
    results.push_back(compare::compare_scene(scene, backends, repeats));
    for (const auto& b : results.back().backends)
      if (b.run.error) {
        std::cerr << "gacompare: " << scene.name << ": " << b.run.backend << ": " << *b.run.error << "\n";
        failed = true;
      }
  }
  compare::write_reports(out, results, compare::machine_info(), repeats);
  std::cout << out.string() << "\n";
  return failed ? 1 : 0;
}

// Reads a stored baseline; nullopt when there is none. A file that is there but
// cannot be read or parsed is an input error naming it.
std::optional<nlohmann::json> read_baseline(const fs::path& file) {
  std::error_code ec;
  if (!fs::exists(file, ec)) return std::nullopt;
  std::ifstream in(file);
  if (!in) throw input_error(file.string() + ": cannot read this baseline");
  try {
    auto j = nlohmann::json::parse(in);
    if (!j.is_object() || !j.contains("runs") || !j.at("runs").is_array())
      throw input_error(file.string() + ": not a gacompare baseline (expected an object with \"runs\")");
    return j;
  } catch (const nlohmann::json::exception& e) {
    throw input_error(file.string() + ": cannot parse this baseline: " + e.what());
  }
}

int check_scenes(const std::vector<core::Scene>& scenes, const fs::path& baseline_dir, bool update, int repeats,
                 bool quiet) {
  std::error_code ec;
  if (!update && !fs::is_directory(baseline_dir, ec))
    throw input_error(baseline_dir.string() + ": no such baseline folder (create it with --update)");
  std::vector<compare::CheckLine> lines;
  for (const auto& scene : scenes) {
    const fs::path file = compare::baseline_path(baseline_dir, scene.name);
    const auto baseline = read_baseline(file);
    if (!baseline && !update)
      throw input_error(file.string() + ": no baseline for scene '" + scene.name + "' (store one with --update)");
    if (!quiet) std::cerr << "gacompare: check " << scene.name << "\n";
    const auto result = compare::compare_scene(scene, compare::backend_names(), repeats);
    auto scene_lines = compare::check_scene(result, update ? std::nullopt : baseline);
    lines.insert(lines.end(), scene_lines.begin(), scene_lines.end());
    if (update) {
      compare::write_file_atomically(file, compare::baseline_json(result).dump(1) + "\n");
      lines.push_back({scene.name, "all", "baseline", 0, 0, compare::CheckLine::Verdict::info, "stored " + file.string()});
    }
  }
  std::cout << compare::check_table(lines);
  auto count = [&](compare::CheckLine::Verdict v) {
    return std::count_if(lines.begin(), lines.end(), [&](const auto& l) { return l.verdict == v; });
  };
  const auto failed = count(compare::CheckLine::Verdict::fail);
  std::cout << "\ncheck: " << count(compare::CheckLine::Verdict::pass) << " passed, " << failed << " failed\n";
  return failed ? 1 : 0;
}

int list_scenes(const fs::path& dir) {
  if (!fs::is_directory(dir)) throw input_error(dir.string() + ": not a folder of scenes");
  std::vector<fs::path> files;
  for (const auto& e : fs::directory_iterator(dir))
    if (e.path().extension() == ".json") files.push_back(e.path());
  std::sort(files.begin(), files.end());
  for (const auto& f : files) {
    const auto s = core::load_scene(f);
    std::cout << f.string() << "\t" << s.name << "\t" << s.description << "\n";
  }
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  CLI::App app{"gacompare: traditional vs geometric-algebra physics, stage by stage"};
  // Progress goes to stderr when it is a terminal; nothing when it is not, or with --quiet.
  app.set_version_flag("--version", "gacompare " + compare::tool_version());
  app.require_subcommand(1);
  app.fallthrough();  // global flags (--quiet) may follow the subcommand
  bool quiet = false;
  app.add_flag("-q,--quiet", quiet, "no progress on stderr");

  std::string run_scene, run_backend = "traditional", run_out;
  int run_repeat = 1;
  auto* run = app.add_subcommand("run", "run one scene through one backend");
  run->add_option("scene", run_scene, "scene file (JSON)")->required();
  run->add_option("--backend", run_backend, "traditional or cga")->check(CLI::IsMember(compare::backend_names()));
  run->add_option("--out", run_out, "report folder (default reports/<scene>-<date>)");
  run->add_option("--repeat", run_repeat, "repeats, for the timing spread")->check(CLI::PositiveNumber);

  std::vector<std::string> cmp_scenes, cmp_backends = compare::backend_names();
  std::string cmp_out;
  int cmp_repeat = 5;
  auto* cmp = app.add_subcommand("compare", "run scenes through every backend and compare");
  cmp->add_option("scenes", cmp_scenes, "scene files (JSON)")->required();
  cmp->add_option("--out", cmp_out, "report folder (default reports/<scene or compare>-<date>)");
  cmp->add_option("--repeat", cmp_repeat, "repeats per backend, interleaved")->check(CLI::PositiveNumber);
  cmp->add_option("--backends", cmp_backends, "backends to run")->check(CLI::IsMember(compare::backend_names()));

  std::vector<std::string> chk_scenes;
  std::string chk_baseline;
  bool chk_update = false;
  int chk_repeat = 1;
  auto* chk = app.add_subcommand("check", "regression checks: backends against each other and against stored baselines");
  chk->add_option("scenes", chk_scenes, "scene files (JSON)")->required();
  chk->add_option("--baseline", chk_baseline, "folder of baselines, one SCENE.json per scene")->required();
  chk->add_flag("--update", chk_update, "store fresh baselines instead of comparing with them");
  chk->add_option("--repeat", chk_repeat, "repeats per backend, for the timing ratio")->check(CLI::PositiveNumber);

  std::string list_dir = std::string(GACOMPARE_DATA_DIR) + "/scenes";
  auto* list = app.add_subcommand("list", "list the bundled scenes");
  list->add_option("--scenes", list_dir, "folder of scene files");

  try {
    app.parse(argc, argv);
    if (!::isatty(STDERR_FILENO)) quiet = true;
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "gacompare: " << e.what() << " (see gacompare --help)\n";
    return 2;
  }

  try {
    if (*run) return run_and_report(load_all({run_scene}), {run_backend}, run_repeat, run_out, quiet);
    if (*cmp) return run_and_report(load_all(cmp_scenes), cmp_backends, cmp_repeat, cmp_out, quiet);
    if (*chk) return check_scenes(load_all(chk_scenes), chk_baseline, chk_update, chk_repeat, quiet);
    if (*list) return list_scenes(list_dir);
  } catch (const gacompare::Error& e) {
    std::cerr << "gacompare: " << e.what() << "\n";
    return e.kind() == ErrorKind::input ? 2 : 1;
  } catch (const std::exception& e) {
    std::cerr << "gacompare: internal error: " << e.what() << "\n";
    return 1;
  }
  return 2;
}
