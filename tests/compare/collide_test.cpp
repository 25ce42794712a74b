// `gacompare collide` and `gacompare corpus` end to end: one entry
// per pair with every method's answer and time, the table, the disagreements
// written as case files that replay, and one-line errors for bad case files.
#include "cli_run.hpp"

#include <gtest/gtest.h>

#include <string>

namespace {

const std::string kHand = std::string(GACOMPARE_DATA_DIR) + "/collision/hand.json";

TEST(Collide, EveryPairGetsEveryMethodsAnswer) {
  const fs::path out = fresh_dir("collide") / "out.json";
  const fs::path table = out.parent_path() / "table.md";
  const fs::path dis = out.parent_path() / "disagreements";
  const Result r = gacompare("collide " + kHand + " --repeat 1 --out " + out.string() + " --table " + table.string() +
                             " --disagreements " + dis.string());
  ASSERT_EQ(r.code, 0) << r.err;
  const json entries = read_json(out);
  ASSERT_EQ(entries.size(), 40u);
  for (const auto& e : entries) {
    for (const char* m : {"traditional", "cga", "traditional_manifold", "cga_manifold", "sat", "fcl", "bullet"}) {
      ASSERT_TRUE(e.contains(m)) << e["name"] << " " << m;
      if (e[m].contains("error")) continue;  // a referee that gave no valid answer says so
      for (const char* k : {"intersect", "depth", "normal", "contact", "time_s"}) EXPECT_TRUE(e[m].contains(k)) << m << k;
      if (e[m]["intersect"].get<bool>() && !e["touching"].get<bool>()) {
        const double nx = e[m]["normal"][0], ny = e[m]["normal"][1], nz = e[m]["normal"][2];
        EXPECT_NEAR(nx * nx + ny * ny + nz * nz, 1, 1e-12) << e["name"] << " " << m;
      }
    }
    // Our backends agree with the reference outside the touching band.
    if (!e["touching"].get<bool>()) {
      EXPECT_EQ(e["traditional"]["intersect"], e["sat"]["intersect"]) << e["name"];
      EXPECT_EQ(e["cga"]["intersect"], e["sat"]["intersect"]) << e["name"];
      EXPECT_EQ(e["traditional_manifold"]["intersect"], e["sat"]["intersect"]) << e["name"];
      EXPECT_EQ(e["cga_manifold"]["intersect"], e["sat"]["intersect"]) << e["name"];
    }
    // The manifold's contacts: some exactly where the pair intersects (our yes/no agrees with the reference).
    if (!e["touching"].get<bool>()) {
      for (const char* m : {"traditional_manifold", "cga_manifold"})
        EXPECT_EQ(e[m]["contacts"].get<int>() > 0, e["sat"]["intersect"].get<bool>()) << e["name"] << " " << m;
    }
  }
  std::ifstream in(table);
  const std::string text((std::istreambuf_iterator<char>(in)), {});
  EXPECT_NE(text.find("| traditional | 30 | 0 | 30 (100%)"), std::string::npos) << text;
  EXPECT_NE(text.find("| traditional_manifold | 30 | 0 | 30 (100%)"), std::string::npos) << text;
  EXPECT_NE(text.find("| cga_manifold | 30 | 0 | 30 (100%)"), std::string::npos) << text;
  // Bullet gives no answer on the 1e-3 scale cubes: each such pair is a case file that replays.
  ASSERT_TRUE(fs::is_directory(dis));
  int files = 0;
  for (const auto& f : fs::directory_iterator(dis)) {
    ++files;
    const Result replay = gacompare("collide " + f.path().string() + " --repeat 1");
    EXPECT_EQ(replay.code, 0) << replay.err;
    EXPECT_EQ(json::parse(replay.out).size(), 1u);
  }
  EXPECT_GE(files, 1);
}

TEST(Collide, BrokenCaseFilesAreOneLineErrors) {
  const fs::path dir = fresh_dir("collide_bad");
  fs::create_directories(dir);
  const auto run = [&](const std::string& name, const std::string& text) {
    std::ofstream(dir / name) << text;
    return gacompare("collide " + (dir / name).string());
  };
  const Result empty = run("empty.json", "[]");
  EXPECT_EQ(empty.code, 2);
  EXPECT_NE(empty.err.find("non-empty array"), std::string::npos) << empty.err;
  const Result missing = run("missing.json", R"([{"a": {"box": [1, 1, 1], "position": [0, 0, 0]}}])");
  EXPECT_EQ(missing.code, 2);
  EXPECT_NE(missing.err.find("/0/b"), std::string::npos) << missing.err;
  const Result flat = run("flat.json", R"([{"a": {"hull": [[0,0,0],[1,0,0],[0,1,0],[1,1,0]], "position": [0, 0, 0]},
                                           "b": {"box": [1, 1, 1], "position": [0, 0, 0]}}])");
  EXPECT_EQ(flat.code, 2);
  EXPECT_NE(flat.err.find("/0/a/hull"), std::string::npos) << flat.err;
  const Result two = run("two.json", R"([{"a": {"box": [1, 1, 1], "tetrahedron": 1, "position": [0, 0, 0]},
                                          "b": {"box": [1, 1, 1], "position": [0, 0, 0]}}])");
  EXPECT_EQ(two.code, 2);
  EXPECT_NE(two.err.find("2 shape keys"), std::string::npos) << two.err;
  for (const Result* r : {&empty, &missing, &flat, &two}) EXPECT_EQ(std::count(r->err.begin(), r->err.end(), '\n'), 1);
}

// The random corpus is reproducible: the same seed writes the same file.
TEST(Collide, CorpusIsReproducible) {
  const fs::path dir = fresh_dir("corpus");
  fs::create_directories(dir);
  ASSERT_EQ(gacompare("corpus --seed 2026 --count 200 --out " + (dir / "r.json").string()).code, 0);
  EXPECT_EQ(read_json(dir / "r.json"), read_json(std::string(GACOMPARE_DATA_DIR) + "/collision/random.json"));
}

}  // namespace
