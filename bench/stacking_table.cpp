// The stacking table (docs/results/stacking.md): every case of the stacking
// family (answers/stacking_family.hpp) through the contact solvers of our two
// backends and through Bullet, each held to its statics answer for its 10
// simulated seconds. A cell is "pass" or "FAIL" with the worst error as a
// multiple of its bound (≤ 1 passes) and the run's wall time per simulated
// second; the reasons for the failures follow the table, with the cases the
// tests know to be open (StackCase::open) saying why. Markdown on stdout,
// progress on stderr.
//
//   build/ci/bench/stacking_table [--filter TEXT] [--columns traditional,cga,pga,bullet,traditional-pgs,cga-pgs,pga-pgs,traditional-tested,cga-tested,pga-tested]
//                                 [--duration SECONDS] [--restitution E] [--counters NAME,NAME,...]
//
// --duration shortens every case's run (the verdict still holds each sample
// to the answer); --restitution replaces every case's coefficient of
// restitution (0.2), to tell what the bounces of the landings do from what the
// solver does; --counters prints those counters of every run on stderr,
// for looking into a failing case.
//
// Default columns: traditional, cga, pga, bullet. A column is a backend with the
// family's default contact solver (direct),
// a backend with projected Gauss–Seidel (NAME-pgs), a backend testing every
// pair at every detection (NAME-tested: the collisions effect's
// reuse_contacts off), or Bullet (its own sequential impulses, 10
// iterations, split impulse).
#include "core/memory.hpp"
#include "answers/stacking_family.hpp"
#include "compare/runner.hpp"
#include "family_table.hpp"
#include "core/error.hpp"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <variant>
#include <vector>

using namespace gacompare;

namespace {

// A column is a backend, with "-pgs" for the Gauss–Seidel solver or
// "-tested" for every pair tested at every detection (no kept contacts).
core::Run run(const std::string& column, const core::Scene& scene) {
  return compare::run_backend(scene, column.substr(0, column.find('-')));
}

core::ContactSolverMethod method_of(const std::string& column) {
  return column.ends_with("-pgs") ? core::ContactSolverMethod::pgs : core::ContactSolverMethod::direct;
}

int usage() {
  std::fprintf(stderr,
               "usage: stacking_table [--filter TEXT] [--columns traditional,cga,pga,bullet,traditional-pgs,cga-pgs,pga-pgs,traditional-tested,cga-tested,pga-tested] "
               "[--duration SECONDS] [--restitution E] [--counters NAME,NAME,...]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  gacompare::core::keep_freed_memory();  // core/memory.hpp: a stack's solves no longer shrink and regrow the heap
  std::string filter, command = "stacking_table";
  double duration = 0;  // 0: each case's own
  double restitution = -1;  // < 0: each case's own
  std::vector<std::string> shown;  // counters printed per run
  std::vector<std::string> columns{"traditional", "cga", "pga", "bullet"};
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage();
    const std::string value = argv[++i];
    command += " " + arg + " " + value;
    if (arg == "--filter") {
      filter = value;
    } else if (arg == "--duration") {
      char* end = nullptr;
      duration = std::strtod(value.c_str(), &end);
      if (*end != '\0' || !(duration > 0)) return usage();
    } else if (arg == "--restitution") {
      char* end = nullptr;
      restitution = std::strtod(value.c_str(), &end);
      if (*end != '\0' || !(restitution >= 0 && restitution <= 1)) return usage();
    } else if (arg == "--counters") {
      shown = bench::comma_list(value);
    } else if (arg == "--columns") {
      const auto list = bench::column_list(value, {"traditional", "cga", "pga", "bullet", "traditional-pgs", "cga-pgs", "pga-pgs",
                                                      "traditional-tested", "cga-tested", "pga-tested"});
      if (!list) return usage();
      columns = *list;
    } else {
      return usage();
    }
  }
  auto direct = core::stacking_family(core::ContactSolverMethod::direct);
  auto pgs = core::stacking_family(core::ContactSolverMethod::pgs);
  if (duration > 0)
    for (auto* family : {&direct, &pgs})
      for (auto& c : *family) c.scene.duration = duration;
  if (restitution >= 0)
    for (auto* family : {&direct, &pgs})
      for (auto& c : *family)
        for (auto& effect : c.scene.effects)
          if (auto* collisions = std::get_if<core::Collisions>(&effect)) collisions->restitution = restitution;

  std::printf("Command: `build/ci/bench/%s`\n\n", command.c_str());
  std::printf("Each cell: pass or FAIL, the worst error over its bound (≤ 1 passes), and the run's wall time per "
              "simulated second.\n\n| case | bodies |");
  for (const auto& c : columns) std::printf(" %s |", c.c_str());
  std::printf("\n|---|---:|");
  for (std::size_t k = 0; k < columns.size(); ++k) std::printf("---|");
  std::printf("\n");
  std::vector<std::string> failures;
  std::map<std::string, int> passed;
  std::map<std::string, double> wall;
  int cases = 0;
  for (std::size_t k = 0; k < direct.size(); ++k) {
    const core::StackCase& base = direct[k];
    if (base.name.find(filter) == std::string::npos) continue;
    ++cases;
    int moving = 0;
    for (const auto& b : base.scene.bodies) moving += !b.is_static;
    std::printf("| %s | %d |", base.name.c_str(), moving);
    for (const auto& column : columns) {
      core::StackCase c = method_of(column) == core::ContactSolverMethod::pgs ? pgs[k] : direct[k];
      if (column.ends_with("-tested"))
        for (auto& effect : c.scene.effects)
          if (auto* collisions = std::get_if<core::Collisions>(&effect)) collisions->reuse_contacts = false;
      std::fprintf(stderr, "%s %s\n", c.name.c_str(), column.c_str());
      core::StackVerdict v;
      double seconds = 0;
      try {
        const core::Run r = run(column, c.scene);
        seconds = r.wall_seconds;
        v = c.evaluate(r);
        for (const auto& name : shown) {
          const auto it = r.counters.find(name);
          std::fprintf(stderr, "  %s %s\n", name.c_str(), it == r.counters.end() ? "(none)" : std::to_string(it->second).c_str());
        }
      } catch (const Error& e) {
        v.pass = false, v.ratio = INFINITY, v.worst = std::string("refused: ") + e.what();
      }
      if (!shown.empty()) std::fprintf(stderr, "  worst: %s\n", v.worst.c_str());
      passed[column] += v.pass;
      wall[column] += seconds;
      std::printf(" %s %.2g, %.3g s |", v.pass ? "pass" : "FAIL", v.ratio, seconds / c.scene.duration);
      if (!v.pass)
        failures.push_back(c.name + " (" + column + "): " + v.worst + "; first: " + v.first_failure +
                           (c.open.empty() || column == "bullet" ? "" : "; open: " + c.open));
      std::fflush(stdout);
    }
    std::printf("\n");
  }
  bench::print_tally(columns, passed, wall, cases, failures, "the worst check, then the first");
  return 0;
}
