// The degenerate-case table (docs/results/contacts.md): every case of the
// contact family (answers/contact_family.hpp) through traditional, cga, pga and Bullet,
// each judged against its analytic outcome. A cell is "pass" or "FAIL" with the
// worst error (the check that came closest to, or went furthest past, its
// tolerance); the reasons for the failures follow the table. Markdown on stdout,
// progress on stderr.
//
//   build/release/bench/contact_table [--filter TEXT] [--backends traditional,cga,pga,bullet]
//                                     [--max-duration S] [--method manifold|report]
//
// --filter keeps the cases whose name contains TEXT; --max-duration shortens
// every case to at most S simulated seconds (the table says so: a shortened
// stack is judged on its shorter run); --method sets how our backends find
// contacts (the collisions effect's "method"; Bullet has its own).
#include "core/memory.hpp"
#include "compare/runner.hpp"
#include "answers/contact_family.hpp"
#include "core/error.hpp"
#include "family_table.hpp"

#include <cstdio>
#include <cstdlib>
#include <map>
#include <string>
#include <vector>

using namespace gacompare;

namespace {

core::Run run(const std::string& backend, const core::Scene& scene) { return compare::run_backend(scene, backend); }

std::string cell(const core::ContactVerdict& v) {
  char buf[64];
  std::snprintf(buf, sizeof buf, "%s %.2g%s%s", v.pass ? "pass" : "FAIL", v.error, v.unit.empty() ? "" : " ",
                v.unit.c_str());
  return buf;
}

int usage() {
  std::fprintf(stderr, "usage: contact_table [--filter TEXT] [--backends traditional,cga,pga,bullet] [--max-duration S] "
                       "[--method manifold|report]\n");
  return 2;
}

}  // namespace

int main(int argc, char** argv) {
  gacompare::core::keep_freed_memory();  // core/memory.hpp: a stack's solves no longer shrink and regrow the heap
  std::string filter, command = "contact_table";
  std::vector<std::string> backends{"traditional", "cga", "pga", "bullet"};
  double max_duration = 0;
  core::ContactMethod method = core::ContactMethod::manifold;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (i + 1 >= argc) return usage();
    const std::string value = argv[++i];
    command += " " + arg + " " + value;
    if (arg == "--filter") {
      filter = value;
    } else if (arg == "--max-duration") {
      max_duration = std::atof(value.c_str());
    } else if (arg == "--method") {
      if (value != "manifold" && value != "report") return usage();
      method = value == "report" ? core::ContactMethod::report : core::ContactMethod::manifold;
    } else if (arg == "--backends") {
      const auto list = bench::column_list(value, {"traditional", "cga", "pga", "bullet"});
      if (!list) return usage();
      backends = *list;
    } else {
      return usage();
    }
  }

  std::printf("Command: `build/release/bench/%s`%s\n\n", command.c_str(),
              max_duration > 0 ? " (every case shortened to the given duration)" : "");
  std::printf("| case |");
  for (const auto& b : backends) std::printf(" %s |", b.c_str());
  std::printf("\n|---|");
  for (std::size_t k = 0; k < backends.size(); ++k) std::printf("---|");
  std::printf("\n");

  std::vector<std::string> failures;
  std::map<std::string, double> wall;
  std::map<std::string, int> passed;
  int cases = 0;
  for (const auto& c : core::contact_family()) {
    if (c.name.find(filter) == std::string::npos) continue;
    ++cases;
    core::Scene scene = c.scene;
    if (max_duration > 0 && scene.duration > max_duration) scene.duration = max_duration;
    for (auto& e : scene.effects)
      if (auto* k = std::get_if<core::Collisions>(&e)) k->method = method;
    std::printf("| %s%s |", c.name.c_str(), c.bundled.empty() ? "" : (" (" + c.bundled + ")").c_str());
    for (const auto& b : backends) {
      std::fprintf(stderr, "%s %s\n", c.name.c_str(), b.c_str());
      core::ContactVerdict v;
      try {
        const core::Run r = run(b, scene);
        wall[b] += r.wall_seconds;
        v = c.evaluate(scene, r);
      } catch (const Error& e) {
        v.pass = false, v.error = INFINITY, v.reason = std::string("refused: ") + e.what();
      }
      passed[b] += v.pass;
      std::printf(" %s |", cell(v).c_str());
      if (!v.pass)
        failures.push_back(c.name + " (" + b + "): " + v.reason +
                           (v.first_failure != v.reason ? "; first: " + v.first_failure : ""));
      std::fflush(stdout);
    }
    std::printf("\n");
  }
  bench::print_tally(backends, passed, wall, cases, failures, "the worst check");
  return 0;
}
