// compare/stored.hpp against what gacompare writes: every file it writes reads
// back (a complete run, a run that stopped early, a baseline, a sweep cell),
// bit for bit where it is a number; and what it refuses, with the file and
// JSON path (the end-to-end cases are in reliability_inputs_test.cpp).
#include "compare/check.hpp"
#include "compare/results.hpp"
#include "compare/stored.hpp"
#include "compare/sweep.hpp"

#include "core/error.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

#include <functional>
#include <string>

namespace {
using namespace gacompare;
using namespace gacompare::compare;
using nlohmann::json;

const std::string kScenes = std::string(GACOMPARE_DATA_DIR) + "/scenes/";

std::string refusal(const std::function<void()>& read) {
  try {
    read();
  } catch (const Error& e) {
    EXPECT_EQ(e.kind(), ErrorKind::input);
    return e.what();
  }
  return "accepted";
}

TEST(Stored, ResultsReadBackAsWritten) {
  const core::Scene scene = core::load_scene(kScenes + "projectile_linear_drag.json");
  const SceneResult r = compare_scene(scene, {"traditional", "cga"}, 2, Selection::exactly);
  const StoredResults back = parse_results(results_json(r, machine_info(), 2).dump(1), "results.json");
  EXPECT_EQ(back.objects.scene, scene.name);
  EXPECT_EQ(back.objects.particles, (std::vector<std::string>{"shot", "lob", "drop"}));
  EXPECT_EQ(back.sha256, scene.sha256);
  EXPECT_EQ(back.repeats, 2);
  ASSERT_EQ(back.runs.size(), 2u);
  for (std::size_t b = 0; b < 2; ++b) {
    const auto& run = back.runs[b];
    const auto& written = r.backends[b].run;
    EXPECT_EQ(run.backend, written.backend);
    ASSERT_EQ(run.samples.size(), written.samples.size());
    for (std::size_t k = 0; k < run.samples.size(); ++k) {
      EXPECT_EQ(run.samples[k].t, written.samples[k].t);
      for (std::size_t i = 0; i < 3; ++i) {
        EXPECT_EQ(run.samples[k].particles[i].position, written.samples[k].particles[i].position);  // bit for bit
        EXPECT_EQ(run.samples[k].particles[i].velocity, written.samples[k].particles[i].velocity);
      }
    }
    EXPECT_EQ(run.stage_seconds.at("integrate").size(), 2u);
    EXPECT_EQ(run.stage_seconds.at("integrate")[1], r.backends[b].profiles[1][core::Stage::integrate].seconds);
  }
}

// A run stopped by its step budget keeps the samples before it: fewer than
// the duration gives, which a file may hold only when it says it stopped.
TEST(Stored, ARunThatStoppedEarlyReadsBackAndOneThatDidNotSayIsRefused) {
  core::Limits limits;
  limits.max_steps = 100;
  const core::Scene scene = core::load_scene(kScenes + "spinning_top.json", limits);
  const SceneResult r = compare_scene(scene, {"cga"}, 1, Selection::exactly);
  ASSERT_TRUE(r.backends[0].run.error);
  json j = results_json(r, machine_info(), 1);
  const StoredResults back = parse_results(j.dump(), "results.json");
  EXPECT_LT(back.runs[0].samples.size(), 501u);
  EXPECT_EQ(*back.runs[0].error, *r.backends[0].run.error);
  j["runs"][0].erase("error");
  const std::string said = refusal([&] { parse_results(j.dump(), "r.json"); });
  EXPECT_NE(said.find("r.json: /runs/0/samples: expected exactly 501 samples (duration 5 s, one every 0.01 s, not stopped early)"), std::string::npos) << said;
}

TEST(Stored, BaselinesReadBackAsWritten) {
  const core::Scene scene = core::load_scene(kScenes + "cube_drop_flat.json");
  core::Scene short_scene = scene;
  short_scene.duration = 0.1;
  const SceneResult r = compare_scene(short_scene, {"traditional", "cga"}, 2, Selection::exactly);
  const Baseline b = parse_baseline(json::parse(baseline_json(r).dump()), "b.json");
  ASSERT_EQ(b.runs.size(), 2u);
  EXPECT_EQ(b.runs[1].backend, "cga");
  EXPECT_EQ(b.runs[1].t, r.backends[1].run.samples.back().t);
  EXPECT_EQ(b.runs[1].bodies.at("cube").orientation, r.backends[1].run.samples.back().bodies[1].orientation);
  EXPECT_TRUE(b.runs[1].velocities);
  EXPECT_EQ(b.runs[1].wall_seconds_each_repeat, r.backends[1].wall_seconds);
  // Two runs of one backend, and an orientation of three numbers.
  json twice = json::parse(baseline_json(r).dump());
  twice["runs"][1]["backend"] = "traditional";
  EXPECT_EQ(refusal([&] { parse_baseline(twice, "b.json"); }), "b.json: /runs/1/backend: expected each backend once, got \"traditional\"");
  json three = json::parse(baseline_json(r).dump());
  three["runs"][0]["final"]["bodies"]["cube"]["orientation"] = {1, 0, 0};
  EXPECT_EQ(refusal([&] { parse_baseline(three, "b.json"); }),
            "b.json: /runs/0/final/bodies/cube/orientation: expected [w, x, y, z], got an array of 3");
}

TEST(Stored, SweepCellsReadBackAsWritten) {
  SweepSpec spec;
  spec.solvers = {core::SolverMethod::rk4};
  spec.dt_halvings = 0;
  spec.repeats = 2;
  spec.peer = false;
  const core::Scene swept = swept_scene(core::load_scene(kScenes + "projectile_linear_drag.json"), spec);
  const auto units = sweep_units(spec, swept);
  ASSERT_EQ(units.size(), 1u);
  const std::string text = run_unit(units[0], swept, sweep_reference(swept), spec).dump(1);
  const SweepCell cell = parse_cell(text, "c.json", units[0].id);
  EXPECT_TRUE(cell_is_current(cell, cell_key(swept, spec)));
  ASSERT_EQ(cell.cells.size(), 3u);  // traditional, cga, pga (a particle scene: no second rotation)
  EXPECT_EQ(cell.cells[0].seconds.size(), 2u);
  EXPECT_GT(cell.cells[1].steps, 0u);
  EXPECT_TRUE(cell.cells[0].errors.count("position"));
  // Filed under another unit's name, it is refused.
  EXPECT_NE(refusal([&] { parse_cell(text, "c.json", "rk4-dt0.5"); }).find("c.json: /unit: expected \"rk4-dt0.5\""), std::string::npos);
  // An older format is not read further: its unit is run again.
  EXPECT_EQ(parse_cell(R"({"format": 3, "cells": "anything"})", "old.json", "x").format, 3);
}

TEST(Stored, MalformedAndDeepJsonAreInputErrors) {
  EXPECT_NE(refusal([] { parse_stored("{\"a\": ", "f.json"); }).find("f.json: malformed JSON: parse error"), std::string::npos);
  EXPECT_EQ(refusal([] { parse_stored(std::string(100, '[') + std::string(100, ']'), "f.json"); }),
            "f.json: malformed: nested more than 64 deep");
  EXPECT_NE(refusal([] { parse_stored("[1e999]", "f.json"); }).find("f.json: malformed JSON"), std::string::npos);
}

}  // namespace
