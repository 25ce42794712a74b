#pragma once
// `gacompare sweep`: what accuracy costs in time. Every solver × tolerance (or
// step) × backend on one scene, plus Boost.Odeint's controlled Cash–Karp 5(4) and
// dense-output Dormand–Prince 5(4) as peers, each cell's error against a
// reference run and its time.
//
// The unit of work is a setting (one solver at one tolerance or step): both
// backends run in it, interleaved, so drift hits them alike. Each finished unit
// is written to DIR/cells/<unit>.json at once, so a sweep that is interrupted and
// run again skips the units already done, and `--shard i/N` runs every N-th unit
// for a scheduler to spread (a Slurm array, GNU parallel); `gacompare merge`
// joins the shards' folders. The report (sweep.md, sweep.csv and the
// work-precision diagram) is written once every unit is there.
//
// Reference: the traditional backend with cash_karp45 at abs = rel = 1e-13 (the
// tightest tolerance at which these scenes still run in seconds); errors of cells
// tighter than ~1e-11 measure the reference as much as the cell. Errors
// (compare/metrics.hpp), each the largest over particles and bodies at the final
// time and the RMS over all samples (50 a run: adaptive steps never cross a
// sample time, so a fine sampling would cap every tolerance at the same step):
// position (m), orientation (rad, bodies), velocity (m/s), angular velocity
// (rad/s, bodies). The work-precision diagram and the Pareto front use one of
// them at the final time: --error, by default orientation for a scene of bodies
// (rotation is where the algebras differ; a centre of mass moves by the same
// formulas in both, and on a spinning body it does not move at all) and
// position for a scene with particles. Time: one warm-up, then the median
// (min–max) of the repeats, each a whole simulation.
#include "compare/metrics.hpp"
#include "compare/stored.hpp"
#include "core/run.hpp"
#include "core/model/scene.hpp"

#include <nlohmann/json.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace gacompare::compare {

struct SweepSpec {
  std::vector<core::SolverMethod> solvers;
  int tol_from = 3, tol_to = 12;  // adaptive: tolerances 10^-from … 10^-to, one per decade
  double dt_from = 1e-2;          // fixed step: dt_from, halved dt_halvings times
  int dt_halvings = 4;
  int repeats = 3;
  double max_duration = 0;        // > 0: cut the scene to this duration
  bool peer = true;               // Boost.Odeint's Cash–Karp and Dormand–Prince, where the scene has no projection
  std::optional<Measure> error;   // the diagram's x-axis; nullopt: default_error(scene)
  // The diagram draws one curve per backend and family of methods (the
  // report's), its best cells: those no other cell of the same backend and
  // family beats in both error and time. The table keeps every cell.
  bool by_family = false;
  std::string build;              // the commit of the build that runs the cells (cell_key)
};

// A method's family, as the diagrams group them: "classical" (Euler, RK4,
// RK4 with step doubling, Cash–Karp, with an I step controller), "PI pairs"
// (Bogacki–Shampine, Dormand–Prince, Tsitouras, Verner, with a PI
// controller), "symplectic", "Lie group" (RKMK 4 and 4(5), Crouch–Grossman 4:
// the rotation stepped on its group), or "Odeint" for the Boost peers.
std::string_view method_family(std::string_view solver);

// One number through a printf format ("%.3g"), as the reports write them.
std::string format_number(const char* printf_format, double x);

// Orientation for a scene with bodies and no particles, position otherwise.
Measure default_error(const core::Scene& scene);

// A unit's record (compare/stored.hpp, SweepCell) is reused by a resumed sweep
// or a merge only when it was written by kSweepCellFormat with this key.
// Everything beside the unit's own solver and setting that changes what its
// cell holds: the scene (sha256), the duration and sample interval it was cut
// to (--max-duration), the repeats its time is the median of (--repeat), and
// the build that ran it (spec.build, a commit: another build times other
// code). A cell with another key is run again, never mixed in.
nlohmann::ordered_json cell_key(const core::Scene& swept, const SweepSpec& spec);
bool cell_is_current(const SweepCell& cell, const nlohmann::json& key);

struct Unit {
  std::string id;       // file name stem: solver-setting
  std::string solver;   // a SolverMethod name, or a peer: "odeint_cash_karp54", "odeint_dopri5"
  std::string setting;  // "tol 1e-06" / "dt 0.005"
  core::SolverSpec spec;
};

// Every unit of the sweep, in a fixed order (the order shards are dealt from).
std::vector<Unit> sweep_units(const SweepSpec& spec, const core::Scene& scene);

// The scene as swept: generators expanded, cut to max_duration, 50 samples.
core::Scene swept_scene(const core::Scene& scene, const SweepSpec& spec);

// The reference run (traditional, cash_karp45 at 1e-13). Throws run_error if it fails.
core::Run sweep_reference(const core::Scene& swept);

// Runs one unit (both backends — for a scene of bodies also the traditional
// backend with its other rotation representation, labelled
// "traditional-quaternion" or "traditional-matrix" — or the peer) against the
// reference and returns
// its record: {"format", "unit", "solver", "setting", "key" (cell_key), "error_of_nothing": {measure: value},
// "cells": [{"backend", "errors": {measure: {"final", "rms"}}, "seconds", "steps", ...}]}
// (an error is null where the run failed; a measure the scene has no object for is absent).
nlohmann::ordered_json run_unit(const Unit& unit, const core::Scene& swept, const core::Run& reference,
                                const SweepSpec& spec);

// Every unit of `spec` on a swept scene (swept_scene), run here and kept in
// memory rather than in a cells folder: the overview report's work-precision
// diagrams of its rigid scenes (compare/report.hpp). Throws run_error when the
// reference run fails.
std::vector<SweepCell> run_units(const core::Scene& swept, const SweepSpec& spec);

// Writes sweep.md, sweep.csv, <scene>_work_precision.svg and sweep.html (the table
// and the diagram on one page) into `dir` from the units' records (in unit order).
// sweep.md ends with the time at equal accuracy: per solver, each backend's
// time and steps interpolated at common error levels (equal_accuracy below).
struct EqualAccuracyPoint {
  double error = 0, time = 0, steps = 0;
};
// A backend's cost of reaching error E along one solver's cells: the cells'
// lower envelope (sorted by time, each kept only when more accurate than every
// faster one) interpolated linearly in log error – log time (and log steps).
// nullopt outside the envelope's range of errors: never extrapolated.
std::optional<EqualAccuracyPoint> cost_at_error(std::vector<EqualAccuracyPoint> cells, double error);
void write_sweep_report(const std::filesystem::path& dir, const core::Scene& scene,
                        const std::vector<SweepCell>& units, const SweepSpec& spec);

}  // namespace gacompare::compare
