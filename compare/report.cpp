#include "compare/report.hpp"

#include "compare/check.hpp"
#include "compare/results.hpp"
#include "compare/sanity.hpp"
#include "compare/stats.hpp"

#include <cmath>
#include <cstdio>
#include <set>
#include <sstream>

namespace gacompare::compare {

namespace {
using core::Stage;

std::string fmt(const char* f, double x) {
  char buf[64];
  std::snprintf(buf, sizeof buf, f, x);
  return buf;
}

std::vector<double> stage_seconds(const BackendResult& b, Stage s) {
  std::vector<double> v;
  for (const auto& p : b.profiles) v.push_back(p[s].seconds);
  return v;
}
std::vector<double> total_seconds(const BackendResult& b) {
  std::vector<double> v;
  for (const auto& p : b.profiles) v.push_back(p.total_seconds());
  return v;
}

// cga/traditional over paired repeats (repeat i of one against repeat i of the
// other, run back to back): the median ratio and its min–max, like hyperfine's
// "Relative ± σ" but robust to the odd slow repeat.
Spread paired_ratio(const std::vector<double>& num, const std::vector<double>& den) {
  std::vector<double> r;
  for (std::size_t i = 0; i < std::min(num.size(), den.size()); ++i)
    if (den[i] > 0) r.push_back(num[i] / den[i]);
  return spread(r);
}

std::string time_cell(const std::vector<double>& secs) {
  const Spread s = spread(secs);
  return format_seconds(s.median) + " (" + format_seconds(s.min) + "–" + format_seconds(s.max) + ")";
}
std::string ratio_cell(const Spread& s) {
  return fmt("%.2f", s.median) + " (" + fmt("%.2f", s.min) + "–" + fmt("%.2f", s.max) + ")";
}

const BackendResult* find(const SceneResult& r, std::string_view name) {
  for (const auto& b : r.backends)
    if (b.run.backend == name) return &b;
  return nullptr;
}

std::string header(const MachineInfo& m, int repeats) {
  std::ostringstream o;
  o << "gacompare " << tool_version() << " (" << m.build_type << ", " << m.compiler << ") on " << m.cpu << ", "
    << m.date << ". Times are medians over " << repeats
    << " repeats, backends interleaved, with min–max in brackets; ratios are cga/traditional over paired repeats.\n";
  return o.str();
}
}  // namespace

std::string format_seconds(double s) {
  if (s == 0) return "0";
  const double a = std::abs(s);
  if (a < 1e-6) return fmt("%.3g ns", s * 1e9);
  if (a < 1e-3) return fmt("%.3g µs", s * 1e6);
  if (a < 1) return fmt("%.3g ms", s * 1e3);
  return fmt("%.3g s", s);
}

std::string scene_report_md(const SceneResult& r, const MachineInfo& machine, int repeats) {
  std::ostringstream o;
  o << "# " << r.scene.name << "\n\n";
  if (!r.scene.description.empty()) o << r.scene.description << "\n\n";
  o << "Scene `" << r.scene.file.filename().string() << "` (sha256 " << r.scene.sha256.substr(0, 12) << "…), "
    << r.scene.duration << " s simulated, solver `" << core::to_string(r.scene.solver.method) << "`.\n"
    << header(machine, repeats) << "\n";

  for (const auto& b : r.backends)
    if (b.run.error) o << "**" << b.run.backend << " stopped early:** " << *b.run.error << "\n\n";
  // Physical sanity first: a run that breaks physics must not read as a
  // timing table with a footnote (the rules: compare/sanity.hpp).
  const std::vector<CheckLine> sanity = sanity_checks(r);
  for (const auto& w : sanity_warnings(sanity)) o << "**WARNING, physical sanity:** " << w << "\n\n";

  o << "## Stage times\n\n| stage |";
  for (const auto& b : r.backends) o << " " << b.run.backend << " | calls | share |";
  const BackendResult* trad = find(r, "traditional");
  const BackendResult* cga = find(r, "cga");
  const bool ratio = trad && cga;
  if (ratio) o << " cga / traditional |";
  o << "\n|---|";
  for (std::size_t i = 0; i < r.backends.size(); ++i) o << "---:|---:|---:|";
  if (ratio) o << "---:|";
  o << "\n";
  for (int k = 0; k < core::kStageCount; ++k) {
    const auto s = static_cast<Stage>(k);
    bool any = false;
    for (const auto& b : r.backends) any = any || b.run.profile.ran(s);
    if (!any) continue;
    o << "| `" << core::stage_name(s) << "` |";
    for (const auto& b : r.backends) {
      const double share = b.run.profile.total_seconds() > 0
                               ? spread(stage_seconds(b, s)).median / spread(total_seconds(b)).median
                               : 0;
      o << " " << time_cell(stage_seconds(b, s)) << " | " << b.run.profile[s].calls << " | "
        << fmt("%.0f%%", 100 * share) << " |";
    }
    if (ratio) o << " " << ratio_cell(paired_ratio(stage_seconds(*cga, s), stage_seconds(*trad, s))) << " |";
    o << "\n";
  }
  o << "| **all stages** |";
  for (const auto& b : r.backends) o << " " << time_cell(total_seconds(b)) << " | | 100% |";
  if (ratio) o << " " << ratio_cell(paired_ratio(total_seconds(*cga), total_seconds(*trad))) << " |";
  o << "\n\n";

  o << "## Solver and invariants\n\n| | ";
  for (const auto& b : r.backends) o << b.run.backend << " | ";
  o << "\n|---|";
  for (std::size_t i = 0; i < r.backends.size(); ++i) o << "---:|";
  o << "\n";
  auto row = [&](const char* name, auto value) {
    o << "| " << name << " |";
    for (const auto& b : r.backends) o << " " << value(b) << " |";
    o << "\n";
  };
  row("steps accepted", [](const BackendResult& b) { return std::to_string(b.run.solver.steps_accepted); });
  row("steps rejected", [](const BackendResult& b) { return std::to_string(b.run.solver.steps_rejected); });
  row("derivative evaluations",
      [](const BackendResult& b) { return std::to_string(b.run.solver.derivative_evaluations); });
  row("smallest / largest step", [](const BackendResult& b) {
    return b.run.solver.steps_accepted ? fmt("%.3g", b.run.solver.min_step) + " / " + fmt("%.3g", b.run.solver.max_step)
                                       : std::string("–");
  });
  row("largest energy change, relative (max ΔE / energy scale)", [](const BackendResult& b) { return fmt("%.3e", energy_drift(b.run)); });
  bool constrained = false;
  for (const auto& b : r.backends) constrained = constrained || !b.run.counters.empty();
  if (constrained) {
    row("largest constraint violation (m, first-order distance)", [](const BackendResult& b) {
      double worst = 0;
      for (const auto& s : b.run.samples) worst = std::max(worst, s.constraint_violation);
      return fmt("%.3e", worst);
    });
    // Every backend's counters, by name (a backend may count what others do
    // not: bullet counts its steps and contact points), a dash where one has none.
    std::set<std::string> names;
    for (const auto& b : r.backends)
      for (const auto& counter : b.run.counters) names.insert(counter.first);
    for (const auto& name : names) {
      o << "| " << name << " |";
      for (const auto& b : r.backends) {
        const auto it = b.run.counters.find(name);
        o << " " << (it == b.run.counters.end() ? std::string("–") : std::to_string(it->second)) << " |";
      }
      o << "\n";
    }
    row("largest CG relative residual", [](const BackendResult& b) {
      const auto it = b.run.metrics.find("max_cg_relative_residual");
      return it == b.run.metrics.end() ? std::string("–") : fmt("%.2e", it->second);
    });
  }
  row("samples", [](const BackendResult& b) { return std::to_string(b.run.samples.size()); });
  row("repeats bit-identical", [](const BackendResult& b) { return std::string(b.deterministic ? "yes" : "**no**"); });
  bool bodies = false;
  for (const auto& b : r.backends)
    bodies = bodies || (!b.run.samples.empty() && !b.run.samples.front().bodies.empty());
  if (bodies)
    row("largest rotation drift (distance of the stored rotation from a rotation)", [](const BackendResult& b) {
      double worst = 0;
      for (const auto& s : b.run.samples) worst = std::max(worst, s.rotation_drift);
      return fmt("%.3e", worst);
    });
  for (const auto& b : r.backends) {
    if (b.run.backend != "bullet") continue;
    const auto metric = [&](const char* k) {
      const auto it = b.run.metrics.find(k);
      return it == b.run.metrics.end() ? std::string("–") : fmt("%g", it->second);
    };
    // Why Bullet's numbers differ from ours (compare/bullet_world.cpp has the details).
    o << "\n**About the Bullet run.** Bullet is a different method, not a third algebra: one fixed step of "
      << metric("bullet_fixed_step_s")
      << " s (symplectic Euler with a first-order implicit gyroscopic term) where our backends integrate with the "
         "scene's solver; contacts are found at the end of a step and solved by "
      << metric("bullet_solver_iterations")
      << " warm-started iterations of sequential impulses with Baumgarte stabilisation (ERP "
      << metric("bullet_erp") << ") where ours retreat to the time of impact and solve the impulses of eq. 53/54; "
         "no restitution below " << metric("bullet_restitution_velocity_threshold_m_per_s")
      << " m/s impact speed (our resting threshold is √(2|g| tol) + 2|g| step); friction and damping 0, margins 0, "
         "sleeping off, restitution combined as our min(ε_a, ε_b). Expect bounce heights to agree to about one "
         "step's travel, rest poses to the penetration tolerance, and many-body scenes to part as chaos "
         "amplifies the differences.\n";
  }
  if (!sanity.empty())
    o << "\n## Physical sanity\n\nThe rules of `gacompare check` that hold for any correct frictionless contact "
         "response (README, `check`); a failing one is the warning at the top of this report.\n\n"
      << check_table(sanity);
  if (r.backends.size() > 1) {
    o << "\nLargest distance between the traditional and cga positions over all samples: "
      << fmt("%.3e", max_divergence(r))
      << " m";
    if (bodies) o << "; largest angle between their orientations: " << fmt("%.3e", max_orientation_divergence(r)) << " rad";
    o << ".\n";
  }
  return o.str();
}

std::string stage_csv(const std::vector<SceneResult>& results) {
  std::ostringstream o;
  o << "scene,backend,stage,median_s,min_s,max_s,calls\n";
  for (const auto& r : results)
    for (const auto& b : r.backends)
      for (int k = 0; k < core::kStageCount; ++k) {
        const auto s = static_cast<Stage>(k);
        if (!b.run.profile.ran(s)) continue;
        const Spread sp = spread(stage_seconds(b, s));
        o << r.scene.name << "," << b.run.backend << "," << core::stage_name(s) << "," << fmt("%.9g", sp.median) << ","
          << fmt("%.9g", sp.min) << "," << fmt("%.9g", sp.max) << "," << b.run.profile[s].calls << "\n";
      }
  return o.str();
}

std::string summary_report_md(const std::vector<SceneResult>& results, const MachineInfo& machine, int repeats) {
  std::ostringstream o;
  o << "# gacompare: " << results.size() << " scenes\n\n" << header(machine, repeats) << "\n";
  o << "| scene | traditional | cga | cga / traditional | max divergence (m) | energy change trad / cga |\n"
    << "|---|---:|---:|---:|---:|---:|\n";
  for (const auto& r : results) {
    const BackendResult* trad = find(r, "traditional");
    const BackendResult* cga = find(r, "cga");
    o << "| [" << r.scene.name << "](" << r.scene.name << "/report.md) | "
      << (trad ? time_cell(total_seconds(*trad)) : "–") << " | " << (cga ? time_cell(total_seconds(*cga)) : "–") << " | "
      << (trad && cga ? ratio_cell(paired_ratio(total_seconds(*cga), total_seconds(*trad))) : "–") << " | "
      << fmt("%.2e", max_divergence(r)) << " | "
      << (trad ? fmt("%.2e", energy_drift(trad->run)) : "–") << " / " << (cga ? fmt("%.2e", energy_drift(cga->run)) : "–")
      << " |\n";
  }

  // Physical sanity (compare/sanity.hpp), every warning of every scene, where
  // nobody reading the summary can miss it.
  std::vector<std::string> warnings;
  for (const auto& r : results)
    for (const auto& w : sanity_warnings(sanity_checks(r))) warnings.push_back(r.scene.name + ": " + w);
  for (const auto& w : warnings) o << "\n**WARNING, physical sanity:** " << w << "\n";

  // Per stage, across scenes: the median over scenes of each scene's median
  // paired ratio, with the smallest and largest scene's.
  std::vector<double> overall;
  o << "\n## cga / traditional by stage, across scenes\n\n| stage | scenes | median ratio (min–max over scenes) |\n"
    << "|---|---:|---:|\n";
  for (int k = 0; k < core::kStageCount; ++k) {
    const auto st = static_cast<Stage>(k);
    std::vector<double> ratios;
    for (const auto& r : results) {
      const BackendResult* trad = find(r, "traditional");
      const BackendResult* cga = find(r, "cga");
      if (trad && cga && trad->run.profile.ran(st) && cga->run.profile.ran(st))
        ratios.push_back(paired_ratio(stage_seconds(*cga, st), stage_seconds(*trad, st)).median);
    }
    if (ratios.empty()) continue;
    o << "| `" << core::stage_name(st) << "` | " << ratios.size() << " | " << ratio_cell(spread(ratios)) << " |\n";
  }
  for (const auto& r : results) {
    const BackendResult* trad = find(r, "traditional");
    const BackendResult* cga = find(r, "cga");
    if (trad && cga) overall.push_back(paired_ratio(total_seconds(*cga), total_seconds(*trad)).median);
  }
  if (!overall.empty()) {
    const Spread sp = spread(overall);
    o << "| **all stages** | " << overall.size() << " | " << ratio_cell(sp) << " |\n\n";
    // The verdict §1.1 asks for (does GA help?), for speed, stated from the numbers.
    const char* speed = sp.median < 0.95 ? "faster than" : sp.median > 1.05 ? "slower than" : "as fast as (within 5% of)";
    double worst_divergence = 0, worst_angle = 0;
    for (const auto& r : results) {
      worst_divergence = std::max(worst_divergence, max_divergence(r));
      worst_angle = std::max(worst_angle, max_orientation_divergence(r));
    }
    o << "**Verdict, from these numbers:** across " << overall.size() << " scenes the geometric-algebra backend ran "
      << speed << " the traditional one (median ratio " << fmt("%.2f", sp.median) << ", " << fmt("%.2f", sp.min) << "–"
      << fmt("%.2f", sp.max) << " over scenes), and the two agreed on every position to " << fmt("%.1e", worst_divergence)
      << " m and every orientation to " << fmt("%.1e", worst_angle)
      << " rad. Coding simplicity is not measured here: compare `traditional/` and `cga/` side by side.\n";
  }
  return o.str();
}

void write_reports(const std::filesystem::path& dir, const std::vector<SceneResult>& results,
                   const MachineInfo& machine, int repeats) {
  auto write_scene = [&](const std::filesystem::path& d, const SceneResult& r) {
    write_file_atomically(d / "results.json", results_json(r, machine, repeats).dump(1) + "\n");
    write_file_atomically(d / "stages.csv", stage_csv({r}));
    write_file_atomically(d / "report.md", scene_report_md(r, machine, repeats));
    write_file_atomically(d / "report.html", scene_report_html(r, machine, repeats));
  };
  if (results.size() == 1) {
    write_scene(dir, results.front());
    return;
  }
  for (const auto& r : results) write_scene(dir / r.scene.name, r);
  write_file_atomically(dir / "stages.csv", stage_csv(results));
  write_file_atomically(dir / "report.md", summary_report_md(results, machine, repeats));
  write_file_atomically(dir / "report.html", summary_report_html(results, machine, repeats));
}

}  // namespace gacompare::compare
