// docs/scenes.md's examples are complete scenes: each ```json block that is a
// scene loads, and runs through both backends with neither stopping early and
// the two agreeing within the scene's check.max_divergence (compare/check.hpp's
// bounds, as `gacompare check` holds every bundled scene). A change to the
// format that the page does not follow fails here.
#include "compare/check.hpp"
#include "compare/runner.hpp"
#include "core/scene.hpp"

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

}  // namespace

TEST(DocsScenes, EveryExampleLoadsAndRunsInBothBackends) {
  std::ifstream in(std::string(GACOMPARE_SOURCE_DIR) + "/docs/scenes.md");
  ASSERT_TRUE(in) << "docs/scenes.md not found";
  std::stringstream text;
  text << in.rdbuf();
  const auto blocks = json_blocks(text.str());
  ASSERT_EQ(blocks.size(), 7u);  // particles, constraints, rigid bodies, collisions, friction, sphere, capsule
  for (const auto& block : blocks) {
    core::Scene scene;
    ASSERT_NO_THROW(scene = core::parse_scene(block, "docs/scenes.md")) << block;
    const auto result = compare::compare_scene(scene, {"traditional", "cga"}, 1, compare::Selection::exactly);
    for (const auto& line : compare::check_scene(result, std::nullopt))
      EXPECT_NE(line.verdict, compare::CheckLine::Verdict::fail)
          << scene.name << ": " << line.backend << " " << line.what << ": " << line.note;
  }
}
