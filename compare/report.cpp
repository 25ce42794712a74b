#include "compare/report.hpp"

#include "compare/check.hpp"
#include "compare/escape.hpp"
#include "compare/replay.hpp"
#include "compare/files.hpp"
#include "compare/plot.hpp"
#include "compare/results.hpp"
#include "compare/sanity.hpp"
#include "compare/stats.hpp"
#include "compare/summary.hpp"

#include <cmath>
#include <cstdio>
#include <set>
#include <span>
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

// One backend's time over another's, over paired repeats (repeat i of one
// against repeat i of the other, run back to back): the median ratio and its
// min–max, like hyperfine's "Relative ± σ" but robust to the odd slow repeat.
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
// The unit a time reads best in: its scale and name (format_seconds' choice).
struct TimeUnit {
  double scale;
  const char* name;
};
TimeUnit time_unit(double seconds) {
  const double a = std::abs(seconds);
  return a < 1e-6 ? TimeUnit{1e9, " ns"} : a < 1e-3 ? TimeUnit{1e6, " µs"} : a < 1 ? TimeUnit{1e3, " ms"} : TimeUnit{1, " s"};
}
// "4.10 ms (4.09–4.17)": the median's unit once, so that a row of backends fits the page.
std::string compact_time_cell(const std::vector<double>& secs) {
  const Spread s = spread(secs);
  const TimeUnit u = time_unit(s.median);
  return fmt("%.3g", s.median * u.scale) + u.name + " (" + fmt("%.4g", s.min * u.scale) + "–" +
         fmt("%.4g", s.max * u.scale) + ")";
}
std::string ratio_cell(const Spread& s) {
  return fmt("%.2f", s.median) + " (" + fmt("%.2f", s.min) + "–" + fmt("%.2f", s.max) + ")";
}

const BackendResult* find(const SceneResult& r, std::string_view name) {
  for (const auto& b : r.backends)
    if (b.run.backend == name) return &b;
  return nullptr;
}

// "a", "a and b", "a, b and c".
std::string and_list(const std::vector<std::string>& items) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i)
    out += (i == 0 ? "" : i + 1 == items.size() ? " and " : ", ") + items[i];
  return out;
}
std::string joined(const std::vector<std::string>& items, const std::string& sep) {
  std::string out;
  for (std::size_t i = 0; i < items.size(); ++i) out += (i ? sep : "") + items[i];
  return out;
}

// The page's opening lines; `pairs`: the ratios it gives, each named.
std::string header(const MachineInfo& m, int repeats, std::span<const BackendPair> pairs) {
  std::vector<std::string> ratios;
  for (const BackendPair p : pairs) ratios.push_back(std::string(p.numerator) + "/" + std::string(p.denominator));
  std::ostringstream o;
  o << "gacompare " << tool_version() << " (" << m.build_type << ", " << m.compiler << ", "
    << (m.allocator.empty() ? "allocator unknown" : m.allocator) << ", commit "
    << m.build.commit.substr(0, 12) << (m.build.dirty == "yes" ? " with uncommitted changes" : m.build.dirty == "no" ? "" : ", tree state unknown")
    << ") on " << m.cpu << " (" << m.usable_cpus << " CPUs usable, load average " << fmt("%.2f", m.load_average[0])
    << " at the start), " << m.date << ". Times are medians over " << repeats
    << " repeats, backends interleaved, with min–max in brackets"
    << (ratios.empty() ? "" : "; ratios are " + and_list(ratios) + " over paired repeats") << ".\n";
  return o.str();
}
}  // namespace

std::string format_seconds(double s) {
  if (s == 0) return "0";
  const TimeUnit u = time_unit(s);
  return fmt("%.3g", s * u.scale) + u.name;
}

std::string scene_report_md(const SceneResult& r, const MachineInfo& machine, int repeats) {
  const std::vector<BackendPair> pairs = pairs_present(std::span(&r, 1));
  std::ostringstream o;
  o << "# " << md_text(r.scene.name) << "\n\n";
  if (!r.scene.description.empty()) o << md_text(r.scene.description) << "\n\n";
  o << "Scene " << md_text(r.scene.file.filename().string()) << " (sha256 " << r.scene.sha256.substr(0, 12) << "…), "
    << r.scene.duration << " s simulated, solver `" << core::to_string(r.scene.solver.method) << "`.\n"
    << header(machine, repeats, pairs) << "\n";

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
  for (const BackendPair p : pairs) o << " " << p.label() << " |";
  o << "\n|---|";
  for (std::size_t i = 0; i < r.backends.size(); ++i) o << "---:|---:|---:|";
  for (std::size_t i = 0; i < pairs.size(); ++i) o << "---:|";
  o << "\n";
  // One ratio cell per pair: `seconds` gives a backend's times of the row.
  const auto ratio_cells = [&](auto seconds, auto ran) {
    for (const BackendPair p : pairs) {
      const BackendResult& num = *find(r, p.numerator);
      const BackendResult& den = *find(r, p.denominator);
      o << " " << (ran(num) && ran(den) ? ratio_cell(paired_ratio(seconds(num), seconds(den))) : std::string("–"))
        << " |";
    }
  };
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
    ratio_cells([&](const BackendResult& b) { return stage_seconds(b, s); },
                [&](const BackendResult& b) { return b.run.profile.ran(s); });
    o << "\n";
  }
  o << "| **all stages** |";
  for (const auto& b : r.backends) o << " " << time_cell(total_seconds(b)) << " | | 100% |";
  ratio_cells(total_seconds, [](const BackendResult&) { return true; });
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
  if (!pairs.empty()) o << "\n";
  for (const BackendPair p : pairs) {
    const StateErrors apart = pair_divergence(r, p);
    o << "Largest distance between the " << p.denominator << " and " << p.numerator
      << " positions over all samples: " << fmt("%.3e", apart[Measure::position]) << " m";
    if (bodies) o << "; largest angle between their orientations: " << fmt("%.3e", apart[Measure::orientation]) << " rad";
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

// One pair's per-category table and its runs compared per unit of work
// (compare/summary.hpp has the rules). The first section says how the numbers
// are made; the others, made the same way, refer to it.
void category_tables(std::ostringstream& o, const PairSummaries& ps, int repeats, bool first) {
  const BackendPair p = ps.pair;
  const std::string num(p.numerator), den(p.denominator), label = p.label();
  o << "\n## " << label << " by category and stage\n\n";
  if (first) {
    o << "Weighted by time: the sum over a category's scenes of the mean time per repeat of the backend named first "
         "over the sum of the mean time of the other (each scene's ratio weighted by the second backend's time, not "
         "one vote per scene). In brackets a 95% bootstrap interval over paired repeats (repeats resampled within "
         "each scene, each repeat of one backend with the repeat of the other it ran beside; "
      << kBootstrapResamples << " resamples, seed " << kBootstrapSeed
      << "; the expanded percentile interval, which widens the plain one for few repeats). The verdict is \"within "
         "noise\" whenever the interval contains 1. Particle scenes run the same formulas in every backend (a "
         "vector of the algebra is a 3-vector): reported, not counted as evidence. A scene whose backends parted "
         "(chaos amplified their different rounding) is left out of its category's ratios: the two runs did "
         "different work, and no count of work makes two piles the same work, so its ratio moves with the chaos. "
         "It has a section of its own below, per unit of work.\n\n";
    if (repeats < static_cast<int>(kMinRepeatsForInterval))
      o << "**Note:** with " << repeats << " repeat" << (repeats == 1 ? "" : "s")
        << " there is no interval and so no verdict: a bootstrap interval from fewer than " << kMinRepeatsForInterval
        << " repeats holds the true ratio well under 95% of the time. Use `--repeat " << kMinRepeatsForInterval
        << "` or more.\n\n";
  } else {
    o << "Weighted, bounded and judged as above.\n\n";
  }
  o << "| category | stage | scenes | " << den << " | " << num << " | " << label << " [95% CI] | verdict |\n"
    << "|---|---|---:|---:|---:|---:|---|\n";
  for (const Category c : kCategories) {
    const Aggregate overall = aggregate(ps.scenes, c, std::nullopt);
    if (overall.scenes == 0 && overall.parted == 0) continue;
    const std::string name = std::string(to_string(c)) + (is_evidence(c) ? "" : " (not evidence)") +
                             (overall.parted ? " (" + std::to_string(overall.parted) + " parted, left out)" : "");
    auto line = [&](const std::string& stage, const Aggregate& a) {
      o << "| " << name << " | " << stage << " | " << a.scenes << " | " << format_seconds(a.denominator_seconds)
        << " | " << format_seconds(a.numerator_seconds) << " | " << interval_cell(a.ratio) << " | "
        << to_string(a.verdict, num) << " |\n";
    };
    for (int k = 0; k < core::kStageCount; ++k) {
      const auto st = static_cast<Stage>(k);
      const Aggregate a = aggregate(ps.scenes, c, st);
      if (a.scenes > 0) line(std::string("`").append(core::stage_name(st)).append("`"), a);
    }
    line("**all stages**", overall);
  }

  for (const auto& s : ps.scenes) {
    if (s.trajectories != Trajectories::parted) continue;
    o << "\n## " << md_text(s.name) << ", " << label << ": parted, compared per unit of work\n\n"
      << "The " << den << " and " << num << " positions moved " << fmt("%.2g", s.divergence)
      << " m apart, beyond the scene's " << s.tolerance.source << " (" << fmt("%.2g", s.tolerance.metres)
      << " m): they no longer follow one trajectory (chaos amplifies the backends' different rounding), so they "
         "did different work, and the scene is left out of its category's " << label << " ratios. Here each stage's "
      << num << " time is scaled to the " << den << " run's work (times the " << den << " units over the " << num
      << " units): a count of the work each did, not a comparison of the algebras on the same work.\n\n"
      << "| stage | unit | " << den << " units | " << num << " units | " << den << " per unit | " << num
      << " per unit | " << label << " [95% CI] |\n|---|---|---:|---:|---:|---:|---:|\n";
    // Mean seconds per repeat over the units of work.
    const auto per = [](const std::vector<double>& v, std::uint64_t n) {
      double sum = 0;
      for (double x : v) sum += x;
      return n && !v.empty() ? format_seconds(sum / static_cast<double>(v.size()) / static_cast<double>(n))
                             : std::string("–");
    };
    for (const auto& st : s.stages) {
      o << "| `" << core::stage_name(st.stage) << "` | " << st.unit << " | " << st.denominator_work << " | "
        << st.numerator_work << " | " << per(st.seconds.denominator, st.denominator_work) << " | "
        << per(st.seconds.numerator, st.numerator_work) << " | " << interval_cell(scene_ratio(s, st.stage)) << " |\n";
    }
  }
}

// The pairs of `pairs`, in their order.
std::vector<BackendPair> pairs_of(const std::vector<PairSummaries>& pairs) {
  std::vector<BackendPair> out;
  for (const auto& ps : pairs) out.push_back(ps.pair);
  return out;
}

// "rotor against matrix (cga / traditional)" where every compared scene of the
// category with bodies stores rotations alike on each side; the bare pair
// otherwise. A headline on rigid bodies must say which representations it
// compares: the rotor against the matrix is not GA against the quaternion.
std::string pair_words(const PairSummaries& ps, Category c) {
  std::string_view num, den;
  bool mixed = false, any = false;
  for (const auto& s : ps.scenes) {
    if (s.category != c || !s.bodies || s.trajectories == Trajectories::not_compared) continue;
    if (any && (s.numerator_form != num || s.denominator_form != den)) mixed = true;
    num = s.numerator_form, den = s.denominator_form, any = true;
  }
  if (!any || mixed || num.empty() || den.empty()) return ps.pair.label();
  return std::string(num) + " against " + std::string(den) + " (" + ps.pair.label() + ")";
}

// Why a rigid-body ratio is what it is: the time ratio is the ratio of solver
// steps (the adaptive solver's error estimate sees each representation's own
// truncation error) times the ratio of the cost of a step. Both from the runs.
void rigid_body_reasons(std::ostringstream& o, const std::vector<PairSummaries>& pairs) {
  std::vector<std::string> lines;
  for (const auto& ps : pairs) {
    const Aggregate a = aggregate(ps.scenes, Category::rigid_bodies, std::nullopt);
    if (a.scenes == 0) continue;
    double num_steps = 0, den_steps = 0;
    for (const auto& s : ps.scenes)
      if (s.category == Category::rigid_bodies && s.trajectories != Trajectories::not_compared)
        num_steps += static_cast<double>(s.numerator_steps), den_steps += static_cast<double>(s.denominator_steps);
    if (num_steps <= 0 || den_steps <= 0) continue;
    const double steps = num_steps / den_steps, per_step = a.ratio.ratio / steps;
    lines.push_back(pair_words(ps, Category::rigid_bodies) + ": " + fmt("%.0f", num_steps) + " solver steps against " +
                    fmt("%.0f", den_steps) + " (" + fmt("%.2f", steps) + "×), each costing " + fmt("%.2f", per_step) +
                    "× as much: " + fmt("%.2f", steps) + " × " + fmt("%.2f", per_step) + " = " +
                    fmt("%.2f", a.ratio.ratio));
  }
  if (lines.empty()) return;
  o << "\n**Why, on rigid bodies:** the time ratio is the ratio of solver steps (accepted and rejected, summed over "
       "the scenes) times the ratio of the time per step.\n\n";
  for (const auto& line : lines) o << "- " << line << ".\n";
}

// The verdict §1.1 asks for (does GA help?), for speed and agreement, stated
// from the numbers above, pair by pair, and claiming no more than they show.
void verdict(std::ostringstream& o, const std::vector<PairSummaries>& pairs) {
  o << "\n**Verdict, from these numbers:**\n\n";
  std::vector<std::string> evidence, shared;
  for (const Category c : kCategories) {
    std::vector<Aggregate> per_pair;
    int scenes = 0;  // the most any pair compared
    for (const auto& ps : pairs) {
      per_pair.push_back(aggregate(ps.scenes, c, std::nullopt));
      scenes = std::max(scenes, per_pair.back().scenes);
    }
    std::vector<std::string> parts;
    for (std::size_t i = 0; i < pairs.size(); ++i) {
      const Aggregate& a = per_pair[i];
      std::vector<std::string> parted = parted_scenes(pairs[i].scenes, c);
      for (auto& name : parted) name = md_text(name);
      const std::string left_out = parted.empty() ? "" : " (" + and_list(parted) + " parted, left out)";
      if (a.scenes == 0) {
        if (!parted.empty()) parts.push_back("no verdict, " + pair_words(pairs[i], c) + ": every scene parted" + left_out);
        continue;
      }
      parts.push_back(to_string(a.verdict, pairs[i].pair.numerator) + ", " + pair_words(pairs[i], c) + " " +
                      interval_cell(a.ratio) +
                      (a.scenes < scenes ? " over " + std::to_string(a.scenes) + " scene" + (a.scenes == 1 ? "" : "s")
                                         : "") +
                      left_out);
    }
    if (parts.empty()) continue;
    (is_evidence(c) ? evidence : shared)
        .push_back(std::string(to_string(c)) + " (" + std::to_string(scenes) + " scene" + (scenes == 1 ? "" : "s") +
                   "): " + joined(parts, "; "));
  }
  if (evidence.empty()) o << "- No rigid-body or collision scene was compared, so there is no evidence either way.\n";
  for (const auto& text : evidence) o << "- " << text << ".\n";
  for (const auto& text : shared)
    o << "- The " << text << ": the same code runs in every backend, so this is reported, not evidence.\n";

  for (const auto& ps : pairs) {
    int identical = 0, agree = 0, own = 0;
    const SceneSummary* closest = nullptr;  // the agreeing scene nearest its tolerance
    std::vector<std::string> parted, not_compared;
    for (const auto& s : ps.scenes) {
      if (s.trajectories == Trajectories::identical) ++identical;
      if (s.trajectories == Trajectories::agree) {
        ++agree;
        if (!closest || s.tolerance_used > closest->tolerance_used) closest = &s;
      }
      if (s.trajectories == Trajectories::parted) parted.push_back(md_text(s.name));
      if (s.trajectories == Trajectories::own_settings) ++own;
      if (s.trajectories == Trajectories::not_compared && s.ran)
        not_compared.push_back(md_text(s.name + " (" + s.not_compared_why + ")"));
    }
    // Scenes where one of the pair did not run at all (the quaternion twin on
    // a collision scene) are not counted: nothing was asked of them.
    std::size_t n = 0;
    for (const auto& s : ps.scenes) n += s.ran;
    if (n == 0) continue;
    o << "- Trajectories of " << ps.pair.numerator << " against " << ps.pair.denominator << ": ";
    if (own)
      o << "each ran at its own setting, the one reaching the same accuracy (`--accuracy`), on " << own << " of " << n
        << " scenes, so they differ by design and no agreement between them is claimed"
        << (own < static_cast<int>(n) ? "; " : ". ");
    if (own < static_cast<int>(n)) {
      o << "identical at every sample on " << identical << " of " << n << " scenes";
      if (agree)
        o << ", within the scene's own tolerance on " << agree << " (nearest it: " << md_text(closest->name) << ", "
          << fmt("%.2g", 100 * closest->tolerance_used) << "% of " << fmt("%.0e", closest->tolerance.metres) << " m)";
      if (!parted.empty()) o << "; parted (chaotic) on " << joined(parted, ", ") << ", where no agreement is claimed";
      if (!not_compared.empty()) o << "; not compared on " << joined(not_compared, ", ");
      o << ".";
    }
    o << "\n";
  }
  std::vector<std::string> folders;
  for (const std::string_view b : backends_of(pairs_of(pairs))) {
    std::string folder("`");  // traditional-quaternion: traditional/ (appended, not +: GCC 12's -Wrestrict)
    folder.append(b.substr(0, b.find('-'))).append("/`");
    if (std::find(folders.begin(), folders.end(), folder) == folders.end()) folders.push_back(folder);
  }
  o << "\nCoding simplicity is not measured here: compare " << and_list(folders) << " side by side.\n";
  rigid_body_reasons(o, pairs);
}

}  // namespace

namespace {
// The overview in the order a reader wants it: what was run, the answer (the
// verdict, and in report.html the figures before it), then the evidence.
struct SummaryParts {
  std::string head, answer, tables;
};

SummaryParts summary_parts(const std::vector<SceneResult>& results, const std::vector<PairSummaries>& pairs,
                           const MachineInfo& machine, int repeats) {
  const std::vector<BackendPair> compared = pairs_of(pairs);
  const std::vector<std::string_view> backends = backends_of(compared);
  SummaryParts parts;
  {
    std::ostringstream o;
    o << "# gacompare: " << results.size() << " scenes\n\n" << header(machine, repeats, compared) << "\n";
    parts.head = o.str();
  }
  {
    std::ostringstream o;
    verdict(o, pairs);
    // Physical sanity (compare/sanity.hpp), every warning of every scene, where
    // nobody reading the summary can miss it.
    for (const auto& r : results)
      for (const auto& w : sanity_warnings(sanity_checks(r)))
        o << "\n**WARNING, physical sanity:** " << md_text(r.scene.name + ": " + w) << "\n";
    parts.answer = o.str();
  }
  std::ostringstream o;
  // Each backend's time, then its energy change, per scene: one column per
  // backend, two tables, so that neither outgrows the page.
  const auto per_backend = [&](const std::string& title, const std::string& what, const auto& cell) {
    o << "\n## " << title << "\n\n" << what << "\n\n| scene | category | tolerance d (m) |";
    for (const std::string_view b : backends) o << " " << b << " |";
    o << "\n|---|---|---:|";
    for (std::size_t i = 0; i < backends.size(); ++i) o << "---:|";
    o << "\n";
    for (std::size_t i = 0; i < results.size(); ++i) {
      const SceneResult& r = results[i];
      const SceneSummary& first = pairs.front().scenes[i];
      o << "| [" << md_text(r.scene.name) << "](" << file_name_for(r.scene.name) << "/report.md) | "
        << to_string(first.category) << " | " << fmt("%.0e", first.tolerance.metres)
        << (first.tolerance.source == "check.max_divergence" ? "" : " (penetration)") << " |";
      for (const std::string_view name : backends) {
        const BackendResult* b = find(r, name);
        o << " " << (b ? cell(*b) : std::string("–")) << " |";
      }
      o << "\n";
    }
  };
  per_backend("Times", "Each backend's whole run: the median over repeats, min–max in brackets.",
              [](const BackendResult& b) { return compact_time_cell(total_seconds(b)); });
  per_backend("Energy", "Each backend's largest energy change over the run, relative to the scene's energy scale.",
              [](const BackendResult& b) { return fmt("%.2e", energy_drift(b.run)); });
  // Each pair that ran on a scene: its ratio, how far apart the two ran, and
  // whether they followed one trajectory. One row per scene and pair, so the
  // table stays as wide as its six columns however many backends ran.
  o << "\n## Pairs\n\n| scene | pair | ratio [95% CI] | apart (m) | apart (rad) | trajectories |\n"
       "|---|---|---:|---:|---:|---|\n";
  for (std::size_t i = 0; i < results.size(); ++i)
    for (const auto& ps : pairs) {
      const SceneSummary& s = ps.scenes[i];
      if (!s.ran) continue;
      const bool compared_here = s.trajectories != Trajectories::not_compared;
      const std::string ratio =
          !compared_here ? "–"
          : s.trajectories == Trajectories::parted
              ? interval_cell(scene_ratio(s, std::nullopt)) + " per unit of work (whole run " +
                    interval_cell(scene_ratio(s, std::nullopt, true)) + ")"
              : interval_cell(scene_ratio(s, std::nullopt));
      const std::string forms =
          s.numerator_form.empty() ? "" : " (" + std::string(s.numerator_form) + " / " + std::string(s.denominator_form) + ")";
      o << "| " << md_text(s.name) << " | " << ps.pair.label() << forms << " | " << ratio << " | "
        << (compared_here ? fmt("%.2e", s.divergence) : "–") << " | "
        << (compared_here && s.bodies ? fmt("%.2e", s.orientation_divergence) : "–") << " | "
        << (compared_here ? to_string(s.trajectories) : md_text("not compared: " + s.not_compared_why)) << " |\n";
    }
  o << "\nRatios are of the mean time per repeat, whole run; where the trajectories parted, per unit of each "
       "stage's work (below), and left out of the category's ratios. Apart: the largest distance between the two "
       "backends' particles and bodies' centres of mass, and angle between their bodies' orientations, over all "
       "samples. Tolerance d: the scene's `check.max_divergence`, or on a collision scene its penetration "
       "tolerance where that is smaller. Within it: every position within d and every moving body's orientation "
       "within d / r (r the body's radius: a turn by d / r moves none of its points further than d), the bounds "
       "`check` applies between backends. No agreement is claimed beyond it.\n";
  for (std::size_t k = 0; k < pairs.size(); ++k) category_tables(o, pairs[k], repeats, k == 0);
  parts.tables = o.str();
  return parts;
}

// The forest plot of the answer: each evidence category's ratio of the first
// pair (cga/traditional), whole run then stage by stage, and each other pair's
// whole run, every row with its 95% interval and the scenes behind it.
ForestPlot forest(const std::vector<PairSummaries>& pairs) {
  ForestPlot f{"Time ratios, 95% intervals: below 1 the first backend named is faster", "time ratio (log scale)", {}};
  for (const Category c : kCategories) {
    if (!is_evidence(c)) continue;
    for (std::size_t k = 0; k < pairs.size(); ++k) {
      const PairSummaries& ps = pairs[k];
      const Aggregate overall = aggregate(ps.scenes, c, std::nullopt);
      if (overall.scenes == 0) continue;
      const auto row = [&](const std::string& label, const Aggregate& a, std::optional<Stage> stage, bool bold) {
        ForestRow r{label, a.ratio.ratio, a.ratio.lo, a.ratio.hi, {}, bold};
        for (const auto& s : ps.scenes)  // the dots of the scenes in the ratio
          if (s.category == c && s.trajectories != Trajectories::parted && !compared_seconds(s, stage).numerator.empty())
            r.scenes.push_back(scene_ratio(s, stage).ratio);
        f.rows.push_back(std::move(r));
      };
      const std::string pair = ps.pair.label();
      row(std::string(to_string(c)) + ": " + pair, overall, std::nullopt, true);
      if (k != 0) continue;  // the stages of the headline pair only: the figure stays readable
      for (int st = 0; st < core::kStageCount; ++st) {
        const auto stage = static_cast<Stage>(st);
        const Aggregate a = aggregate(ps.scenes, c, stage);
        if (a.scenes > 0) row("   " + std::string(core::stage_name(stage)), a, stage, false);
      }
    }
  }
  return f;
}
}  // namespace

namespace {
// The forest plot's SVG ("" when no evidence category was compared), drawn
// once per report folder: report.md links it as forest.svg, report.html
// inlines it.
std::string forest_svg(const std::vector<PairSummaries>& pairs) {
  const ForestPlot f = forest(pairs);
  return f.rows.empty() ? "" : render_svg(f);
}

std::string summary_md(const std::vector<SceneResult>& results, const std::vector<PairSummaries>& pairs,
                       const MachineInfo& machine, int repeats, bool with_forest) {
  const SummaryParts p = summary_parts(results, pairs, machine, repeats);
  const std::string figure =
      with_forest ? "![Time ratios by category and stage, with 95% intervals](forest.svg)\n\n" : "";
  return p.head + figure + p.answer + p.tables;
}

std::string summary_html(const std::vector<SceneResult>& results, const std::vector<PairSummaries>& pairs,
                         const MachineInfo& machine, int repeats, const std::string& forest,
                         const std::vector<Figure>& work_precision) {
  const SummaryParts p = summary_parts(results, pairs, machine, repeats);
  std::string figures;
  if (!forest.empty())
    figures += "<figure id=\"forest\">" + inline_svg(forest) +
               "<figcaption>Each row: a ratio of times over a category's scenes, weighted by time, with its 95% "
               "bootstrap interval over paired repeats; grey circles: the single scenes behind it. Left of the dashed "
               "line the first backend named is faster. Stages are shown for the first pair.</figcaption></figure>\n";
  for (const Figure& w : work_precision)
    figures += "<figure>" + inline_svg(w.svg) + "<figcaption>" + markdown_to_html(w.caption) + "</figcaption></figure>\n";
  return html_page("gacompare", markdown_to_html(p.head) + figures + markdown_to_html(p.answer) + markdown_to_html(p.tables),
                   "overview");
}
}  // namespace

std::string summary_report_md(const std::vector<SceneResult>& results, const MachineInfo& machine, int repeats,
                              double equal_accuracy) {
  const std::vector<PairSummaries> pairs = summarise(results, equal_accuracy > 0);
  return summary_md(results, pairs, machine, repeats, !forest(pairs).rows.empty());
}

std::string summary_report_html(const std::vector<SceneResult>& results, const MachineInfo& machine, int repeats,
                                double equal_accuracy, const std::vector<Figure>& work_precision) {
  const std::vector<PairSummaries> pairs = summarise(results, equal_accuracy > 0);
  return summary_html(results, pairs, machine, repeats, forest_svg(pairs), work_precision);
}

void write_reports(const std::filesystem::path& dir, const std::vector<SceneResult>& results,
                   const MachineInfo& machine, int repeats, double equal_accuracy,
                   const std::vector<Figure>& work_precision) {
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
  // One summary and one forest plot for every file that shows them.
  const std::vector<PairSummaries> pairs = summarise(results, equal_accuracy > 0);
  const std::string forest = forest_svg(pairs);
  if (!forest.empty()) write_file_atomically(dir / "forest.svg", forest);
  write_file_atomically(dir / "summary.json", summary_json(pairs, machine, repeats, equal_accuracy).dump(1) + "\n");
  write_file_atomically(dir / "report.md", summary_md(results, pairs, machine, repeats, !forest.empty()));
  write_file_atomically(dir / "report.html", summary_html(results, pairs, machine, repeats, forest, work_precision));
}

}  // namespace gacompare::compare
