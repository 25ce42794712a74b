#include "compare/report.hpp"

#include "compare/check.hpp"
#include "compare/escape.hpp"
#include "compare/replay.hpp"
#include "compare/files.hpp"
#include "compare/results.hpp"
#include "compare/sanity.hpp"
#include "compare/stats.hpp"
#include "compare/summary.hpp"

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
  o << "gacompare " << tool_version() << " (" << m.build_type << ", " << m.compiler << ", commit "
    << m.build.commit.substr(0, 12) << (m.build.dirty == "yes" ? " with uncommitted changes" : m.build.dirty == "no" ? "" : ", tree state unknown")
    << ") on " << m.cpu << " (" << m.usable_cpus << " CPUs usable, load average " << fmt("%.2f", m.load_average[0])
    << " at the start), " << m.date << ". Times are medians over " << repeats
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
  o << "# " << md_text(r.scene.name) << "\n\n";
  if (!r.scene.description.empty()) o << md_text(r.scene.description) << "\n\n";
  o << "Scene " << md_text(r.scene.file.filename().string()) << " (sha256 " << r.scene.sha256.substr(0, 12) << "…), "
    << r.scene.duration << " s simulated, solver `" << core::to_string(r.scene.solver.method) << "`.\n"
    << header(machine, repeats) << "\n";

  for (const auto& b : r.backends)
    if (b.run.error) o << "**" << md_text(b.run.backend) << " stopped early:** " << md_text(*b.run.error) << "\n\n";
  // Physical sanity first: a run that breaks physics must not read as a
  // timing table with a footnote (the rules: compare/sanity.hpp).
  const std::vector<CheckLine> sanity = sanity_checks(r);
  for (const auto& w : sanity_warnings(sanity)) o << "**WARNING, physical sanity:** " << md_text(w) << "\n\n";

  bool gaps = false, bullet = false;  // a stage one backend ran and another did not
  for (const auto& b : r.backends) bullet = bullet || b.run.backend == "bullet";
  for (int k = 0; k < core::kStageCount; ++k)
    for (const auto& b : r.backends)
      gaps = gaps || (b.run.profile.ran(static_cast<Stage>(k)) != r.backends.front().run.profile.ran(static_cast<Stage>(k)));
  o << "## Stage times\n\n";
  if (gaps)
    o << "A dash: the backend has no such stage"
      << (bullet ? " (Bullet finds and answers contacts inside its own step, all timed as `integrate`)" : "") << ".\n\n";
  o << "| stage |";
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
      if (!b.run.profile.ran(s)) {  // Bullet has no time of impact: not "0 (0–0) 0%"
        o << " – | – | – |";
        continue;
      }
      const double share = b.run.profile.total_seconds() > 0
                               ? spread(stage_seconds(b, s)).median / spread(total_seconds(b)).median
                               : 0;
      o << " " << time_cell(stage_seconds(b, s)) << " | " << b.run.profile[s].calls << " | "
        << fmt("%.0f%%", 100 * share) << " |";
    }
    if (ratio)
      o << " "
        << (cga->run.profile.ran(s) && trad->run.profile.ran(s)
                ? ratio_cell(paired_ratio(stage_seconds(*cga, s), stage_seconds(*trad, s)))
                : std::string("–"))
        << " |";
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
      o << "| " << md_text(name) << " |";
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
         "response (docs/using-gacompare.md, \"Physical sanity\"); a failing one is the warning at the top of this report.\n\n"
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
        o << csv_field(r.scene.name) << "," << csv_field(b.run.backend) << "," << core::stage_name(s) << "," << fmt("%.9g", sp.median) << ","
          << fmt("%.9g", sp.min) << "," << fmt("%.9g", sp.max) << "," << b.run.profile[s].calls << "\n";
      }
  return o.str();
}

namespace {
std::string interval_cell(const RatioInterval& r) {
  if (std::isnan(r.ratio)) return "–";
  if (std::isnan(r.lo)) return fmt("%.2f", r.ratio);
  return fmt("%.2f", r.ratio) + " [" + fmt("%.2f", r.lo) + ", " + fmt("%.2f", r.hi) + "]";
}

// The summary's per-category table and the runs compared per unit of work
// (compare/summary.hpp has the rules).
void category_tables(std::ostringstream& o, const std::vector<SceneSummary>& scenes, int repeats) {
  o << "\n## cga / traditional by category and stage\n\n"
    << "Weighted by time: the sum over a category's scenes of the mean cga time per repeat over the sum of the mean "
       "traditional time (each scene's ratio weighted by its traditional time, not one vote per scene). In brackets "
       "a 95% bootstrap interval over paired repeats (repeats resampled within each scene, each cga repeat with the "
       "traditional repeat it ran beside; "
    << kBootstrapResamples << " resamples, seed " << kBootstrapSeed
    << "; the expanded percentile interval, which widens the plain one for few repeats). The verdict is \"within "
       "noise\" whenever the interval contains 1. Particle scenes run the same formulas in both backends (a Cl(3,0) "
       "vector is a 3-vector): reported, not counted as evidence.\n\n";
  if (repeats < static_cast<int>(kMinRepeatsForInterval))
    o << "**Note:** with " << repeats << " repeat" << (repeats == 1 ? "" : "s")
      << " there is no interval and so no verdict: a bootstrap interval from fewer than " << kMinRepeatsForInterval
      << " repeats holds the true ratio well under 95% of the time. Use `--repeat " << kMinRepeatsForInterval
      << "` or more.\n\n";
  o << "| category | stage | scenes | traditional | cga | cga / traditional [95% CI] | verdict |\n"
    << "|---|---|---:|---:|---:|---:|---|\n";
  for (const Category c : kCategories) {
    const Aggregate overall = aggregate(scenes, c, std::nullopt);
    if (overall.scenes == 0) continue;
    const std::string name = std::string(to_string(c)) + (is_evidence(c) ? "" : " (not evidence)");
    auto line = [&](const std::string& stage, const Aggregate& a) {
      o << "| " << name << " | " << stage << " | " << a.scenes << " | " << format_seconds(a.traditional_seconds)
        << " | " << format_seconds(a.cga_seconds) << " | " << interval_cell(a.ratio) << " | "
        << to_string(a.verdict) << " |\n";
    };
    for (int k = 0; k < core::kStageCount; ++k) {
      const auto st = static_cast<Stage>(k);
      const Aggregate a = aggregate(scenes, c, st);
      if (a.scenes > 0) line(std::string("`").append(core::stage_name(st)).append("`"), a);
    }
    line("**all stages**", overall);
  }

  for (const auto& s : scenes) {
    if (s.trajectories != Trajectories::parted) continue;
    o << "\n## " << md_text(s.name) << ": parted, compared per unit of work\n\n"
      << "The backends' positions moved " << fmt("%.2g", s.divergence) << " m apart, beyond the scene's "
      << s.tolerance.source << " (" << fmt("%.2g", s.tolerance.metres)
      << " m): they no longer follow one trajectory (chaos amplifies the backends' different rounding), so they "
         "did different work. Each stage's cga time is scaled to the traditional run's work (times the traditional "
         "units over the cga units), and the scene enters its category's ratios that way.\n\n"
      << "| stage | unit | traditional units | cga units | traditional per unit | cga per unit | cga / traditional "
         "[95% CI] |\n|---|---|---:|---:|---:|---:|---:|\n";
    // Mean seconds per repeat over the units of work.
    const auto per = [](const std::vector<double>& v, std::uint64_t n) {
      double sum = 0;
      for (double x : v) sum += x;
      return n && !v.empty() ? format_seconds(sum / static_cast<double>(v.size()) / static_cast<double>(n))
                             : std::string("–");
    };
    for (const auto& st : s.stages) {
      o << "| `" << core::stage_name(st.stage) << "` | " << st.unit << " | " << st.traditional_work << " | "
        << st.cga_work << " | " << per(st.seconds.traditional, st.traditional_work) << " | "
        << per(st.seconds.cga, st.cga_work) << " | " << interval_cell(scene_ratio(s, st.stage)) << " |\n";
    }
  }
}

// The verdict §1.1 asks for (does GA help?), for speed and agreement, stated
// from the numbers above and claiming no more than they show.
void verdict(std::ostringstream& o, const std::vector<SceneSummary>& scenes) {
  o << "\n**Verdict, from these numbers:** ";
  std::vector<std::string> evidence, shared;
  for (const Category c : kCategories) {
    const Aggregate a = aggregate(scenes, c, std::nullopt);
    if (a.scenes == 0) continue;
    std::string parted;
    for (const auto& s : scenes)
      if (s.category == c && s.trajectories == Trajectories::parted) parted += (parted.empty() ? "" : ", ") + md_text(s.name);
    (is_evidence(c) ? evidence : shared)
        .push_back(std::string(to_string(c)) + " (" + std::to_string(a.scenes) + " scene" + (a.scenes == 1 ? "" : "s") +
                   (parted.empty() ? "" : "; " + parted + " per unit of work") + "): " + to_string(a.verdict) +
                   ", cga / traditional " + interval_cell(a.ratio));
  }
  if (evidence.empty()) o << "no rigid-body or collision scene was compared, so there is no evidence either way";
  for (std::size_t i = 0; i < evidence.size(); ++i) o << (i ? "; " : "") << evidence[i];
  o << ". ";
  for (const auto& text : shared)
    o << "The " << text << ": the same code runs in both backends, so this is reported, not evidence. ";

  int identical = 0, agree = 0, own = 0;
  const SceneSummary* closest = nullptr;  // the agreeing scene nearest its tolerance
  std::vector<std::string> parted, not_compared;
  for (const auto& s : scenes) {
    if (s.trajectories == Trajectories::identical) ++identical;
    if (s.trajectories == Trajectories::agree) {
      ++agree;
      if (!closest || s.tolerance_used > closest->tolerance_used) closest = &s;
    }
    if (s.trajectories == Trajectories::parted) parted.push_back(md_text(s.name));
    if (s.trajectories == Trajectories::own_settings) ++own;
    if (s.trajectories == Trajectories::not_compared) not_compared.push_back(md_text(s.name + " (" + s.not_compared_why + ")"));
  }
  if (own)
    o << "Each backend ran at its own setting, the one reaching the same accuracy (`--accuracy`), on " << own << " of "
      << scenes.size() << " scenes: their trajectories differ by design and no agreement between them is claimed. ";
  if (own < static_cast<int>(scenes.size())) {
    o << "Trajectories: identical at every sample on " << identical << " of " << scenes.size() << " scenes";
    if (agree)
      o << ", within the scene's own tolerance on " << agree << " (nearest it: " << md_text(closest->name) << ", "
        << fmt("%.2g", 100 * closest->tolerance_used) << "% of " << fmt("%.0e", closest->tolerance.metres) << " m)";
    const auto list = [](const std::vector<std::string>& v) {
      std::string out;
      for (const auto& x : v) out += (out.empty() ? "" : ", ") + x;
      return out;
    };
    if (!parted.empty()) o << "; parted (chaotic) on " << list(parted) << ", where no agreement is claimed";
    if (!not_compared.empty()) o << "; not compared on " << list(not_compared);
    o << ". ";
  }
  o << "Coding simplicity is not measured here: compare `traditional/` and `cga/` side by side.\n";
}
}  // namespace

std::string summary_report_md(const std::vector<SceneResult>& results, const MachineInfo& machine, int repeats,
                              double equal_accuracy) {
  std::vector<SceneSummary> scenes;
  for (const auto& r : results) scenes.push_back(summarise_scene(r, equal_accuracy > 0));
  std::ostringstream o;
  o << "# gacompare: " << results.size() << " scenes\n\n" << header(machine, repeats) << "\n";
  o << "| scene | category | traditional | cga | cga / traditional [95% CI] | apart (m) | apart (rad) | "
       "tolerance d (m) | trajectories | energy change trad / cga |\n"
    << "|---|---|---:|---:|---:|---:|---:|---:|---|---:|\n";
  for (std::size_t i = 0; i < results.size(); ++i) {
    const SceneResult& r = results[i];
    const SceneSummary& s = scenes[i];
    const BackendResult* trad = find(r, "traditional");
    const BackendResult* cga = find(r, "cga");
    const bool compared = s.trajectories != Trajectories::not_compared;
    o << "| [" << md_text(r.scene.name) << "](" << file_name_for(r.scene.name) << "/report.md) | " << to_string(s.category) << " | "
      << (trad ? time_cell(total_seconds(*trad)) : "–") << " | " << (cga ? time_cell(total_seconds(*cga)) : "–")
      << " | "
      << (!compared ? "–"
          : s.trajectories == Trajectories::parted
              ? interval_cell(scene_ratio(s, std::nullopt)) + " per unit of work (whole run " +
                    interval_cell(scene_ratio(s, std::nullopt, true)) + ")"
              : interval_cell(scene_ratio(s, std::nullopt)))
      << " | " << (compared ? fmt("%.2e", s.divergence) : "–") << " | "
      << (compared && s.bodies ? fmt("%.2e", s.orientation_divergence) : "–") << " | "
      << fmt("%.0e", s.tolerance.metres) << (s.tolerance.source == "check.max_divergence" ? "" : " (penetration)")
      << " | " << to_string(s.trajectories) << " | "
      << (trad ? fmt("%.2e", energy_drift(trad->run)) : "–") << " / " << (cga ? fmt("%.2e", energy_drift(cga->run)) : "–")
      << " |\n";
  }
  o << "\nRatios are of the mean time per repeat, whole run; where the trajectories parted, per unit of each "
       "stage's work (below). Apart: the largest distance between the backends' particles and bodies' centres "
       "of mass, and angle between their bodies' orientations, over all samples. Tolerance d: the scene's "
       "`check.max_divergence`, or on a collision scene its penetration tolerance where that is smaller. Within "
       "it: every position within d and every moving body's orientation within d / r (r the body's radius: a "
       "turn by d / r moves none of its points further than d), the bounds `check` applies between backends. No "
       "agreement is claimed beyond it.\n";

  // Physical sanity (compare/sanity.hpp), every warning of every scene, where
  // nobody reading the summary can miss it.
  std::vector<std::string> warnings;
  for (const auto& r : results)
    for (const auto& w : sanity_warnings(sanity_checks(r))) warnings.push_back(md_text(r.scene.name + ": " + w));
  for (const auto& w : warnings) o << "\n**WARNING, physical sanity:** " << w << "\n";

  category_tables(o, scenes, repeats);
  verdict(o, scenes);
  return o.str();
}

void write_reports(const std::filesystem::path& dir, const std::vector<SceneResult>& results,
                   const MachineInfo& machine, int repeats, double equal_accuracy) {
  auto write_scene = [&](const std::filesystem::path& d, const SceneResult& r) {
    write_file_atomically(d / "results.json", results_json(r, machine, repeats).dump(1) + "\n");
    write_file_atomically(d / "stages.csv", stage_csv({r}));
    write_file_atomically(d / "report.md", scene_report_md(r, machine, repeats));
    write_file_atomically(d / "report.html", scene_report_html(r, machine, repeats));
    write_file_atomically(d / "trajectories.csv", trajectories_csv(r));
    write_file_atomically(d / "replay.html", replay_html(r));
  };
  if (results.size() == 1) {
    write_scene(dir, results.front());
    return;
  }
  for (const auto& r : results) write_scene(dir / file_name_for(r.scene.name), r);
  write_file_atomically(dir / "stages.csv", stage_csv(results));
  std::vector<SceneSummary> scenes;
  for (const auto& r : results) scenes.push_back(summarise_scene(r, equal_accuracy > 0));
  write_file_atomically(dir / "summary.json", summary_json(scenes, machine, repeats, equal_accuracy).dump(1) + "\n");
  write_file_atomically(dir / "report.md", summary_report_md(results, machine, repeats, equal_accuracy));
  write_file_atomically(dir / "report.html", summary_report_html(results, machine, repeats, equal_accuracy));
}

}  // namespace gacompare::compare
