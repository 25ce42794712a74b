// gacompare-state-hash: runs scenes through backends and prints each run's
// state hash (core/run.hpp: every sample's state to the bit, the solver's
// steps and every counter), one line per run: `HASH  SCENE  BACKEND`. The determinism check
// runs it on 1 and 2 threads and from the gcc and clang builds and compares
// the lines (tests/scripts/determinism_test.sh); it links the backends and
// nothing of the harness, so that a second compiler builds it in minutes.
// Exit codes: 0 every run finished, 1 a run stopped (its hash and reason are
// still printed), 2 bad usage or bad input.
#include "core/memory.hpp"
#include "cga/backend.hpp"
#include "core/collision/pair_memory.hpp"
#include "core/error.hpp"
#include "core/model/generators.hpp"
#include "core/model/scene.hpp"
#include "core/parallel.hpp"
#include "core/run.hpp"
#include "pga/backend.hpp"
#include "traditional/backend.hpp"

#include <CLI/CLI.hpp>

#include <cstdio>
#include <sstream>
#include <string>
#include <vector>

using namespace gacompare;

namespace {

core::Run run_on(const std::string& backend, const core::Scene& scene) {
  if (backend == traditional::Backend::name) return core::simulate<traditional::Backend>(scene);
  if (backend == cga::Backend::name) return core::simulate<cga::Backend>(scene);
  if (backend == pga::Backend::name) return core::simulate<pga::Backend>(scene);
  throw input_error("--backends: unknown backend '" + backend + "' (expected traditional, cga or pga)");
}

}  // namespace

int main(int argc, char** argv) {
  gacompare::core::keep_freed_memory();  // core/memory.hpp: a stack's solves no longer shrink and regrow the heap
  CLI::App app{"Runs scenes through backends and prints each run's state hash: HASH  SCENE  BACKEND"};
  std::vector<std::string> files;
  std::string backends = "traditional,cga";
  int threads = 1;
  bool fine = false, move_tables = false;
  app.add_option("scenes", files, "scene files")->required();
  app.add_option("--backends", backends, "comma-separated: traditional, cga, pga");
  app.add_option("--threads", threads, "threads the stages may use (1 to 256)");
  app.add_flag("--fine-grains", fine,
               "split every parallel loop into chunks of at most 4 items (slower; runs every parallel path)");
  app.add_flag("--move-pair-tables", move_tables,
               "move every entry of the pair tables at each insertion (slower; a pointer kept across one "
               "then changes the hash)");
  CLI11_PARSE(app, argc, argv);
  int status = 0;
  try {
    core::set_threads(threads);
    core::set_fine_grains(fine);
    collision::set_move_pair_tables(move_tables);
    std::vector<std::string> names;
    std::stringstream list(backends);
    for (std::string b; std::getline(list, b, ',');) names.push_back(b);
    for (const auto& file : files) {
      const core::Scene scene = core::expand_generators(core::load_scene(file));
      for (const auto& b : names) {
        const core::Run run = run_on(b, scene);
        std::printf("%s  %s  %s\n", core::state_hash(run).c_str(), scene.name.c_str(), b.c_str());
        std::fflush(stdout);
        if (run.error) {
          std::fprintf(stderr, "gacompare-state-hash: %s on %s stopped: %s\n", b.c_str(), file.c_str(),
                       run.error->c_str());
          status = 1;
        }
      }
    }
  } catch (const Error& e) {
    std::fprintf(stderr, "gacompare-state-hash: %s\n", e.what());
    return e.kind() == ErrorKind::input ? 2 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "gacompare-state-hash: %s\n", e.what());
    return 2;
  }
  return status;
}
