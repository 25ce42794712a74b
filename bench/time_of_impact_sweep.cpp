// What the time of impact costs, two tables, markdown on
// stdout:
//
//   time_of_impact_sweep [repeats=3] [scene names...]
//     the bundled drops with tolerances 1e-3 … 1e-7 m through bisection and
//     Illinois, and without a search (time_of_impact "none": each impact
//     taken where its step ends and pushed out): what a tighter penetration
//     tolerance costs, and what the search costs at each;
//   time_of_impact_sweep --methods [repeats=3] [scene names...]
//     each scene at its own tolerance through the four searches of
//     core/collision/time_of_impact.hpp (bisection, Illinois, golden section,
//     conservative advancement) with both motions (the island re-integrated
//     per trial, or interpolated in each backend's algebra: quaternion slerp
//     or rotor power along a line, then integrated once), and without a
//     search (one row: no motion to choose).
//
// Per cell and backend: impact searches, depth trials and island integrations
// per search, interpolation misses (the time found by interpolation not in the
// band on the true motion), unresolved searches, the time_of_impact stage and
// the whole run (medians of the repeats; backends and cells interleaved).
#include "cga/backend.hpp"
#include "compare/stats.hpp"
#include "core/dynamics/simulator.hpp"
#include "traditional/backend.hpp"

#include <cstdio>
#include <cstring>
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

struct Setting {
  double tol;
  core::TimeOfImpact method;
  core::ImpactMotion motion;
};

core::Scene with(core::Scene s, const Setting& x) {
  for (auto& e : s.effects)
    if (auto* c = std::get_if<core::Collisions>(&e)) {
      if (x.tol > 0) c->penetration_tolerance = x.tol;
      c->time_of_impact = x.method, c->impact_motion = x.motion;
    }
  return s;
}

const char* method_name(core::TimeOfImpact m) {
  switch (m) {
    case core::TimeOfImpact::bisection: return "bisection";
    case core::TimeOfImpact::illinois: return "illinois";
    case core::TimeOfImpact::golden_section: return "golden_section";
    case core::TimeOfImpact::conservative_advancement: return "conservative_advancement";
    case core::TimeOfImpact::none: return "none";
  }
  return "?";
}

double tolerance_of(const core::Scene& s) { return s.find_effect<core::Collisions>()->penetration_tolerance; }

// Both backends `repeats` times on one setting, the order alternating.
std::map<std::string, Cell> measure(const core::Scene& scene, int repeats) {
  std::map<std::string, Cell> cells;
  for (int r = 0; r < repeats; ++r)
    for (int k = 0; k < 2; ++k) {
      const bool trad = (k + r) % 2 == 0;
      core::Run run = trad ? core::simulate<traditional::Backend>(scene) : core::simulate<cga::Backend>(scene);
      Cell& c = cells[run.backend];
      c.wall.push_back(run.wall_seconds);
      c.toi.push_back(run.profile[core::Stage::time_of_impact].seconds);
      c.last = std::move(run);
    }
  return cells;
}

}  // namespace

int main(int argc, char** argv) {
  int arg = 1;
  const bool methods = argc > 1 && std::strcmp(argv[1], "--methods") == 0;
  if (methods) ++arg;
  const int repeats = argc > arg ? std::max(1, std::atoi(argv[arg])) : 3;
  std::vector<std::string> names;
  for (int i = arg + 1; i < argc; ++i) names.push_back(argv[i]);
  if (names.empty()) names = methods ? std::vector<std::string>{"cube_drop_corner", "contact_stack5", "bodies_in_box"}
                                     : std::vector<std::string>{"cube_drop_flat", "cube_drop_corner"};
  std::string command = "time_of_impact_sweep";
  for (int i = 1; i < argc; ++i) command += std::string(" ") + argv[i];
  std::printf("Command: `%s` (wall: median of %d interleaved repeats)\n\n", command.c_str(), repeats);
  std::printf("| scene | tolerance m | search | motion | backend | searches | trials / search | integrations / search | "
              "misses | unresolved | time of impact ms | run ms |\n"
              "|---|---|---|---|---|---:|---:|---:|---:|---:|---:|---:|\n");
  for (const auto& name : names) {
    const auto base = core::load_scene(std::filesystem::path(GACOMPARE_DATA_DIR) / "scenes" / (name + ".json"));
    std::vector<Setting> settings;
    if (methods) {
      for (const auto m : {core::TimeOfImpact::bisection, core::TimeOfImpact::illinois, core::TimeOfImpact::golden_section,
                           core::TimeOfImpact::conservative_advancement})
        for (const auto motion : {core::ImpactMotion::integrate, core::ImpactMotion::interpolate})
          settings.push_back({tolerance_of(base), m, motion});
      settings.push_back({tolerance_of(base), core::TimeOfImpact::none, core::ImpactMotion::integrate});
    } else {
      for (const double tol : {1e-3, 1e-4, 1e-5, 1e-6, 1e-7})
        for (const auto m : {core::TimeOfImpact::bisection, core::TimeOfImpact::illinois, core::TimeOfImpact::none})
          settings.push_back({tol, m, core::ImpactMotion::integrate});
    }
    for (const auto& x : settings) {
      const auto cells = measure(with(base, x), repeats);
      for (const auto& [backend, c] : cells) {
        const auto& k = c.last.counters;
        const double searches = static_cast<double>(k.at("impact_searches"));
        const auto per = [&](const char* what) { return searches ? static_cast<double>(k.at(what)) / searches : 0.0; };
        std::printf("| %s | %.0e | %s | %s | %s | %.0f | %.2f | %.2f | %llu | %llu | %.2f | %.1f |\n", name.c_str(), x.tol,
                    method_name(x.method),
                    x.method == core::TimeOfImpact::none                 ? "–"
                    : x.motion == core::ImpactMotion::integrate ? "integrate"
                                                                : "interpolate",
                    backend.c_str(), searches, per("impact_iterations"), per("impact_state_evaluations"),
                    static_cast<unsigned long long>(k.at("impact_interpolation_misses")),
                    static_cast<unsigned long long>(k.at("impact_searches_unresolved")),
                    1e3 * compare::spread(c.toi).median, 1e3 * compare::spread(c.wall).median);
      }
    }
  }
  return 0;
}
