// What a tighter penetration tolerance costs in time (issue #7): the bundled
// drop scenes run with tolerances 1e-3 … 1e-7 m through both time-of-impact
// searches (bisection, §2.5.1; Illinois on the separating-axis depth, §4.3)
// and both backends. Per cell: impact searches, iterations and state
// evaluations per search, the time_of_impact stage's share, and the whole run's
// wall time (median of the repeats, interleaved). Markdown on stdout.
//
//   build/release/bench/time_of_impact_sweep [repeats=3] [scene names...]
#include "cga/backend.hpp"
#include "compare/stats.hpp"
#include "core/simulator.hpp"
#include "traditional/backend.hpp"

#include <cstdio>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

using namespace gacompare;

namespace {

struct Cell {
  std::vector<double> wall, toi;
  core::Run last;
};

core::Scene with(core::Scene s, double tol, core::TimeOfImpact m) {
  for (auto& e : s.effects)
    if (auto* c = std::get_if<core::Collisions>(&e)) c->penetration_tolerance = tol, c->time_of_impact = m;
  return s;
}

}  // namespace

int main(int argc, char** argv) {
  const int repeats = argc > 1 ? std::max(1, std::atoi(argv[1])) : 3;
  std::vector<std::string> names;
  for (int i = 2; i < argc; ++i) names.push_back(argv[i]);
  if (names.empty()) names = {"cube_drop_flat", "cube_drop_corner"};
  const std::vector<double> tolerances{1e-3, 1e-4, 1e-5, 1e-6, 1e-7};
  std::printf("Command: `time_of_impact_sweep %d%s` (wall: median of %d interleaved repeats)\n\n", repeats,
              argc > 2 ? " ..." : "", repeats);
  std::printf("| scene | tolerance m | search | backend | searches | iterations / search | evaluations / search | "
              "unresolved | time of impact ms | run ms |\n|---|---|---|---|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& name : names) {
    const auto base = core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
    for (const double tol : tolerances)
      for (const auto method : {core::TimeOfImpact::bisection, core::TimeOfImpact::illinois}) {
        const core::Scene scene = with(base, tol, method);
        std::map<std::string, Cell> cells;
        for (int r = 0; r < repeats; ++r)
          for (int k = 0; k < 2; ++k) {  // ABBA-ish: the order alternates per repeat
            const bool trad = (k + r) % 2 == 0;
            core::Run run = trad ? core::simulate<traditional::Backend>(scene) : core::simulate<cga::Backend>(scene);
            Cell& c = cells[run.backend];
            c.wall.push_back(run.wall_seconds);
            c.toi.push_back(run.profile[core::Stage::time_of_impact].seconds);
            c.last = std::move(run);
          }
        for (const auto& [backend, c] : cells) {
          const auto& k = c.last.counters;
          const double searches = static_cast<double>(k.at("impact_searches"));
          std::printf("| %s | %.0e | %s | %s | %.0f | %.1f | %.1f | %llu | %.2f | %.1f |\n", name.c_str(), tol,
                      method == core::TimeOfImpact::bisection ? "bisection" : "illinois", backend.c_str(), searches,
                      searches ? k.at("impact_iterations") / searches : 0.0,
                      searches ? k.at("impact_state_evaluations") / searches : 0.0,
                      static_cast<unsigned long long>(k.at("impact_searches_unresolved")),
                      1e3 * compare::spread(c.toi).median, 1e3 * compare::spread(c.wall).median);
        }
      }
  }
  return 0;
}
