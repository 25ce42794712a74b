#include "core/stage.hpp"

namespace gacompare::core {

namespace {
constexpr std::array<std::string_view, kStageCount> kNames = {
    "forces", "constraints", "integrate", "broadphase", "narrowphase", "time_of_impact",
    "response", "mass_properties", "bounding_volumes"};
// (No `referee` stage: the referees, FCL and Bullet, answer `gacompare collide`
// queries, which time each library per pair in their own table; nothing in a
// simulation run calls them, so a stage for them only ever read 0.)
}

std::string_view stage_name(Stage s) { return kNames[static_cast<int>(s)]; }

std::optional<Stage> stage_from_name(std::string_view name) {
  for (int i = 0; i < kStageCount; ++i)
    if (kNames[i] == name) return static_cast<Stage>(i);
  return std::nullopt;
}

}  // namespace gacompare::core
