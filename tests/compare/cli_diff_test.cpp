// gacompare diff on real runs: its own executable, run alone by ctest
// (RUN_SERIAL), since it holds two runs made seconds apart to within 3x of
// each other in time, which a heavy test on the other core could break.
#include "cli_run.hpp"

#include <gtest/gtest.h>
#include <nlohmann/json.hpp>

#include <filesystem>
#include <string>

namespace {

// gacompare diff on two real runs of the same scenes (times within noise,
// states bit-identical: exit 0), then on a copy doctored to be slower in one
// stage and on one doctored to have moved (exit 1 each).
TEST(Cli, DiffPassesEqualRunsAndFailsASlowerStageOrAMovedState) {
  const std::string data = std::string(GACOMPARE_DATA_DIR) + "/scenes/";
  const std::string scenes = data + "tumbling_box.json " + kScene;
  const fs::path a = fresh_dir("diff_a"), b = fresh_dir("diff_b");
  // 9 repeats: a loaded machine slows a repeat now and then by 20x; the
  // medians of 9 see through one or two (compare/stats.hpp).
  ASSERT_EQ(gacompare("compare " + scenes + " --repeat 9 --quiet --out " + a.string()).code, 0);
  ASSERT_EQ(gacompare("compare " + scenes + " --repeat 9 --quiet --out " + b.string()).code, 0);
  // A run against itself: every interval holds 1, whatever the machine did.
  EXPECT_EQ(gacompare("diff " + a.string() + " " + a.string() + " --max-time-ratio 1.0001").code, 0);
  // 3: the two runs share this machine seconds apart; a whole interval above
  // 3x is a regression, not its load.
  const Result equal = gacompare("diff " + a.string() + " " + b.string() + " --max-time-ratio 3");
  EXPECT_EQ(equal.code, 0) << equal.out;
  EXPECT_NE(equal.out.find("| tumbling_box | cga | `integrate` time, B / A |"), std::string::npos) << equal.out;
  EXPECT_NE(equal.out.find("| tumbling_box | traditional | largest orientation difference, B − A (rad) | 0 |"),
            std::string::npos)
      << equal.out;
  EXPECT_NE(equal.out.find("equal everywhere"), std::string::npos) << equal.out;
  EXPECT_NE(equal.out.find("A: " + a.string()), std::string::npos) << equal.out;

  // B's cga integrate 10x slower on tumbling_box.
  const fs::path slow = fresh_dir("diff_slow");
  fs::copy(a, slow, fs::copy_options::recursive);
  json j = read_json(slow / "tumbling_box" / "results.json");
  for (auto& t : j["runs"][1]["stages"]["integrate"]["seconds_each_repeat"]) t = t.get<double>() * 10;
  write_text(slow / "tumbling_box" / "results.json", j.dump());
  const Result slower = gacompare("diff " + a.string() + " " + slow.string() + " --max-time-ratio 3");
  EXPECT_EQ(slower.code, 1) << slower.out;
  EXPECT_NE(slower.out.find("| tumbling_box | cga | `integrate` time, B / A |"), std::string::npos);
  EXPECT_NE(slower.out.find("**FAIL**: A "), std::string::npos) << slower.out;
  EXPECT_NE(slower.out.find("the whole interval lies above 3"), std::string::npos) << slower.out;
  EXPECT_EQ(gacompare("diff " + a.string() + " " + slow.string()).code, 0);  // time reported, not checked

  // B's traditional box 1 µm higher at one sample: beyond the scene's 1e-9 m.
  const fs::path moved = fresh_dir("diff_moved");
  fs::copy(a / "tumbling_box" / "results.json", moved.string() + ".json");
  j = read_json(moved.string() + ".json");
  auto& z = j["runs"][0]["samples"][100]["bodies"]["box"]["position"][2];
  z = z.get<double>() + 1e-6;
  write_text(moved.string() + ".json", j.dump());
  const std::string diff_moved = "diff " + (a / "tumbling_box" / "results.json").string() + " " + moved.string() + ".json";
  const Result far = gacompare(diff_moved);
  EXPECT_EQ(far.code, 1) << far.out;
  EXPECT_NE(far.out.find("| tumbling_box | traditional | largest position difference, B − A (m) | 1e-06 | 1e-09 | **FAIL**: "
                         "worst: body 'box'"),
            std::string::npos)
      << far.out;
  EXPECT_EQ(gacompare(diff_moved + " --tolerance 1e-5").code, 0);

  const Result missing = gacompare("diff " + a.string() + " /no/such/run");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("/no/such/run: no such results.json or report folder"), std::string::npos) << missing.err;
  j = read_json(a / "tumbling_box" / "results.json");
  j["scene"].erase("bodies");
  write_text(moved.string() + ".json", j.dump());
  const Result old = gacompare(diff_moved);
  EXPECT_EQ(old.code, 2);
  EXPECT_NE(old.err.find("/scene/bodies: missing (written before results.json carried it: run it again)"),
            std::string::npos)
      << old.err;
}

}  // namespace
