// gacompare: runs physics scenes through the traditional and geometric-algebra
// backends and writes comparison reports. Results go to files, logs to stderr.
// Exit codes: 0 success, 1 a run or check failed, 2 bad usage or bad input.
#include "compare/machine.hpp"
#include "compare/report.hpp"
#include "compare/runner.hpp"
#include "core/error.hpp"
#include "core/scene.hpp"

#include <CLI/CLI.hpp>

#include <algorithm>
#include <filesystem>
#include <iostream>
#include <set>

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

  std::string list_dir = std::string(GACOMPARE_DATA_DIR) + "/scenes";
  auto* list = app.add_subcommand("list", "list the bundled scenes");
  list->add_option("--scenes", list_dir, "folder of scene files");

  try {
    app.parse(argc, argv);
  } catch (const CLI::Success& e) {
    return app.exit(e);
  } catch (const CLI::ParseError& e) {
    std::cerr << "gacompare: " << e.what() << " (see gacompare --help)\n";
    return 2;
  }

  try {
    if (*run) return run_and_report(load_all({run_scene}), {run_backend}, run_repeat, run_out, quiet);
    if (*cmp) return run_and_report(load_all(cmp_scenes), cmp_backends, cmp_repeat, cmp_out, quiet);
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
