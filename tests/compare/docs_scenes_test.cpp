// The examples of docs/scenes.md and README.md are complete scenes: each
// ```json block loads, and runs through both backends with neither stopping
// early and the two agreeing within the scene's check.max_divergence
// (compare/check.hpp's bounds, as `gacompare check` holds every bundled
// scene). A change to the format that the pages do not follow fails here.
#include "compare/check.hpp"
#include "compare/runner.hpp"
#include "core/model/scene.hpp"

#include <gtest/gtest.h>

#include <fstream>
#include <sstream>

using namespace gacompare;

namespace {

std::vector<std::string> json_blocks(const std::string& md) {
  std::vector<std::string> out;
  const std::string open = "```json\n", close = "\n```";
  for (auto at = md.find(open); at != std::string::npos; at = md.find(open, at + 1)) {
    const auto end = md.find(close, at + open.size());
    if (end == std::string::npos) break;
    out.push_back(md.substr(at + open.size(), end - at - open.size()));
  }
  return out;
}

std::vector<std::string> json_blocks_of(const std::string& relative) {
  std::ifstream in(std::string(GACOMPARE_SOURCE_DIR) + "/" + relative);
  EXPECT_TRUE(in) << relative << " not found";
  std::stringstream text;
  text << in.rdbuf();
  return json_blocks(text.str());
}

// Loads each block as a scene and runs it through both backends, which must
// pass every check between them.
void expect_runs(const std::vector<std::string>& blocks, const std::string& where) {
  for (const auto& block : blocks) {
    core::Scene scene;
    ASSERT_NO_THROW(scene = core::parse_scene(block, where)) << block;
    const auto result = compare::compare_scene(scene, {"traditional", "cga"}, 1, compare::Selection::exactly);
    for (const auto& line : compare::check_scene(result, std::nullopt))
      EXPECT_NE(line.verdict, compare::CheckLine::Verdict::fail)
          << scene.name << ": " << line.backend << " " << line.what << ": " << line.note;
  }
}

}  // namespace

TEST(DocsScenes, EveryExampleLoadsAndRunsInBothBackends) {
  const auto blocks = json_blocks_of("docs/scenes.md");
  ASSERT_EQ(blocks.size(), 7u);  // particles, constraints, rigid bodies, collisions, friction, sphere, capsule
  expect_runs(blocks, "docs/scenes.md");
}

// The README's one example is a complete scene too.
TEST(DocsScenes, TheReadmeExampleLoadsAndRuns) {
  const auto blocks = json_blocks_of("README.md");
  ASSERT_EQ(blocks.size(), 1u);
  expect_runs(blocks, "README.md");
}
